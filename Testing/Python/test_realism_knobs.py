"""pvpython: the realism knobs of FiberCubeSource (periodic and open) and FiberBundleSource, measured
with numpy on the output: per-fiber tortuosity, closure on lattice vectors, <cos^2> of the
end-to-end directions against the reported dispersion_c2, the crossing axes, the along-fiber radius
CV, inner_radius by both g-ratio models (and kept through the solver), defaults leaving the
fibers untouched, and the errors naming the property."""
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
