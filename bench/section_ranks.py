"""The millimetre section's 3D-PLI simulation on R MPI ranks (bench/README.md "A millimetre section"):
    mpiexec -n R pvbatch bench/section_ranks.py <FiberPLI.so> <section.h5> <out.npz> [--threads T]
Reads the solved section written by `section_bench.py --save` (FiberReader reads on rank 0; the
tile exchange sends every rank the fibers that reach its image tile), simulates it as
section_bench.py does (VoxelSize 0.5 µm, PixelSize 1.3 µm, 9 rotations, untilted + 4 tilts of
5.5°) and analyses it. Rank 0 puts the ranks' tiles together, writes them to out.npz and prints
the wall time, the fibers each rank received and a hash of the images. Run it with R = 1 and
R = 2 and compare the two files (`python3 bench/section_ranks.py --compare a.npz b.npz`): the
images must be equal bit for bit."""
import argparse
import hashlib
import sys
import time

import numpy as np

if len(sys.argv) > 1 and sys.argv[1] == "--compare":
    a, b = np.load(sys.argv[2]), np.load(sys.argv[3])
    names = sorted(set(a.files) | set(b.files))
    same = [n for n in names if n in a.files and n in b.files and np.array_equal(a[n], b[n], equal_nan=True)]
    print("%d of %d images equal bit for bit%s" % (len(same), len(names),
                                                   "" if len(same) == len(names) else
                                                   ": differ " + " ".join(sorted(set(names) - set(same)))))
    sys.exit(0 if len(same) == len(names) else 1)

from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("plugin")
parser.add_argument("section")
parser.add_argument("out")
parser.add_argument("--threads", type=int, default=1, help="OpenMP threads per rank")
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()

reader = FiberReader(FileName=args.section)
reader.UpdatePipeline()
bounds = reader.GetDataInformation().GetBounds()
L = round(bounds[1])  # the section spans [0, L]² × [0, T]; fibers may stick out by a radius
T = 60.0
simulation = PLISimulation(Input=reader, VolumeOfInterest=[0.0, L, 0.0, L, 0.0, T], VoxelSize=0.5, PixelSize=1.3,
                           NumberOfRotations=9, TiltAngle=5.5, NumberOfThreads=args.threads)
analysis = PLIAnalysis(Input=simulation, NumberOfThreads=args.threads)
start = time.time()
simulation.UpdatePipeline()
simulated = time.time() - start
analysis.UpdatePipeline()
analysed = time.time() - start - simulated


def gathered(proxy, names):
    """Every rank's tile placed by its extent in the whole image, and the fibers it received."""
    whole = proxy.GetDataInformation().GetExtent()
    nx, ny = whole[1] - whole[0] + 1, whole[3] - whole[2] + 1
    out, received = {}, []
    for rank in range(ranks):
        data = servermanager.Fetch(proxy, rank)
        tile = data.GetFieldData().GetArray("tile_fibers")
        received.append(int(tile.GetValue(0)) if tile else 0)
        e = data.GetExtent()
        if data.GetNumberOfPoints() == 0:
            continue
        for name in names:
            values = vtk_to_numpy(data.GetPointData().GetArray(name))
            values = values.reshape((e[3] - e[2] + 1, e[1] - e[0] + 1, -1))
            full = out.setdefault(name, np.full((ny, nx, values.shape[2]), np.nan, values.dtype))
            full[e[2] - whole[2]:e[3] - whole[2] + 1, e[0] - whole[0]:e[1] - whole[0] + 1] = values
    return out, received


images, received = gathered(simulation, ["intensity"] + ["intensity_tilt_%d" % k for k in range(4)])
maps, _ = gathered(analysis, ["transmittance", "direction", "retardation", "inclination"])
images.update({"map_" + k: v for k, v in maps.items()})
np.savez(args.out, **images)
digest = hashlib.sha256()
for name in sorted(images):
    digest.update(np.ascontiguousarray(images[name]).tobytes())
print("ranks %d: PLISimulation %.1f s, PLIAnalysis %.1f s; fibers received per rank %s; images %s"
      % (ranks, simulated, analysed, received, digest.hexdigest()[:12]))
