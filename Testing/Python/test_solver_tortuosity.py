"""pvpython: FiberCollisionSolver's Tortuosity keeps undulating fibers undulating (docs/solver.md
§5.3). A dense periodic cell of Gamma radii is given a smooth random undulation of tortuosity
1.04 here (numpy, independent of the sources); solved without the rule the pushes flatten it,
with it the solved cell keeps 1.04 within a tenth of the excess and has no overlap, also by a
brute-force capsule check of its own. A bad value (Tortuosity, TortuosityWavelength) names the
property. HoldTortuosity (§5.5): a dense interwoven crossing made at 1.25 solves beyond it (its
weave comes on top), held it solves at 1.25 per population; combined with what it cannot serve it
names both properties and the pipeline recovers."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402

load_plugin(globals())

EDGE, TARGET = 20.0, 1.04
straight = servermanager.Fetch(FiberCubeSource(
    Populations=1, EdgeLength=EDGE, FiberRadius=1.0, RadiusSpread=0.5, RadiusDistribution="Gamma", Periodic=1,
    VolumeFraction=0.70, Seeding="Lattice", SegmentLength=1.0, Displacement=0.0, Seed=5))
points = vtk_to_numpy(straight.GetPoints().GetData()).copy()
lines = straight.GetLines()
conn = vtk_to_numpy(lines.GetConnectivityArray())
offsets = vtk_to_numpy(lines.GetOffsetsArray())
fibers = [conn[offsets[i]:offsets[i + 1]] for i in range(len(offsets) - 1)]
axis = int(np.argmax(np.abs(points[fibers[0][-1]] - points[fibers[0][0]])))
across = [d for d in range(3) if d != axis]


def tortuosity(p):
    return np.sum(np.linalg.norm(np.diff(p, axis=0), axis=1)) / np.linalg.norm(p[-1] - p[0])


# Every fiber: two random waves of wavelength EDGE/2 (periodic over the cell), scaled by bisection
# to the target tortuosity.
rng = np.random.default_rng(1)
for f in fibers:
    s = points[f, axis] - points[f[0], axis]
    wave = np.zeros((len(f), 3))
    for d in across:
        wave[:, d] = np.sin(4.0 * np.pi * s / EDGE + rng.uniform(0.0, 2.0 * np.pi))
    lo, hi = 0.0, 5.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if tortuosity(points[f] + mid * wave) < TARGET else (lo, mid)
    points[f] += lo * wave
model = vtkPolyData()
model.DeepCopy(straight)
model.GetPoints().SetData(numpy_to_vtk(points, deep=1))
undulating = TrivialProducer()
undulating.GetClientSideObject().SetOutput(model)


def solved_tortuosity(proxy):
    out = servermanager.Fetch(proxy)
    p = vtk_to_numpy(out.GetPoints().GetData())
    c = vtk_to_numpy(out.GetLines().GetConnectivityArray())
    o = vtk_to_numpy(out.GetLines().GetOffsetsArray())
    return out, np.array([tortuosity(p[c[o[i]:o[i + 1]]]) for i in range(len(o) - 1)])


def field(out, name):
    return out.GetFieldData().GetArray(name).GetValue(0)


flat = FiberCollisionSolver(Input=undulating, SegmentLength=1.0, MaxSteps=5000, MaxDisplacement=0.4, NumberOfThreads=2)
flat.UpdatePipeline()
out, tau = solved_tortuosity(flat)
check(field(out, "collisions") == 0, "the cell without Tortuosity is not solved")
print("without Tortuosity: mean tortuosity %.4f" % tau.mean())
check(tau.mean() < 1.0 + 0.75 * (TARGET - 1.0), "the pushes did not flatten the fibers (%.4f)" % tau.mean())

kept = FiberCollisionSolver(Input=undulating, SegmentLength=1.0, MaxSteps=5000, MaxDisplacement=0.4, NumberOfThreads=2,
                            Tortuosity=TARGET)
kept.UpdatePipeline()
out, tau = solved_tortuosity(kept)
print("with Tortuosity %.2f: mean tortuosity %.4f (%.4f-%.4f), %d steps" % (TARGET, tau.mean(), tau.min(), tau.max(),
                                                                        field(out, "steps")))
check(field(out, "collisions") == 0 and field(out, "shape_ok") == 1, "the cell with Tortuosity is not solved")
check(abs(tau.mean() - TARGET) <= 0.1 * (TARGET - 1.0), "mean tortuosity %.4f, asked %.2f" % (tau.mean(), TARGET))
check(tau.min() >= TARGET - 0.05 * (TARGET - 1.0) - 1e-9, "a fiber fell below the tolerance: %.4f" % tau.min())

# No two capsules of different fibers overlap, by brute force over the minimum image.
p = vtk_to_numpy(out.GetPoints().GetData())
r = vtk_to_numpy(out.GetPointData().GetArray("radius"))
c = vtk_to_numpy(out.GetLines().GetConnectivityArray())
o = vtk_to_numpy(out.GetLines().GetOffsetsArray())
a, b, rho, fid = [], [], [], []
for i in range(len(o) - 1):
    ids = c[o[i]:o[i + 1]]
    a.append(p[ids[:-1]]); b.append(p[ids[1:]]); rho.append(np.maximum(r[ids[:-1]], r[ids[1:]]))
    fid.append(np.full(len(ids) - 1, i))
a, b, rho, fid = map(np.concatenate, (a, b, rho, fid))


def segment_distance(p0, p1, q0, q1):
    # Closest points of segments p0-p1 and q0-q1 (arrays, minimum image), by sampling both finely
    # enough for a tolerance far below the radii: 65 x 65 points per pair of ~1 µm links.
    t = np.linspace(0.0, 1.0, 65)
    P = p0[:, None, :] + t[None, :, None] * (p1 - p0)[:, None, :]
    Q = q0[:, None, :] + t[None, :, None] * (q1 - q0)[:, None, :]
    d = P[:, :, None, :] - Q[:, None, :, :]
    d -= EDGE * np.round(d / EDGE)
    return np.sqrt((d ** 2).sum(-1)).min(axis=(1, 2))


mid = 0.5 * (a + b)
worst = np.inf
for i in range(len(a)):
    d = mid - mid[i]
    d -= EDGE * np.round(d / EDGE)
    near = np.where((np.sqrt((d ** 2).sum(1)) < rho + rho[i] + 1.5) & (fid != fid[i]))[0]
    near = near[near > i]
    if len(near):
        gap = segment_distance(np.repeat(a[i:i + 1], len(near), 0), np.repeat(b[i:i + 1], len(near), 0),
                               a[near], b[near]) - rho[near] - rho[i]
        worst = min(worst, gap.min())
print("smallest capsule gap (sampled): %.4f um" % worst)
check(worst > -0.01, "capsules overlap by %.4f um" % -worst)

catcher = ErrorCatcher(kept)
kept.Tortuosity = 5.0
kept.UpdatePipeline()
check("Tortuosity" in catcher.text() and "5" in catcher.text(), "error must name Tortuosity: %r" % catcher.text())
kept.Tortuosity = TARGET
for value, text in ((-2.0, "-2"), (float("nan"), "nan")):
    catcher = ErrorCatcher(kept)
    kept.TortuosityWavelength = value
    kept.UpdatePipeline()
    check("TortuosityWavelength" in catcher.text() and text in catcher.text().lower(),
          "error must name TortuosityWavelength and %s: %r" % (text, catcher.text()))

# HoldTortuosity: a dense interwoven crossing, measured per population with the numpy tortuosity.
HELD = 1.25
crossing = FiberCubeSource(Populations=2, EdgeLength=16.0, FiberRadius=0.8, Periodic=1, VolumeFraction=0.55,
                           Seeding="Random", Arrangement="Interwoven", SegmentLength=1.0, Displacement=0.0, Seed=5,
                           Tortuosity=HELD, UndulationWavelength=8.0)
hold = FiberCollisionSolver(Input=crossing, SegmentLength=1.0, MaxSteps=4000, MaxDisplacement=0.4,
                            NumberOfThreads=2, Tortuosity=HELD)
check(not hold.HoldTortuosity, "HoldTortuosity must default to off")


def population_means(proxy):
    out, tau = solved_tortuosity(proxy)
    bundle = vtk_to_numpy(out.GetCellData().GetArray("bundle_id"))
    return out, [tau[bundle == b].mean() for b in (0, 1)]


hold.UpdatePipeline()
out, means = population_means(hold)
print("crossing without HoldTortuosity: %.4f / %.4f" % tuple(means))
check(field(out, "collisions") == 0, "the crossing is not solved")
check(min(means) > HELD + 0.1 * (HELD - 1.0), "the weave did not lengthen the crossing: %r" % means)
check(out.GetFieldData().GetArray("tortuosity_solves") is None, "tortuosity_solves without a hold")
hold.HoldTortuosity = 1
hold.UpdatePipeline()
out, means = population_means(hold)
print("crossing with HoldTortuosity: %.4f / %.4f in %d solves" % (means[0], means[1],
                                                                   field(out, "tortuosity_solves")))
check(field(out, "collisions") == 0, "the held crossing is not solved")
check(field(out, "tortuosity_solves") >= 2, "the hold solved once")
for m in means:
    check(abs(m - HELD) <= 0.05 * (HELD - 1.0), "held crossing at %.4f, asked %.2f" % (m, HELD))
held_points = vtk_to_numpy(out.GetPoints().GetData()).copy()

for prop, value in (("IterationsAsTime", 1), ("CheckpointInterval", 10)):
    catcher = ErrorCatcher(hold)
    setattr(hold, prop, value)
    hold.UpdatePipeline()
    check("HoldTortuosity" in catcher.text() and prop in catcher.text(),
          "error must name HoldTortuosity and %s: %r" % (prop, catcher.text()))
    setattr(hold, prop, 0)
catcher = ErrorCatcher(hold)
hold.Tortuosity = 0.0
hold.UpdatePipeline()
check("Tortuosity" in catcher.text() and "HoldTortuosity" in catcher.text(),
      "error must name Tortuosity with HoldTortuosity: %r" % catcher.text())
hold.Tortuosity = HELD
hold.UpdatePipeline()
out = servermanager.Fetch(hold)
check(np.array_equal(vtk_to_numpy(out.GetPoints().GetData()), held_points),
      "pipeline must recover and solve the same held crossing")
print("test_solver_tortuosity passed")
