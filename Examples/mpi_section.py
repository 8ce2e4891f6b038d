"""A section strip on R MPI ranks (pvbatch): a periodic cell of two perpendicular fiber populations
(in the section plane, along x and y) is generated, solved to zero overlaps and simulated as a
3D-PLI measurement (PLISimulation + PLIAnalysis) over a strip of several cells along x, the cell
tiling the strip. Every stage runs distributed over the ranks with the parallel engine of
ParaView: FiberCubeSource gives each rank its share of the fibers, FiberCollisionSolver solves them
over boxes with a halo exchange, PLISimulation gives each rank the fibers reaching its image tile,
PLIAnalysis analyses its tile; the result is bit for bit the one-process result for any rank
count. Prints what each stage did and how long it took.

    mpiexec -n 2 pvbatch Examples/mpi_section.py <FiberPLI.so> [--edge 30] [--strip 4]
        [--fraction 0.3] [--voxel 0.4] [--pixel 1.0] [--rotations 9] [--tilt 0] [--threads 1]
        [--max-steps 20000] [--out folder]

--out writes the solved fibers (.dat, gathered to one file) and the analysis maps (.pvti, one piece per rank).
Under mpiexec set OMP_WAIT_POLICY=PASSIVE in the shell (idle OpenMP threads must not spin on a busy node).
"""
import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import passive_openmp  # noqa: E402,F401  (serial runs: restarts with OMP_WAIT_POLICY=PASSIVE; set it for mpiexec)
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("plugin")
parser.add_argument("--edge", type=float, default=30.0, help="edge of the periodic cell (um)")
parser.add_argument("--strip", type=int, default=4, help="cells along x in the simulated strip")
parser.add_argument("--fraction", type=float, default=0.3, help="fiber volume fraction of the cell")
parser.add_argument("--voxel", type=float, default=0.4, help="PLISimulation VoxelSize (um)")
parser.add_argument("--pixel", type=float, default=1.0, help="PLISimulation PixelSize (um)")
parser.add_argument("--rotations", type=int, default=9)
parser.add_argument("--tilt", type=float, default=0.0, help="TiltAngle (degrees; 0 = no tilted views)")
parser.add_argument("--threads", type=int, default=1, help="OpenMP threads per rank")
parser.add_argument("--max-steps", type=int, default=20000)
parser.add_argument("--out", default=None)
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()


def field(proxy, name):
    """First value of a field-data array of the (distributed) output, from the data information."""
    info = proxy.FieldData.get(name) if hasattr(proxy.FieldData, "get") else proxy.FieldData[name]
    return info.GetRange(0)[0] if info else float("nan")


def timed(proxy):
    started = time.time()
    proxy.UpdatePipeline()
    return time.time() - started


half = 0.5 * args.edge
cell = FiberCubeSource(Populations=2, EdgeLength=args.edge, Periodic=1, VolumeFraction=args.fraction, Seed=42)
t_cell = timed(cell)
fibers = cell.GetDataInformation().GetNumberOfCells()
print("mpi_section: %d ranks x %d threads; cell (%.0f um)^3, 2 populations, %d fibers (%.2f volume fraction), "
      "made in %.1f s" % (ranks, args.threads, args.edge, fibers, args.fraction, t_cell))

solver = FiberCollisionSolver(Input=cell, MinCurvatureRadius=4.0, MaxSteps=args.max_steps,
                              NumberOfThreads=args.threads)
t_solve = timed(solver)
collisions = int(field(solver, "collisions"))
print("mpi_section: solved in %.1f s: %d steps, %d collisions left, volume fraction %.3f" % (
    t_solve, int(field(solver, "steps")), collisions, field(solver, "volume_fraction")))

strip = [-half * args.strip, half * args.strip, -half, half, -half, half]
sim = PLISimulation(Input=solver, VolumeOfInterest=strip, VoxelSize=args.voxel, PixelSize=args.pixel,
                    NumberOfRotations=args.rotations, TiltAngle=args.tilt)
t_sim = timed(sim)
dims = sim.GetDataInformation().GetExtent()
print("mpi_section: PLISimulation of the %.0f x %.0f x %.0f um strip (%d cells) in %.1f s: %d x %d pixels, "
      "%d rotations" % (strip[1] - strip[0], strip[3] - strip[2], strip[5] - strip[4], args.strip, t_sim,
                        dims[1] - dims[0] + 1, dims[3] - dims[2] + 1, args.rotations))

ana = PLIAnalysis(Input=sim)
t_ana = timed(ana)
retardation = ana.PointData["retardation"].GetRange(0)
transmittance = ana.PointData["transmittance"].GetRange(0)
print("mpi_section: PLIAnalysis in %.1f s: retardation %.3f .. %.3f, transmittance %.3f .. %.3f" % (
    t_ana, retardation[0], retardation[1], transmittance[0], transmittance[1]))

if args.out:
    os.makedirs(args.out, exist_ok=True)
    SaveData(os.path.join(args.out, "section_fibers.dat"), proxy=solver)
    SaveData(os.path.join(args.out, "section_maps.pvti"), proxy=ana, DataMode="Binary")
    print("mpi_section: wrote %s/section_fibers.dat and section_maps.pvti" % args.out)

print("mpi_section: done in %.1f s (%s)" % (t_cell + t_solve + t_sim + t_ana,
                                           "solved" if collisions == 0 else "NOT solved: raise --max-steps"))
