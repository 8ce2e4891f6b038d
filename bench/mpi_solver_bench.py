"""MPI benchmark of the distributed collision solver (bench/README.md "Distributed solver"):
    mpiexec -n R pvbatch bench/mpi_solver_bench.py <FiberPLI.so> <workload> [--threads T]
        [--max-steps N] [--size L] [--seed-candidates C]
Workloads: cube-a|cube-b|cube-c (the 1000-fiber cubes of solver_bench: 1/2/3 populations, edge
√3·30 µm, r 0.8 µm, point spacing 2 µm, displacement ±0.5 µm, seed 42, SegmentLength 2,
MinCurvatureRadius 4) and cell (the (100 µm)³ periodic cell, 2 populations, VolumeFraction 0.7,
Seeding Lattice, displacement 0.5 µm) and section (section_bench.py's recipe cut to an edge of
`--size` µm × 60 µm: FiberFieldSource, radius 1 µm, SegmentLength 2, seed 1, solved with
SeparationSpeed 0.1 and MaxDisplacement 0.4). The source makes the pieces; rank 0 times the solver's
update (the source is updated first and not timed) and prints one line: ranks, threads, steps, wall
seconds, seconds per step, collisions left, per rank its fibers, peak points held, of them halo,
the most links held for its pair tests, halo bytes sent per step, per rank its peak resident memory during the run (VmHWM) and its resident
memory before the solve (VmRSS after the source), per rank the CPU seconds of its solve, and a hash of the joined output (the same for
every R and T). --timeline also prints to stderr, per rank, the minor page faults of its solve (pages
the kernel handed it, each one's first touch) and, of rank 0's solver, the wall seconds since the
update began of every progress report (the solver reports at the end of every step and, from
200 000 links on, after every step's detection too; the last report is the finished solve), so
that the start, the steps and the end of a solve can be compared between rank counts."""
import argparse
import hashlib
import os
import sys
import tempfile
import time

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.util.numpy_support import vtk_to_numpy

parser = argparse.ArgumentParser()
parser.add_argument("plugin")
parser.add_argument("workload", choices=["cube-a", "cube-b", "cube-c", "cell", "section"])
parser.add_argument("--threads", type=int, default=1)
parser.add_argument("--max-steps", type=int, default=10000)
parser.add_argument("--size", type=float, default=250.0, help="section: edge L (µm)")
parser.add_argument("--max-fiber-length", type=float, default=0.0,
                    help="section: FiberFieldSource's MaxFiberLength (µm; 0 = lines end at the faces only)")
parser.add_argument("--seed-candidates", type=int, default=1,
                    help="section: FiberFieldSource's SeedCandidates (section_bench.py uses 64)")
parser.add_argument("--timeline", action="store_true",
                    help="also print the page faults per rank and rank 0's progress reports with their times (stderr)")
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()

if args.workload == "cell":
    source = FiberCubeSource(Populations=2, EdgeLength=100.0, Periodic=1, VolumeFraction=0.7, Seeding=1,
                             Displacement=0.5, Seed=42)
    solver = FiberCollisionSolver(Input=source, MaxSteps=args.max_steps, NumberOfThreads=args.threads)
elif args.workload == "section":
    # Every rank reads the field from a file (the script runs on rank 0 only), written in binary
    # mode: Debian's expat cannot read raw-appended XML.
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from section_field import section_field
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
    field_file = os.path.join(tempfile.mkdtemp(prefix="section_field_"), "field.vti")
    writer = vtkXMLImageDataWriter()
    writer.SetInputData(section_field(args.size, 60.0, 0.3))
    writer.SetDataModeToBinary()
    writer.SetFileName(field_file)
    writer.Write()
    field = XMLImageDataReader(FileName=[field_file])
    source = FiberFieldSource(Input=field, VolumeFraction=0.57 + 0.10 * 0.3, FiberRadius=1.0, SegmentLength=2.0,
                              MaxFiberLength=args.max_fiber_length, Seed=1, SeedCandidates=args.seed_candidates,
                              NumberOfThreads=args.threads)
    source.OrientationArray = ["POINTS", "a"]
    source.SecondOrientationArray = ["POINTS", "b"]
    source.PopulationShares = [0.57, 0.10 * 0.3]
    solver = FiberCollisionSolver(Input=source, SegmentLength=2.0, SeparationSpeed=0.1, MaxDisplacement=0.4,
                                  MaxSteps=args.max_steps, NumberOfThreads=args.threads)
else:
    source = FiberCubeSource(Populations=" abc".index(args.workload[-1]), NumberOfFibers=1000,
                             EdgeLength=3 ** 0.5 * 30.0, Seed=42)
    solver = FiberCollisionSolver(Input=source, SegmentLength=2.0, MinCurvatureRadius=4.0,
                                  MaxSteps=args.max_steps, NumberOfThreads=args.threads)
# Memory per rank: a ProgrammableFilter runs on every rank and puts that process's resident set
# (VmRSS) and peak (VmHWM, the high-water mark since the start) into field data: once after the
# source (the pvbatch process plus its input piece), once after the solve (the peak includes it).
MEMORY_SCRIPT = """
import resource
from vtkmodules.vtkCommonCore import vtkDoubleArray
with open("/proc/self/status") as status:
    kb = dict((l.split(":")[0], float(l.split()[1])) for l in status if l.startswith(("VmRSS", "VmHWM")))
usage = resource.getrusage(resource.RUSAGE_SELF)
values = {"VmRSS": kb["VmRSS"] / 1024.0, "VmHWM": kb["VmHWM"] / 1024.0, "cpu": usage.ru_utime + usage.ru_stime,
          "minflt": float(usage.ru_minflt)}
for name, value in values.items():
    a = vtkDoubleArray()
    a.SetName(name)
    a.InsertNextValue(value)
    self.GetOutput().GetFieldData().AddArray(a)
"""


def memory_probe(upstream):
    probe = ProgrammableFilter(Input=upstream, Script=MEMORY_SCRIPT)
    probe.UpdatePipeline()
    return probe


before = memory_probe(source)
reports = []  # (seconds since the update began, progress) of rank 0's solver
if args.timeline:
    solver.GetClientSideObject().AddObserver(
        "ProgressEvent", lambda algorithm, event: reports.append((time.perf_counter(), algorithm.GetProgress())))
start = time.perf_counter()
solver.UpdatePipeline()
wall = time.perf_counter() - start
after = memory_probe(solver)


def probed(probe, rank, name):
    return servermanager.Fetch(probe, rank).GetFieldData().GetArray(name).GetTuple1(0)


memory = ["%.0f / %.0f MiB" % (probed(after, r, "VmHWM"), probed(before, r, "VmRSS")) for r in range(ranks)]
# CPU seconds of each rank's process during the solve (user + system): what a rank costs when the
# machine is shared and wall time is not its own.
cpu = ["%.1f" % (probed(after, r, "cpu") - probed(before, r, "cpu")) for r in range(ranks)]
if args.timeline:
    sys.stderr.write("page faults per rank: %s\n" % " / ".join(
        "%.0f" % (probed(after, r, "minflt") - probed(before, r, "minflt")) for r in range(ranks)))
    for at, progress in reports:
        sys.stderr.write("progress %.6f at %.3f s\n" % (progress, at - start))

pieces = [servermanager.Fetch(solver, r) for r in range(ranks)]
h = hashlib.sha256()
for name in ("points", "radius"):
    for p in pieces:
        if p.GetNumberOfPoints() > 0:
            array = p.GetPoints().GetData() if name == "points" else p.GetPointData().GetArray(name)
            h.update(vtk_to_numpy(array).tobytes())
fd = pieces[0].GetFieldData()
steps = int(fd.GetArray("steps").GetTuple1(0))
share = []
for p in pieces:
    f = p.GetFieldData()
    if f.GetArray("rank_points"):
        share.append("%d fibers/%d pts/%d halo/%d held/%.0f B" % (p.GetNumberOfLines(), f.GetArray("rank_points").GetTuple1(0),
                     f.GetArray("halo_links").GetTuple1(0), f.GetArray("held_links").GetTuple1(0),
                     f.GetArray("halo_bytes_per_step").GetTuple1(0)))
print("| %s | %d | %d | %d | %.2f | %.4f | %d | %s | %s | %s | %s |" % (
    args.workload, ranks, args.threads, steps, wall, wall / (steps if steps > 0 else 1), int(fd.GetArray("collisions").GetTuple1(0)),
    "; ".join(share) if share else "-", "; ".join(memory), " / ".join(cpu), h.hexdigest()[:12]))
