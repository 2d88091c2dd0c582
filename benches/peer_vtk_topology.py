"""VTK peer for the flow topology benchmark: the 1024 x 1024 double gyre (t = 0) on [0, 2] x [0, 1]
as vtkImageData with a 3-component vector array (w = 0), run through vtkVectorFieldTopology.
Prints the critical points (position, VTK type) and the in-process filter time to stderr.
Needs numpy and vtk (pip install numpy vtk; VTK >= 9.0 has the filter).

Usage: python3 benches/peer_vtk_topology.py [N]
"""
import sys
import time

import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1024
x = np.linspace(0.0, 2.0, n)
y = np.linspace(0.0, 1.0, n)
xx, yy = np.meshgrid(x, y)  # row j = y[j]: VTK's point order (x fastest)
u = -np.pi * 0.1 * np.sin(np.pi * xx) * np.cos(np.pi * yy)
v = np.pi * 0.1 * np.cos(np.pi * xx) * np.sin(np.pi * yy)
vec = np.column_stack([u.ravel(), v.ravel(), np.zeros(n * n)])

image = vtk.vtkImageData()
image.SetDimensions(n, n, 1)
image.SetOrigin(0.0, 0.0, 0.0)
image.SetSpacing(2.0 / (n - 1), 1.0 / (n - 1), 1.0)
arr = numpy_to_vtk(vec, deep=True)
arr.SetName("velocity")
image.GetPointData().AddArray(arr)
image.GetPointData().SetActiveVectors("velocity")

topo = vtk.vtkVectorFieldTopology()
topo.SetInputData(image)
topo.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "velocity")
topo.SetComputeSurfaces(False)
topo.SetIntegrationStepUnit(vtk.vtkStreamTracer.CELL_LENGTH_UNIT)
topo.SetMaxNumSteps(1)  # critical points are wanted; keep separatrix tracing minimal
start = time.perf_counter()
topo.Update()
elapsed = time.perf_counter() - start

points = topo.GetOutput(0)
names = {-1: "degenerate", 0: "sink", 1: "saddle", 2: "source", 3: "centre"}
types = points.GetPointData().GetArray("type")
print(f"vtk {vtk.vtkVersion.GetVTKVersion()}: {points.GetNumberOfPoints()} critical points")
for k in range(points.GetNumberOfPoints()):
    px, py, _ = points.GetPoint(k)
    t = int(types.GetTuple1(k)) if types is not None else None
    print(f"  ({px:.4f}, {py:.4f}) {names.get(t, t)}")
print(f"vtkVectorFieldTopology in-process: {elapsed:.3f} s", file=sys.stderr)
