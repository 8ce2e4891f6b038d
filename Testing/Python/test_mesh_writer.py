"""pvpython: FiberMeshWriter writes a periodic cell as an ASCII PLY that MC/DC parses (x y z vertex
lines, 3 i j k faces), every vertex inside the cell, closed modulo the cell (every edge in two
triangles, in opposite directions), with inner surfaces, the counts it reports and the MC/DC
snippet; an open model gives capped closed tubes; bad options are errors naming them."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())
tmp = option("-T")


def read_ply(path):
    with open(path) as f:
        lines = f.read().split("\n")
    end = lines.index("end_header")
    header = lines[:end]
    check(not any("normal" in h for h in header), "normals in the header")
    nv = int([h for h in header if h.startswith("element vertex")][0].split()[2])
    nf = int([h for h in header if h.startswith("element face")][0].split()[2])
    body = lines[end + 1:]
    verts = [tuple(float(x) for x in body[i].split()) for i in range(nv)]
    check(all(len(v) == 3 for v in verts), "a vertex line is not x y z")
    faces = []
    for i in range(nv, nv + nf):
        t = body[i].split()
        check(len(t) == 4 and t[0] == "3", "face line %r" % body[i])
        faces.append(tuple(int(x) for x in t[1:]))
    check(body[nv + nf:] in ([], [""]), "content after the faces")
    return verts, faces


def check_closed(verts, faces, cell):
    ids = {}
    vid = []
    for v in verts:
        key = list(v)
        if cell:
            for a in range(3):
                check(cell[2 * a] <= v[a] <= cell[2 * a + 1], "vertex %s outside the cell" % (v,))
                if key[a] == cell[2 * a + 1]:
                    key[a] = cell[2 * a]
        vid.append(ids.setdefault(tuple(key), len(ids)))
    directed = {}
    for t in faces:
        for i in range(3):
            e = (vid[t[i]], vid[t[(i + 1) % 3]])
            directed[e] = directed.get(e, 0) + 1
    bad = [e for e, n in directed.items() if n != 1 or directed.get((e[1], e[0])) != 1]
    check(not bad, "%d of %d directed edges are not paired" % (len(bad), len(directed)))


cube = FiberCubeSource(Populations=2, EdgeLength=14.0, Periodic=1, VolumeFraction=0.3, FiberRadius=0.8,
                       SegmentLength=2.0, Displacement=0.3, Seed=4, GRatio=0.7)
fibers = servermanager.Fetch(cube)
cell_array = fibers.GetFieldData().GetArray("periodic_cell")
cell = [cell_array.GetValue(i) for i in range(6)]
path = os.path.join(tmp, "cell.ply")
writer = FiberMeshWriter(Input=cube, FileName=path, NumberOfSides=8, WriteMCDCConfig=1)
writer.UpdatePipeline()
verts, faces = read_ply(path)
check_closed(verts, faces, cell)
writer.UpdatePropertyInformation()
reported = [writer.GetPropertyValue(n) for n in ("VerticesWritten", "TrianglesWritten", "BytesWritten")]
check(reported == [len(verts), len(faces), os.path.getsize(path)], "reported %s" % reported)
# Outer and inner surfaces: at least 2 · 2 · sides triangles per link.
links = sum(fibers.GetCell(c).GetNumberOfPoints() - 1 for c in range(fibers.GetNumberOfCells()))
check(len(faces) >= 2 * 2 * 8 * links, "%d triangles for %d links" % (len(faces), links))
with open(os.path.join(tmp, "cell.mcdc.conf")) as f:
    conf = f.read()
check("ply cell.ply\nply_scale 0.001\n" in conf and "-0.007 -0.007 -0.007\n0.007 0.007 0.007\n" in conf, conf)

# Open model: capped tubes, closed without identification.
opened = FiberCubeSource(Populations=1, EdgeLength=14.0, NumberOfFibers=5, FiberRadius=0.8, Seed=2)
plain = os.path.join(tmp, "open.ply")
w2 = FiberMeshWriter(Input=opened, FileName=plain, Tolerance=0.01)
w2.UpdatePipeline()
verts, faces = read_ply(plain)
check_closed(verts, faces, None)

bad = FiberMeshWriter(Input=opened, FileName=os.path.join(tmp, "bad.ply"), NumberOfSides=2)
catcher = ErrorCatcher(bad)
bad.UpdatePipeline()
check("NumberOfSides is 2" in catcher.text(), "bad sides: %s" % catcher.text())
check(not os.path.exists(os.path.join(tmp, "bad.ply")), "a file was written for bad options")
print("test_mesh_writer passed")
