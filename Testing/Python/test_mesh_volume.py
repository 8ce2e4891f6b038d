"""pvpython: the volume FiberMeshWriter's periodic substrate encloses, by the divergence theorem over
the written triangles (the cut pieces closed by their cross-sections on the cell faces), equals the
capsule volume FiberMetrics measures times the polygon factor (N/2π)·sin(2π/N) of an N-sided ring,
within FiberMetrics' own Monte Carlo error; and equals that factor times the closed form exactly,
for the outer and for the inner (axon) surfaces."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import check, load_plugin, option  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())
import fiberpli  # noqa: E402  (embedded in the plugin)
import numpy as np  # noqa: E402
from vtkmodules.vtkCommonCore import vtkDoubleArray  # noqa: E402

tmp = option("-T")
L = 20.0
lo = np.zeros(3)
hi = np.full(3, L)
G = 0.6  # g-ratio of every fiber


def closed_fiber(start, lattice, r, n=5):
    """A straight fiber closed through the cell: n points from start to start + lattice vector."""
    t = np.linspace(0.0, 1.0, n)[:, None]
    return np.c_[np.asarray(start) + t * np.asarray(lattice), np.full(n, r)]


# Four straight fibers closed through the (20 µm)³ cell, apart by more than their radii under the
# minimum image: along z at (3, 3) and (3, 13), along x at y = 8, z = 5, and along the diagonal
# (1, 1, 0) in the plane z = 15 on the line x − y = 5, which crosses x and y faces twice each.
fibers = [closed_fiber((3, 3, 0), (0, 0, L), 1.0), closed_fiber((3, 13, 0), (0, 0, L), 1.5),
          closed_fiber((0, 8, 5), (L, 0, 0), 1.2), closed_fiber((5, 0, 15), (L, L, 0), 0.8)]
lengths = [L, L, L, L * math.sqrt(2.0)]
capsules = sum(math.pi * f[0, 3] ** 2 * length for f, length in zip(fibers, lengths))  # no ends, no overlaps
poly = fiberpli.from_arrays(fibers)
cell = vtkDoubleArray()
cell.SetName("periodic_cell")
for a in range(3):
    cell.InsertNextValue(lo[a])
    cell.InsertNextValue(hi[a])
poly.GetFieldData().AddArray(cell)
inner = vtkDoubleArray()
inner.SetName("inner_radius")
for i in range(poly.GetNumberOfPoints()):
    inner.InsertNextValue(G * poly.GetPointData().GetArray("radius").GetValue(i))
poly.GetPointData().AddArray(inner)
source = fiberpli.producer(poly)


def read_ply(path):
    with open(path) as f:
        lines = f.read().split("\n")
    end = lines.index("end_header")
    nv = int([h for h in lines[:end] if h.startswith("element vertex")][0].split()[2])
    nf = int([h for h in lines[:end] if h.startswith("element face")][0].split()[2])
    verts = np.array([[float(x) for x in lines[end + 1 + i].split()] for i in range(nv)])
    faces = np.array([[int(x) for x in lines[end + 1 + nv + i].split()[1:]] for i in range(nf)])
    return verts, faces


def enclosed_volume(verts, faces):
    """Σ det(a, b, c)/6 over the triangles, plus the cross-sections on the cell faces: every
    directed edge whose reverse no triangle has is a boundary edge; it must lie in a face plane,
    and the fan triangle (c, b, a) from a point c of that plane closes the piece there."""
    p = verts - lo  # origin at the cell corner: smaller numbers, less cancellation
    tri = p[faces]
    volume = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6.0
    key = [tuple(v) for v in verts]  # vertices are matched by position: the cut vertices are exact
    directed = set()
    for t in faces:
        for i in range(3):
            directed.add((key[t[i]], key[t[(i + 1) % 3]]))
    boundary = [(a, b) for (a, b) in directed if (b, a) not in directed]
    for a, b in boundary:
        plane = [(axis, bound) for axis in range(3) for bound in (lo[axis], hi[axis])
                 if a[axis] == bound and b[axis] == bound]
        check(plane, "boundary edge %s-%s off the cell faces: the mesh is not closed" % (a, b))
        axis, bound = plane[0]
        c = np.zeros(3)
        c[axis] = bound - lo[axis]
        pa, pb = np.array(a) - lo, np.array(b) - lo
        volume += np.dot(c, np.cross(pb, pa)) / 6.0
    return volume, len(boundary)


# FiberMetrics' measure of the capsule union in the cell, with its standard error.
metrics = FiberMetrics(Input=source, Samples=400000, Seed=3)
metrics.UpdatePipeline()
summary = servermanager.Fetch(metrics, idx=1)
phi = summary.GetColumnByName("volume_fraction").GetValue(0)
sigma = summary.GetColumnByName("volume_fraction_error").GetValue(0)
cell_volume = L ** 3
check(abs(phi * cell_volume - capsules) <= 4 * sigma * cell_volume,
      "FiberMetrics %g against the closed form %g" % (phi * cell_volume, capsules / cell_volume))

for sides in (8, 32):
    fill = sides / (2 * math.pi) * math.sin(2 * math.pi / sides)  # polygon area / circle area
    outer = os.path.join(tmp, "outer%d.ply" % sides)
    w = FiberMeshWriter(Input=source, FileName=outer, NumberOfSides=sides, InnerSurfaces=0)
    w.UpdatePipeline()
    v_outer, cuts = enclosed_volume(*read_ply(outer))
    check(cuts > 0, "no piece was cut at the faces")
    # Straight closed tubes: prisms of the inscribed polygon, cut and wrapped without loss.
    check(abs(v_outer - fill * capsules) <= 1e-9 * capsules,
          "N=%d: mesh volume %.12g, polygon prisms %.12g" % (sides, v_outer, fill * capsules))
    # Against FiberMetrics: the mesh under-fills the measured capsules by exactly the polygon
    # factor, so |V_mesh − fill·φ·V| <= fill · 4σ · V. Without the factor the check would fail at
    # N = 8 (1 − fill = 10 % against σ ≈ 0.05 %).
    measured = phi * cell_volume
    check(abs(v_outer - fill * measured) <= fill * 4 * sigma * cell_volume,
          "N=%d: mesh %.6g against FiberMetrics %.6g x %.6f" % (sides, v_outer, measured, fill))
    check(sides == 32 or abs(v_outer - measured) > 4 * sigma * cell_volume, "the check cannot tell N=8")
    both = os.path.join(tmp, "both%d.ply" % sides)
    w2 = FiberMeshWriter(Input=source, FileName=both, NumberOfSides=sides, InnerSurfaces=1)
    w2.UpdatePipeline()
    v_both, _ = enclosed_volume(*read_ply(both))
    # The axon surfaces are closed and outward too: they add the prisms at the inner radius.
    check(abs((v_both - v_outer) - fill * G * G * capsules) <= 1e-9 * capsules,
          "N=%d: inner surfaces enclose %.12g, expected %.12g" % (sides, v_both - v_outer, fill * G * G * capsules))
    Delete(w)
    Delete(w2)
print("test_mesh_volume passed")
