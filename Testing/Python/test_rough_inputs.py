"""pvpython: single properties and files a hostile user tries, each answered by one clear error
naming the property or file and the value in short form, in bounded time, with the pipeline usable
afterwards:
- RadiusSpread 1e300 (and 1000) with LogNormal radii, Lattice seeding: used to crash (the radii
  underflowed to 0 and an empty disk packing was read); both sources refuse it;
- a number like 1e300 is written "1e+300", never with 301 digits;
- PLISimulation reports an error once per update (it used to report it for both output ports);
- FileName and ResumeFromCheckpoint naming a FIFO: used to block forever; refused at once."""
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402

signal.alarm(120)  # a blocked read fails the test instead of hanging it
load_plugin(globals())
tmp = option("-T")


def errors_of(proxy):
    catcher = ErrorCatcher(proxy)
    proxy.UpdatePipeline()
    return [e for e in catcher.errors if "returned failure for request" not in e]


for spread in (1e300, 1000.0):
    cube = FiberCubeSource(Populations=1, EdgeLength=20, Periodic=1, NumberOfFibers=50,
                           RadiusDistribution="LogNormal", RadiusSpread=spread, Seeding="Lattice")
    text = "\n".join(errors_of(cube))
    short = "1e+300" if spread == 1e300 else "1000"
    check("RadiusSpread is %s, must be <= 2 for RadiusDistribution LogNormal" % short in text,
          "FiberCubeSource RadiusSpread %g: %r" % (spread, text))
    check(len(text) < 400, "a long number in: %r" % text)
    bundle = FiberBundleSource(RadiusDistribution="LogNormal", RadiusSpread=spread)
    text = "\n".join(errors_of(bundle))
    check("RadiusSpread is %s" % short in text, "FiberBundleSource RadiusSpread %g: %r" % (spread, text))
    # The pipeline is usable again with a sound spread.
    cube.RadiusSpread = 0.5
    check(errors_of(cube) == [], "cube errors after the fix")
    check(cube.GetDataInformation().GetNumberOfCells() == 50, "no fibers after the fix")
    Delete(cube)
    Delete(bundle)

# One error, once.
cube = FiberCubeSource(NumberOfFibers=5, EdgeLength=10.0)
sim = PLISimulation(Input=cube, VoxelSize=-1.0)
reported = errors_of(sim)
check(len(reported) == 1 and "VoxelSize is -1" in reported[0], "PLISimulation reported %r" % reported)

# A FIFO as FileName and as checkpoint: refused at once.
fifo = os.path.join(tmp, "pipe.dat")
if os.path.exists(fifo):
    os.remove(fifo)
os.mkfifo(fifo)
reader = FiberReader(FileName=fifo)
text = "\n".join(errors_of(reader))
check("is a FIFO (named pipe), not a regular file" in text and fifo in text, "FiberReader on a FIFO: %r" % text)
solver = FiberCollisionSolver(Input=cube, MaxSteps=10, NumberOfThreads=1, CheckpointFile=fifo,
                              ResumeFromCheckpoint=1)
text = "\n".join(errors_of(solver))
check("'%s'" % fifo in text and "FIFO" in text, "ResumeFromCheckpoint on a FIFO: %r" % text)
solver.ResumeFromCheckpoint = 0
solver.CheckpointFile = ""
check(errors_of(solver) == [], "the solver after the fix")
os.remove(fifo)
signal.alarm(0)
print("test_rough_inputs passed")
