"""pvbatch: PLISimulation splits the image plane (and the tissue port) over MPI ranks
(docs/pli-simulation.md §6.2) and gives exactly the one-process result.

Usage: pvbatch mpi_pli_split.py <plugin> <tmp dir> serial   (one process: writes the reference)
       mpiexec -n 2 pvbatch mpi_pli_split.py <plugin> <tmp dir>   (compares with the reference)
Both runs build the same pipeline; the arrays are fetched to rank 0 and keyed by pixel position
(pieces of an image share their boundary points)."""
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
serial = len(sys.argv) > 3 and sys.argv[3] == "serial"
reference = os.path.join(tmp, "pli_split_reference.npz")
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
check(ranks == (1 if serial else 2), "expected %d ranks, got %d" % (1 if serial else 2, ranks))

ARRAYS = ["intensity"] + ["intensity_tilt_%d" % k for k in range(4)]
PIXEL = 0.5
cube = FiberCubeSource(Populations=2, NumberOfFibers=40, EdgeLength=20.0, FiberRadius=1.0,
                       SegmentLength=2.0, Displacement=0.3, Seed=3)
sim = PLISimulation(Input=cube, VolumeOfInterest=[-8, 8, -6, 6, -4, 4], VoxelSize=0.25, PixelSize=PIXEL,
                    Wavelength=525.0, LightIntensity=26000.0, NumberOfRotations=9, TiltAngle=5.5,
                    Birefringence=-0.004, Absorption=0.5, Seed=4, Layers="", BackgroundAbsorption=0.0,
                    StepSize=1.0, Interpolation="Slerp", OpticalSigma=0.71, NoiseGain=3.0,
                    RefractiveIndex=1.0, NumberOfThreads=1, ExportTissue=1)
sim.UpdatePipeline()
# Fetch every rank's piece on its own (PassThrough = rank) and assemble the image by pixel position;
# pieces of an image share their boundary points, which must agree.
pieces = [servermanager.Fetch(sim, r) for r in range(ranks)]
image = {name: numpy.full((32, 24, 9), numpy.nan) for name in ARRAYS}
owners = set()
for rank, data in enumerate(pieces):
    n = data.GetNumberOfPoints()
    print("mpi_pli_split: rank %d: %s, %d points, extent %s" % (rank, data.GetClassName(), n, data.GetExtent()))
    if n == 0:
        continue
    owners.add(rank)
    pts = numpy.array([data.GetPoint(i) for i in range(n)])
    keys = numpy.rint((pts[:, :2] - [-8 + PIXEL / 2, -6 + PIXEL / 2]) / PIXEL).astype(int)
    check(numpy.abs(keys * PIXEL + [-8 + PIXEL / 2, -6 + PIXEL / 2] - pts[:, :2]).max() < 1e-9,
          "points off the pixel grid")
    for name in ARRAYS:
        values = vtk_to_numpy(data.GetPointData().GetArray(name))
        full = image[name]
        for (i, j), v in zip(keys, values):
            if not numpy.isnan(full[i, j, 0]):
                check((full[i, j] == v).all(), "%s: shared boundary pixel (%d, %d) differs between pieces" % (name, i, j))
            full[i, j] = v
for name in ARRAYS:
    check(not numpy.isnan(image[name]).any(), "%s: pixels missing from the pieces" % name)

# The tissue port (ExportTissue) is split over the ranks too: every voxel of the 64 x 48 x 32
# lattice once (extent = global voxel indices, x fastest), equal to the serial one.
tissue = {"label": numpy.full((64, 48, 32), -1.0), "optic_axis": numpy.full((64, 48, 32, 3), numpy.nan)}
tissueOwners = set()
for rank in range(ranks):
    data = servermanager.Fetch(sim, rank, idx=1)
    e = data.GetExtent()
    print("mpi_pli_split: tissue rank %d: %d points, extent %s" % (rank, data.GetNumberOfPoints(), e))
    if data.GetNumberOfPoints() == 0:
        continue
    tissueOwners.add(rank)
    shape = (e[5] - e[4] + 1, e[3] - e[2] + 1, e[1] - e[0] + 1)
    box = (slice(e[0], e[1] + 1), slice(e[2], e[3] + 1), slice(e[4], e[5] + 1))
    for name in tissue:
        values = vtk_to_numpy(data.GetPointData().GetArray(name))
        values = values.reshape(shape + values.shape[1:]).swapaxes(0, 2)  # to [x, y, z(, c)]
        seen = tissue["label"][box] >= 0
        if name == "label":
            check((tissue[name][box][seen] == values[seen]).all(), "tissue: shared voxels differ between pieces")
        tissue[name][box] = values
check((tissue["label"] >= 0).all(), "tissue voxels missing from the pieces")
check((tissue["label"] > 0).sum() > 1000, "the tissue has hardly any fiber voxel: not a real comparison")
image.update({"tissue_" + name: tissue[name] for name in tissue})

if serial:
    numpy.savez(reference, **image)
    print("mpi_pli_split: serial reference written to", reference)
    sys.exit(0)

check(owners == {0, 1}, "the image plane was not split over both ranks: %s" % (owners,))
ref = numpy.load(reference)
for name in ARRAYS:
    diff = numpy.abs(image[name] - ref[name]).max()
    check(diff == 0.0, "%s: max |parallel - serial| = %g, must be 0" % (name, diff))
    check(image[name].max() - image[name].min() > 100.0, "%s is flat: not a real comparison" % name)
check(tissueOwners == {0, 1}, "the tissue was not split over both ranks: %s" % (tissueOwners,))
for name in ["tissue_label", "tissue_optic_axis"]:
    check(numpy.array_equal(image[name], ref[name], equal_nan=True), "%s differs between 2 ranks and 1" % name)
print("mpi_pli_split: 2 ranks equal the serial result bit for bit (image and tissue)")
