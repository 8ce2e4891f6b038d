"""pvpython: the pipelines a new user builds from the menus, every property at its default, run
without a warning or an error (the test is registered with "WARN|" as a failure):
cube -> FiberCollisionSolver -> FiberTubes, cube -> PLISimulation -> PLIAnalysis ->
FiberOrientationMap (map and legend), FiberBundleSource -> PLISimulation. Every stage is shown in a
render view, as Apply does in the GUI. The solve of the default cube (1000 fibers) takes about a
minute."""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, load_plugin  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402

load_plugin(globals())
view = CreateView("RenderView")
legend_view = CreateView("FOMLegendView")


def apply(proxy, port=0, in_view=None):
    """What Apply does: update and show the new stage."""
    start = time.time()
    Show(OutputPort(proxy, port), in_view or view)
    Render(in_view or view)
    print("%s port %d: %.1f s" % (proxy.GetXMLName(), port, time.time() - start), flush=True)
    return proxy


SetActiveSource(None)  # a source from the Sources menu has no input
cube = apply(FiberCubeSource())
solver = apply(FiberCollisionSolver(Input=cube))
apply(FiberTubes(Input=solver))
collisions = servermanager.Fetch(solver).GetFieldData().GetArray("collisions").GetValue(0)
check(collisions == 0, "the default solve left %d collisions" % collisions)

sim = apply(PLISimulation(Input=cube))
analysis = apply(PLIAnalysis(Input=sim))
fom = apply(FiberOrientationMap(Input=analysis))
apply(fom, 1, legend_view)
check(servermanager.Fetch(fom).GetPointData().GetArray("fom") is not None, "no FOM")

SetActiveSource(None)
bundle = apply(FiberBundleSource())
bundle_sim = apply(PLISimulation(Input=bundle))
check(servermanager.Fetch(bundle_sim).GetPointData().GetArray("intensity") is not None, "no bundle image")

Delete(legend_view)
Delete(view)
del view, legend_view
print("default pipelines ran without warnings")
