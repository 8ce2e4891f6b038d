"""pvpython (needs PLISimulation): FiberCubeSource (population x) → FiberCollisionSolver →
PLISimulation → PLIAnalysis; the analysed direction agrees with the known fiber direction (0°)
and with FiberOrientationGroundTruth on the same pixel grid.
Register with: fiberpli_add_pvpython_test(pli_chain)"""
import builtins
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())


def dir_diff(a, b):
    d = builtins.abs(a - b) % 180.0
    return builtins.min(d, 180.0 - d)


cube = FiberCubeSource(Populations=1, NumberOfFibers=40, EdgeLength=30.0, FiberRadius=0.8, SegmentLength=2.0,
                       Displacement=0.3, Seed=11)
solver = FiberCollisionSolver(Input=cube, SegmentLength=2.0, MinCurvatureRadius=0.0, MaxSteps=5000,
                              SeparationSpeed=0.025, NumberOfThreads=2)
voi = [-8.0, 8.0, -8.0, 8.0, -4.0, 4.0]
sim = PLISimulation(Input=solver, VolumeOfInterest=voi, VoxelSize=0.25, PixelSize=1.0, Wavelength=525.0,
                    LightIntensity=26000.0, NumberOfRotations=9, TiltAngle=0.0, Birefringence=-0.001,
                    Absorption=0.0, Seed=1)
ana = PLIAnalysis(Input=sim, InclinationMethod="Retardation", ReferenceRetardation=0.0, NumberOfThreads=2)
truth = FiberOrientationGroundTruth(Input=solver, VolumeOfInterest=voi, VoxelSize=0.25, PixelSize=1.0,
                                    NumberOfThreads=2)
ana.UpdatePipeline()
truth.UpdatePipeline()
a = servermanager.Fetch(ana)
t = servermanager.Fetch(truth)
check(a.GetDimensions() == t.GetDimensions(), "grids differ: %s vs %s" % (a.GetDimensions(), t.GetDimensions()))
for k in range(3):
    check(builtins.abs(a.GetOrigin()[k] - t.GetOrigin()[k]) < 1e-9 or k == 2, "origin %d" % k)
    check(builtins.abs(a.GetSpacing()[k] - t.GetSpacing()[k]) < 1e-9 or k == 2, "spacing %d" % k)
ad = a.GetPointData().GetArray("direction")
ar = a.GetPointData().GetArray("retardation")
td = t.GetPointData().GetArray("direction")
tf = t.GetPointData().GetArray("fraction")
used = 0
for p in range(a.GetNumberOfPoints()):
    # Pixels well inside tissue with a clear signal: the direction is the fiber axis (0°).
    if tf.GetValue(p) > 0.5 and ar.GetValue(p) > 0.1 and not math.isnan(td.GetValue(p)):
        check(dir_diff(ad.GetValue(p), 0.0) < 2.0, "pixel %d direction %g" % (p, ad.GetValue(p)))
        check(dir_diff(ad.GetValue(p), td.GetValue(p)) < 2.0, "pixel %d vs truth %g" % (p, td.GetValue(p)))
        used += 1
check(used > 20, "only %d pixels with tissue" % used)
print("test_pli_chain passed (%d pixels)" % used)
