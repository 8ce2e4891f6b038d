"""Exports a solved periodic cell of one population along x as a PLY substrate for MC/DC, with the
fibers (for the inside check) as a FiberPLI .dat."""
import sys
from paraview.simple import *
from paraview import servermanager
LoadPlugin(sys.argv[1], remote=False, ns=globals())
out = sys.argv[2]
cube = FiberCubeSource(Populations=1, EdgeLength=20.0, Periodic=1, VolumeFraction=0.55, FiberRadius=1.0,
                       RadiusDistribution="Gamma", RadiusSpread=0.3, SegmentLength=2.0, Displacement=0.3,
                       Tortuosity=1.03, Seed=11)
solved = FiberCollisionSolver(Input=cube, SegmentLength=2.0, MaxSteps=5000)
f = servermanager.Fetch(solved)
fd = f.GetFieldData()
print("fibers", f.GetNumberOfLines(), "collisions", fd.GetArray("collisions").GetValue(0),
      "volume_fraction %.4f" % fd.GetArray("volume_fraction").GetValue(0),
      "cell", [fd.GetArray("periodic_cell").GetValue(i) for i in range(6)])
w = FiberMeshWriter(Input=solved, FileName=out + "/cell.ply", NumberOfSides=16, WriteMCDCConfig=1)
w.UpdatePipeline()
w.UpdatePropertyInformation()
print("mesh", w.GetPropertyValue("VerticesWritten"), "vertices", w.GetPropertyValue("TrianglesWritten"),
      "triangles", w.GetPropertyValue("BytesWritten"), "bytes")
SaveData(out + "/cell.dat", proxy=solved)
