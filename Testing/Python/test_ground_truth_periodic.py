"""pvpython: FiberOrientationGroundTruth honours periodic_cell as PLISimulation does — the cell is
tiled into the volume of interest (Model/PeriodicTiling.h tileSection) — checked pixel by pixel
against the closed form. One straight fiber along x (radius 1 um, at y = z = 0) closed through
the cell [-5, 5]^3; the volume of interest [-15, 15] x [-15, 15] x [-2, 2] then holds its
translates at y = -10, 0 and 10 (those at z = +-10 lie outside), each running the whole width.
A pixel column is tissue iff its centre lies within the radius of one of them (give or take a
voxel). The ground truth used to ignore the cell: one stripe, one cell wide (x in [-5, 5])."""
import builtins
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())
SCRIPT = """
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray
out = self.GetPolyDataOutput()
points = vtkPoints()
points.SetDataTypeToDouble()
radius = vtkDoubleArray()
radius.SetName("radius")
lines = vtkCellArray()
lines.InsertNextCell(6)
for k in range(6):
    lines.InsertCellPoint(points.InsertNextPoint(-5.0 + 2.0 * k, 0.0, 0.0))
    radius.InsertNextValue(1.0)
out.SetPoints(points)
out.SetLines(lines)
out.GetPointData().AddArray(radius)
cell = vtkDoubleArray()
cell.SetName("periodic_cell")
for v in (-5.0, 5.0, -5.0, 5.0, -5.0, 5.0):
    cell.InsertNextValue(v)
out.GetFieldData().AddArray(cell)
"""
fibers = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=SCRIPT)
VOXEL, PIXEL = 0.25, 1.0
voi = [-15.0, 15.0, -15.0, 15.0, -2.0, 2.0]
truth = FiberOrientationGroundTruth(Input=fibers, VolumeOfInterest=voi, VoxelSize=VOXEL, PixelSize=PIXEL,
                                    NumberOfThreads=2)
errors = ErrorCatcher(truth)
truth.UpdatePipeline()
check(not errors.errors, "ground truth errors: %r" % errors.text())
t = servermanager.Fetch(truth)
fraction = t.GetPointData().GetArray("fraction")
nx, ny, _ = t.GetDimensions()
check((nx, ny) == (30, 30), "pixel grid %s" % ((nx, ny),))
tissue, wrong = 0, []
for j in range(ny):
    for i in range(nx):
        x, y, _ = t.GetPoint(i + nx * j)
        nearest = builtins.min(builtins.abs(y - c) for c in (-10.0, 0.0, 10.0))
        is_tissue = fraction.GetValue(i + nx * j) > 0.0
        tissue += is_tissue
        # A pixel whose centre lies inside a tube (by a voxel) must be tissue, one whose footprint
        # lies outside all tubes (by a voxel) must not; the boundary rows are not judged.
        if nearest < 1.0 - VOXEL and not is_tissue:
            wrong.append(("missing", x, y))
        if nearest > 1.0 + PIXEL / 2 + VOXEL and is_tissue:
            wrong.append(("extra", x, y))
check(not wrong, "%d pixels differ from the tiled cell, e.g. %s" % (len(wrong), wrong[:5]))
# Three stripes the whole width: about 3 x 30 x (2 radii / 1 um) pixels.
check(150 <= tissue <= 240, "%d tissue pixels" % tissue)

# PLISimulation reads the same tissue: the mean intensity over the rotations (the transmitted light,
# whatever the retardation) is below the background exactly in the columns the ground truth calls
# tissue (absorbing fibers, no blur, no noise, no background absorption).
sim = PLISimulation(Input=fibers, VolumeOfInterest=voi, VoxelSize=VOXEL, PixelSize=PIXEL, NumberOfRotations=4,
                    NoiseGain=0.0, OpticalSigma=0.0, Absorption=10.0, BackgroundAbsorption=0.0, NumberOfThreads=2)
sim_errors = ErrorCatcher(sim)
sim.UpdatePipeline()
check(not sim_errors.errors, "PLISimulation errors: %r" % sim_errors.text())
s = servermanager.Fetch(sim)
check(s.GetDimensions()[:2] == (nx, ny), "grids differ")
intensity = s.GetPointData().GetArray("intensity")
rotations = intensity.GetNumberOfComponents()
mean = [builtins.sum(intensity.GetComponent(p, c) for c in range(rotations)) / rotations for p in range(nx * ny)]
background = builtins.max(mean)
differ = [p for p in range(nx * ny) if (mean[p] < background * (1 - 1e-6)) != (fraction.GetValue(p) > 0.0)]
check(not differ, "%d pixels where simulation and ground truth disagree on tissue, e.g. %s" % (
    len(differ), [t.GetPoint(p) for p in differ[:5]]))
print("test_ground_truth_periodic passed: %d tissue pixels" % tissue)
