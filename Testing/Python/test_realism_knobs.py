"""pvpython: the realism knobs of FiberCubeSource (periodic and open) and FiberBundleSource, measured
with numpy on the output: per-fiber tortuosity, closure on lattice vectors, <cos^2> of the
end-to-end directions against the reported dispersion_c2, the crossing axes, the along-fiber radius
CV, inner_radius by both g-ratio models (and kept through the solver), bead phasing (radii only
turned, fewer beads meeting), coherent undulation (neighbours correlated, tortuosity kept), beads
kept through the solver, defaults leaving the fibers untouched, and the errors naming the property."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())
import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402


def fibers_of(proxy):
    """(points, radius, inner_radius or None, bundle_id) per fiber, and the polydata."""
    pd = servermanager.Fetch(proxy)
    pts = vtk_to_numpy(pd.GetPoints().GetData()) if pd.GetNumberOfPoints() else np.zeros((0, 3))
    rad = vtk_to_numpy(pd.GetPointData().GetArray("radius")) if pd.GetNumberOfPoints() else None
    inner_array = pd.GetPointData().GetArray("inner_radius")
    inner = vtk_to_numpy(inner_array) if inner_array is not None else None
    bid = pd.GetCellData().GetArray("bundle_id")
    out = []
    for c in range(pd.GetNumberOfCells()):
        ids = pd.GetCell(c).GetPointIds()
        idx = [ids.GetId(i) for i in range(ids.GetNumberOfIds())]
        out.append((pts[idx], rad[idx], inner[idx] if inner is not None else None, bid.GetValue(c)))
    return out, pd


def tortuosity(p):
    return np.linalg.norm(np.diff(p, axis=0), axis=1).sum() / np.linalg.norm(p[-1] - p[0])


def cv(values):
    return values.std() / values.mean()


EDGE = 24.0
# --- periodic cube: tortuosity, dispersion, beading, myelin --------------------------------------
cube = FiberCubeSource(Populations=2, NumberOfFibers=200, EdgeLength=EDGE, FiberRadius=0.8, Periodic=1,
                       Displacement=0.1, Seed=3, Tortuosity=1.05, UndulationWavelength=10.0,
                       DispersionC2=0.9, BeadingCV=0.2, BeadingLength=4.0, GRatio=0.65)
fibers, pd = fibers_of(cube)
check(len(fibers) == 200, "fiber count %d" % len(fibers))
taus = np.array([tortuosity(p) for p, _, _, _ in fibers])
check(np.all(np.abs(taus - 1.05) < 0.005), "periodic tortuosity range %g..%g" % (taus.min(), taus.max()))
reported = vtk_to_numpy(pd.GetFieldData().GetArray("dispersion_c2"))
for k in (0, 1):
    c2 = []
    for p, r, inner, b in fibers:
        if b != k:
            continue
        span = p[-1] - p[0]
        # Closed on a lattice vector: whole cell edges along every axis.
        check(np.allclose(span / EDGE, np.round(span / EDGE), atol=1e-9), "not a lattice vector: %s" % span)
        c2.append((span[k] / np.linalg.norm(span)) ** 2)
    c2 = np.array(c2)
    check(abs(c2.mean() - reported[k]) < 1e-12, "dispersion_c2 %g, measured %g" % (reported[k], c2.mean()))
    check(abs(c2.mean() - 0.9) < 0.015, "population %d c2 %g, asked 0.9" % (k, c2.mean()))
cvs = np.array([cv(r[:-1]) for _, r, _, _ in fibers])  # closed fibers: the last point repeats the first
check(np.all(np.abs(cvs - 0.2) < 1e-6), "radius CV %g..%g" % (cvs.min(), cvs.max()))
means = np.array([r[:-1].mean() for _, r, _, _ in fibers])
check(np.allclose(means, 0.8, rtol=1e-9), "mean radius per fiber must be FiberRadius")
for _, r, inner, _ in fibers:
    check(inner is not None and np.allclose(inner, 0.65 * r, rtol=1e-12), "inner_radius != 0.65 radius")

# --- myelin through the solver: inner_radius stays beside radius (interpolated where links split)
small = FiberCubeSource(Populations=2, VolumeFraction=0.3, EdgeLength=14.0, Periodic=1, Seed=5, GRatio=0.6,
                        Tortuosity=1.04, UndulationWavelength=7.0, Displacement=0.1)
solver = FiberCollisionSolver(Input=small, MaxSteps=2000, NumberOfThreads=2)
solved, spd = fibers_of(solver)
check(spd.GetFieldData().GetArray("solved").GetValue(0) == 1, "small realistic cell not solved")
for _, r, inner, _ in solved:
    check(inner is not None and np.allclose(inner, 0.6 * r, rtol=1e-12), "solver lost inner_radius")

# --- Lee2019 on a bundle: myelin thickness = 0.35 + 0.006 d + 0.024 ln d of the inner diameter d
bundle = FiberBundleSource(Shape="Cylinder", BundleRadius=8.0, Length=40.0, FiberRadius=1.0, RadiusSpread=0.3,
                           RadiusDistribution="Gamma", Displacement=0.1, Seed=2, Tortuosity=1.06,
                           UndulationWavelength=12.0, BeadingCV=0.25, DispersionC2=0.95, GRatio=0.5,
                           GRatioModel="Lee2019")
bfibers, _ = fibers_of(bundle)
check(len(bfibers) > 20, "bundle fibers %d" % len(bfibers))
btaus = np.array([tortuosity(p) for p, _, _, _ in bfibers])
check(np.all(np.abs(btaus - 1.06) < 0.01) and abs(btaus.mean() - 1.06) < 0.003, "bundle tortuosity %s" % btaus)
check(np.all(np.abs(np.array([cv(r) for _, r, _, _ in bfibers]) - 0.25) < 1e-6), "bundle radius CV")
for _, r, inner, _ in bfibers:
    d = 2.0 * inner
    check(np.allclose(r - inner, 0.35 + 0.006 * d + 0.024 * np.log(d), rtol=0, atol=1e-9), "Lee2019 closed form")

# --- open cube at a crossing angle: fibers along (cos 40°, sin 40°, 0), axes reported -------------
crossing = FiberCubeSource(Populations=2, NumberOfFibers=60, EdgeLength=20.0, Displacement=0.0, Seed=1,
                           CrossingAngle=40.0, PopulationShares=[2, 1, 1], Tortuosity=1.1)
cfibers, cpd = fibers_of(crossing)
axes = vtk_to_numpy(cpd.GetFieldData().GetArray("population_axes")).reshape(-1, 3)
check(np.allclose(axes[1], [math.cos(math.radians(40)), math.sin(math.radians(40)), 0.0]), "axes %s" % axes)
counts = [sum(1 for f in cfibers if f[3] == k) for k in (0, 1)]
check(counts == [40, 20], "shares 2:1 of 60 fibers gave %s" % counts)
for p, _, _, b in cfibers:
    d = (p[-1] - p[0]) / np.linalg.norm(p[-1] - p[0])
    check(abs(math.degrees(math.atan2(d[1], d[0])) - (40.0 if b == 1 else 0.0)) < 1e-6, "direction %s" % d)
    check(abs(tortuosity(p) - 1.1) < 1e-3, "open tortuosity %g" % tortuosity(p))

# --- periodic crossing at 45°: population 1 closes on (L, L, 0) -----------------------------------
diag = FiberCubeSource(Populations=2, NumberOfFibers=20, EdgeLength=20.0, Periodic=1, Seed=1, CrossingAngle=45.0)
for p, _, _, b in fibers_of(diag)[0]:
    check(np.allclose(p[-1] - p[0], [20.0, 20.0, 0.0] if b == 1 else [20.0, 0.0, 0.0], atol=1e-12), "closure")

# --- defaults: myelin alone adds an array and changes no point or radius -------------------------
plain = fibers_of(FiberCubeSource(Populations=2, NumberOfFibers=50, EdgeLength=20.0, Seed=9))[0]
myelin = fibers_of(FiberCubeSource(Populations=2, NumberOfFibers=50, EdgeLength=20.0, Seed=9, GRatio=0.7))[0]
for a, b in zip(plain, myelin):
    check(np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1]) and a[2] is None, "defaults changed")

# --- bead phasing: the same points, each fiber's radii turned cyclically, fewer beads meeting -----
def lattice_cell(phasing):
    return fibers_of(FiberCubeSource(Populations=1, VolumeFraction=0.7, EdgeLength=20.0, Periodic=1, Seed=4,
                                     Seeding="Lattice", Displacement=0.0, BeadingCV=0.25, BeadingLength=4.0,
                                     BeadPhasing=phasing))[0]


def overlapping_point_pairs(fibers):
    """Pairs of points of different fibers whose spheres overlap (minimum image in a 20 µm cell)."""
    pts = np.concatenate([p[:-1] for p, _, _, _ in fibers])
    rad = np.concatenate([r[:-1] for _, r, _, _ in fibers])
    owner = np.concatenate([np.full(len(p) - 1, i) for i, (p, _, _, _) in enumerate(fibers)])
    count = 0
    for i in range(len(pts)):
        d = pts[i + 1:] - pts[i]
        d -= 20.0 * np.round(d / 20.0)
        close = np.linalg.norm(d, axis=1) < rad[i + 1:] + rad[i]
        count += int(np.count_nonzero(close & (owner[i + 1:] != owner[i])))
    return count


drawn, turned = lattice_cell(0), lattice_cell(1)
check(len(drawn) == len(turned) and len(drawn) > 30, "lattice fibers %d / %d" % (len(drawn), len(turned)))
shifted = 0
for (pa, ra, _, _), (pb, rb, _, _) in zip(drawn, turned):
    check(np.array_equal(pa, pb), "BeadPhasing moved points")
    n = len(ra) - 1
    shifts = [s for s in range(n) if np.array_equal(np.roll(ra[:-1], -s), rb[:-1])]
    check(len(shifts) > 0 and rb[-1] == rb[0], "BeadPhasing must only turn a fiber's radii cyclically")
    shifted += shifts[0] != 0
check(shifted > 0, "BeadPhasing turned no fiber")
before, after = overlapping_point_pairs(drawn), overlapping_point_pairs(turned)
check(after < before, "beads meeting: %d drawn, %d phased" % (before, after))

# --- coherent undulation: neighbours bend together, every fiber keeps its tortuosity -------------
def neighbour_correlation(coherence):
    fibers = fibers_of(FiberCubeSource(Populations=1, NumberOfFibers=64, EdgeLength=24.0, Periodic=1, Seed=6,
                                       Seeding="Lattice", Displacement=0.0, Tortuosity=1.05,
                                       UndulationWavelength=8.0, UndulationCoherence=coherence))[0]
    taus = np.array([tortuosity(p) for p, _, _, _ in fibers])
    check(np.all(np.abs(taus - 1.05) < 0.005), "coherence %g: tortuosity %g..%g" % (coherence, taus.min(),
                                                                                    taus.max()))
    # Transverse (y, z) deviations from each fiber's mean axis, resampled on a common x grid.
    grid = np.linspace(0.0, 24.0, 49)[:-1]
    axes, devs = [], []
    for p, _, _, _ in fibers:
        x = p[:, 0] - p[0, 0]
        dev = np.stack([np.interp(grid, x, p[:, a]) for a in (1, 2)])
        axes.append(dev.mean(axis=1))
        devs.append((dev - dev.mean(axis=1, keepdims=True)).ravel())
    corr = []
    for i in range(len(fibers)):
        for j in range(i + 1, len(fibers)):
            d = axes[j] - axes[i]
            d -= 24.0 * np.round(d / 24.0)
            if np.linalg.norm(d) < 4.0:
                corr.append(np.dot(devs[i], devs[j]) / np.linalg.norm(devs[i]) / np.linalg.norm(devs[j]))
    return np.mean(corr)


independent, coherent = neighbour_correlation(0.0), neighbour_correlation(5.0)
check(abs(independent) < 0.2 and coherent > 0.5, "neighbour correlation %g independent, %g coherent"
      % (independent, coherent))

# --- KeepBeads: through the solver, a beaded fiber keeps its radii as drawn (mean, range, CV) -----
beaded = FiberCubeSource(Populations=1, VolumeFraction=0.5, EdgeLength=16.0, Periodic=1, Seed=8,
                         Displacement=0.3, BeadingCV=0.25, BeadingLength=4.0, Tortuosity=1.05,
                         UndulationWavelength=8.0)
kept = FiberCollisionSolver(Input=beaded, MaxSteps=3000, NumberOfThreads=2, KeepBeads=1)
inputs, (outputs, kpd) = fibers_of(beaded)[0], fibers_of(kept)
check(kpd.GetFieldData().GetArray("solved").GetValue(0) == 1, "KeepBeads cell at 0.5 not solved")
for (_, ri, _, _), (po, ro, _, _) in zip(inputs, outputs):
    seg = np.linalg.norm(np.diff(po, axis=0), axis=1)
    along = 0.5 * (ro[:-1] + ro[1:])  # the radius along the arc, by length
    check(abs(np.dot(seg, along) / seg.sum() / ri[:-1].mean() - 1.0) < 0.03, "KeepBeads changed a mean radius")
    check(ro.min() >= ri.min() - 1e-9 and ro.max() <= ri.max() + 1e-9, "KeepBeads radius outside the drawn range")
    check(abs(cv(ro[:-1]) - cv(ri[:-1])) < 0.05, "KeepBeads CV %g, drawn %g" % (cv(ro[:-1]), cv(ri[:-1])))

# --- bad values name the property; the pipeline recovers ----------------------------------------
bad = FiberCubeSource(Populations=2, NumberOfFibers=10, EdgeLength=20.0)
catcher = ErrorCatcher(bad)
for prop, value in (("Tortuosity", 0.9), ("Tortuosity", float("nan")), ("UndulationWavelength", 0.0),
                    ("DispersionC2", 0.3), ("DispersionC2", 1.5), ("BeadingCV", -0.1), ("GRatio", 1.2),
                    ("CrossingAngle", 120.0), ("PopulationShares", [1.0, -1.0, 1.0]), ("Arrangement", "Sheets"),
                    ("UndulationCoherence", -1.0), ("UndulationCoherence", float("nan"))):
    catcher.clear()
    kwargs = {prop: value}
    if prop == "UndulationWavelength":
        kwargs["Tortuosity"] = 1.1
    if prop == "Arrangement":
        kwargs["Populations"] = 3
    SetProperties(bad, **kwargs)
    bad.UpdatePipeline()
    check(prop in catcher.text(), "%s=%r: error must name it, got %r" % (prop, value, catcher.text()))
    check(servermanager.Fetch(bad).GetNumberOfLines() == 0, "no output on a bad value")
    SetProperties(bad, Populations=2, Tortuosity=1.0, UndulationWavelength=20.0, DispersionC2=1.0, BeadingCV=0.0,
                  GRatio=0.0, CrossingAngle=90.0, PopulationShares=[1, 1, 1], Arrangement="Auto",
                  UndulationCoherence=0.0)
bad.UpdatePipeline()
check(servermanager.Fetch(bad).GetNumberOfLines() == 10, "pipeline must recover")
bundle_bad = FiberBundleSource(GRatio=-0.5)
bcatcher = ErrorCatcher(bundle_bad)
bundle_bad.UpdatePipeline()
check("GRatio" in bcatcher.text(), "bundle error must name GRatio: %r" % bcatcher.text())
print("test_realism_knobs passed")
