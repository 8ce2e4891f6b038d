"""The colour tables FiberPLI displays start with (Plugin/FiberPLIDisplayDefaults.cxx) beyond the
first choice of array: `direction` (an axis angle, 0 deg = 180 deg) on a cyclic table whose two
ends are one colour; the shared bundle_id table keeps every model's bundle colours when a model
with fewer bundles is shown later; and a display made while its output was empty (an aborted first
run) is coloured by bundle_id once data arrives, not left in ParaView's plain colour."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402

from paraview.simple import *  # noqa: E402,F401,F403

load_plugin(globals())
view = CreateView("RenderView")
try:
    # --- direction: cyclic over [0, 180], not rescaled to the data's range.
    cube = FiberCubeSource(Populations=2, NumberOfFibers=60, EdgeLength=20.0, Seed=3)
    sim = PLISimulation(Input=cube, VolumeOfInterest=[-10, 10, -10, 10, -1.5, 1.5], NoiseGain=0.0)
    analysis = PLIAnalysis(Input=sim)
    display = Show(analysis, view)
    lut = GetColorTransferFunction("direction")
    points = list(lut.RGBPoints)
    check(points[0] == 0.0 and points[-4] == 180.0, "direction table spans %g..%g" % (points[0], points[-4]))
    # Picking the array again (the GUI's colour menu, ColorBy) rescales it to the data's range;
    # the table stays a wheel whose ends have one colour.
    ColorBy(display, ("POINTS", "direction"))
    table = lut.GetClientSideObject()


    def colour(value):
        rgb = [0.0, 0.0, 0.0]
        table.GetColor(value, rgb)
        return rgb


    first, last = colour(0.0), colour(180.0)
    check(max(abs(a - b) for a, b in zip(first, last)) < 0.02,
          "0 and 180 deg have different colours: %r %r" % (first, last))
    middle = colour(90.0)
    check(max(abs(a - b) for a, b in zip(first, middle)) > 0.5, "the table is not a colour wheel: %r" % (middle,))
    Hide(analysis, view)

    # --- bundle_id: a one-bundle model shown after a two-bundle one leaves bundle 1's colour.
    two = FiberCubeSource(Populations=2, NumberOfFibers=40, EdgeLength=20.0, Seed=4)
    Show(two, view)
    lut = GetColorTransferFunction("bundle_id")
    before = list(lut.IndexedColors)
    check(list(lut.Annotations) == ["0", "bundle 0", "1", "bundle 1"], repr(lut.Annotations))
    one = FiberCubeSource(Populations=1, NumberOfFibers=20, EdgeLength=20.0, Seed=5)
    Show(one, view)
    check(list(lut.Annotations) == ["0", "bundle 0", "1", "bundle 1"],
          "the one-bundle model shrank the table: %r" % (list(lut.Annotations),))
    check(list(lut.IndexedColors) == before, "bundle colours changed: %r -> %r" % (before, list(lut.IndexedColors)))
    Hide(two, view)
    Hide(one, view)

    # --- A first run aborted: the display is coloured once the data comes.
    source = FiberCubeSource(NumberOfFibers=50, EdgeLength=20.0, Seed=6)
    solver = FiberCollisionSolver(Input=source, MaxSteps=300)
    algorithm = solver.GetClientSideObject()
    aborts = {"n": 0}

    def abort_once(obj, event):
        if aborts["n"] == 0:
            obj.SetAbortExecute(1)
        aborts["n"] += 1

    tag = algorithm.AddObserver("ProgressEvent", abort_once)
    messages = ErrorCatcher(solver)
    display = Show(solver, view)
    algorithm.RemoveObserver(tag)
    check(solver.GetDataInformation().GetNumberOfPoints() == 0, "the aborted solve passed something on")
    check(any("aborted by the user" in w for w in messages.warnings), "no abort message: %r" % messages.warnings)
    solver.MaxSteps = 299
    solver.UpdatePipeline()
    check(solver.GetDataInformation().GetNumberOfPoints() > 0, "the solve after the property change made nothing")
    check(list(display.ColorArrayName) == ["CELLS", "bundle_id"],
          "display after the aborted first run coloured by %r" % (list(display.ColorArrayName),))
    print("display tables: ok")
finally:
    Delete(view)
    del view
