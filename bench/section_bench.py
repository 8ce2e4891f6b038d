"""A whole section on one machine (bench/README.md "A millimetre section"):
    pvpython bench/section_bench.py <FiberPLI.so> [--size 1000] [--thickness 60] [--threads 2]
        [--seed-candidates 64] [--out folder]
An L × L × T µm section whose fibers follow an orientation field with bends and a crossing:
population A runs along x on sinusoidal paths y = y0 + a·sin(2πx/λ) (a 25 µm, λ 400 µm: the
steepest part 21° off x, the tightest bend of radius λ²/(4π²a) = 162 µm) at `--fraction-a` of the
volume; population B runs along y through a band |x − L/2| < `--band`·L/2, at `--fraction-b` of
the band's volume. Radii 1 µm, `SegmentLength` 2 µm. Phases, each timed (wall s) with the peak
resident memory of the process during it (VmHWM, reset before every phase):
  field  the grid of the field (10 µm spacing), NumPy;
  trace  FiberFieldSource (`SeedCandidates` 64: each fiber the least overlapping of 64 lines);
  solve  FiberCollisionSolver (SeparationSpeed 0.1, MaxDisplacement 0.4);
  check  an independent overlap check (NumPy/SciPy, no FiberPLI code) in `--boxes` random
         sub-volumes of (`--box` µm)² × T: every pair of links of different fibers whose capsules
         reach into the box, closest points by sampling both links, plus the union volume
         fraction of the capsules there by Monte Carlo;
  pli    PLISimulation over the whole section (VoxelSize 0.5 µm, PixelSize 1.3 µm, 9 rotations,
         untilted and 4 tilts of 5.5°), then PLIAnalysis; the simulation streams column tiles, so
         the section's voxels are never held at once;
  fom    (with --out) the fiber orientation map and a zoom on the tubes of one sub-volume as PNG.
The whole section's fiber volume fraction (Σ π r² · length / section volume) is printed for the
traced and the solved model."""
import argparse
import os
import sys
import time

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from scipy.spatial import cKDTree
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from section_field import section_field  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("plugin")
parser.add_argument("--size", type=float, default=1000.0, help="edge L of the section (µm)")
parser.add_argument("--thickness", type=float, default=60.0, help="T (µm)")
parser.add_argument("--fraction-a", type=float, default=0.57, help="population A's volume fraction")
parser.add_argument("--fraction-b", type=float, default=0.10, help="population B's in its band")
parser.add_argument("--band", type=float, default=0.3, help="B's band width over L")
parser.add_argument("--radius", type=float, default=1.0)
parser.add_argument("--threads", type=int, default=2)
parser.add_argument("--seed-candidates", type=int, default=64, help="FiberFieldSource's SeedCandidates")
parser.add_argument("--max-steps", type=int, default=20000)
parser.add_argument("--boxes", type=int, default=8)
parser.add_argument("--box", type=float, default=40.0)
parser.add_argument("--no-pli", action="store_true")
parser.add_argument("--save", default=None, help="write the solved section to this fiber file (.h5, .dat)")
parser.add_argument("--out", default=None, help="folder for the FOM and the tube zoom (PNG)")
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
L, T = args.size, args.thickness
rows = []


def memory():
    with open("/proc/self/status") as f:
        fields = dict(line.split(":", 1) for line in f)
    return int(fields["VmRSS"].split()[0]) / 1024.0, int(fields["VmHWM"].split()[0]) / 1024.0


def phase(name, work):
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")  # resets VmHWM to the current RSS: the peak of this phase alone
    start = time.time()
    result = work()
    seconds = time.time() - start
    rss, peak = memory()
    rows.append((name, seconds, peak, rss))
    print("%-6s %8.1f s  peak %7.0f MB  after %7.0f MB" % (name, seconds, peak, rss), flush=True)
    return result


def make_field():
    producer = TrivialProducer()
    producer.GetClientSideObject().SetOutput(section_field(L, T, args.band))
    return producer


def fibers_of(polydata):
    points = vtk_to_numpy(polydata.GetPoints().GetData()).astype(np.float64)
    radius = vtk_to_numpy(polydata.GetPointData().GetArray("radius")).astype(np.float64)
    lines = polydata.GetLines()
    offsets = vtk_to_numpy(lines.GetOffsetsArray()).astype(np.int64)
    conn = vtk_to_numpy(lines.GetConnectivityArray()).astype(np.int64)
    return points, radius, offsets, conn


def links_of(points, radius, offsets, conn):
    """Every link as its two end points, capsule radius and fiber index."""
    counts = np.diff(offsets)
    fiber = np.repeat(np.arange(len(counts)), counts)
    first = np.ones(len(conn), bool)
    first[offsets[:-1][counts > 0]] = False  # a link ends at every point but a fiber's first
    end = np.nonzero(first)[0]
    i, j = conn[end - 1], conn[end]
    return points[i], points[j], np.maximum(radius[i], radius[j]), fiber[end]


def fiber_fraction(a, b, rho):
    return float(np.sum(np.pi * rho ** 2 * np.linalg.norm(b - a, axis=1))) / (L * L * T)


def closest_distance(a1, b1, a2, b2, samples=24):
    """Smallest distance of two families of segments, by sampling both (own code)."""
    t = np.linspace(0.0, 1.0, samples)
    p = a1[:, None, :] + t[None, :, None] * (b1 - a1)[:, None, :]
    q = a2[:, None, :] + t[None, :, None] * (b2 - a2)[:, None, :]
    d = np.linalg.norm(p[:, :, None, :] - q[:, None, :, :], axis=-1)
    return d.reshape(len(a1), -1).min(axis=1)


def check(a, b, rho, fid):
    rng = np.random.default_rng(7)
    mid = 0.5 * (a + b)
    found, fractions = 0, []
    for _ in range(args.boxes):
        lo = rng.uniform(0.0, L - args.box, 2)
        reach = 2.0 * rho.max() + 4.0
        sel = np.nonzero(np.all((mid[:, :2] > lo - reach) & (mid[:, :2] < lo + args.box + reach), axis=1))[0]
        tree = cKDTree(mid[sel])
        half = 0.5 * np.linalg.norm(b[sel] - a[sel], axis=1)
        pairs = tree.query_pairs(2.0 * half.max() + 2.0 * rho.max(), output_type="ndarray")
        pairs = pairs[fid[sel][pairs[:, 0]] != fid[sel][pairs[:, 1]]]
        i, j = sel[pairs[:, 0]], sel[pairs[:, 1]]
        centre_gap = np.linalg.norm(mid[i] - mid[j], axis=1) - half[pairs[:, 0]] - half[pairs[:, 1]]
        near = centre_gap < rho[i] + rho[j]
        i, j = i[near], j[near]
        for s in range(0, len(i), 4000):
            c = slice(s, s + 4000)
            d = closest_distance(a[i[c]], b[i[c]], a[j[c]], b[j[c]])
            found += int(np.sum(d < rho[i[c]] + rho[j[c]] - 0.01))
        x = np.c_[rng.uniform(lo[0], lo[0] + args.box, 100000), rng.uniform(lo[1], lo[1] + args.box, 100000),
                  rng.uniform(0.0, T, 100000)]
        _, nearest = tree.query(x, k=16)  # a covering capsule is among the 16 nearest link centres
        m = sel[nearest]
        ab = b[m] - a[m]
        t = np.clip(np.einsum("ijk,ijk->ij", x[:, None, :] - a[m], ab) / np.maximum(np.einsum("ijk,ijk->ij", ab, ab),
                                                                                    1e-30), 0.0, 1.0)
        covered = np.any(np.linalg.norm(a[m] + t[..., None] * ab - x[:, None, :], axis=-1) < rho[m], axis=1)
        fractions.append(covered.mean())
    return found, fractions


WINDOW = (0.5 * L * (1.0 - args.band) - 30.0, 0.5 * L - 30.0)  # 60 µm wide, across the band's left edge


def window_of(polydata):
    """The runs of fiber points inside the 60 × 60 µm window (whole thickness) as polylines with
    their radius and bundle_id, for the tube picture."""
    points, radius, offsets, conn = fibers_of(polydata)
    bundle = vtk_to_numpy(polydata.GetCellData().GetArray("bundle_id"))
    x0, y0 = WINDOW
    out_points, out_radius, out_bundle, lines = [], [], [], vtkCellArray()
    first = 0  # index of the next run's first point in the window
    for f in range(len(offsets) - 1):
        ids = conn[offsets[f]:offsets[f + 1]]
        p = points[ids]
        inside = (p[:, 0] >= x0) & (p[:, 0] <= x0 + 60.0) & (p[:, 1] >= y0) & (p[:, 1] <= y0 + 60.0)
        if not inside.any():
            continue
        edges = np.flatnonzero(np.diff(np.r_[0, inside.astype(np.int8), 0]))
        for start, stop in zip(edges[::2], edges[1::2]):
            if stop - start < 2:
                continue
            out_points.append(p[start:stop])
            out_radius.append(radius[ids[start:stop]])
            out_bundle.append(bundle[f])
            lines.InsertNextCell(stop - start, list(range(first, first + stop - start)))
            first += stop - start
    window = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.concatenate(out_points), deep=1))
    window.SetPoints(pts)
    window.SetLines(lines)
    r = numpy_to_vtk(np.concatenate(out_radius), deep=1)
    r.SetName("radius")
    window.GetPointData().AddArray(r)
    b = numpy_to_vtk(np.asarray(out_bundle, dtype=np.int32), deep=1)
    b.SetName("bundle_id")
    window.GetCellData().AddArray(b)
    return window


def top_down(view, centre, half_height):
    view.CameraPosition = [centre[0], centre[1], centre[2] + 1000.0]
    view.CameraFocalPoint = centre
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = half_height


def white_view():
    view = CreateView("RenderView")
    view.ViewSize = [900, 900]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1, 1, 1]
    return view


def pictures(analysis, window):
    """The fiber orientation map of the whole section, and the tubes of a 60 µm window at the
    crossing band's edge, as PNG files in --out."""
    os.makedirs(args.out, exist_ok=True)
    fom = FiberOrientationMap(Input=analysis)
    view = white_view()
    Show(OutputPort(fom, 0), view)
    top_down(view, [0.5 * L, 0.5 * L, 0.5 * T], 0.5 * L)
    SaveScreenshot(os.path.join(args.out, "section_fom.png"), view, ImageResolution=[900, 900])
    Delete(view)
    producer = TrivialProducer()
    producer.GetClientSideObject().SetOutput(window)
    tubes = FiberTubes(Input=producer, NumberOfSides=12)
    view = white_view()
    display = Show(tubes, view)
    ColorBy(display, ("CELLS", "bundle_id"))
    x0, y0 = WINDOW
    view.CameraPosition = [x0 - 40.0, y0 - 70.0, T + 80.0]
    view.CameraFocalPoint = [x0 + 30.0, y0 + 30.0, 0.5 * T]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    SaveScreenshot(os.path.join(args.out, "section_tubes.png"), view, ImageResolution=[900, 900])
    Delete(view)


producer = phase("field", make_field)
source = FiberFieldSource(Input=producer, VolumeFraction=args.fraction_a + args.fraction_b * args.band,
                          FiberRadius=args.radius, SegmentLength=2.0, Seed=1,
                          SeedCandidates=args.seed_candidates, NumberOfThreads=args.threads)
source.OrientationArray = ["POINTS", "a"]
source.SecondOrientationArray = ["POINTS", "b"]
source.PopulationShares = [args.fraction_a, args.fraction_b * args.band]
phase("trace", source.UpdatePipeline)
traced = source.GetDataInformation()
print("traced: %d fibers, %d points, traced_volume_fraction %.3f" % (
    traced.GetNumberOfCells(), traced.GetNumberOfPoints(),
    source.FieldData["traced_volume_fraction"].GetRange()[0]), flush=True)
solver = FiberCollisionSolver(Input=source, SegmentLength=2.0, MaxSteps=args.max_steps, NumberOfThreads=args.threads,
                              SeparationSpeed=0.1, MaxDisplacement=0.4)
phase("solve", solver.UpdatePipeline)
solved = servermanager.Fetch(solver)
field = solved.GetFieldData()
print("solved: steps %d, collisions %d (the solver's count)" % (field.GetArray("steps").GetValue(0),
                                                                 field.GetArray("collisions").GetValue(0)), flush=True)
a, b, rho, fid = links_of(*fibers_of(solved))
print("fiber volume fraction of the section (sum pi r^2 length / volume): %.3f" % fiber_fraction(a, b, rho),
      flush=True)
overlaps, fractions = phase("check", lambda: check(a, b, rho, fid))
print("check: %d overlapping pairs in %d sub-volumes of %g x %g x %g um; union volume fraction there %s"
      % (overlaps, args.boxes, args.box, args.box, T, " ".join("%.3f" % f for f in fractions)), flush=True)
window = window_of(solved) if args.out else None
del solved, a, b, rho, fid
if args.save:
    phase("save", lambda: SaveData(args.save, proxy=solver))
if not args.no_pli:
    simulation = PLISimulation(Input=solver, VolumeOfInterest=[0.0, L, 0.0, L, 0.0, T], VoxelSize=0.5,
                               PixelSize=1.3, NumberOfRotations=9, TiltAngle=5.5, NumberOfThreads=args.threads)
    phase("pli", simulation.UpdatePipeline)
    analysis = PLIAnalysis(Input=simulation, NumberOfThreads=args.threads)
    phase("analysis", analysis.UpdatePipeline)
if args.out and not args.no_pli:
    phase("fom", lambda: pictures(analysis, window))
print("\n| phase | wall [s] | peak RSS [MB] |\n|---|---|---|")
for name, seconds, peak, _ in rows:
    print("| %s | %.1f | %.0f |" % (name, seconds, peak))
print("| all | %.1f | %.0f |" % (sum(r[1] for r in rows), max(r[2] for r in rows)))
