"""pvpython: FiberOrientationGroundTruth of a small crossing cube (x and y populations) coloured
by FiberOrientationMap (HSV-black): known colours, the RGB scheme, the legend port, and a
regression image of the ground-truth FOM next to its legend."""
import os
import builtins
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager, smtesting  # noqa: E402

load_plugin(globals())

cube = FiberCubeSource(Populations=2, NumberOfFibers=24, EdgeLength=20.0, FiberRadius=1.5, SegmentLength=2.0,
                       Displacement=0.0, Seed=5)
truth = FiberOrientationGroundTruth(Input=cube, VolumeOfInterest=[-10, 10, -10, 10, -3, 3], VoxelSize=0.5,
                                    PixelSize=1.0, NumberOfThreads=2)
fom = FiberOrientationMap(Input=truth, ColorScheme="HSV-black", LegendSize=64, NumberOfThreads=1)
fom.UpdatePipeline()
t = servermanager.Fetch(truth)
check(t.GetDimensions()[0] == 20 and t.GetDimensions()[1] == 20, "grid %s" % (t.GetDimensions(),))
m = servermanager.Fetch(fom)
colours = m.GetPointData().GetArray("fom")
check(colours is not None and colours.GetNumberOfComponents() == 3, "fom array")
direction = t.GetPointData().GetArray("direction")
inclination = t.GetPointData().GetArray("inclination")
fraction = t.GetPointData().GetArray("fraction")
import math  # noqa: E402
seen = {"x": 0, "y": 0}
for p in range(t.GetNumberOfPoints()):
    d, i, f = direction.GetValue(p), inclination.GetValue(p), fraction.GetValue(p)
    rgb = [int(colours.GetComponent(p, c)) for c in range(3)]
    if math.isnan(d):
        check(rgb == [0, 0, 0], "empty pixel must be black")
        continue
    check(0.0 <= d < 180.0 and 0.0 <= i <= 90.0 and 0.0 < f <= 1.0, "ranges at %d" % p)
    # Straight fibers of the two populations: pure x (red) or pure y (cyan) pixels.
    if builtins.min(d, 180.0 - d) < 1e-6 and i < 1e-6:
        check(rgb == [255, 0, 0], "x fiber pixel %d is %s" % (p, rgb))
        seen["x"] += 1
    if builtins.abs(d - 90.0) < 1e-6 and i < 1e-6:
        check(rgb == [0, 255, 255], "y fiber pixel %d is %s" % (p, rgb))
        seen["y"] += 1
check(seen["x"] > 20 and seen["y"] > 20, "both populations visible: %s" % seen)

legend = servermanager.Fetch(fom, idx=1)
check(legend.GetDimensions()[0] == 64 and legend.GetPointData().GetArray("fom") is not None, "legend port")

fom.ColorScheme = "RGB"
fom.UpdatePipeline()
m = servermanager.Fetch(fom)
for p in range(t.GetNumberOfPoints()):
    d, i = direction.GetValue(p), inclination.GetValue(p)
    if not math.isnan(d) and builtins.abs(d - 90.0) < 1e-6 and i < 1e-6:
        check([int(m.GetPointData().GetArray("fom").GetComponent(p, c)) for c in range(3)] == [0, 255, 0], "RGB y")
fom.ColorScheme = "HSV-black"

smtesting.ProcessCommandLineArguments()
view = CreateView("RenderView")
view.ViewSize = [400, 300]
view.OrientationAxesVisibility = 0
view.Background = [0.3, 0.3, 0.3]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
d0 = Show(OutputPort(fom, 0), view)
d0.Representation = "Slice"
ColorBy(d0, ("POINTS", "fom"))
d0.MapScalars = 0
d1 = Show(OutputPort(fom, 1), view)
d1.Scale = [5.0, 5.0, 1.0]
d1.Position = [16.0, 0.0, 0.0]
d1.Representation = "Slice"
ColorBy(d1, ("POINTS", "fom"))
d1.MapScalars = 0
view.CameraPosition = [3.0, 0.0, 60.0]
view.CameraFocalPoint = [3.0, 0.0, 0.0]
view.CameraViewUp = [0, 1, 0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 11.5
Render(view)
if not smtesting.DoRegressionTesting(view.SMProxy):
    raise RuntimeError("image differs from the baseline")
print("test_fom passed")
