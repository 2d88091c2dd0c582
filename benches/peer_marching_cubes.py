"""Peers of `dataink::enrich::volume::isosurface::extract` (benches/isosurface.rs): scikit-image's
`measure.marching_cubes` (Lewiner's marching cubes, its default) and VTK's `vtkFlyingEdges3D` and
`vtkMarchingCubes`, extracting the isosurface of the 256³ float32 field of four Gaussian blobs
(benches/data/blobs_256.npy, written by benches/make_blobs.py) at 0.5 and 0.05. Each filter
computes normals (gradient normals for VTK, as dataink's default; scikit-image always does).
Prints the best of five runs after one warm-up run, with the vertex and triangle counts
(extraction only: the field is already in memory).

Usage: python3 benches/peer_marching_cubes.py [--threads N]   (pip install numpy scikit-image vtk)
"""
import os
import sys
import time

import numpy as np
import vtk
from skimage import measure
from vtk.util import numpy_support

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
LEVELS = [0.5, 0.05]
RUNS = 5


def best_of(run):
    """Runs `run` once to warm up, then RUNS times; the best time in ms and the last result."""
    result = run()
    times = []
    for _ in range(RUNS):
        t = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - t)
    return min(times) * 1e3, result


def skimage_runner(vol, level):
    def run():
        verts, faces, _normals, _values = measure.marching_cubes(vol, level)
        return len(verts), len(faces)

    return run


def vtk_runner(image, make_filter, level):
    def run():
        f = make_filter()
        f.SetInputData(image)
        f.SetValue(0, level)
        f.ComputeNormalsOn()
        f.ComputeGradientsOff()
        f.ComputeScalarsOff()
        f.Update()
        out = f.GetOutput()
        return out.GetNumberOfPoints(), out.GetNumberOfPolys()

    return run


def main():
    vol = np.load(os.path.join(HERE, "blobs_256.npy"))
    if "--threads" in sys.argv:
        vtk.vtkMultiThreader.SetGlobalMaximumNumberOfThreads(int(sys.argv[sys.argv.index("--threads") + 1]))
    nz, ny, nx = vol.shape
    image = vtk.vtkImageData()
    image.SetDimensions(nx, ny, nz)
    image.GetPointData().SetScalars(numpy_support.numpy_to_vtk(vol.ravel(order="C"), deep=True))
    smp = vtk.vtkSMPTools()
    print(f"VTK {vtk.vtkVersion.GetVTKVersion()} SMP backend {smp.GetBackend()}, "
          f"{smp.GetEstimatedNumberOfThreads()} threads; field {nx}x{ny}x{nz} {vol.dtype}")
    for level in LEVELS:
        peers = [
            ("skimage.measure.marching_cubes", skimage_runner(vol, level)),
            ("vtkFlyingEdges3D", vtk_runner(image, vtk.vtkFlyingEdges3D, level)),
            ("vtkMarchingCubes", vtk_runner(image, vtk.vtkMarchingCubes, level)),
        ]
        for name, run in peers:
            ms, (verts, tris) = best_of(run)
            print(f"iso {level}: {name}: best {ms:.1f} ms, {verts} vertices, {tris} triangles")


if __name__ == "__main__":
    main()
