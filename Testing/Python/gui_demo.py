"""GUI smoke test, run inside the ParaView client (paraview --script=... --exit): loads the plugin,
builds cube -> tubes, renders and saves a screenshot. Paths come from the environment because
sys.argv is [''] inside paraview --script."""
import os

from paraview.simple import *  # noqa: F401,F403

LoadPlugin(os.environ["FIBERPLI_PLUGIN"], remote=False, ns=globals())
out_dir = os.environ["FIBERPLI_OUT"]
src = FiberCubeSource(Populations=3, NumberOfFibers=90, EdgeLength=30.0, FiberRadius=0.8,
                      SegmentLength=2.0, Displacement=0.5, Seed=2)
tub = FiberTubes(Input=src, NumberOfSides=10, Capping=1)
view = GetActiveViewOrCreate("RenderView")
display = Show(tub, view)
ColorBy(display, ("CELLS", "bundle_id"))
view.CameraPosition = [60, 45, 75]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
Render(view)
cells = tub.GetDataInformation().GetNumberOfCells()
if cells <= 0:
    raise RuntimeError("the GUI pipeline produced no tubes")
shot = os.path.join(out_dir, "gui_demo.png")
SaveScreenshot(shot, view, ImageResolution=[640, 480])
if not os.path.getsize(shot) > 0:
    raise RuntimeError("no screenshot written")
print("gui_demo: %d triangles, screenshot %s" % (cells, shot))
