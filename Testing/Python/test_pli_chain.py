"""pvpython (needs PLISimulation): FiberCubeSource (population x) → FiberCollisionSolver →
PLISimulation → PLIAnalysis; the analysed direction agrees with the known fiber direction (0°)
and with FiberOrientationGroundTruth on the same pixel grid.
"""
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


# A dense single population along x (the paper's density), solved, then a 16 µm thick section.
cube = FiberCubeSource(Populations=1, NumberOfFibers=120, EdgeLength=51.96 * (120 / 1000.0) ** 0.5, FiberRadius=0.8,
                       SegmentLength=2.0, Displacement=0.5, Seed=11)
solver = FiberCollisionSolver(Input=cube, SegmentLength=2.0, MinCurvatureRadius=0.0, MaxSteps=5000,
                              SeparationSpeed=0.025, NumberOfThreads=2)
voi = [-6.0, 6.0, -6.0, 6.0, -8.0, 8.0]
sim = PLISimulation(Input=solver, VolumeOfInterest=voi, VoxelSize=0.25, PixelSize=1.0, Wavelength=525.0,
                    LightIntensity=26000.0, NumberOfRotations=9, TiltAngle=0.0, Birefringence=-0.001,
                    Absorption=0.0, Seed=1, NoiseGain=0.0)
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
used, vs_truth, vs_axis = 0, [], []
for p in range(a.GetNumberOfPoints()):
    # Pixels well inside tissue with a clear signal.
    if tf.GetValue(p) > 0.3 and ar.GetValue(p) > 0.05 and not math.isnan(td.GetValue(p)):
        vs_truth.append(dir_diff(ad.GetValue(p), td.GetValue(p)))
        # Signed deviation from the population axis (0°), in (-90, 90].
        vs_axis.append((ad.GetValue(p) + 90.0) % 180.0 - 90.0)
        used += 1
check(used > 20, "only %d pixels with tissue" % used)
vs_truth.sort()
print("pixels %d; |simulated - true| median %.2f, 90%% %.2f, max %.2f deg; mean direction %.2f deg" % (
    used, vs_truth[used // 2], vs_truth[int(0.9 * used)], vs_truth[-1], sum(vs_axis) / used))
# Noise-free: the bundle's direction (mean over its pixels) is the population axis within 2°, and
# pixel by pixel the simulated direction follows the true local mean axis (median within 1.5°,
# 90 % within 3°; blur mixes neighbouring fibers at the rest).
check(builtins.abs(sum(vs_axis) / used) < 2.0, "mean direction %.2f deg" % (sum(vs_axis) / used))
check(vs_truth[used // 2] < 1.5, "median deviation from the truth %.2f deg" % vs_truth[used // 2])
check(vs_truth[int(0.9 * used)] < 3.0, "90th percentile deviation %.2f deg" % vs_truth[int(0.9 * used)])
print("test_pli_chain passed")
