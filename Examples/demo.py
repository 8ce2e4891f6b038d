"""FiberPLI demo (pvbatch), what FiberPLI is best at, end to end in well under a minute: a dense
periodic cell of two crossing fiber populations (72 % volume fraction, lattice seeding) ->
FiberCollisionSolver to zero overlaps -> watertight tubes coloured by population -> PLISimulation of
a section four cells wide (the cell tiles seamlessly) -> PLIAnalysis -> fiber orientation map with
its colour legend. Writes into the output folder:

    demo.png          one picture: tubes | FOM | legend | retardation
    demo_tubes.vtp    the tubes (binary XML, readable by Debian's ParaView 5.11)
    demo_fibers.h5    the solved fibers with their periodic cell (readable by FiberReader)

and prints what it shows (fibers, steps, collisions and volume fraction as FiberMetrics measures
them, seconds).

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


# A periodic (30 µm)^3 cell of two perpendicular populations (r = 0.8 µm) at 72 % volume fraction,
# seeded on a lattice commensurate with the cell; a fiber leaving through a face comes back through
# the opposite one, so the solved cell tiles space without a seam.
edge = 30.0
cell = timed("cell", FiberCubeSource(Populations=2, EdgeLength=edge, Periodic=1, VolumeFraction=0.72,
                                     Seeding="Lattice", FiberRadius=0.8, SegmentLength=2.0,
                                     Displacement=0.5, Seed=42))
solved = timed("solve", FiberCollisionSolver(Input=cell, SegmentLength=2.0, MinCurvatureRadius=4.0,
                                             MaxSteps=20000))
# Measured by FiberMetrics' own code, not the solver's: collisions by minimum image and the volume
# fraction of the whole cell with every periodic image (Monte Carlo, 10^6 points, its standard error).
metrics = timed("metrics", FiberMetrics(Input=solved))
summary = servermanager.Fetch(metrics, idx=1)
fibers = int(summary.GetColumnByName("fibers").GetValue(0))
phi = summary.GetColumnByName("volume_fraction").GetValue(0)
phi_error = summary.GetColumnByName("volume_fraction_error").GetValue(0)
collisions = int(summary.GetColumnByName("collisions").GetValue(0))
periodic = int(summary.GetColumnByName("periodic").GetValue(0))
steps = int(servermanager.Fetch(solved).GetFieldData().GetArray("steps").GetValue(0))

tubes = timed("tubes", FiberTubes(Input=solved, NumberOfSides=10, Capping=1))
# A thin section (3 µm) through the middle, 2 x 2 cells wide (PLISimulation fills it with copies of
# the cell), with 0.8 µm camera pixels and 18 polarizer angles; noise-free (NoiseGain 0), since a
# 3 µm section's retardation (about 0.04) is of the order of the default camera noise.
section = [-edge, edge, -edge, edge, -1.5, 1.5]
sim = timed("simulate", PLISimulation(Input=solved, VolumeOfInterest=section, PixelSize=0.8, NoiseGain=0.0))
analysis = timed("analyse", PLIAnalysis(Input=sim))
fom = timed("orientation map", FiberOrientationMap(Input=analysis))

# Files: binary XML (Debian's expat rejects raw appended data) and the fibers as .h5, which keeps
# the periodic cell (attribute periodic_cell).
vtp = os.path.join(out_dir, "demo_tubes.vtp")
SaveData(vtp, proxy=tubes, DataMode="Binary")
h5 = os.path.join(out_dir, "demo_fibers.h5")
SaveData(h5, proxy=solved)

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


tube_view = add_view("periodic cell, %d fibers, %d collisions" % (fibers, collisions), [600, 600])
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
tube_view.ResetCamera()  # keeps the direction, fits the cell

# Cells of the 1200 x 700 picture: tubes 600 x 700 | FOM 420 x 350, legend 180 x 350, and the
# retardation 600 x 350 below; the parallel scale (half the height) fits each image in its cell.
fom_view = add_view("fiber orientation map", [420, 350])
Show(OutputPort(fom, 0), fom_view)
top_down(fom_view, edge + 3.0)

legend_view = add_view("legend", [180, 350])
Show(OutputPort(fom, 1), legend_view)
top_down(legend_view, 1.15 * 350 / 180)

ret_view = add_view("retardation", [600, 350])
ret_display = Show(analysis, ret_view)
ColorBy(ret_display, ("POINTS", "retardation"))
ret_lut = GetColorTransferFunction("retardation")
ret_lut.ApplyPreset("Grayscale", True)
ret_display.RescaleTransferFunctionToDataRange(False, True)
top_down(ret_view, edge + 3.0)

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
print("fibers: %d (2 populations, r = 0.8 um, periodic %.0f um cell)" % (fibers, edge))
print("solved in %d steps; collisions (FiberMetrics, minimum image): %d" % (steps, collisions))
print("volume fraction of the %s (FiberMetrics, Monte Carlo): %.1f %% +- %.2f %%"
      % ("periodic cell" if periodic else "fibers' bounds", 100.0 * phi, 100.0 * phi_error))
print("seconds: " + ", ".join("%s %.1f" % kv for kv in seconds.items()) + "; total %.1f" % total)
print("wrote", png)
print("wrote", vtp)
print("wrote", h5)
for view in views:
    Delete(view)
del views
