"""Exports a solved periodic cell as a PLY substrate for MC/DC, with the fibers (for the inside check)
as a FiberPLI .dat:
    pvpython export_cell.py <FiberPLI.so> <folder> [crossing]
Default: cell.ply / cell.dat, one population along x. `crossing`: crossing.ply / crossing.dat, a
realistic crossing region (two interwoven populations along x and y, undulating and beaded,
the crossing-90 recipe of bench/README.md "Realistic substrates" in a (20 µm)³ cell)."""
import sys
from paraview.simple import *
from paraview import servermanager
LoadPlugin(sys.argv[1], remote=False, ns=globals())
out = sys.argv[2]
crossing = len(sys.argv) > 3 and sys.argv[3] == "crossing"
name = "crossing" if crossing else "cell"
if crossing:
    cube = FiberCubeSource(Populations=2, EdgeLength=20.0, Periodic=1, Seeding="Random", Arrangement="Interwoven",
                           CrossingAngle=90.0, VolumeFraction=0.65, FiberRadius=1.0, RadiusDistribution="Gamma",
                           RadiusSpread=0.5, SegmentLength=2.0, Displacement=0.0, Tortuosity=1.25,
                           UndulationWavelength=15.0, BeadingCV=0.22, BeadingLength=8.0, Seed=42)
    solved = FiberCollisionSolver(Input=cube, SegmentLength=2.0, MaxSteps=6000, MaxDisplacement=0.4, Tortuosity=1.25)
else:
    cube = FiberCubeSource(Populations=1, EdgeLength=20.0, Periodic=1, VolumeFraction=0.55, FiberRadius=1.0,
                           RadiusDistribution="Gamma", RadiusSpread=0.3, SegmentLength=2.0, Displacement=0.3,
                           Tortuosity=1.03, Seed=11)
    solved = FiberCollisionSolver(Input=cube, SegmentLength=2.0, MaxSteps=5000)
f = servermanager.Fetch(solved)
fd = f.GetFieldData()
print("fibers", f.GetNumberOfLines(), "collisions", fd.GetArray("collisions").GetValue(0),
      "volume_fraction %.4f" % fd.GetArray("volume_fraction").GetValue(0),
      "cell", [fd.GetArray("periodic_cell").GetValue(i) for i in range(6)])
w = FiberMeshWriter(Input=solved, FileName=out + "/" + name + ".ply", NumberOfSides=16, WriteMCDCConfig=1)
w.UpdatePipeline()
w.UpdatePropertyInformation()
print("mesh", w.GetPropertyValue("VerticesWritten"), "vertices", w.GetPropertyValue("TrianglesWritten"),
      "triangles", w.GetPropertyValue("BytesWritten"), "bytes")
SaveData(out + "/" + name + ".dat", proxy=solved)
