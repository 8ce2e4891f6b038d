"""Dense periodic cells (pvbatch): 1, 2 and 3 perpendicular populations in a periodic cube
(FiberCubeSource Periodic=1 with a VolumeFraction target), solved by FiberCollisionSolver; prints
the density table (target, fibers, the solver's volume_fraction, FiberMetrics' independent Monte
Carlo measure over the cell with all periodic images, collisions, smallest gap, steps, time) and
renders every solved cell with its tubes, plus a 2 x 2 x 2 tiling of the first one to show that the
cell tiles space, and a large cell of two populations.

    pvbatch Examples/periodic_cells.py <FiberPLI.so> <output folder> [--edge 30]
        [--targets 0.85,0.72,0.58] [--large-edge 100] [--large-target 0.70]
        [--seeding Lattice|Random] [--threads 2] [--max-steps 20000] [--size 440]

The defaults are the dense-cell benchmark (bench/README.md "Lattice seeding, equal radii"): a (30 µm)³ cell
(r = 0.8 µm, points 2 µm apart, displacement 0.5 µm, seed 42, MinCurvatureRadius 4 µm) with
Seeding = Lattice at 85 / 72 / 58 %, which solve without overlaps in 1 327 / 44 / 50 steps, and a
(100 µm)³ cell of two populations at 70 % (3 482 fibers, 65 steps; --large-edge 0 leaves it out).
A VolumeFraction target gives the smallest fiber count that reaches it (0.85: 381 fibers, 85.1 %).
With --seeding Random the densest targets solved are about 0.75, 0.50, 0.48; denser ones stop at
--max-steps with overlaps left, and the table then shows how many.
"""
import passive_openmp  # noqa: F401  (first: restarts once with OMP_WAIT_POLICY=PASSIVE when unset)
import argparse
import os
import time

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

parser = argparse.ArgumentParser()
parser.add_argument("plugin")
parser.add_argument("out")
parser.add_argument("--edge", type=float, default=30.0)
parser.add_argument("--targets", default="0.85,0.72,0.58")
parser.add_argument("--large-edge", type=float, default=100.0, help="edge of the large cell, 0 = none")
parser.add_argument("--large-target", type=float, default=0.70)
parser.add_argument("--seeding", choices=("Lattice", "Random"), default="Lattice")
parser.add_argument("--threads", type=int, default=2)
parser.add_argument("--max-steps", type=int, default=20000)
parser.add_argument("--size", type=int, default=440, help="pixels of every picture (square)")
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.out, exist_ok=True)
targets = [float(t) for t in args.targets.split(",")]


def summary(metrics):
    """The one-row Summary table of FiberMetrics as a dict of column -> first value."""
    metrics.UpdatePipeline()
    table = servermanager.Fetch(metrics, idx=1)
    return {table.GetColumnName(c): table.GetColumn(c).GetValue(0) for c in range(table.GetNumberOfColumns())}


def render(source, name, size):
    """The tubes of source coloured by bundle, seen from a corner, the whole model in the picture."""
    tubes = FiberTubes(Input=source, NumberOfSides=10)
    view = CreateView("RenderView")
    view.ViewSize = [size, size]
    view.OrientationAxesVisibility = 0
    display = Show(tubes, view)
    ColorBy(display, ("CELLS", "bundle_id"))
    view.CameraPosition = [1.5, 1.2, 1.8]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0, 1, 0]
    view.ResetCamera()
    Render(view)
    SaveScreenshot(os.path.join(args.out, name), view, CompressionLevel="9")
    Delete(view)
    Delete(tubes)


def solve_cell(pops, edge, target, image, size):
    """Builds, solves, measures and renders one cell; prints its row; returns the solver."""
    cube = FiberCubeSource(Populations=pops, EdgeLength=edge, Periodic=1, VolumeFraction=target,
                           FiberRadius=0.8, SegmentLength=2.0, Displacement=0.5, Seed=42,
                           Seeding=args.seeding)
    solver = FiberCollisionSolver(Input=cube, SegmentLength=2.0, MinCurvatureRadius=4.0,
                                  MaxSteps=args.max_steps, NumberOfThreads=args.threads)
    t0 = time.time()
    solver.UpdatePipeline()
    seconds = time.time() - t0
    field = servermanager.Fetch(solver).GetFieldData()
    # Monte Carlo over the whole cell with every periodic image (standard error 0.04 % at 1e6).
    m = summary(FiberMetrics(Input=solver, UsePeriodicCell=1, VolumeFractionMethod="MonteCarlo",
                             Samples=1000000, NumberOfThreads=args.threads))
    print("%6.0f %-5d %6.0f%% %7d %11.1f%% %8.1f ± %4.2f%% %10d %9.4f %7d %9.1f" % (
        edge, pops, 100 * target, servermanager.Fetch(cube).GetNumberOfLines(),
        100 * field.GetArray("volume_fraction").GetValue(0), 100 * m["volume_fraction"],
        100 * m["volume_fraction_error"], m["collisions"], m["min_gap"],
        field.GetArray("steps").GetValue(0), seconds))
    render(solver, image, size)
    return solver


print("%6s %-5s %7s %7s %12s %15s %10s %9s %7s %9s" % (
    "cell", "pops", "target", "fibers", "solver VF", "metrics VF", "collisions", "min gap", "steps", "time [s]"))
first = None
for pops, target in zip((1, 2, 3), targets):
    solver = solve_cell(pops, args.edge, target, "periodic_cell_%dpop.png" % pops, args.size)
    if first is None:
        first = solver
if args.large_edge > 0:
    # Smaller: thousands of thin tubes make a large PNG.
    solve_cell(2, args.large_edge, args.large_target, "periodic_cell_large.png", args.size * 3 // 4)

# The first cell and its 7 translates by the lattice vectors: the fibers continue across the faces.
pieces = []
for i in (0, 1):
    for j in (0, 1):
        for k in (0, 1):
            t = Transform(Input=first)
            t.Transform.Translate = [i * args.edge, j * args.edge, k * args.edge]
            pieces.append(t)
render(AppendGeometry(Input=pieces), "periodic_cell_tiled.png", args.size)
print("images in", args.out)
