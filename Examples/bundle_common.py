"""Shared by the bundle_*.py examples (pvbatch): build a FiberBundleSource model, solve it with
FiberCollisionSolver, render the solved fibers as tubes coloured by bundle_id to <out>/<name>.png
(480x360) and print solved/steps/collisions."""
import os
import sys
import time

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from plain_view import plain_view


def run(name, camera, **properties):
    plugin, out_dir = sys.argv[1], sys.argv[2]
    LoadPlugin(plugin, remote=False, ns=globals())
    os.makedirs(out_dir, exist_ok=True)
    source = globals()["FiberBundleSource"](**properties)
    source.UpdatePipeline()
    model = servermanager.Fetch(source)
    print("%s: %d fibers, %d points" % (name, model.GetNumberOfLines(), model.GetNumberOfPoints()))
    solver = globals()["FiberCollisionSolver"](Input=source, SegmentLength=properties.get("SegmentLength", 2.0),
                                               MinCurvatureRadius=0.0, MaxSteps=20000, NumberOfThreads=0)
    start = time.time()
    solver.UpdatePipeline()
    seconds = time.time() - start
    field = servermanager.Fetch(solver).GetFieldData()
    solved, steps, collisions = (int(field.GetArray(n).GetValue(0)) for n in ("solved", "steps", "collisions"))
    print("%s: solved=%d steps=%d collisions=%d (%.1f s)" % (name, solved, steps, collisions, seconds))

    tubes = globals()["FiberTubes"](Input=solver, NumberOfSides=12, Capping=1)
    view = CreateView("RenderView")
    view.ViewSize = [480, 360]
    plain_view(view, [0.1, 0.1, 0.15])
    display = Show(tubes, view)
    ColorBy(display, ("CELLS", "bundle_id"))
    lut = GetColorTransferFunction("bundle_id")
    lut.ApplyPreset("Rainbow Uniform", True)
    lut.RescaleTransferFunction(0.0, 3.0)
    view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = camera
    view.CameraParallelProjection = 0
    Render(view)
    view.ResetCamera()  # keeps the direction, fits the whole model
    Render(view)
    png = os.path.join(out_dir, name + ".png")
    SaveScreenshot(png, view, ImageResolution=[480, 360])
    print("wrote", png)
    return solved
