"""The seed paper's cube table (pvbatch): 1, 2 and 3 perpendicular fiber populations, solved with
FiberCollisionSolver; prints steps, time, collisions left and the volume fraction in the central
cube, and writes a tube image per cube.

    pvbatch Examples/paper_cubes.py <FiberPLI.so> <output folder> [--fibers 1000] [--threads 0]

With 1000 fibers (the paper's size; a few minutes on 2 cores) the cube edge is √3·30 µm and the
volume fraction is measured by FiberMetrics (Monte Carlo, 400 000 points, ± its standard error) in
the central (30 µm)³,
as in the paper (65 / 52 / 45 % there; the
reference toolbox reaches 73 / 59 / 55 % with this construction). Fewer fibers keep the density:
edge √3·30·√(N/1000), central cube edge/√3.
"""
import passive_openmp  # noqa: F401  (first: restarts once with OMP_WAIT_POLICY=PASSIVE when unset)
import argparse
import math
import os
import time

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

parser = argparse.ArgumentParser()
parser.add_argument("plugin")
parser.add_argument("out")
parser.add_argument("--fibers", type=int, default=1000)
parser.add_argument("--threads", type=int, default=0)
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.out, exist_ok=True)


def summary(metrics):
    """The one-row Summary table of FiberMetrics as a dict of column -> first value."""
    metrics.UpdatePipeline()
    table = servermanager.Fetch(metrics, idx=1)
    columns = [table.GetColumn(c) for c in range(table.GetNumberOfColumns())]
    return {c.GetName(): c.GetValue(0) for c in columns if c.GetNumberOfComponents() == 1}


edge = math.sqrt(3.0) * 30.0 * math.sqrt(args.fibers / 1000.0)
print("%-6s %7s %7s %9s %8s %10s %14s %9s" % ("pops", "fibers", "steps", "time [s]", "solved", "collisions",
                                             "VF [%] ± s.e.", "min gap"))
for pops in (1, 2, 3):
    cube = FiberCubeSource(Populations=pops, NumberOfFibers=args.fibers, EdgeLength=edge, FiberRadius=0.8,
                           SegmentLength=2.0, Displacement=0.5, Seed=42)
    solver = FiberCollisionSolver(Input=cube, SegmentLength=2.0, MinCurvatureRadius=4.0, MaxSteps=100000,
                                  NumberOfThreads=args.threads)
    t0 = time.time()
    solver.UpdatePipeline()
    seconds = time.time() - t0
    solved = servermanager.Fetch(solver)
    field = solved.GetFieldData()
    # Volume fraction in the central cube and an independent collision count (FiberMetrics).
    half = edge / math.sqrt(3.0) / 2
    m = summary(FiberMetrics(Input=solver, Box=[-half, half] * 3, VolumeFractionMethod="MonteCarlo",
                             Samples=400000, Seed=1, NumberOfThreads=args.threads))
    print("%-6d %7d %7d %9.1f %8d %10d %8.1f ± %4.2f %9.1e" % (
        pops, args.fibers, field.GetArray("steps").GetValue(0), seconds, field.GetArray("solved").GetValue(0),
        m["collisions"], 100.0 * m["volume_fraction"], 100.0 * m["volume_fraction_error"], m["min_gap"]))
    if m["collisions"] != field.GetArray("collisions").GetValue(0):
        print("  the solver counts %d collisions" % field.GetArray("collisions").GetValue(0))

    tubes = FiberTubes(Input=solver, NumberOfSides=10, Capping=1)
    view = CreateView("RenderView")
    view.ViewSize = [800, 800]
    display = Show(tubes, view)
    ColorBy(display, ("CELLS", "bundle_id"))
    view.CameraPosition = [edge * 1.4, edge * 1.1, edge * 1.7]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    Render(view)
    SaveScreenshot(os.path.join(args.out, "cube_%dpop.png" % pops), view)
    Delete(view)
print("images in", args.out)
