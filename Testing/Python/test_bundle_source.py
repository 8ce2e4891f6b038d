"""pvpython: FiberBundleSource builds every shape (every property set explicitly); fiber counts
against an independent count of triangular-grid seeds in the disc, ids, bundle ids, radii, the
Trajectory input, field data, and the error for Shape=Trajectory without an input."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())


def grid_count(radius, fiber_radius, spacing):
    """Seeds of a centred triangular grid (docs/tissue-models.md §1.1) whose whole disc is inside."""
    h = spacing * math.sqrt(3.0) / 2.0
    limit = (radius - fiber_radius) ** 2
    n = int(radius / h) + 2
    count = 0
    for j in range(-n, n + 1):
        for i in range(-2 * n, 2 * n + 1):
            x = (i + (j % 2) / 2.0) * spacing
            y = j * h
            if x * x + y * y <= limit + 1e-9:
                count += 1
    return count


def build(shape, **overrides):
    props = dict(Shape=shape, BundleRadius=6.0, Length=30.0, FiberRadius=0.8, RadiusSpread=0.0,
                 RadiusDistribution="LogNormal", FiberSpacing=2.0, NumberOfFibers=0, SegmentLength=2.0,
                 Displacement=0.2, CrossingAngle=90.0, UncrossedFraction=0.25, RanvierSpacing=0.0,
                 RanvierDepth=0.3, RanvierLength=1.0, Seed=7)
    props.update(overrides)
    return FiberBundleSource(**props)


def summary(proxy):
    pd = servermanager.Fetch(proxy)
    fid = pd.GetCellData().GetArray("fiber_id")
    bid = pd.GetCellData().GetArray("bundle_id")
    ids = [fid.GetValue(c) for c in range(pd.GetNumberOfCells())]
    bundles = {}
    for c in range(pd.GetNumberOfCells()):
        bundles[bid.GetValue(c)] = bundles.get(bid.GetValue(c), 0) + 1
    check(sorted(ids) == list(range(len(ids))), "fiber_id must be 0..N-1")
    return pd, bundles


n = grid_count(6.0, 0.8, 2.0)
check(n == 19, "grid count %d (1 + 6 + 6 + 6 seeds at 0, 2, 2*sqrt(3), 4)" % n)
uncrossed = int(math.ceil(0.25 * n - 1e-9))

pd, bundles = summary(build("Cylinder"))
check(bundles == {0: n}, "Cylinder: %s, expected %d" % (bundles, n))
check(pd.GetFieldData().GetArray("segment_length").GetValue(0) == 2.0, "segment_length")
check(pd.GetFieldData().GetArray("seed").GetValue(0) == 7, "seed")
bounds = pd.GetBounds()
check(abs(bounds[0] + 15.0) <= 0.2 + 1e-9 and abs(bounds[1] - 15.0) <= 0.2 + 1e-9, "Cylinder along x: %s" % (bounds,))

_, bundles = summary(build("Crossing"))
check(bundles == {0: n, 1: n}, "Crossing: %s" % bundles)
_, bundles = summary(build("YShape", CrossingAngle=60.0))
check(sorted(bundles) == [0, 1] and bundles[0] + bundles[1] == n and abs(bundles[0] - bundles[1]) <= n // 4,
      "YShape: %s" % bundles)
pd, bundles = summary(build("Chiasm", RanvierSpacing=-1.0))
check(bundles == {0: n - uncrossed, 1: n - uncrossed, 2: uncrossed, 3: uncrossed}, "Chiasm: %s" % bundles)
radius = pd.GetPointData().GetArray("radius").GetRange()
check(abs(radius[0] - 0.8 * 0.7) < 1e-6 and radius[1] == 0.8, "Chiasm nodes of Ranvier: radius %s" % (radius,))

# Random seeds and uniform radii.
pd, bundles = summary(build("Cylinder", NumberOfFibers=20, RadiusSpread=0.2, RadiusDistribution="Uniform"))
check(bundles == {0: 20}, "NumberOfFibers=20: %s" % bundles)
radius = pd.GetPointData().GetArray("radius").GetRange()
check(0.64 - 1e-9 <= radius[0] < radius[1] <= 0.96 + 1e-9, "Uniform radii %s" % (radius,))

# Trajectory: a line source along z; fibers run from z = 0 to z = 20 within the bundle.
line = Line(Point1=[0.0, 0.0, 0.0], Point2=[0.0, 0.0, 20.0], Resolution=4)
traj = build("Trajectory", Trajectory=line)
pd, bundles = summary(traj)
check(bundles == {0: n}, "Trajectory: %s" % bundles)
b = pd.GetBounds()
check(b[4] >= -0.2 - 1e-9 and b[5] <= 20.2 + 1e-9 and max(abs(v) for v in b[:4]) <= 5.2 + 0.2 * 1.5,
      "Trajectory bounds %s" % (b,))

# Shape=Trajectory without an input: a clear error, then recovery. (paraview.simple connects the
# active source to the first input property, as for any filter: disconnect it explicitly.)
bad = build("Trajectory", Trajectory=None)
check(bad.Trajectory is None, "Trajectory input must be empty")
catcher = ErrorCatcher(bad)
bad.UpdatePipeline()
check("no polyline is connected to input port 0" in catcher.text(), "error: %s" % catcher.text())
check(servermanager.Fetch(bad).GetNumberOfLines() == 0, "empty output on error")
catcher.clear()
bad.Shape = "Cylinder"
bad.UpdatePipeline()
check(not catcher.errors and servermanager.Fetch(bad).GetNumberOfLines() == n, "recovered")
print("bundle source: %d fibers per disc, %d uncrossed per nerve" % (n, uncrossed))
