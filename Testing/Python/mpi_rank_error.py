"""pvbatch --symmetric under mpiexec -n 2: an error on one rank reaches every rank (FiberCollective).
The input is bad on rank 1 only (a negative radius); PLISimulation used to fail there alone while
PLIAnalysis on rank 0 waited in its reduction forever, and SaveData wrote rank 0's fibers only.
Now every rank reports an error, produces empty output and nobody hangs (an alarm kills a hung
rank long before the ctest timeout); SaveData fails on every rank and keeps the existing file; the
pipeline works again once the input is fixed. Every rank runs this script and checks itself."""
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, rank_fibers_script  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from vtkmodules.vtkParallelCore import vtkMultiProcessController  # noqa: E402

signal.alarm(100)  # a rank stuck in a collective dies instead of hanging
load_plugin(globals())
out_dir = sys.argv[2]
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId()
check(controller.GetNumberOfProcesses() == 2, "expected 2 MPI ranks")

# One fiber along x; its radius is BAD on rank 1 only (ProgrammableSource runs on every rank).
CELLS = "[[(-4.0 + 2.0 * k, 0.1 * rank, 0.0) for k in range(5)]]"
fibers = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=rank_fibers_script(CELLS, -1.0))

# (1) PLISimulation -> PLIAnalysis: both ranks fail, nobody waits.
sim = PLISimulation(Input=fibers, VolumeOfInterest=[-5, 5, -3, 3, -2, 2], VoxelSize=0.5, PixelSize=1.0,
                    NumberOfRotations=6, NoiseGain=0.0, NumberOfThreads=1)
ana = PLIAnalysis(Input=sim, NumberOfThreads=1)
sim_errors = ErrorCatcher(sim)
ana_errors = ErrorCatcher(ana)
ana.UpdatePipeline()
text = sim_errors.text()
if rank == 1:
    check("radius -1" in text, "rank 1: PLISimulation must name the bad radius: %r" % text)
else:
    check("rank 1 failed" in text and "radius -1" in text,
          "rank 0: PLISimulation must report rank 1's error: %r" % text)
check(sim.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() == 0, "rank %d: PLISimulation output" % rank)
check(ana.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() == 0, "rank %d: PLIAnalysis output" % rank)

# (1b) FiberOrientationGroundTruth: the fiber exchange agrees on the bad piece first, so both
# ranks fail with the message of rank 1 (FiberTileExchange.h).
truth = FiberOrientationGroundTruth(Input=fibers, VolumeOfInterest=[-5, 5, -3, 3, -2, 2], VoxelSize=0.5,
                                    PixelSize=1.0, NumberOfThreads=1)
truth_errors = ErrorCatcher(truth)
truth.UpdatePipeline()
text = truth_errors.text()
check("radius -1" in text and (rank == 1 or "rank 1 failed" in text),
      "rank %d: FiberOrientationGroundTruth must report rank 1's error: %r" % (rank, text))
check(truth.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() == 0, "rank %d: truth output" % rank)

# (2) SaveData gathers to rank 0, whose FiberWriter refuses the bad fiber: every rank fails and the
# existing file stays as it was.
target = os.path.join(out_dir, "fibers.dat")
if rank == 0:
    with open(target, "w") as f:
        f.write("0 0 0 1\n1 0 0 1\n")
controller.Barrier()
writer = CreateWriter(target, fibers)
outer_errors = ErrorCatcher(writer.GetClientSideObject())
inner_errors = ErrorCatcher(writer.GetClientSideObject().GetWriter())
writer.UpdatePipeline()
text = outer_errors.text() + inner_errors.text()
if rank == 0:
    check("radius -1" in text, "rank 0: the writer must name the bad radius: %r" % text)
else:
    check("rank 0 failed" in text and "radius -1" in text, "rank 1: the writer must report rank 0's error: %r" % text)
controller.Barrier()
with open(target) as f:
    check(f.read() == "0 0 0 1\n1 0 0 1\n", "rank %d: the existing file was changed" % rank)
check(sorted(os.listdir(out_dir)) == ["fibers.dat"], "left behind: %s" % os.listdir(out_dir))

# (3) Fixed input: everything works again on both ranks.
fibers.Script = rank_fibers_script(CELLS, 1.0)
sim_errors.clear()
ana_errors.clear()
ana.UpdatePipeline()
check(not sim_errors.errors and not ana_errors.errors, "rank %d: errors after the fix: %r" % (rank, sim_errors.text() + ana_errors.text()))
truth_errors.clear()
truth.UpdatePipeline()
check(not truth_errors.errors, "rank %d: truth errors after the fix: %r" % (rank, truth_errors.text()))
check(truth.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() > 0, "rank %d: no truth after the fix" % rank)
# Each rank holds its part of the 10 x 6 pixel image (pieces share a boundary row).
points = ana.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints()
check(0 < points < 10 * 6, "rank %d: analysis after the fix has %d points" % (rank, points))
outer_errors.clear()
inner_errors.clear()
writer.UpdatePipeline()
check(not outer_errors.errors and not inner_errors.errors, "rank %d: write errors after the fix" % rank)
controller.Barrier()
with open(target) as f:
    check(f.read().count("\n") >= 10, "rank %d: the fixed write is missing" % rank)
signal.alarm(0)
print("mpi_rank_error passed on rank %d" % rank)
