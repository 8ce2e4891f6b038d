"""Fibers per rank and wall time of PLISimulation on distributed fibers (docs/pli-simulation.md §6.3).

    mpiexec -n R pvbatch bench/mpi_pli_tiles.py <FiberPLI.so> [fibers]

The paper's cube (two populations, r = 0.8 um, the edge for 1000 fibers scaled to `fibers`) is made
in pieces by FiberCubeSource and simulated as a 10 um section through its middle (the whole x-y
extent, 4 tilted views, one thread per rank). Prints the fibers each rank received against the
model, and the seconds of the source and of PLISimulation (with the exchange) on rank 0."""
import sys
import time

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

LoadPlugin(sys.argv[1], remote=False, ns=globals())
fibers = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
edge = 51.96 * (fibers / 1000.0) ** 0.5
h = edge / 2
cube = FiberCubeSource(Populations=2, NumberOfFibers=fibers, EdgeLength=edge, FiberRadius=0.8, SegmentLength=2.0,
                       Displacement=0.5, Seed=42)
sim = PLISimulation(Input=cube, VolumeOfInterest=[-h, h, -h, h, -5, 5], VoxelSize=0.5, PixelSize=1.0,
                    NumberOfRotations=9, TiltAngle=5.5, NoiseGain=3.0, Seed=1, NumberOfThreads=1)
start = time.time()
cube.UpdatePipeline()
sourceSeconds = time.time() - start
sim.UpdatePipeline()
seconds = time.time() - start - sourceSeconds
held = []
for r in range(ranks):
    fd = servermanager.Fetch(sim, r).GetFieldData()
    held.append((int(fd.GetArray("tile_fibers").GetValue(0)), int(fd.GetArray("model_fibers").GetValue(0))))
print("ranks %d, fibers %d, edge %.1f um: fibers per rank %s of %d; source %.2f s, PLISimulation %.2f s"
      % (ranks, fibers, edge, [t for t, _ in held], held[0][1], sourceSeconds, seconds))
