"""GUI test, run inside the ParaView client (paraview --script=... --exit): loads the plugin and
builds the two pipelines a user builds, cube -> solver -> tubes and cube -> PLISimulation ->
PLIAnalysis -> FiberOrientationMap, shows them with the client's defaults only (no colouring set
here), checks that the legend's preferred view is a FOM Legend View of its own, and compares a screenshot of the map with its baseline: the fom bytes must be the pixel colours
(Map Scalars off by default), not "fom Magnitude" through a blue-red colour map.

Paths come from the environment because sys.argv is [''] inside paraview --script:
FIBERPLI_PLUGIN, FIBERPLI_OUT (output folder), FIBERPLI_BASELINE (the map's baseline PNG),
FIBERPLI_EXAMPLES (the Examples folder, for the views' look)."""
import os
import sys

import paraview.simple
from paraview import servermanager, smtesting
from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.environ["FIBERPLI_EXAMPLES"])
from plain_view import plain_view  # noqa: E402

LoadPlugin(os.environ["FIBERPLI_PLUGIN"], remote=False, ns=globals())
out_dir = os.environ["FIBERPLI_OUT"]
paraview.simple._DisableFirstRenderCameraReset()  # keep the explicit camera


def fail(message):
    raise RuntimeError("gui_demo: " + message)


cube = FiberCubeSource(Populations=2, NumberOfFibers=60, EdgeLength=16.0, FiberRadius=0.8,
                       SegmentLength=2.0, Displacement=0.5, Seed=2)
solver = FiberCollisionSolver(Input=cube)
tubes = FiberTubes(Input=solver, NumberOfSides=10)
view = GetActiveViewOrCreate("RenderView")
tube_display = Show(tubes, view)
if list(tube_display.ColorArrayName) != ["CELLS", "bundle_id"]:
    fail("tubes coloured by %r, not bundle_id" % (tube_display.ColorArrayName,))
if GetColorTransferFunction("bundle_id").InterpretValuesAsCategories != 1:
    fail("bundle_id is not shown as categories")
fd = servermanager.Fetch(solver).GetFieldData()
if fd.GetArray("collisions").GetValue(0) != 0:
    fail("the solver left collisions")
plain_view(view, [0.1, 0.1, 0.15])
view.CameraPosition = [40, 30, 50]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
view.ResetCamera()  # keeps the direction, fits the tubes
Render(view)
SaveScreenshot(os.path.join(out_dir, "gui_tubes.png"), view, ImageResolution=[480, 360])
Hide(tubes, view)

# A thin noise-free section, so that the map shows single fibers of both populations.
sim = PLISimulation(Input=solver, VolumeOfInterest=[-8, 8, -8, 8, -1.5, 1.5], PixelSize=0.8, NoiseGain=0.0)
analysis = PLIAnalysis(Input=sim)
fom = FiberOrientationMap(Input=analysis)
fom_display = Show(OutputPort(fom, 0), view)
if fom_display.MapScalars != 0 or list(fom_display.ColorArrayName) != ["POINTS", "fom"]:
    fail("the FOM is not shown in true colour: MapScalars %d, %r" % (
        fom_display.MapScalars, fom_display.ColorArrayName))

# The legend: on Apply the client shows every port in its preferred view; port 1's hint asks
# for a FOM Legend View of its own, so the disc never covers the map.
controller = servermanager.vtkSMParaViewPipelineControllerWithRendering()
if controller.GetPreferredViewType(fom.SMProxy, 1) != "FOMLegendView":
    fail("the legend's preferred view is %r" % controller.GetPreferredViewType(fom.SMProxy, 1))
if controller.GetPreferredViewType(fom.SMProxy, 0) is not None:
    fail("the map does not open in the active render view")
legend_view = CreateView("FOMLegendView")
legend_display = Show(OutputPort(fom, 1), legend_view)
if legend_display.MapScalars != 0:
    fail("the legend is not shown in true colour")
Delete(legend_view)  # (a view outside the GUI's layouts is not rendered here)

view.ViewSize = [400, 400]
view.CameraPosition = [0, 0, 60]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 8.5
Render(view)
smtesting.BaselineImage = os.environ["FIBERPLI_BASELINE"]
smtesting.TempDir = out_dir
if not smtesting.DoRegressionTesting(view.SMProxy):
    fail("the FOM screenshot differs from the baseline")
print("gui_demo: tubes by bundle_id, FOM in true colour, legend in its own view")
