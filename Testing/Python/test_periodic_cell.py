"""pvpython: a periodic cell from FiberCubeSource solved by FiberCollisionSolver, its field data,
closure of every fiber, Gamma radii, bad input, and a rendering of the solved cell's tubes."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, compare_image, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())
EDGE = 14.0
src = FiberCubeSource(Populations=2, EdgeLength=EDGE, Periodic=1, VolumeFraction=0.45,
                      FiberRadius=0.8, SegmentLength=2.0, Displacement=0.3, Seed=4)
src.UpdatePipeline()
fibers = servermanager.Fetch(src)
cell = fibers.GetFieldData().GetArray("periodic_cell")
check(cell is not None and cell.GetNumberOfTuples() == 6, "periodic_cell missing")
check([cell.GetValue(i) for i in range(6)] == [-7.0, 7.0] * 3, "periodic_cell values")
# The smallest N with N π r² L >= φ L³: φ L² / (π r²) = 0.45 · 196 / (π · 0.64) = 43.9 -> 44 fibers
check(fibers.GetNumberOfLines() == 44, "fiber count %d" % fibers.GetNumberOfLines())


def closed_shift(pd):
    """Per fiber: last point − first point (must be one period along one axis)."""
    shifts = []
    lines = pd.GetLines()
    lines.InitTraversal()
    from vtkmodules.vtkCommonCore import vtkIdList
    ids = vtkIdList()
    while lines.GetNextCell(ids):
        a = pd.GetPoint(ids.GetId(0))
        b = pd.GetPoint(ids.GetId(ids.GetNumberOfIds() - 1))
        shifts.append(tuple(b[d] - a[d] for d in range(3)))
    return shifts


solver = FiberCollisionSolver(Input=src, MaxSteps=4000, NumberOfThreads=2)
solver.UpdatePipeline()
solved = servermanager.Fetch(solver)
fd = solved.GetFieldData()
check(fd.GetArray("solved").GetValue(0) == 1, "not solved: %d collisions" % fd.GetArray("collisions").GetValue(0))
phi = fd.GetArray("volume_fraction").GetValue(0)
check(0.45 <= phi < 0.55, "volume_fraction %g" % phi)
check(fd.GetArray("min_gap").GetValue(0) >= 0.0, "negative min_gap")
check(fd.GetArray("periodic_cell") is not None, "periodic_cell not passed on")
for s in closed_shift(solved):
    moved = [abs(x) for x in s if abs(x) > 1e-9]
    check(len(moved) == 1 and abs(moved[0] - EDGE) < 1e-6, "fiber not closed: %s" % (s,))
r = solved.GetPointData().GetArray("radius").GetRange()
check(r[0] == 0.8 and r[1] == 0.8, "radii changed: %s" % (r,))

# Gamma radii by name (docs/api.md §1): mean r, spread s; MEDUSA's alpha = 4, beta = 0.25 um.
gamma = FiberCubeSource(Populations=1, EdgeLength=20.0, Periodic=1, VolumeFraction=0.3,
                        FiberRadius=1.0, RadiusSpread=0.5, RadiusDistribution="Gamma", Seed=2)
gamma.UpdatePipeline()
g = servermanager.Fetch(gamma)
radii = g.GetPointData().GetArray("radius")
lo, hi = radii.GetRange()
check(0.25 <= lo < hi <= 4.0, "gamma radii range %s" % ((lo, hi),))
volume = 0.0
lines = g.GetLines()
lines.InitTraversal()
from vtkmodules.vtkCommonCore import vtkIdList  # noqa: E402
ids = vtkIdList()
while lines.GetNextCell(ids):
    rr = radii.GetValue(ids.GetId(0))
    volume += math.pi * rr * rr * 20.0
# At least the target, and less than one fiber (of the largest radius) above it.
check(0.3 <= volume / 8000.0 < 0.3 + math.pi * hi * hi * 20.0 / 8000.0, "gamma fiber volume %g" % (volume / 8000.0))

bad = FiberCubeSource(Periodic=1, EdgeLength=20.0, VolumeFraction=0.3)
catcher = ErrorCatcher(bad)
bad.VolumeFraction = 1.5
bad.UpdatePipeline()
check("VolumeFraction is 1.5" in catcher.text(), "no VolumeFraction error: %s" % catcher.text())

# Polydisperse Lattice seeding (docs/periodic-cells.md, "Polydisperse seeding"): a target the
# disk packing cannot separate warns and still gives every fiber; two fibers in a huge cell are
# packed at once (the packing's grid is bounded by the fiber count).
dense = FiberCubeSource(Periodic=1, Seeding="Lattice", EdgeLength=14.0, FiberRadius=1.0, RadiusSpread=0.5,
                        RadiusDistribution="Gamma", VolumeFraction=0.93, Seed=3)
catcher = ErrorCatcher(dense)
dense.UpdatePipeline()
check(any("the radii could not be separated" in w for w in catcher.warnings),
      "no infeasible seeding warning: %s" % catcher.warnings)
check(dense.GetDataInformation().GetNumberOfCells() > 40, "fibers dropped")
huge = FiberCubeSource(Periodic=1, Seeding="Lattice", EdgeLength=1e5, SegmentLength=2e4, NumberOfFibers=2,
                       FiberRadius=1.0, RadiusSpread=0.5, RadiusDistribution="Gamma")
catcher = ErrorCatcher(huge)
huge.UpdatePipeline()
check(huge.GetDataInformation().GetNumberOfCells() == 2 and not catcher.errors and not catcher.warnings,
      "two fibers in a (1e5)^3 cell: %s %s" % (catcher.errors, catcher.warnings))

# The packing reports progress and honours an abort: no output, no new packing at the next
# request, and a property change packs again.
packed = FiberCubeSource(Periodic=1, Seeding="Lattice", EdgeLength=30.0, FiberRadius=1.0, RadiusSpread=0.5,
                         RadiusDistribution="Gamma", VolumeFraction=0.85, Seed=42)
source = packed.GetClientSideObject()
calls = {"n": 0}


def abort_once(obj, event):
    if calls["n"] == 0 and 0.0 < obj.GetProgress() < 0.7:
        obj.SetAbortExecute(1)
        calls["n"] += 1


tag = source.AddObserver("ProgressEvent", abort_once)
source.Update()
source.RemoveObserver(tag)
check(calls["n"] == 1, "the packing reported no progress")
check(source.GetOutputDataObject(0).GetNumberOfCells() == 0, "an aborted seeding passes nothing on")
check(not source.GetAbortExecute(), "the abort request must end with the execution")
source.Update()
check(source.GetOutputDataObject(0).GetNumberOfCells() == 0, "the request after an abort packed again")
packed.Seed = 43
packed.UpdatePipeline()
check(source.GetOutputDataObject(0).GetNumberOfCells() > 150, "the update after an abort must pack again")

# Equal radii on the lattice: no packing, but thousands of fibers' points take seconds in a large
# cell; progress runs over them (not only 0 % and the end).
large = FiberCubeSource(Periodic=1, Seeding="Lattice", Populations=2, EdgeLength=60.0, VolumeFraction=0.7, Seed=42)
seen = []
tag = large.GetClientSideObject().AddObserver("ProgressEvent", lambda obj, event: seen.append(obj.GetProgress()))
large.UpdatePipeline()
large.GetClientSideObject().RemoveObserver(tag)
inside = sorted({round(p, 6) for p in seen if 0.0 < p < 0.7})
check(large.GetDataInformation().GetNumberOfCells() > 1000 and len(inside) >= 3,
      "lattice seeding of %d fibers reported progress %r" % (large.GetDataInformation().GetNumberOfCells(), inside))

tubes = FiberTubes(Input=solver, NumberOfSides=8)
compare_image(tubes, "bundle_id", position=(30, 24, 36))
print("test_periodic_cell passed")
