"""The displays FiberPLI outputs start with (Plugin/FiberPLIDisplayDefaults.cxx): a fiber
orientation map and its legend in true colour (Map Scalars off, so the fom bytes are the pixel
colours), PLISimulation's intensity stack by its component 0 in grey, fibers and tubes by bundle_id
as categories; and the default pipeline cube -> solver -> PLISimulation warns about nothing."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402

from paraview.simple import *  # noqa: E402,F401,F403

load_plugin(globals())
view = CreateView("RenderView")
try:
    cube = FiberCubeSource(Populations=2, NumberOfFibers=60, EdgeLength=20.0, Seed=3)
    solver = FiberCollisionSolver(Input=cube)
    sim = PLISimulation(Input=solver)
    sim_messages = ErrorCatcher(sim)
    analysis = PLIAnalysis(Input=sim)
    fom = FiberOrientationMap(Input=analysis)
    tubes = FiberTubes(Input=solver)

    for proxy, name in ((cube, "fibers"), (tubes, "tubes")):
        display = Show(proxy, view)
        check(list(display.ColorArrayName) == ["CELLS", "bundle_id"], "%s coloured by %r" % (
            name, display.ColorArrayName))
        lut = GetColorTransferFunction("bundle_id")
        check(lut.InterpretValuesAsCategories == 1, "%s: bundle_id is not categorical" % name)
        # One annotated colour per bundle (two populations: 0 and 1), distinct colours.
        check(list(lut.Annotations) == ["0", "bundle 0", "1", "bundle 1"], repr(lut.Annotations))
        colors = list(lut.IndexedColors)
        check(len(colors) == 6 and colors[:3] != colors[3:], repr(colors))
        Hide(proxy, view)

    display = Show(sim, view)
    check(list(display.ColorArrayName) == ["POINTS", "intensity"], repr(display.ColorArrayName))
    lut = GetColorTransferFunction("intensity")
    check(lut.VectorMode == "Component" and lut.VectorComponent == 0,
          "intensity shown as %s %d" % (lut.VectorMode, lut.VectorComponent))
    check(not sim_messages.errors and not sim_messages.warnings,
          "default pipeline warns: %r" % (sim_messages.errors + sim_messages.warnings))
    Hide(sim, view)

    for port in (0, 1):
        display = Show(OutputPort(fom, port), view)
        check(list(display.ColorArrayName) == ["POINTS", "fom"], repr(display.ColorArrayName))
        check(display.MapScalars == 0, "FOM port %d maps its colours through a table" % port)
        Hide(OutputPort(fom, port), view)

    # The defaults are only the start: the user's choice stays.
    display = Show(tubes, view)
    ColorBy(display, ("CELLS", "fiber_id"))
    check(list(display.ColorArrayName) == ["CELLS", "fiber_id"], repr(display.ColorArrayName))
    # A saved state comes back as it was saved, not re-coloured by the defaults (pvpython's
    # LoadState replaces the session's views and displays by the state's).
    state = os.path.join(option("-T"), "fiber_id_colouring.pvsm")
    SaveState(state)
    LoadState(state)
    tube_displays = [r for r in GetRepresentations().values()
                     if r.Input is not None and r.Input.GetXMLName() == "FiberTubes"
                     and r.Visibility]
    check(len(tube_displays) >= 1, "state not loaded: no tube display")
    for r in tube_displays:
        check(list(r.ColorArrayName) == ["CELLS", "fiber_id"], "loaded state re-coloured: %r" % (
            list(r.ColorArrayName),))
    print("display defaults: ok")
finally:
    for v in list(GetViews()):  # LoadState may have replaced the view created above
        Delete(v)
    del view
