"""pvpython: PLISimulation on a small fiber cube with explicit properties; extents, arrays and field
data, the transmittance invariant, bad input with recovery, and a regression image of the polarizer
image at 40° (grey colormap)."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager, smtesting  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

load_plugin(globals())

cube = FiberCubeSource(Populations=2, NumberOfFibers=40, EdgeLength=20.0, FiberRadius=1.0,
                       SegmentLength=2.0, Displacement=0.3, Seed=3)
sim = PLISimulation(Input=cube, VolumeOfInterest=[-8, 8, -6, 6, -4, 4], VoxelSize=0.25, PixelSize=0.5,
                    Wavelength=525.0, LightIntensity=26000.0, NumberOfRotations=9, TiltAngle=5.5,
                    Birefringence=-0.004, Absorption=0.0, Seed=2, Layers="", BackgroundAbsorption=0.0,
                    StepSize=1.0, Interpolation="Slerp", OpticalSigma=0.71, NoiseGain=0.0,
                    RefractiveIndex=1.0, NumberOfThreads=2)
sim.UpdatePipeline()
img = servermanager.Fetch(sim)
check(img.GetExtent() == (0, 31, 0, 23, 0, 0), "extent %s" % (img.GetExtent(),))
check(abs(img.GetOrigin()[0] + 7.75) < 1e-12 and abs(img.GetSpacing()[0] - 0.5) < 1e-12,
      "origin/spacing %s %s" % (img.GetOrigin(), img.GetSpacing()))
fd = img.GetFieldData()
angles = vtk_to_numpy(fd.GetArray("polarizer_angles"))
check(len(angles) == 9 and abs(angles[1] - 20.0) < 1e-12, "polarizer_angles %s" % (angles,))
check(abs(fd.GetArray("tilt_angle").GetValue(0) - 5.5) < 1e-12, "tilt_angle")
check(abs(fd.GetArray("section_thickness").GetValue(0) - 8.0) < 1e-12, "section_thickness")
check(fd.GetArray("wavelength").GetValue(0) == 525.0, "wavelength")
check(fd.GetArray("tilt_convention").GetValue(0) == 0 and fd.GetArray("empty_section").GetValue(0) == 0,
      "tilt_convention / empty_section")
check(list(vtk_to_numpy(fd.GetArray("tilt_directions"))) == [0, 90, 180, 270], "tilt_directions")
for name in ["intensity"] + ["intensity_tilt_%d" % k for k in range(4)]:
    a = img.GetPointData().GetArray(name)
    check(a is not None and a.GetNumberOfComponents() == 9, "array %s" % name)
    stack = vtk_to_numpy(a)
    # Without absorption every retarder stack transmits I0/4 on average over equidistant polarizer
    # angles (only the 2ρ harmonic varies), and blur and binning are averages.
    check(abs(stack.mean(axis=1) - 6500.0).max() < 1e-6, "%s: mean over angles must be I0/4" % name)
    check(stack.max() - stack.min() > 500.0, "%s shows no birefringence" % name)
    if name == "intensity":
        shown = (stack[:, 2].min(), stack[:, 2].max())

# Bad input is an error naming the property, and the pipeline recovers.
errors = ErrorCatcher(sim)
sim.VoxelSize = 0.0
sim.UpdatePipeline()
check("VoxelSize" in errors.text(), "no VoxelSize error: %r" % errors.text())
check(sim.GetDataInformation().GetNumberOfPoints() == 0, "output not empty after an error")
errors.clear()
sim.VoxelSize = 0.25
sim.UpdatePipeline()
check(not errors.errors and sim.GetDataInformation().GetNumberOfPoints() == 32 * 24, "no recovery")

smtesting.ProcessCommandLineArguments()
view = CreateView("RenderView")
view.ViewSize = [400, 300]
view.OrientationAxesVisibility = 0
view.Background = [0.2, 0.2, 0.3]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
display = Show(sim, view)
display.SetRepresentationType("Slice")
# The cube's populations run along x and y (φ 0° and 90°), where ρ = 0° shows no contrast
# (sin 2(ρ − φ) = 0); ρ = 40° (component 2) separates them best.
ColorBy(display, ("POINTS", "intensity", "2"))
lut = GetColorTransferFunction("intensity")
lut.ApplyPreset("Grayscale", True)
lut.VectorMode = "Component"
lut.VectorComponent = 2
lut.AutomaticRescaleRangeMode = "Never"
lut.RescaleTransferFunction(shown[0], shown[1])
Render(view)
view.CameraPosition = [0, 0, 40]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 6.5
Render(view)
if not smtesting.DoRegressionTesting(view.SMProxy):
    raise RuntimeError("image differs from the baseline")
print("test_pli_simulation passed")
