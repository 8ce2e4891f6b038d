"""pvpython: the fiberpli module shipped inside the plugin (fibers as NumPy (n, 4) arrays and back)."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402

load_plugin(globals())
import fiberpli  # noqa: E402  (importable only after LoadPlugin: it is embedded in FiberPLI.so)
import numpy as np  # noqa: E402

# fastPLI-style fiber_bundles -> polydata -> back: exactly the same arrays, bundle ids = index.
rng = np.random.default_rng(5)
bundles = [[np.c_[rng.normal(size=(n, 3)), rng.uniform(0.5, 1.0, n)] for n in (2, 5)],
           [np.c_[rng.normal(size=(3, 3)), np.full(3, 0.7)]]]
pd = fiberpli.from_bundles(bundles)
check(pd.GetNumberOfCells() == 3 and pd.GetNumberOfPoints() == 10, "from_bundles: %d cells" % pd.GetNumberOfCells())
back = fiberpli.to_bundles(pd)
check(len(back) == 2 and [len(b) for b in back] == [2, 1], "to_bundles layout %s" % [len(b) for b in back])
for b, bundle in enumerate(bundles):
    for f, fiber in enumerate(bundle):
        check(np.array_equal(back[b][f], fiber), "bundle %d fiber %d differs" % (b, f))
fibers, fiber_ids, bundle_ids = fiberpli.to_arrays(pd)
check(list(fiber_ids) == [0, 1, 2] and list(bundle_ids) == [0, 0, 1], "ids %s %s" % (fiber_ids, bundle_ids))

# A pipeline's output (fetched through the proxy): points and radii match the VTK arrays.
cube = FiberCubeSource(Populations=2, NumberOfFibers=30, EdgeLength=20, Seed=4)
fibers, fiber_ids, bundle_ids = fiberpli.to_arrays(cube)
data = servermanager.Fetch(cube)
check(len(fibers) == data.GetNumberOfCells() and sum(len(f) for f in fibers) == data.GetNumberOfPoints(), "sizes")
p = data.GetPoints().GetPoint(data.GetCell(7).GetPointId(2))
check(np.allclose(fibers[7][2, :3], p, rtol=0, atol=0), "point of fiber 7 differs")
check(set(bundle_ids) == {0, 1} and len(set(fiber_ids)) == 30, "cube ids")

# Arrays back into the pipeline: the solver keeps ids; FiberMetrics measures the same fibers.
moved = [f + np.array([100.0, 0, 0, 0]) for f in fibers]
source = fiberpli.producer(fiberpli.from_arrays(moved, fiber_ids, bundle_ids))
solved = FiberCollisionSolver(Input=source)
out_fibers, out_ids, out_bundles = fiberpli.to_arrays(solved)
check(list(out_ids) == list(fiber_ids) and list(out_bundles) == list(bundle_ids), "solver lost ids")
metrics = FiberMetrics(Input=source, ComputeVolumeFraction=0)
metrics.UpdatePipeline()
summary = servermanager.Fetch(metrics, idx=1)
check(summary.GetColumnByName("fibers").GetValue(0) == 30, "FiberMetrics on NumPy fibers")
check(abs(summary.GetColumnByName("radius_mean").GetValue(0) - np.concatenate(fibers)[:, 3].mean()) < 1e-12, "radii")

# Bad arrays raise ValueError naming the fiber; empty input gives empty data.
for bad, word in (([np.zeros((1, 4))], "fiber 0 has shape"), ([np.ones((3, 3))], "fiber 0 has shape"),
                  ([np.ones((2, 4)), np.c_[np.ones((2, 3)), [1, -1]]], "fiber 1"),
                  ([np.ones((2, 4)), np.ones((2, 4))], None)):
    try:
        fiberpli.from_arrays(bad, fiber_ids=[3, 3] if word is None else None)
        check(False, "no error for %s" % word)
    except ValueError as e:
        check(word is None and "not unique" in str(e) or word is not None and word in str(e), str(e))

# The Python checks reject what the C++ conversion (FiberPolyData, here through FiberMetrics)
# rejects, in the same words.
for bad, fiber, words in (([np.ones((2, 4)), np.c_[np.ones((2, 3)), [1, -1]]], 1, "point 1 has radius -1 (must be finite and > 0)"),
                          ([np.ones((2, 4)), np.c_[np.ones((2, 3)), [0, 1]]], 1, "point 0 has radius 0 (must be finite and > 0)"),
                          ([np.c_[[[1, np.nan, 1], [1, 1, 1]], [1, 1]]], 0, "point 0 has a non-finite coordinate"),
                          ([np.c_[[[1, 1, 1], [1, 1, np.inf]], [1, 1]]], 0, "point 1 has a non-finite coordinate")):
    try:
        fiberpli.from_arrays(bad)
        check(False, "Python: no error for %s" % words)
    except ValueError as e:
        check(words in str(e) and "fiber %d" % fiber in str(e), "Python: %s" % e)
    raw = fiberpli.producer(fiberpli._unchecked_polydata(bad, np.arange(len(bad)), np.zeros(len(bad), np.int32)))
    cxx = FiberMetrics(Input=raw)
    errors = ErrorCatcher(cxx)
    cxx.UpdatePipeline()
    check(words in errors.text() and "fiber %d" % fiber in errors.text(), "C++: %r" % errors.text())
    Delete(cxx)
    Delete(raw)
check(fiberpli.to_arrays(fiberpli.from_arrays([]))[0] == [], "empty")
print("fiberpli NumPy module checks passed")
