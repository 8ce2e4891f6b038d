"""pvpython: FiberFieldSource on guide lines. A bundle of half-circle guides of radius R is written
to an MRtrix .tck file (by hand, as a tractography tool writes it), read back with FiberReader and
filled with fibers: they stay in the bundle's tube, keep their distance from the axis and follow
e_phi; after FiberCollisionSolver there are zero collisions (FiberMetrics) and the directions still
agree. Two crossing bundles given by bundle_id become two populations, and bad guides or properties
give errors naming them while the pipeline recovers."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402

load_plugin(globals())
import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData  # noqa: E402

tmp = option("-T")
R, SPREAD, GUIDE_RADIUS = 30.0, 2.0, 3.0


def write_tck(path, streamlines):
    """MRtrix tracks, Float32LE: the header, then each streamline's points and a NaN triplet, then
    an Inf triplet (the MRtrix "Tracks file format")."""
    def header(offset):
        return ("mrtrix tracks\ndatatype: Float32LE\ncount: %d\nfile: . %d\nEND\n" % (len(streamlines), offset)).encode()
    offset = len(header(0))
    while len(header(offset)) != offset:
        offset = len(header(offset))
    data = [np.asarray(s, dtype="<f4").ravel().tolist() + [math.nan] * 3 for s in streamlines]
    with open(path, "wb") as f:
        f.write(header(offset))
        f.write(np.asarray(sum(data, []) + [math.inf] * 3, dtype="<f4").tobytes())


def arc(radius, z):
    phi = np.radians(np.arange(0, 181, 1.0))
    return np.c_[radius * np.cos(phi), radius * np.sin(phi), np.full_like(phi, z)]


def producer(data):
    p = TrivialProducer()
    p.GetClientSideObject().SetOutput(data)
    return p


def polylines(lines, bundles=None):
    """A vtkPolyData of the given (n, 3) point arrays, with a bundle_id cell array if given."""
    pts, cells = vtkPoints(), vtkCellArray()
    for line in lines:
        cells.InsertNextCell(len(line))
        for p in line:
            cells.InsertCellPoint(pts.InsertNextPoint(*p))
    poly = vtkPolyData()
    poly.SetPoints(pts)
    poly.SetLines(cells)
    if bundles is not None:
        b = numpy_to_vtk(np.asarray(bundles, dtype=np.int32), deep=1)
        b.SetName("bundle_id")
        poly.GetCellData().AddArray(b)
    return poly


def fibers_of(proxy):
    data = servermanager.Fetch(proxy)
    pts = vtk_to_numpy(data.GetPoints().GetData()) if data.GetNumberOfPoints() else np.zeros((0, 3))
    lines = []
    for c in range(data.GetNumberOfCells()):
        ids = data.GetCell(c).GetPointIds()
        lines.append(pts[[ids.GetId(i) for i in range(ids.GetNumberOfIds())]])
    bundles = vtk_to_numpy(data.GetCellData().GetArray("bundle_id")) if data.GetNumberOfCells() else []
    return lines, np.asarray(bundles), data


def mean_ephi_error(lines):
    """Mean angle (degrees) between the segments and e_phi at their midpoints."""
    angles = []
    for p in lines:
        d = np.diff(p, axis=0)
        m = 0.5 * (p[1:] + p[:-1])
        e = np.c_[-m[:, 1], m[:, 0], np.zeros(len(m))] / np.hypot(m[:, 0], m[:, 1])[:, None]
        c = np.abs(np.sum(d * e, axis=1)) / np.linalg.norm(d, axis=1)
        angles.extend(np.degrees(np.arccos(np.minimum(c, 1.0))))
    return float(np.mean(angles))


# 1. Guides: 25 half circles of radius R +- 2 um, heights -2..2 um, written as .tck and read back.
tck = os.path.join(tmp, "arc_bundle.tck")
guides = [arc(R + dr, dz) for dr in np.linspace(-SPREAD, SPREAD, 5) for dz in np.linspace(-SPREAD, SPREAD, 5)]
write_tck(tck, guides)
reader = FiberReader(FileName=tck)
reader.UpdatePipeline()
check(reader.GetDataInformation().GetNumberOfCells() == 25, "%d streamlines read" % reader.GetDataInformation().GetNumberOfCells())

# 2. Fibers around them: inside the tube (R +- (2 + GuideRadius + half a voxel diagonal)), each at its
# own distance from the axis to 2 % of R, along e_phi.
src = FiberFieldSource(Input=reader, GuideRadius=GUIDE_RADIUS, GuideSpacing=1.0, VolumeFraction=0.2, FiberRadius=0.5,
                       SegmentLength=1.0, Seed=3)
src.UpdatePipeline()
lines, bundles, data = fibers_of(src)
check(len(lines) > 10, "only %d fibers" % len(lines))
check(set(bundles.tolist()) == {0}, "bundle ids %s" % set(bundles.tolist()))
reach = SPREAD + GUIDE_RADIUS + 0.5 * math.sqrt(3.0)
for p in lines:
    rho = np.hypot(p[:, 0], p[:, 1])
    check(np.all(np.abs(rho - R) < reach) and np.all(np.abs(p[:, 2]) < reach), "a fiber leaves the bundle's tube")
    check(rho.max() - rho.min() < 0.02 * R, "a fiber drifts by %g um across the bundle" % (rho.max() - rho.min()))
before = mean_ephi_error(lines)
check(before < 2.0, "mean direction error %g degrees" % before)
reached = data.GetFieldData().GetArray("traced_volume_fraction").GetValue(0)
check(reached >= 0.2, "traced_volume_fraction %g" % reached)
print("guides: %d fibers, fraction %.3f, mean direction error %.3g degrees" % (len(lines), reached, before))

# The same properties give the same fibers, whatever the thread count.
again = FiberFieldSource(Input=reader, GuideRadius=GUIDE_RADIUS, GuideSpacing=1.0, VolumeFraction=0.2, FiberRadius=0.5,
                         SegmentLength=1.0, Seed=3, NumberOfThreads=1)
same, _, _ = fibers_of(again)
check(len(same) == len(lines) and all(np.array_equal(a, b) for a, b in zip(same, lines)), "not reproducible")

# 3. Solved: zero collisions, still along e_phi.
raw = servermanager.Fetch(FiberMetrics(Input=src, ComputeVolumeFraction=0), idx=1)
check(raw.GetColumnByName("collisions").GetValue(0) > 0, "the traced fibers do not overlap: nothing to solve")
solver = FiberCollisionSolver(Input=src, SegmentLength=1.0, MaxSteps=5000, NumberOfThreads=2)
metrics = FiberMetrics(Input=solver, ComputeVolumeFraction=0)
metrics.UpdatePipeline()
collisions = servermanager.Fetch(metrics, idx=1).GetColumnByName("collisions").GetValue(0)
check(collisions == 0, "%d colliding pairs after solving" % collisions)
solved, _, solved_data = fibers_of(solver)
check(solved_data.GetFieldData().GetArray("solved").GetValue(0) == 1, "solver did not finish")
after = mean_ephi_error(solved)
check(after < 5.0, "mean direction error after solving %g degrees" % after)
print("solved: 0 collisions, mean direction error %.3g degrees" % after)

# 4. Two crossing bundles (bundle_id 5 along x, 2 along y) as two populations with ByBundle: bundle_id
# 0 (the guides' 2) along y, 1 along x, also where they cross.
xs = [np.c_[np.linspace(-12, 12, 25), np.full(25, y), np.full(25, z)] for y in (-1.0, 1.0) for z in (-1.0, 1.0)]
ys = [np.c_[np.full(25, x), np.linspace(-12, 12, 25), np.full(25, z)] for x in (-1.0, 1.0) for z in (-1.0, 1.0)]
crossing = producer(polylines(xs + ys, [5] * 4 + [2] * 4))
two = FiberFieldSource(Input=crossing, GuideRadius=2.0, GuideSpacing=0.5, GuidePopulations="ByBundle",
                       VolumeFraction=0.2, FiberRadius=0.3, SegmentLength=1.0, Seed=1)
lines, bundles, _ = fibers_of(two)
check(set(bundles.tolist()) == {0, 1}, "bundles %s" % set(bundles.tolist()))
for p, b in zip(lines, bundles):
    d = np.diff(p, axis=0)
    axis = np.array([0, 1.0, 0]) if b == 0 else np.array([1.0, 0, 0])
    check(np.all(np.linalg.norm(np.cross(d, axis), axis=1) < 1e-9 * np.linalg.norm(d, axis=1)), "bundle %d off its axis" % b)
one = FiberFieldSource(Input=crossing, GuideRadius=2.0, GuideSpacing=0.5, VolumeFraction=0.2, FiberRadius=0.3,
                       SegmentLength=1.0, Seed=1)
_, bundles, _ = fibers_of(one)
check(set(bundles.tolist()) == {0}, "GuidePopulations One: bundles %s" % set(bundles.tolist()))


# The GUI offers the filter for fiber and streamline polydata as well as for images with vectors.
def accepts(source):
    proto = servermanager.ProxyManager().SMProxyManager.GetPrototypeProxy("filters", "FiberFieldSource")
    prop = proto.GetProperty("Input")
    prop.RemoveAllUncheckedProxies()
    prop.AddUncheckedInputConnection(source.SMProxy, 0)
    ok = prop.IsInDomains()
    prop.RemoveAllUncheckedProxies()
    return bool(ok)


check(accepts(reader) and accepts(crossing), "guide polydata is not accepted")
check(not accepts(Wavelet()), "an image without a vector array is accepted")

# 5. Bad guides and properties: errors naming them, no output; the pipeline recovers.
bad = FiberFieldSource(Input=reader, GuideRadius=GUIDE_RADIUS, GuideSpacing=1.0, VolumeFraction=0.2, FiberRadius=0.5,
                       SegmentLength=1.0)
catcher = ErrorCatcher(bad)
for prop, value, words in (("GuideRadius", 0.0, "GuideRadius is 0, must be > 0"),
                           ("GuideRadius", -2.0, "GuideRadius is -2, must be > 0"),
                           ("GuideSpacing", 0.0, "GuideSpacing is 0, must be > 0"),
                           ("GuideSpacing", 4.0, "GuideSpacing is 4 um, must be at most GuideRadius".replace("um", "\u00b5m")),
                           ("GuidePopulations", 7, "GuidePopulations is 7"),
                           ("NumberOfThreads", -1, "NumberOfThreads is -1")):
    ok = {"GuideRadius": GUIDE_RADIUS, "GuideSpacing": 1.0, "GuidePopulations": 0, "NumberOfThreads": 0}
    for k, v in ok.items():
        setattr(bad, k, v)
    if prop == "GuidePopulations":  # not one of its entries: through the server-manager property
        bad.SMProxy.GetProperty(prop).SetElement(0, value)
        bad.SMProxy.UpdateVTKObjects()
    else:
        setattr(bad, prop, value)
    catcher.clear()
    bad.UpdatePipeline()
    check(words in catcher.text(), "no error %r: %r" % (words, catcher.text()))
    check(servermanager.Fetch(bad).GetNumberOfCells() == 0, "output after a bad %s" % prop)
bad.GuideRadius, bad.GuideSpacing, bad.GuidePopulations, bad.NumberOfThreads = GUIDE_RADIUS, 1.0, "One", 0
catcher.clear()
bad.UpdatePipeline()
check(not catcher.errors and servermanager.Fetch(bad).GetNumberOfCells() > 0, "no recovery: %r" % catcher.text())

nan_guide = np.array([[0.0, 0, 0], [1.0, math.nan, 0], [2.0, 0, 0]])
for data, words in ((Sphere(), "the guides have no line with two distinct points"),
                    (producer(polylines([arc(R, 0.0), nan_guide])), "point 1 of guide line 1 is not finite"),
                    (producer(polylines(xs + ys + [arc(R, 0.0)], [5] * 4 + [2] * 4 + [9])),
                     "GuidePopulations is 1 (ByBundle), but the guides have 3 bundle_id values (2, 5, 9)")):
    bad.Input = data
    bad.GuidePopulations = "ByBundle" if "ByBundle" in words else "One"
    catcher.clear()
    bad.UpdatePipeline()
    check(words in catcher.text(), "no error %r: %r" % (words, catcher.text()))
    check(servermanager.Fetch(bad).GetNumberOfCells() == 0, "output after bad guides %r" % words)
bad.Input = reader
bad.GuidePopulations = "One"
catcher.clear()
bad.UpdatePipeline()
check(not catcher.errors and servermanager.Fetch(bad).GetNumberOfCells() > 0, "no recovery: %r" % catcher.text())
print("guide source checks passed")
