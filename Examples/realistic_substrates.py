"""Realistic periodic substrates (pvbatch): a corpus-callosum-like cell (one population, undulating,
beaded, myelinated), interwoven crossing regions (two populations at 90° and at 45°) and three
interwoven populations, made by
FiberCubeSource with its realism knobs, solved by FiberCollisionSolver keeping the tortuosity (and
holding it from above in the crossings: HoldTortuosity), and
measured by FiberMetrics. Prints one row per cell and population (FiberMetrics' figures: volume
fraction over the cell with all periodic images, collisions, tortuosity, c2 of segments, radius CV,
g-ratio, myelin and axon fractions, mixing) and renders every cell: outer tubes coloured by fiber,
and the axons inside the myelin (FiberTubes InnerTubes) in a cut-away view.

    pvbatch Examples/realistic_substrates.py <FiberPLI.so> <output folder> [--edge 40] [--threads 2]
        [--size 480] [--cells NAME ...]

Cells: corpus_callosum, crossing, crossing_45, three_populations (the default: all four), and
corpus_callosum_large, the corpus-callosum recipe for large cells above 80 % (beads over 8 µm and
the solver's momentum for its first 500 steps; `--cells corpus_callosum_large --edge 100` takes
about 4 minutes on two threads).

The figures and how they compare with the targets are in bench/README.md, "Realistic substrates"
(measured there by the benchmark's own code); this example is the user's version of the recipe.
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
parser.add_argument("--edge", type=float, default=40.0)
parser.add_argument("--threads", type=int, default=2)
parser.add_argument("--max-steps", type=int, default=6000)
parser.add_argument("--size", type=int, default=480, help="pixels of every picture (square)")
parser.add_argument("--cells", nargs="*", default=["corpus_callosum", "crossing", "crossing_45", "three_populations"])
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.out, exist_ok=True)

CELLS = {
    # corpus callosum: tortuosity ≈ 1.03–1.06, radius CV 0.15–0.3, g-ratio 0.6–0.7
    "corpus_callosum": (dict(Populations=1, Seeding="Lattice", VolumeFraction=0.87, Tortuosity=1.03,
                             UndulationWavelength=10.0, BeadingCV=0.16, BeadingLength=16.0, GRatio=0.7),
                        dict(Tortuosity=1.03)),
    # the same for large cells, denser: coherent undulation, beads over 8 µm (a periodic cell bounds
    # the beads' length, so longer ones would differ between cell sizes), half the push, and momentum
    # for the first 500 steps (docs/tissue-models.md §10.6)
    "corpus_callosum_large": (dict(Populations=1, Seeding="Lattice", VolumeFraction=0.89, Tortuosity=1.03,
                                   UndulationWavelength=10.0, UndulationCoherence=5.0, BeadingCV=0.17,
                                   BeadingLength=8.0, GRatio=0.7),
                              dict(Tortuosity=1.03, SeparationSpeed=0.0125, TortuosityWavelength=15.0, Drag=0.8,
                                   DragSteps=500)),
    # crossing region: two populations interwoven at 90° (or 45°: population 1 along (1, 1, 0)); in
    # a dense crossing the fibers weave over and under each other, which adds about 0.1 to the
    # tortuosity they were made with: HoldTortuosity solves again from less undulating shapes until
    # each population's mean is the one asked (docs/solver.md §5.5); VolumeFraction counts the
    # lengths as made, so it is set above the fraction wanted
    "crossing": (dict(Populations=2, Seeding="Random", Arrangement="Interwoven", CrossingAngle=90.0,
                      VolumeFraction=0.72, Tortuosity=1.25, UndulationWavelength=15.0, BeadingCV=0.22,
                      BeadingLength=8.0, GRatio=0.7),
                 dict(Tortuosity=1.25, HoldTortuosity=1)),
    "crossing_45": (dict(Populations=2, Seeding="Random", Arrangement="Interwoven", CrossingAngle=45.0,
                         VolumeFraction=0.72, Tortuosity=1.25, UndulationWavelength=15.0, BeadingCV=0.22,
                         BeadingLength=8.0, GRatio=0.7),
                    dict(Tortuosity=1.25, HoldTortuosity=1)),
    # three populations interwoven along x, y and z
    "three_populations": (dict(Populations=3, Seeding="Random", Arrangement="Interwoven", VolumeFraction=0.62,
                               Tortuosity=1.15, UndulationWavelength=15.0, GRatio=0.7),
                          dict(Tortuosity=1.15, HoldTortuosity=1)),
}


def table(proxy, port):
    proxy.UpdatePipeline()
    t = servermanager.Fetch(proxy, idx=port)
    return [{t.GetColumnName(c): t.GetColumn(c).GetValue(r) for c in range(t.GetNumberOfColumns())}
            for r in range(t.GetNumberOfRows())]


def render(solved, name):
    """Outer tubes coloured by fiber from a corner; beside it the axons (inner tubes) alone."""
    tubes = FiberTubes(Input=solved, NumberOfSides=12, InnerTubes=1)
    for part, surface in (("tubes", 0), ("axons", 1)):
        only = Threshold(Input=tubes, Scalars=["CELLS", "tube_surface"], LowerThreshold=surface,
                         UpperThreshold=surface)
        view = CreateView("RenderView")
        view.ViewSize = [args.size, args.size]
        view.OrientationAxesVisibility = 0
        display = Show(only, view)
        ColorBy(display, ("CELLS", "fiber_id"))
        display.LookupTable = GetColorTransferFunction("fiber_id")
        display.LookupTable.ApplyPreset("Rainbow Uniform", True)
        view.CameraPosition = [1.5, 1.2, 1.8]
        view.CameraFocalPoint = [0.0, 0.0, 0.0]
        view.CameraViewUp = [0, 1, 0]
        view.ResetCamera()
        Render(view)
        SaveScreenshot(os.path.join(args.out, "%s_%s.png" % (name, part)), view, CompressionLevel="9")
        Delete(view)
        Delete(only)
    Delete(tubes)


print("| cell | population | fibers | steps | solve [s] | volume fraction | collisions | tortuosity mean [min, max] "
      "| c2 segments | radius CV | g-ratio | myelin / axon fraction | mixing |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
unknown = [name for name in args.cells if name not in CELLS]
if unknown:
    raise SystemExit("unknown cell %s; cells: %s" % (", ".join(unknown), ", ".join(CELLS)))
for name in args.cells:
    knobs, solver_knobs = CELLS[name]
    cell = FiberCubeSource(Periodic=1, EdgeLength=args.edge, FiberRadius=1.0, RadiusDistribution="Gamma",
                           RadiusSpread=0.5, SegmentLength=2.0, Displacement=0.0, Seed=42, **knobs)
    cell.UpdatePipeline()
    solved = FiberCollisionSolver(Input=cell, SegmentLength=2.0, MaxDisplacement=0.4, MaxSteps=args.max_steps,
                                  NumberOfThreads=args.threads, **solver_knobs)
    start = time.time()
    solved.UpdatePipeline()
    seconds = time.time() - start
    steps = servermanager.Fetch(solved).GetFieldData().GetArray("steps").GetValue(0)
    metrics = FiberMetrics(Input=solved, UsePeriodicCell=1, VolumeFractionMethod="MonteCarlo", Samples=400000,
                           NumberOfThreads=args.threads)
    summary = table(metrics, 1)[0]
    for row in table(metrics, 3):
        print("| %s | %d | %d | %d | %.1f | %.1f ± %.1f %% | %d | %.3f [%.3f, %.3f] | %.3f | %.3f | %.2f | %.1f / %.1f %% | %.2f |" % (
            name, row["bundle_id"], row["fibers"], steps, seconds, 100 * summary["volume_fraction"],
            100 * summary["volume_fraction_error"], summary["collisions"], row["tortuosity_mean"],
            row["tortuosity_min"], row["tortuosity_max"], row["c2_segments"], row["radius_cv"], row["g_ratio_mean"],
            100 * summary["myelin_fraction"], 100 * summary["axon_fraction"], row["mixing_min_share"]))
    render(solved, name)
    Delete(metrics)
    Delete(solved)
    Delete(cell)
print("pictures in %s" % args.out)
