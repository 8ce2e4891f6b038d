"""pvbatch under mpiexec -n R (R = argv[3]): PLISimulation, FiberOrientationGroundTruth and
PLIAnalysis on distributed fibers (docs/pli-simulation.md §6.3). Each rank asks the upstream for
its own piece and receives only the fibers its image tile reads; the pieces, put together, equal
bit for bit the one-process result of the same pipeline, computed afterwards on rank 0 alone
(client-side objects, one piece). Checked as well: every rank held fewer fibers than the model
(field data tile_fibers < model_fibers), a rank whose tile no fiber reaches gives the background
of the serial image, a periodic cell tiled into a larger section, input that sits on rank 0 only
(FiberReader cannot make pieces), the bounds sentinel, a distributed solve upstream, and myelinated
fibers (inner_radius)."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, load_plugin  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
import numpy  # noqa: E402

load_plugin(globals())
tmp = sys.argv[2]
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
check(ranks == int(sys.argv[3]), "expected %s ranks, got %d" % (sys.argv[3], ranks))


def field(data, name):
    a = data.GetFieldData().GetArray(name)
    return a.GetValue(0) if a else None


def gathered(proxy, names):
    """Every rank's piece (Fetch with PassThrough = rank), placed by its global extent."""
    whole = proxy.GetDataInformation().GetExtent()
    nx, ny = whole[1] - whole[0] + 1, whole[3] - whole[2] + 1
    out, tiles = {}, []
    for rank in range(ranks):
        data = servermanager.Fetch(proxy, rank)
        e = data.GetExtent()
        tiles.append((e, field(data, "tile_fibers"), field(data, "model_fibers")))
        if data.GetNumberOfPoints() == 0:
            continue
        for name in names:
            values = vtk_to_numpy(data.GetPointData().GetArray(name))
            values = values.reshape((e[3] - e[2] + 1, e[1] - e[0] + 1, -1))
            full = out.setdefault(name, numpy.full((ny, nx, values.shape[2]), numpy.nan))
            block = full[e[2]:e[3] + 1, e[0]:e[1] + 1]
            seen = ~numpy.isnan(block[..., 0])
            check(numpy.array_equal(block[seen], values[seen], equal_nan=True),
                  "%s: a pixel shared by two pieces differs" % name)
            block[...] = values
    return out, tiles


def serial(proxy, names):
    """The same pipeline as one piece on rank 0 alone (no MPI communication)."""
    algorithm = proxy.GetClientSideObject()
    algorithm.UpdatePiece(0, 1, 0)
    data = algorithm.GetOutputDataObject(0)
    e = data.GetExtent()
    return {name: vtk_to_numpy(data.GetPointData().GetArray(name)).reshape((e[3] - e[2] + 1, e[1] - e[0] + 1, -1))
            for name in names}


def same(parallel, reference, what):
    for name, ref in reference.items():
        par = parallel.get(name)
        check(par is not None and par.shape == ref.shape, "%s %s: shape %s, serial %s"
              % (what, name, None if par is None else par.shape, ref.shape))
        check(numpy.array_equal(par, ref, equal_nan=True), "%s %s: %d of %d values differ from the serial run"
              % (what, name, int((~numpy.isclose(par, ref, equal_nan=True, rtol=0, atol=0)).sum()), ref.size))


IMAGE = ["intensity"] + ["intensity_tilt_%d" % k for k in range(4)]
TRUTH = ["direction", "inclination", "fraction"]
MAPS = ["transmittance", "direction", "retardation", "inclination"]
# The cube spans about [-6, 6]^3; the section x from -7 to 29 leaves the right part of the image
# without fibers (the tile of the last rank), z from -2 to 2 leaves most fibers out of every tile.
VOI = [-7, 29, -6, 6, -2, 2]
cube = FiberCubeSource(Populations=2, NumberOfFibers=60, EdgeLength=12.0, FiberRadius=0.6, SegmentLength=1.0,
                       Displacement=0.3, Seed=3)
sim = PLISimulation(Input=cube, VolumeOfInterest=VOI, VoxelSize=0.25, PixelSize=0.5, NumberOfRotations=6,
                    TiltAngle=5.5, Birefringence=-0.004, Absorption=0.5, Seed=4, NoiseGain=3.0, OpticalSigma=0.71,
                    NumberOfThreads=1)
truth = FiberOrientationGroundTruth(Input=cube, VolumeOfInterest=VOI, VoxelSize=0.25, PixelSize=1.0,
                                    NumberOfThreads=1)
ana = PLIAnalysis(Input=sim, NumberOfThreads=1)
for proxy in (sim, truth, ana):
    proxy.UpdatePipeline()

image, simTiles = gathered(sim, IMAGE)
gt, truthTiles = gathered(truth, TRUTH)
maps, _ = gathered(ana, MAPS)
for what, tiles in (("PLISimulation", simTiles), ("FiberOrientationGroundTruth", truthTiles)):
    for rank, (extent, held, whole) in enumerate(tiles):
        print("mpi_pli_tiles: %s rank %d: extent %s, %s of %s fibers" % (what, rank, extent, held, whole))
    model = tiles[0][2]
    check(model == 60, "%s: model_fibers %s, expected 60" % (what, model))
    if ranks > 1:
        check(all(t[1] is not None and t[1] < model for t in tiles),
              "%s: some rank held the whole model: %s" % (what, [t[1] for t in tiles]))
        check(any(t[1] == 0 for t in tiles), "%s: no rank has a tile without fibers" % what)
        check(all(t[0][1] >= t[0][0] for t in tiles), "%s: a rank computed no pixel" % what)

# The sources make pieces: no rank generated (or held as input) the whole model.
cubePieces = [servermanager.Fetch(cube, r).GetNumberOfCells() for r in range(ranks)]
check(sum(cubePieces) == 60 and (ranks == 1 or max(cubePieces) < 60), "the cube's pieces: %s" % cubePieces)

# The VolumeOfInterest sentinel (input bounds): under MPI the ranks' bounds are reduced when the
# image is planned; the image equals the one of the explicit volume of the whole model's bounds.
whole = servermanager.Fetch(cube)
points = vtk_to_numpy(whole.GetPoints().GetData())
radius = vtk_to_numpy(whole.GetPointData().GetArray("radius"))
bounds = [float(v) for a in range(3) for v in ((points[:, a] - radius).min(), (points[:, a] + radius).max())]
simAuto = PLISimulation(Input=cube, VoxelSize=0.5, PixelSize=1.0, NumberOfRotations=6, TiltAngle=5.5,
                        Birefringence=-0.004, Seed=4, NoiseGain=3.0, NumberOfThreads=1)
simBounds = PLISimulation(Input=cube, VolumeOfInterest=bounds, VoxelSize=0.5, PixelSize=1.0, NumberOfRotations=6,
                          TiltAngle=5.5, Birefringence=-0.004, Seed=4, NoiseGain=3.0, NumberOfThreads=1)
for proxy in (simAuto, simBounds):
    proxy.UpdatePipeline()
check(simAuto.GetDataInformation().GetExtent() == simBounds.GetDataInformation().GetExtent(),
      "sentinel extent %s, bounds extent %s" % (simAuto.GetDataInformation().GetExtent(),
                                                simBounds.GetDataInformation().GetExtent()))
same(gathered(simAuto, IMAGE)[0], gathered(simBounds, IMAGE)[0], "PLISimulation (input bounds)")

# Rank 0 only: the cube written by the parallel writer (it gathers) and read back.
dat = os.path.join(tmp, "cube_%d.dat" % ranks)
SaveData(dat, proxy=cube)
reader = FiberReader(FileName=dat)
simRead = PLISimulation(Input=reader, VolumeOfInterest=VOI, VoxelSize=0.25, PixelSize=0.5, NumberOfRotations=6,
                        TiltAngle=5.5, Birefringence=-0.004, Absorption=0.5, Seed=4, NoiseGain=3.0, OpticalSigma=0.71,
                        NumberOfThreads=1)
simRead.UpdatePipeline()
readPieces = [servermanager.Fetch(reader, r).GetNumberOfCells() for r in range(ranks)]
check(readPieces[0] == 60 and sum(readPieces) == 60, "the reader's fibers are not all on rank 0: %s" % readPieces)
imageRead, readTiles = gathered(simRead, IMAGE)
if ranks > 1:
    check(all(t[1] < 60 for t in readTiles), "input on rank 0: some rank held every fiber: %s" % readTiles)

# A periodic cell (8 um) tiled into a 24 x 16 um section: each rank tiles only what its tile reads.
cell = FiberCubeSource(Populations=2, EdgeLength=8.0, Periodic=1, VolumeFraction=0.3, FiberRadius=0.6,
                       SegmentLength=1.0, Seed=5)
simCell = PLISimulation(Input=cell, VolumeOfInterest=[-12, 12, -8, 8, -2, 2], VoxelSize=0.25, PixelSize=0.5,
                        NumberOfRotations=6, TiltAngle=5.5, Birefringence=-0.004, Seed=4, NoiseGain=0.0,
                        NumberOfThreads=1)
simCell.UpdatePipeline()
imageCell, cellTiles = gathered(simCell, IMAGE)
for rank, (extent, held, whole) in enumerate(cellTiles):
    print("mpi_pli_tiles: periodic rank %d: extent %s, %s fibers (translates) of %s in the cell" % (rank, extent, held, whole))

# The whole chain: cube -> FiberCollisionSolver (distributed, docs/solver.md §13) -> PLISimulation.
small = FiberCubeSource(Populations=2, NumberOfFibers=24, EdgeLength=8.05, FiberRadius=0.8, SegmentLength=2.0,
                        Displacement=0.5, Seed=5)
solver = FiberCollisionSolver(Input=small, SegmentLength=2.0, MinCurvatureRadius=4.0, MaxSteps=20000,
                              NumberOfThreads=1)
simSolved = PLISimulation(Input=solver, VolumeOfInterest=[-4, 4, -4, 4, -1, 1], VoxelSize=0.25, PixelSize=0.5,
                          NumberOfRotations=6, TiltAngle=5.5, Birefringence=-0.004, Seed=4, NoiseGain=3.0,
                          NumberOfThreads=1)
simSolved.UpdatePipeline()
imageSolved, _ = gathered(simSolved, IMAGE)

# Myelinated fibers (inner_radius sent with the fibers, the layer table agreed by every rank).
myelinated = FiberCubeSource(Populations=2, NumberOfFibers=60, EdgeLength=12.0, FiberRadius=0.6, SegmentLength=1.0,
                             Displacement=0.3, Seed=3, GRatio=0.6)
simMyelin = PLISimulation(Input=myelinated, VolumeOfInterest=VOI, VoxelSize=0.25, PixelSize=0.5, NumberOfRotations=6,
                          TiltAngle=5.5, Birefringence=-0.004, Seed=4, NoiseGain=0.0, NumberOfThreads=1)
simMyelin.UpdatePipeline()
imageMyelin, _ = gathered(simMyelin, IMAGE)

# The one-process results, on rank 0 alone, after every parallel update.
same(image, serial(sim, IMAGE), "PLISimulation")
same(gt, serial(truth, TRUTH), "FiberOrientationGroundTruth")
same(maps, serial(ana, MAPS), "PLIAnalysis")
same(imageRead, serial(simRead, IMAGE), "PLISimulation (input on rank 0)")
same(imageCell, serial(simCell, IMAGE), "PLISimulation (periodic cell)")
same(imageSolved, serial(simSolved, IMAGE), "PLISimulation (solved cube)")
same(imageMyelin, serial(simMyelin, IMAGE), "PLISimulation (myelinated cube)")
check(numpy.nanmax(gt["fraction"]) > 0.3 and numpy.nanmin(gt["fraction"]) == 0.0, "the ground truth is flat")
check(numpy.ptp(image["intensity"]) > 100.0, "the image is flat: not a real comparison")
print("mpi_pli_tiles passed on %d ranks: image, ground truth, analysis, rank-0 input and periodic cell equal "
      "the serial result bit for bit" % ranks)
