"""pvpython: the polarimeter set-up of PLISimulation as lists (RotationAngles, TiltAngles,
TiltAzimuths, TiltConvention), analysed by PLIAnalysis from the field data alone; bad lists are
errors naming the property and the value, and the pipeline recovers; the Tissue output port
(ExportTissue, TissueVolume) and its memory guard."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

load_plugin(globals())

# One thick fiber (radius 1 mm) cut into a uniform 20 x 20 x 60 µm slab: axis direction 60°,
# inclination 35°.
DIRECTION, INCLINATION = 60.0, 35.0
d = math.radians(DIRECTION)
a = math.radians(INCLINATION)
u = [math.cos(a) * math.cos(d), math.cos(a) * math.sin(d), math.sin(a)]
line = PolyLineSource(Points=[-2000 * c for c in u] + [2000 * c for c in u])
fiber = Calculator(Input=line, ResultArrayName="radius", Function="1000")
sim = PLISimulation(Input=fiber, VolumeOfInterest=[-10, 10, -10, 10, -30, 30], VoxelSize=2.0, PixelSize=2.0,
                    OpticalSigma=0.0, NoiseGain=0.0, Birefringence=-0.001, NumberOfThreads=1)
sim.RotationAngles = [0, 15, 50, 100, 170]
sim.TiltAngles = [3.9, 8]
sim.TiltAzimuths = [30, 150, 270]
sim.TiltConvention = "FastPLI"
sim.UpdatePipeline()
img = servermanager.Fetch(sim)
fd = img.GetFieldData()
check(list(vtk_to_numpy(fd.GetArray("polarizer_angles"))) == [0, 15, 50, 100, 170], "polarizer_angles")
check(list(vtk_to_numpy(fd.GetArray("tilt_directions"))) == [30, 150, 270] * 2, "tilt_directions")
tilts = vtk_to_numpy(fd.GetArray("tilt_angles"))
check(len(tilts) == 6 and abs(tilts[0] - 3.9) < 1e-12 and abs(tilts[5] - 8) < 1e-12, "tilt_angles %s" % tilts)
check(abs(fd.GetArray("tilt_angle").GetValue(0) - 8) < 1e-12, "tilt_angle is the largest tilt")
check(fd.GetArray("tilt_convention").GetValue(0) == 1, "tilt_convention")
for name in ["intensity"] + ["intensity_tilt_%d" % v for v in range(6)]:
    arr = img.GetPointData().GetArray(name)
    check(arr is not None and arr.GetNumberOfComponents() == 5, "array %s" % name)
check(img.GetPointData().GetArray("intensity_tilt_6") is None, "more tilted views than 2 x 3")

ana = PLIAnalysis(Input=sim)
ana.UpdatePipeline()
maps = servermanager.Fetch(ana)
check(maps.GetFieldData().GetArray("inclination_method").GetValue(0) == 2, "Auto must pick the tilt fit")
direction = vtk_to_numpy(maps.GetPointData().GetArray("direction"))
inclination = vtk_to_numpy(maps.GetPointData().GetArray("inclination_signed"))
check(abs(direction - DIRECTION).max() < 0.01, "direction %s" % direction[:3])
check(abs(inclination - INCLINATION).max() < 0.01, "inclination %s" % inclination[:3])

# Bad lists: an error naming the property and the value; the output is empty; then recovery.
errors = ErrorCatcher(sim)
for prop, value, words in [("RotationAngles", [0, 15, 15], ["RotationAngles[1] and [2]", "15"]),
                           ("RotationAngles", [0, 90], ["RotationAngles", "2 values"]),
                           ("TiltAngles", [3.9, 95], ["TiltAngles[1]", "95"]),
                           ("TiltAzimuths", [0, float("nan")], ["TiltAzimuths[1]", "nan"])]:
    good = list(getattr(sim, prop))
    setattr(sim, prop, value)
    sim.UpdatePipeline()
    check(all(w in errors.text() for w in words), "%s %s: %r" % (prop, value, errors.text()))
    check(sim.GetDataInformation().GetNumberOfPoints() == 0, "output not empty after an error")
    errors.clear()
    setattr(sim, prop, good)
    sim.UpdatePipeline()
    check(not errors.errors and sim.GetDataInformation().GetNumberOfPoints() == 100, "no recovery")

# Empty lists are the defaults: NumberOfRotations angles and TiltAngle at 0, 90, 180, 270.
sim.RotationAngles = []
sim.TiltAngles = []
sim.TiltAzimuths = []
sim.NumberOfRotations = 6
sim.TiltAngle = 5.5
sim.UpdatePipeline()
img = servermanager.Fetch(sim)
check(list(vtk_to_numpy(img.GetFieldData().GetArray("polarizer_angles"))) == [0, 30, 60, 90, 120, 150],
      "default polarizer angles")
check(list(vtk_to_numpy(img.GetFieldData().GetArray("tilt_directions"))) == [0, 90, 180, 270],
      "default azimuths")
# Output port 1, "Tissue": the voxelised sub-volume with label and optic_axis (the slab is inside
# the fiber, so every voxel has label 1 and the fiber's axis).
sim.ExportTissue = 1
sim.TissueVolume = [-5, 5, -10, 0, -2, 2]
sim.UpdatePipeline()
tissue = servermanager.Fetch(sim, idx=1)
check(tissue.GetExtent() == (2, 7, 0, 4, 14, 15), "tissue extent %s" % (tissue.GetExtent(),))
check(tissue.GetSpacing() == (2.0, 2.0, 2.0), "tissue spacing %s" % (tissue.GetSpacing(),))
labels = vtk_to_numpy(tissue.GetPointData().GetArray("label"))
axes = vtk_to_numpy(tissue.GetPointData().GetArray("optic_axis"))
check(len(labels) == 6 * 5 * 2 and (labels == 1).all(), "labels %s" % labels[:5])
check(abs(abs(axes.dot(u)) - 1).max() < 1e-6, "optic_axis is not the fiber axis: %s" % axes[0])
check(list(vtk_to_numpy(tissue.GetFieldData().GetArray("label_bundle_ids"))) == [0], "label_bundle_ids")

# A tissue volume above the memory budget is refused with a clear error; then recovery.
# At 0.25 µm voxels the whole section (80 x 80 x 240 voxels) needs about 49 MB as tissue, more
# than the 30 MB the untilted simulation plans for.
os.environ["FIBERPLI_MEMORY_LIMIT"] = "30M"
errors.clear()
sim.TiltAngle = 0
sim.VoxelSize = 0.25
sim.TissueVolume = [1, -1, 1, -1, 1, -1]
sim.UpdatePipeline()
check(sim.GetDataInformation().GetNumberOfPoints() == 100, "the image must still be simulated")
check("memory budget" in errors.text() and "TissueVolume" in errors.text(), "no budget error: %r" % errors.text())
del os.environ["FIBERPLI_MEMORY_LIMIT"]
errors.clear()
sim.VoxelSize = 2.0
sim.TissueVolume = [-5, 5, -10, 0, -2, 2]
sim.UpdatePipeline()
n = servermanager.Fetch(sim, idx=1).GetNumberOfPoints()
check(not errors.errors and n == 60, "no tissue recovery: %d points, %r" % (n, errors.text()))
print("test_pli_setup passed")
