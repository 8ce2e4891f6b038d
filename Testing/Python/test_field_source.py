"""pvpython: FiberFieldSource on fields built in NumPy: fibers follow a bend at constant radius and
two crossing fields in their own directions, the same Seed gives the same fibers, the solver then
leaves zero collisions (FiberMetrics) with the directions still on the field, and bad input gives
errors naming the property while the pipeline recovers."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402

load_plugin(globals())
import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402


def image(dims, arrays, spacing=1.0):
    """A vtkImageData from the origin with the given point arrays, each a function of (x, y, z)
    grids (x fastest, as VTK stores points) returning an (n, 3) array."""
    img = vtkImageData()
    img.SetDimensions(*dims)
    img.SetSpacing(spacing, spacing, spacing)
    z, y, x = np.meshgrid(*[np.arange(n) * spacing for n in dims[::-1]], indexing="ij")
    for name, value in arrays.items():
        v = np.ascontiguousarray(value(x.ravel(), y.ravel(), z.ravel()), dtype=np.float64)
        a = numpy_to_vtk(v, deep=1)
        a.SetName(name)
        img.GetPointData().AddArray(a)
    return img


def producer(data):
    p = TrivialProducer()
    p.GetClientSideObject().SetOutput(data)
    return p


def fibers_of(proxy):
    """(list of (n, 3) point arrays, bundle ids) of a fiber output."""
    data = servermanager.Fetch(proxy)
    pts = vtk_to_numpy(data.GetPoints().GetData()) if data.GetNumberOfPoints() else np.zeros((0, 3))
    lines = []
    for c in range(data.GetNumberOfCells()):
        ids = data.GetCell(c).GetPointIds()
        lines.append(pts[[ids.GetId(i) for i in range(ids.GetNumberOfIds())]])
    bundles = vtk_to_numpy(data.GetCellData().GetArray("bundle_id")) if data.GetNumberOfCells() else []
    return lines, np.asarray(bundles), data


def bend(x, y, z):
    """e_phi about the z axis in the annulus 12 <= rho <= 28, zero elsewhere."""
    rho = np.hypot(x, y)
    v = np.c_[-y, x, np.zeros_like(x)] / np.maximum(rho, 1e-300)[:, None]
    v[(rho < 12) | (rho > 28)] = 0.0
    return v


def mean_bend_error(lines):
    """Mean angle (degrees) between the segments and e_phi at their midpoints."""
    angles = []
    for p in lines:
        d = np.diff(p, axis=0)
        m = 0.5 * (p[1:] + p[:-1])
        e = np.c_[-m[:, 1], m[:, 0], np.zeros(len(m))] / np.hypot(m[:, 0], m[:, 1])[:, None]
        c = np.abs(np.sum(d * e, axis=1)) / np.linalg.norm(d, axis=1)
        angles.extend(np.degrees(np.arccos(np.minimum(c, 1.0))))
    return float(np.mean(angles))


# 1. A bend: every fiber keeps its distance from the axis (1 % at SegmentLength 1 µm), ends on
# the box (x = 0 or y = 0) or the annulus' edge, and follows e_phi.
field = producer(image((41, 41, 7), {"orientation": bend}))
src = FiberFieldSource(Input=field, VolumeFraction=0.2, FiberRadius=0.5, SegmentLength=1.0, Seed=3)
src.OrientationArray = ["POINTS", "orientation"]
src.UpdatePipeline()
lines, bundles, data = fibers_of(src)
check(len(lines) > 10, "only %d fibers" % len(lines))
check(set(bundles.tolist()) == {0}, "bundle ids %s" % set(bundles.tolist()))
for name in ("radius",):
    check(data.GetPointData().GetArray(name) is not None, "no point array " + name)
check(data.GetCellData().GetArray("fiber_id") is not None, "no fiber_id")
reached = data.GetFieldData().GetArray("traced_volume_fraction").GetValue(0)
check(reached >= 0.2, "traced_volume_fraction %g" % reached)
for p in lines:
    rho = np.hypot(p[:, 0], p[:, 1])
    check(rho.max() - rho.min() < 0.01 * rho.mean(), "radius drifts by %g at %g" % (rho.max() - rho.min(), rho.mean()))
    for end in (p[0], p[-1]):
        on_face = min(abs(end[0]), abs(end[1])) < 1e-9
        on_edge = abs(math.hypot(end[0], end[1]) - 12) < 1 or abs(math.hypot(end[0], end[1]) - 28) < 1
        check(on_face or on_edge, "fiber ends inside the field at %s" % end)
before = mean_bend_error(lines)
check(before < 2.0, "mean direction error %g degrees" % before)
print("bend: %d fibers, fraction %.3f, mean direction error %.3g degrees" % (len(lines), reached, before))

# The same Seed gives the same fibers; another gives others.
again = FiberFieldSource(Input=field, VolumeFraction=0.2, FiberRadius=0.5, SegmentLength=1.0, Seed=3)
again.OrientationArray = ["POINTS", "orientation"]
same, _, _ = fibers_of(again)
check(len(same) == len(lines) and all(np.array_equal(a, b) for a, b in zip(same, lines)), "Seed not reproducible")
again.Seed = 4
other, _, _ = fibers_of(again)
check(not np.array_equal(other[0], lines[0]), "another Seed gave the same first fiber")

# 2. Solved: zero collisions by FiberMetrics' own count (the traced fibers overlap), still along
# the field.
raw = servermanager.Fetch(FiberMetrics(Input=src, ComputeVolumeFraction=0), idx=1)
check(raw.GetColumnByName("collisions").GetValue(0) > 0, "the traced fibers do not overlap: nothing to solve")
solver = FiberCollisionSolver(Input=src, SegmentLength=1.0, MaxSteps=5000, NumberOfThreads=2)
solver.UpdatePipeline()
metrics = FiberMetrics(Input=solver, ComputeVolumeFraction=0)
metrics.UpdatePipeline()
summary = servermanager.Fetch(metrics, idx=1)
collisions = summary.GetColumnByName("collisions").GetValue(0)
check(collisions == 0, "%d colliding pairs after solving" % collisions)
solved, _, solved_data = fibers_of(solver)
check(solved_data.GetFieldData().GetArray("solved").GetValue(0) == 1, "solver did not finish")
after = mean_bend_error(solved)
check(after < 5.0, "mean direction error after solving %g degrees" % after)
print("solved: 0 collisions, mean direction error %.3g degrees" % after)

# 3. Two crossing fields: bundle 0 along x, bundle 1 along y, volume shares 1 : 1.
cross = producer(image((16, 16, 16), {"ax": lambda x, y, z: np.tile([1.0, 0, 0], (len(x), 1)),
                                      "ay": lambda x, y, z: np.tile([0, -1.0, 0], (len(x), 1))}))
two = FiberFieldSource(Input=cross, VolumeFraction=0.3, FiberRadius=0.5, SegmentLength=1.0, Seed=1)
two.OrientationArray = ["POINTS", "ax"]
two.SecondOrientationArray = ["POINTS", "ay"]
lines, bundles, _ = fibers_of(two)
check(set(bundles.tolist()) == {0, 1}, "bundles %s" % set(bundles.tolist()))
length = {0: 0.0, 1: 0.0}
for p, b in zip(lines, bundles):
    d = p[-1] - p[0]
    axis = np.array([1.0, 0, 0]) if b == 0 else np.array([0, 1.0, 0])
    check(np.linalg.norm(np.cross(d / np.linalg.norm(d), axis)) < 1e-9, "bundle %d fiber off its axis" % b)
    length[int(b)] += np.linalg.norm(d)
check(abs(length[0] - length[1]) <= 15.0, "volume shares %s" % length)

# Two axes per voxel in one 6-component array (axis 2 absent above z = 8): exactly the model of the
# two 3-component arrays, each population along its axis.
def axis_x(x, y, z):
    return np.c_[np.where(x % 2 == 0, 2.0, -1.0), 0 * x, 0 * x]


def axis_y(x, y, z):
    v = np.c_[0 * x, -np.ones_like(x), 0 * x]
    v[z > 8] = 0.0
    return v


pairs = producer(image((16, 16, 16), {"first": axis_x, "second": axis_y,
                                      "both": lambda x, y, z: np.c_[axis_x(x, y, z), axis_y(x, y, z)],
                                      "quad": lambda x, y, z: np.c_[axis_x(x, y, z), 0 * x]}))
as_two = FiberFieldSource(Input=pairs, VolumeFraction=0.3, FiberRadius=0.5, SegmentLength=1.0, Seed=2,
                          PopulationShares=[1, 2])
as_two.OrientationArray = ["POINTS", "first"]
as_two.SecondOrientationArray = ["POINTS", "second"]
as_six = FiberFieldSource(Input=pairs, VolumeFraction=0.3, FiberRadius=0.5, SegmentLength=1.0, Seed=2,
                          PopulationShares=[1, 2])
as_six.OrientationArray = ["POINTS", "both"]
two_lines, two_bundles, two_data = fibers_of(as_two)
six_lines, six_bundles, six_data = fibers_of(as_six)
check(set(six_bundles.tolist()) == {0, 1}, "6-component bundles %s" % set(six_bundles.tolist()))
check(len(six_lines) == len(two_lines) and all(np.array_equal(a, b) for a, b in zip(six_lines, two_lines))
      and np.array_equal(six_bundles, two_bundles), "the 6-component array gave another model")
check(np.array_equal(vtk_to_numpy(six_data.GetPointData().GetArray("radius")),
                     vtk_to_numpy(two_data.GetPointData().GetArray("radius"))), "6-component radii differ")
for p, b in zip(six_lines, six_bundles):
    d = np.diff(p, axis=0)
    axis = np.array([1.0, 0, 0]) if b == 0 else np.array([0, 1.0, 0])
    check(np.all(np.linalg.norm(np.cross(d, axis), axis=1) < 1e-9 * np.linalg.norm(d, axis=1)), "bundle %d off its axis" % b)
    check(b == 0 or p[:, 2].max() <= 8.5 + 1e-9, "bundle 1 where its axis is absent: z %g" % p[:, 2].max())
print("6-component field: %d fibers, the same as from two arrays" % len(six_lines))
catcher = ErrorCatcher(as_six)
for first, second, words in (("quad", "None", "OrientationArray 'quad': the point array 'quad' has 4 components"),
                             ("both", "second", "SecondOrientationArray 'second' is set, but OrientationArray 'both' has 6 components"),
                             ("first", "both", "SecondOrientationArray 'both' has 6 components, must have 3")):
    as_six.OrientationArray = ["POINTS", first]
    as_six.SecondOrientationArray = ["POINTS", second]
    catcher.clear()
    as_six.UpdatePipeline()
    check(words in catcher.text(), "no error %r: %r" % (words, catcher.text()))
    check(servermanager.Fetch(as_six).GetNumberOfCells() == 0, "output after %s + %s" % (first, second))
as_six.OrientationArray = ["POINTS", "both"]
as_six.SecondOrientationArray = ["POINTS", "None"]
catcher.clear()
as_six.UpdatePipeline()
check(not catcher.errors and servermanager.Fetch(as_six).GetNumberOfCells() == len(six_lines), "no recovery: %r" % catcher.text())

# A cell array lives on the cell centres: fibers along z from z = 0.5 to z = 10.5.
cells = vtkImageData()
cells.SetDimensions(12, 12, 12)
axes = numpy_to_vtk(np.tile([0.0, 0.0, -2.0], (11 ** 3, 1)), deep=1)
axes.SetName("cell_axis")
cells.GetCellData().AddArray(axes)
by_cell = FiberFieldSource(Input=producer(cells), NumberOfFibers=20, FiberRadius=0.3, SegmentLength=1.0)
by_cell.OrientationArray = ["CELLS", "cell_axis"]
lines, _, _ = fibers_of(by_cell)
check(len(lines) == 20, "%d fibers from the cell array" % len(lines))
for p in lines:
    check(np.allclose(sorted([p[0, 2], p[-1, 2]]), [0.5, 10.5], atol=1e-9, rtol=0), "cell field ends %s %s" % (p[0], p[-1]))
    check(np.all(np.abs(p[:, :2] - p[0, :2]) < 1e-9), "cell field fiber not along z")
    check(0.5 <= p[0, 0] <= 10.5 and 0.5 <= p[0, 1] <= 10.5, "outside the cell centres' box: %s" % p[0])

# Realism: beading varies the radius along a fiber around the drawn one, myelin adds inner_radius.
real = FiberFieldSource(Input=field, VolumeFraction=0.2, FiberRadius=0.5, SegmentLength=1.0, Seed=3,
                        BeadingCV=0.2, BeadingLength=4.0, GRatio=0.6)
real.OrientationArray = ["POINTS", "orientation"]
real.UpdatePipeline()
rdata = servermanager.Fetch(real)
radius = vtk_to_numpy(rdata.GetPointData().GetArray("radius"))
inner = rdata.GetPointData().GetArray("inner_radius")
check(inner is not None and np.allclose(vtk_to_numpy(inner), 0.6 * radius, rtol=1e-12, atol=0), "inner_radius")
check(radius.std() > 0.05 and abs(radius.mean() - 0.5) < 0.05, "beaded radii mean %g std %g" % (radius.mean(), radius.std()))

# The GUI enables the filter (Filters > FiberPLI) for what its Input domains accept, checked as the
# filters menu does: any image with a 3- or 6-component point or cell array, and polydata (guide
# lines, test_guide_source.py), nothing else.
def accepts(source):
    proto = servermanager.ProxyManager().SMProxyManager.GetPrototypeProxy("filters", "FiberFieldSource")
    prop = proto.GetProperty("Input")
    prop.RemoveAllUncheckedProxies()
    prop.AddUncheckedInputConnection(source.SMProxy, 0)
    ok = prop.IsInDomains()
    prop.RemoveAllUncheckedProxies()
    return bool(ok)


check(accepts(field) and accepts(producer(cells)), "an image with a vector array is not accepted")
check(accepts(pairs), "an image with a 6-component array is not accepted")
check(not accepts(Wavelet()), "an image without a 3-component array is accepted")
check(accepts(FiberCubeSource(NumberOfFibers=2)), "fiber polydata (guide lines) is not accepted")
check(not accepts(producer(cells.NewInstance())), "an empty image is accepted")

# 4. Bad input: errors name the property and value; the pipeline recovers.
bad = FiberFieldSource(Input=field, VolumeFraction=0.95, FiberRadius=0.5, SegmentLength=1.0)
bad.OrientationArray = ["POINTS", "orientation"]
catcher = ErrorCatcher(bad)
for prop, value, words in (("VolumeFraction", 0.95, "VolumeFraction is 0.95"), ("SegmentLength", 0.0, "SegmentLength is 0"),
                           ("Seed", -2, "Seed is -2"), ("NumberOfFibers", 2000000000, "NumberOfFibers 2000000000"),
                           ("SeedCandidates", 0, "SeedCandidates is 0"), ("SeedCandidates", 65, "SeedCandidates is 65")):
    ok = {"VolumeFraction": 0.2, "SegmentLength": 1.0, "Seed": 42, "NumberOfFibers": 0, "SeedCandidates": 1}
    for k, v in ok.items():
        setattr(bad, k, v)
    setattr(bad, prop, value)
    catcher.clear()
    bad.UpdatePipeline()
    check(words in catcher.text(), "no error %r: %r" % (words, catcher.text()))
    check(servermanager.Fetch(bad).GetNumberOfCells() == 0, "output after a bad %s" % prop)
bad.NumberOfFibers = 0
bad.SeedCandidates = 1
bad.OrientationArray = ["POINTS", "missing"]
catcher.clear()
bad.UpdatePipeline()
check("OrientationArray 'missing'" in catcher.text(), "missing array: %r" % catcher.text())
bad.OrientationArray = ["POINTS", "orientation"]
catcher.clear()
bad.UpdatePipeline()
check(not catcher.errors and servermanager.Fetch(bad).GetNumberOfCells() > 0, "no recovery: %r" % catcher.text())

# A field too large for the memory budget is refused before it is copied.
os.environ["FIBERPLI_MEMORY_LIMIT"] = "100K"
bad.Seed = 43
catcher.clear()
bad.UpdatePipeline()
del os.environ["FIBERPLI_MEMORY_LIMIT"]
check("OrientationArray" in catcher.text() and "memory budget" in catcher.text(), "budget: %r" % catcher.text())
bad.Seed = 44
catcher.clear()
bad.UpdatePipeline()
check(not catcher.errors and servermanager.Fetch(bad).GetNumberOfCells() > 0, "no recovery: %r" % catcher.text())

# NaN vectors are empty, with a warning that counts them; a flat image is refused.
def nan_bend(x, y, z):
    v = bend(x, y, z)
    v[::97] = np.nan
    return v


nan_src = FiberFieldSource(Input=producer(image((41, 41, 7), {"orientation": nan_bend})), VolumeFraction=0.1,
                           FiberRadius=0.5, SegmentLength=1.0)
nan_src.OrientationArray = ["POINTS", "orientation"]
catcher = ErrorCatcher(nan_src)
nan_src.UpdatePipeline()
expected = len(range(0, 41 * 41 * 7, 97))
check(any("%d orientation vector(s) are NaN" % expected in w for w in catcher.warnings), "warnings %r" % catcher.warnings)
check(not catcher.errors and servermanager.Fetch(nan_src).GetNumberOfCells() > 0, "NaN field: %r" % catcher.text())
flat = FiberFieldSource(Input=producer(image((8, 8, 1), {"orientation": bend})))
flat.OrientationArray = ["POINTS", "orientation"]
catcher = ErrorCatcher(flat)
flat.UpdatePipeline()
check("1 point(s) along z" in catcher.text(), "flat image: %r" % catcher.text())

# Progress during tracing, and an abort there stops it with an empty output; the next property
# change runs it again.
big = FiberFieldSource(Input=producer(image((40, 40, 40), {"orientation": lambda x, y, z: np.c_[x * 0 + 1, 0.5 + y * 0, z * 0]})),
                       VolumeFraction=0.3, FiberRadius=0.3, SegmentLength=2.0)
big.OrientationArray = ["POINTS", "orientation"]
alg = big.GetClientSideObject()
seen = []


def abort_while_tracing(obj, event):
    seen.append(obj.GetProgress())
    if 0.0 < obj.GetProgress() < 0.9:
        obj.SetAbortExecute(1)


catcher = ErrorCatcher(big)
tag = alg.AddObserver("ProgressEvent", abort_while_tracing)
big.UpdatePipeline()
alg.RemoveObserver(tag)
check(any(0.0 < p < 0.9 for p in seen), "no progress while tracing: %s" % seen)
check(alg.GetOutputDataObject(0).GetNumberOfCells() == 0, "an aborted run passed fibers on")
check(any("aborted by the user" in w for w in catcher.warnings), "no abort message: %r" % catcher.warnings)
big.Seed = 7
big.UpdatePipeline()
check(alg.GetOutputDataObject(0).GetNumberOfCells() > 64, "no fibers after the abort")
print("field source checks passed")
