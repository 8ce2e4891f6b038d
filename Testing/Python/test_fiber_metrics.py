"""pvpython: FiberMetrics against closed forms (straight fibers through a box, two capsules at a known
gap, a periodic cell), against the solver's own collision count, and its error and empty cases."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData  # noqa: E402

load_plugin(globals())


def polydata(fibers, field=None):
    """A trivial-producer proxy holding fibers given as lists of (x, y, z, r)."""
    points, lines, radius = vtkPoints(), vtkCellArray(), vtkDoubleArray()
    points.SetDataTypeToDouble()
    radius.SetName("radius")
    for fiber in fibers:
        lines.InsertNextCell(len(fiber))
        for x, y, z, r in fiber:
            lines.InsertCellPoint(points.InsertNextPoint(x, y, z))
            radius.InsertNextValue(r)
    pd = vtkPolyData()
    pd.SetPoints(points)
    pd.SetLines(lines)
    pd.GetPointData().AddArray(radius)
    for name, values in (field or {}).items():
        a = vtkDoubleArray()
        a.SetName(name)
        for v in values:
            a.InsertNextValue(v)
        pd.GetFieldData().AddArray(a)
    producer = TrivialProducer()
    producer.GetClientSideObject().SetOutput(pd)
    return producer


def line(a, b, n, r):
    return [tuple(a[i] + (b[i] - a[i]) * k / n for i in range(3)) + (r,) for k in range(n + 1)]


def summary(metrics):
    metrics.UpdatePipeline()
    table = servermanager.Fetch(metrics, idx=1)  # output port 1: the one-row Summary table
    check(table.GetNumberOfRows() == 1, "Summary has %d rows" % table.GetNumberOfRows())
    columns = [table.GetColumn(c) for c in range(table.GetNumberOfColumns())]
    return {c.GetName(): c.GetTuple(0) if hasattr(c, "GetTuple") else c.GetValue(0) for c in columns}


# 3 x 3 fibers along x crossing the whole box [-5, 5]^3: phi = 9 pi r^2 10 / 10^3 exactly.
r = 1.0
lattice = [line((-8, 2.5 * j, 2.5 * k), (8, 2.5 * j, 2.5 * k), 8, r) for j in (-1, 0, 1) for k in (-1, 0, 1)]
metrics = FiberMetrics(Input=polydata(lattice), Box=[-5, 5, -5, 5, -5, 5], VoxelSize=0.05,
                       VolumeFractionMethod="Voxels")
s = summary(metrics)
exact = 9 * math.pi * r * r * 10 / 1000
print("lattice:", s["volume_fraction"], "+-", s["volume_fraction_error"], "exact", exact)
check(abs(s["volume_fraction"][0] - exact) <= s["volume_fraction_error"][0], "phi outside its error bound")
check(abs(s["volume_fraction"][0] - exact) < 0.002, "phi %s, exact %s" % (s["volume_fraction"], exact))
check(s["collisions"][0] == 0 and abs(s["min_gap"][0] - 0.5) < 1e-12, "lattice pairs %s" % s)
check(abs(s["c2"][0] - 1) < 1e-12 and abs(s["mean_direction"][0] - 1) < 1e-12, "parallel fibers: c2 %s" % s)
check(s["fibers"][0] == 9 and s["links"][0] == 72 and abs(s["tortuosity_mean"][0] - 1) < 1e-12, "counts %s" % s)
fibers = servermanager.Fetch(metrics)
check(abs(fibers.GetFieldData().GetArray("volume_fraction").GetValue(0) - s["volume_fraction"][0]) == 0,
      "field data differs from the table")
check(abs(fibers.GetCellData().GetArray("fiber_length").GetValue(0) - 16) < 1e-12, "fiber_length")
check(s["volume_fraction_method"] == "Voxels", "method %s" % s["volume_fraction_method"])
mc = summary(FiberMetrics(Input=polydata(lattice), Box=[-5, 5, -5, 5, -5, 5], VolumeFractionMethod="MonteCarlo",
                          Samples=200000, Seed=3, ComputeCollisions=0))
print("lattice, Monte Carlo:", mc["volume_fraction"], "+-", mc["volume_fraction_error"])
check(mc["volume_fraction_method"] == "MonteCarlo" and abs(mc["volume_fraction"][0] - exact) <= 4 * mc["volume_fraction_error"][0]
      and abs(mc["volume_fraction_error"][0] - math.sqrt(exact * (1 - exact) / 200000)) < 1e-4, "Monte Carlo %s" % mc)
# The default is the Monte Carlo estimate with 10^6 samples: its error is the standard error
# (at most 0.05 points), not a voxel bound of several points.
default = summary(FiberMetrics(Input=polydata(lattice), Box=[-5, 5, -5, 5, -5, 5], ComputeCollisions=0))
print("lattice, default:", default["volume_fraction"], "+-", default["volume_fraction_error"])
check(default["volume_fraction_method"] == "MonteCarlo" and default["volume_fraction_error"][0] <= 0.0005
      and abs(default["volume_fraction"][0] - exact) <= 4 * default["volume_fraction_error"][0],
      "default volume fraction %s" % default)
bundles = servermanager.Fetch(metrics, idx=2)
check(bundles.GetNumberOfRows() == 1 and bundles.GetColumnByName("fibers").GetValue(0) == 9, "Bundles table")

# Two capsules at a known surface gap g: collisions 1 exactly when g < 0.
for g in (0.2, 1e-6, -1e-6, -0.3):
    pair = polydata([line((0, 0, 0), (1, 0, 0), 1, 0.5), line((0.5, 1 + g, -1), (0.5, 1 + g, 1), 1, 0.5)])
    s = summary(FiberMetrics(Input=pair, ComputeVolumeFraction=0))
    check(abs(s["min_gap"][0] - g) < 1e-12 and s["collisions"][0] == (1 if g < 0 else 0), "gap %g: %s" % (g, s))

# A periodic cell (field data periodic_cell): a fiber near the +y face wraps to -y; the fiber at
# y = -4.8 and the one at y = 4.8 are 0.4 apart through the boundary.
cell = {"periodic_cell": [-5, 5, -5, 5, -5, 5]}
s = summary(FiberMetrics(Input=polydata([line((-5, 4.5, 0), (5, 4.5, 0), 10, 1.0)], cell), VoxelSize=0.05,
                         VolumeFractionMethod="Voxels"))
check(s["periodic"][0] == 1 and abs(s["volume_fraction"][0] - math.pi * 10 / 1000) < 1e-3, "periodic phi %s" % s)
two = [line((-1.5, -4.8, 0), (1.5, -4.8, 0), 3, 0.5), line((-1.5, 4.8, 0), (1.5, 4.8, 0), 3, 0.5)]
check(abs(summary(FiberMetrics(Input=polydata(two, cell), ComputeVolumeFraction=0))["min_gap"][0] + 0.6) < 1e-12,
      "minimum image")
check(abs(summary(FiberMetrics(Input=polydata(two, cell), ComputeVolumeFraction=0, UsePeriodicCell=0))["min_gap"][0]
          - 8.6) < 1e-12, "UsePeriodicCell off")

# Independent of the solver, but agreeing with it: unsolved (MaxSteps 0) and solved cubes.
cube = FiberCubeSource(Populations=2, NumberOfFibers=60, EdgeLength=20, Seed=3)
for steps in (0, 10000):
    solver = FiberCollisionSolver(Input=cube, MaxSteps=steps)
    ErrorCatcher(solver)  # the unsolved run warns, as it should
    solver.UpdatePipeline()
    own = servermanager.Fetch(solver).GetFieldData().GetArray("collisions").GetValue(0)
    s = summary(FiberMetrics(Input=solver, ComputeVolumeFraction=0))
    print("solver steps <= %d: solver %d collisions, FiberMetrics %d, min_gap %g" % (steps, own, s["collisions"][0], s["min_gap"][0]))
    check(s["collisions"][0] == own, "FiberMetrics %s vs solver %d" % (s["collisions"], own))
    check((own > 0) == (steps == 0) and (s["min_gap"][0] < 0) == (own > 0), "solved/unsolved %s" % s)

# The same in a periodic cell (periodic_cell field data from the source): pairs by minimum image.
periodic = FiberCubeSource(Populations=2, NumberOfFibers=40, EdgeLength=16, Periodic=1, Seed=6)
solver = FiberCollisionSolver(Input=periodic, MaxSteps=0)
ErrorCatcher(solver)
solver.UpdatePipeline()
own = servermanager.Fetch(solver).GetFieldData().GetArray("collisions").GetValue(0)
s = summary(FiberMetrics(Input=solver, ComputeVolumeFraction=0))
print("periodic cube: solver %d collisions, FiberMetrics %d" % (own, s["collisions"][0]))
check(s["periodic"][0] == 1 and s["collisions"][0] == own > 0, "periodic: FiberMetrics %s vs solver %d" % (s, own))

# Bad options: an error naming Box; the pipeline works again once it is fixed.
bad = FiberMetrics(Input=polydata(lattice), Box=[0, 0, -5, 5, -5, 5])
errors = ErrorCatcher(bad)
bad.UpdatePipeline()
check("Box 0 0" in errors.text(), "no Box error: %r" % errors.text())
bad.Box = [-5, 5, -5, 5, -5, 5]
bad.VoxelSize = 0.1
check(summary(bad)["fibers"][0] == 9, "pipeline not usable after the error")

# Out-of-range codes typed in Python are errors naming the value, never clamped.
# (SetElement bypasses the XML domains, as a script calling the VTK setter would.)
for prop, value, text in (("VolumeFractionMethod", 5, "VolumeFractionMethod is 5"),
                          ("Seed", -3, "Seed is -3"), ("VoxelSize", -1.0, "VoxelSize -1")):
    bad = FiberMetrics(Input=polydata(lattice), Box=[-5, 5, -5, 5, -5, 5])
    errors = ErrorCatcher(bad)
    bad.SMProxy.GetProperty(prop).SetElement(0, value)
    bad.SMProxy.UpdateVTKObjects()
    bad.UpdatePipeline()
    check(text in errors.text(), "%s %s: %r" % (prop, value, errors.text()))

# Empty input: empty outputs, no error.
empty = FiberMetrics(Input=polydata([]))
errors = ErrorCatcher(empty)
empty.UpdatePipeline()
check(not errors.errors and servermanager.Fetch(empty, idx=1).GetNumberOfRows() == 0, "empty input")
# What the GUI's Apply does with the outputs (pqApplyBehavior: ShowInPreferredView per port, the
# current view a render view): the fibers in that view and one spreadsheet for the Summary; the
# other six tables open no view of their own.
from paraview.modules.vtkRemotingViews import vtkSMParaViewPipelineControllerWithRendering  # noqa: E402

render = CreateView("RenderView")
shown = FiberMetrics(Input=polydata(lattice), ComputeCollisions=0)
controller = vtkSMParaViewPipelineControllerWithRendering()
views = [controller.ShowInPreferredView(shown.SMProxy, port, render.SMProxy) for port in range(8)]
spreadsheets = {v.GetGlobalIDAsString() for v in views if v is not None and v.GetXMLName() == "SpreadSheetView"}
check(views[0] is not None and views[0].GetXMLName() == "RenderView", "fibers shown in %r" % (views[0],))
check(len(spreadsheets) == 1 and views[1] is not None and views[1].GetXMLName() == "SpreadSheetView",
      "Apply opens %d spreadsheet views: %r" % (len(spreadsheets), [v.GetXMLName() if v else None for v in views]))
for v in GetViews():
    Delete(v)
print("FiberMetrics checks passed")
