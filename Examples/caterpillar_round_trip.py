"""A CATERPillar substrate through FiberPLI: read its voxel.csv (axon sphere chains become fibers
with radius and inner_radius), measure it with FiberMetrics (density, overlaps, orientation),
separate its fibers with FiberCollisionSolver, measure again, simulate a 3D-PLI measurement of it and
analyse it; the solved substrate is written back as voxel.csv for CATERPillar's tools and as a
PLY mesh (with the MC/DC snippet) for diffusion simulators.

    pvpython Examples/caterpillar_round_trip.py <FiberPLI.so> <output folder> [voxel.csv]

Without a file it reads the small sample Testing/Data/substrates/voxel.csv (three myelinated axons,
one glial cell that is skipped with a warning).
"""
import passive_openmp  # noqa: F401  (first: restarts once with OMP_WAIT_POLICY=PASSIVE when unset)
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

plugin, out = sys.argv[1], sys.argv[2]
here = os.path.dirname(os.path.abspath(__file__))
source = sys.argv[3] if len(sys.argv) > 3 else os.path.join(here, "..", "Testing", "Data", "substrates", "voxel.csv")
LoadPlugin(plugin, remote=False, ns=globals())
os.makedirs(out, exist_ok=True)


def summary(metrics):
    """FiberMetrics' one-row Summary table (output port 1) as column -> value."""
    metrics.UpdatePipeline()
    table = servermanager.Fetch(metrics, idx=1)
    return {table.GetColumnName(c): table.GetColumn(c).GetValue(0) for c in range(table.GetNumberOfColumns())}


# ParaView's CSV reader also takes .csv: name FiberReader (the GUI asks which reader to use).
substrate = FiberReader(FileName=source)
before = summary(FiberMetrics(Input=substrate))
print("read:   volume fraction %.4f, colliding pairs %d, smallest gap %.3f um"
      % (before["volume_fraction"], before["collisions"], before["min_gap"]))

solved = FiberCollisionSolver(Input=substrate, SegmentLength=0.6, MaxSteps=2000)
after = summary(FiberMetrics(Input=solved))
print("solved: volume fraction %.4f, colliding pairs %d, smallest gap %.3f um"
      % (after["volume_fraction"], after["collisions"], after["min_gap"]))

pli = PLISimulation(Input=solved, VoxelSize=0.1, PixelSize=0.5)
maps = PLIAnalysis(Input=pli)
maps.UpdatePipeline()
image = servermanager.Fetch(maps)
retardation = image.GetPointData().GetArray("retardation").GetRange()
print("PLI:    %d x %d pixels, retardation %.3f .. %.3f" % (image.GetDimensions()[0], image.GetDimensions()[1],
                                                           retardation[0], retardation[1]))

writer = FiberWriter(Input=solved, FileName=os.path.join(out, "voxel_solved.csv"))
writer.UpdatePipeline()
mesh = FiberMeshWriter(Input=solved, FileName=os.path.join(out, "substrate.ply"), WriteMCDCConfig=1)
mesh.UpdatePipeline()
mesh.UpdatePropertyInformation()
print("wrote %s (CATERPillar) and %s (%d triangles, %d bytes)"
      % (writer.FileName, mesh.FileName, mesh.GetPropertyValue("TrianglesWritten"), mesh.GetPropertyValue("BytesWritten")))
