"""Peer of `kind = "volume"` in benches/volume_256.toml: VTK's CPU ray caster
(vtkFixedPointVolumeRayCastMapper, offscreen) rendering the 256³ float32 field of four Gaussian
blobs (benches/data/blobs_256.npy, written by benches/make_blobs.py) to a 512 × 512
image with the same opacity points, sample distance half a voxel, shading off. Prints the best
of five frames after one warm-up frame (rendering only: the field is already in memory).

Usage: python3 benches/peer_vtk_volume.py [--threads N]   (pip install numpy vtk)
"""
import os
import sys
import time

import numpy as np
import vtk
from vtk.util import numpy_support

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
OPACITY = [(0.2, 0.0), (0.5, 0.3), (1.0, 0.8)]


def main():
    vol = np.load(os.path.join(HERE, "blobs_256.npy"))
    n = vol.shape[0]
    if "--threads" in sys.argv:
        vtk.vtkMultiThreader.SetGlobalMaximumNumberOfThreads(int(sys.argv[sys.argv.index("--threads") + 1]))
    image = vtk.vtkImageData()
    image.SetDimensions(n, n, n)
    image.GetPointData().SetScalars(numpy_support.numpy_to_vtk(vol.ravel(order="C"), deep=True))

    opacity = vtk.vtkPiecewiseFunction()
    for v, a in OPACITY:
        opacity.AddPoint(v, a)
    colour = vtk.vtkColorTransferFunction()
    colour.AddRGBPoint(0.2, 0.0, 0.0, 0.0)
    colour.AddRGBPoint(1.0, 1.0, 0.9, 0.6)
    prop = vtk.vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(colour)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()

    mapper = vtk.vtkFixedPointVolumeRayCastMapper()
    mapper.SetInputData(image)
    mapper.SetSampleDistance(0.5)
    mapper.SetAutoAdjustSampleDistances(0)
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)

    renderer = vtk.vtkRenderer()
    renderer.AddVolume(volume)
    renderer.SetBackground(1, 1, 1)
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.AddRenderer(renderer)
    window.SetSize(512, 512)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Azimuth(30)
    renderer.GetActiveCamera().Elevation(20)
    window.Render()
    times = []
    for _ in range(5):
        renderer.GetActiveCamera().Azimuth(0.5)
        t = time.perf_counter()
        window.Render()
        times.append(time.perf_counter() - t)
    print(f"vtkFixedPointVolumeRayCastMapper 512x512: best {min(times) * 1e3:.1f} ms a frame")


if __name__ == "__main__":
    main()
