"""FiberPLI demo (pvbatch), the main job end to end on an embedded default, in well under a minute:
a dense two-population fiber cube (the paper's benchmark density) -> FiberCollisionSolver to zero
overlaps -> watertight tubes coloured by bundle -> PLISimulation -> PLIAnalysis -> fiber orientation
map with its colour legend. Writes into the output folder:

    demo.png          one picture: tubes | FOM | legend | retardation
    demo_tubes.vtp    the tubes (binary XML, readable by Debian's ParaView 5.11)
    demo_fibers.dat   the solved fibers as a fastPLI text file (also readable by FiberReader)

and prints what it shows (fibers, volume fraction, collisions, seconds).

    pvbatch Examples/demo.py <path to FiberPLI.so> <output folder>
"""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import passive_openmp  # noqa: E402,F401  (restarts once with OMP_WAIT_POLICY=PASSIVE when unset)

from paraview.simple import *  # noqa: E402,F401,F403
import paraview.simple  # noqa: E402
from plain_view import plain_view  # noqa: E402

plugin, out_dir = sys.argv[1], sys.argv[2]
LoadPlugin(plugin, remote=False, ns=globals())
paraview.simple._DisableFirstRenderCameraReset()  # keep the explicit cameras
os.makedirs(out_dir, exist_ok=True)
start = time.time()
seconds = {}


def timed(name, proxy):
    t = time.time()
    proxy.UpdatePipeline()
    seconds[name] = time.time() - t
    return proxy


# The paper's cube benchmark (two perpendicular populations, r = 0.8 µm) at its fiber density
# (1000 fibers per 51.96 µm edge), on a 24 µm edge: 214 fibers.
edge = 24.0
cube = timed("cube", FiberCubeSource(Populations=2, NumberOfFibers=214, EdgeLength=edge, FiberRadius=0.8,
                                     SegmentLength=2.0, Displacement=0.5, Seed=42))
solved = timed("solve", FiberCollisionSolver(Input=cube, SegmentLength=2.0, MinCurvatureRadius=4.0))
# Measured by FiberMetrics' own code, not the solver's: collisions of the whole model, volume
# fraction of the central (16 µm)³ away from the cube's open faces.
central = [-8.0, 8.0, -8.0, 8.0, -8.0, 8.0]
metrics = timed("metrics", FiberMetrics(Input=solved, Box=central))
summary = servermanager.Fetch(metrics, idx=1)
fibers = int(summary.GetColumnByName("fibers").GetValue(0))
phi = summary.GetColumnByName("volume_fraction").GetValue(0)
collisions = int(summary.GetColumnByName("collisions").GetValue(0))
steps = int(servermanager.Fetch(solved).GetFieldData().GetArray("steps").GetValue(0))

tubes = timed("tubes", FiberTubes(Input=solved, NumberOfSides=10, Capping=1))
# A thin section (3 µm) through the middle with 0.8 µm camera pixels and 18 polarizer angles, so
# that single fibers of both populations show (in thicker sections the crossing populations in
# every pixel cancel each other's retardation); noise-free (NoiseGain 0), since a 3 µm section's
# retardation (about 0.04) is of the order of the default camera noise.
section = [-edge / 2, edge / 2, -edge / 2, edge / 2, -1.5, 1.5]
sim = timed("simulate", PLISimulation(Input=solved, VolumeOfInterest=section, PixelSize=0.8, NoiseGain=0.0))
analysis = timed("analyse", PLIAnalysis(Input=sim))
fom = timed("orientation map", FiberOrientationMap(Input=analysis))

# Files: binary XML (Debian's expat rejects raw appended data) and a fastPLI fiber file.
vtp = os.path.join(out_dir, "demo_tubes.vtp")
SaveData(vtp, proxy=tubes, DataMode="Binary")
dat = os.path.join(out_dir, "demo_fibers.dat")
SaveData(dat, proxy=solved)

# One picture of four views. The displays start as FiberPLI sets them up (bundle_id as
# categories, the FOM and its legend in true colour); only cameras and labels are set here.
layout = CreateLayout("FiberPLI demo")
views = []


def add_view(title, size):
    view = CreateView("RenderView")
    view.ViewSize = size
    plain_view(view, [1, 1, 1])
    text = Text(Text=title)
    label = Show(text, view)
    label.FontSize = 14
    label.Color = [0, 0, 0]
    label.WindowLocation = "Upper Center"
    views.append(view)
    return view


def top_down(view, half_width):
    view.CameraPosition = [0, 0, 100]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = half_width


tube_view = add_view("%d fibers, solved: %d collisions" % (fibers, collisions), [600, 600])
tube_display = Show(tubes, tube_view)
tube_display.SetScalarBarVisibility(tube_view, True)
bar = GetScalarBar(GetColorTransferFunction("bundle_id"), tube_view)
bar.Title = "bundle_id"
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0, 0, 0]
bar.WindowLocation = "Lower Right Corner"
tube_view.CameraPosition = [55, 40, 70]
tube_view.CameraFocalPoint = [0, 0, 0]
tube_view.CameraViewUp = [0, 1, 0]
tube_view.ResetCamera()  # keeps the direction, fits the cube

# Cells of the 1200 x 700 picture: tubes 600 x 700 | FOM 420 x 350, legend 180 x 350, and the
# retardation 600 x 350 below; the parallel scale (half the height) fits each image in its cell.
fom_view = add_view("fiber orientation map", [420, 350])
Show(OutputPort(fom, 0), fom_view)
top_down(fom_view, 0.5 * edge + 1.5)

legend_view = add_view("legend", [180, 350])
Show(OutputPort(fom, 1), legend_view)
top_down(legend_view, 1.15 * 350 / 180)

ret_view = add_view("retardation", [600, 350])
ret_display = Show(analysis, ret_view)
ColorBy(ret_display, ("POINTS", "retardation"))
ret_lut = GetColorTransferFunction("retardation")
ret_lut.ApplyPreset("Grayscale", True)
ret_display.RescaleTransferFunctionToDataRange(False, True)
top_down(ret_view, 0.5 * edge + 1.5)

# tubes on the left; FOM and legend on the top right, retardation below.
AssignViewToLayout(view=tube_view, layout=layout, hint=0)
layout.SplitHorizontal(0, 0.5)
layout.AssignView(1, tube_view)
layout.SplitVertical(2, 0.5)
layout.SplitHorizontal(5, 0.7)
layout.AssignView(11, fom_view)
layout.AssignView(12, legend_view)
layout.AssignView(6, ret_view)
png = os.path.join(out_dir, "demo.png")
SaveScreenshot(png, layout, SaveAllViews=1, ImageResolution=[1200, 700])

total = time.time() - start
print("fibers: %d (2 populations, r = 0.8 um, %.0f um cube)" % (fibers, edge))
print("solved in %d steps; collisions (FiberMetrics): %d" % (steps, collisions))
print("volume fraction of the central (16 um)^3: %.1f %%" % (100.0 * phi))
print("seconds: " + ", ".join("%s %.1f" % kv for kv in seconds.items()) + "; total %.1f" % total)
print("wrote", png)
print("wrote", vtp)
print("wrote", dat)
for view in views:
    Delete(view)
del views
