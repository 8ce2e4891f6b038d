"""pvpython: FiberMeshWriter's CylinderList writes MC/DC cylinder lists beside the mesh whose lines
are the model's fibers (first point, last point, largest radius), checked against the arrays the
model was built from; a fiber that is not straight within StraightnessTolerance refuses the write
by name and leaves no file; the default writes no list."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402

load_plugin(globals())
import fiberpli  # noqa: E402  (embedded in the plugin)
import numpy as np  # noqa: E402

tmp = option("-T")
for name in os.listdir(tmp):  # what a previous run wrote would pass the "no file" checks for it
    os.remove(os.path.join(tmp, name))
rng = np.random.default_rng(11)


def straight(a, b, n, radii):
    """n points evenly on the segment a-b with the given radii, as an (n, 4) array."""
    t = np.linspace(0.0, 1.0, n)[:, None]
    return np.c_[np.asarray(a) + t * (np.asarray(b) - np.asarray(a)), radii]


def lines_of(path):
    with open(path) as f:
        text = f.read()
    check(text.endswith("\n"), "the list does not end with a newline")
    rows = text.split("\n")[:-1]
    check(rows[0] == "0.001", "line 1 is %r, not the scale 0.001" % rows[0])
    for r in rows[1:]:
        check(r == " ".join(r.split()) and "  " not in r, "fields not single-space separated: %r" % r)
    return [[float(x) for x in r.split(" ")] for r in rows[1:]]


# z-parallel fibers with tapered radii: cylinders_list is `x y z r`, the first point and the
# largest radius of each fiber.
zfibers = [straight((1.5, -2.0, 0.0), (1.5, -2.0, 12.0), 7, rng.uniform(0.4, 0.9, 7)),
           straight((-3.25, 4.0, -1.0), (-3.25, 4.0, 9.5), 4, rng.uniform(0.4, 0.9, 4)),
           straight((0.1, 0.2, 2.0), (0.1, 0.2, 3.0), 2, [0.3, 0.35])]
zsource = fiberpli.producer(fiberpli.from_arrays(zfibers, [4, 9, 2], [0, 0, 1]))
zpath = os.path.join(tmp, "z.ply")
w = FiberMeshWriter(Input=zsource, FileName=zpath, NumberOfSides=6, CylinderList=1)
w.UpdatePipeline()
got = lines_of(os.path.join(tmp, "z.cylinders.txt"))
check(len(got) == len(zfibers), "%d cylinders for %d fibers" % (len(got), len(zfibers)))
for g, f in zip(got, zfibers):
    check(g == [f[0, 0], f[0, 1], f[0, 2], f[:, 3].max()], "cylinders_list line %s for fiber %s" % (g, f[[0, -1]]))
check(os.path.getsize(zpath) > 0, "the mesh was not written beside the list")

# Straight fibers in any direction: oriented_cylinders_list is `x y z ox oy oz r`.
ofibers = []
for k in range(5):
    a = rng.uniform(-10, 10, 3)
    b = a + rng.normal(size=3) * 6.0
    n = int(rng.integers(2, 9))
    ofibers.append(straight(a, b, n, rng.uniform(0.5, 1.2, n)))
osource = fiberpli.producer(fiberpli.from_arrays(ofibers))
opath = os.path.join(tmp, "o.ply")
w2 = FiberMeshWriter(Input=osource, FileName=opath, NumberOfSides=6, CylinderList=2)
w2.UpdatePipeline()
got = lines_of(os.path.join(tmp, "o.cylinders.txt"))
check(len(got) == len(ofibers), "%d oriented cylinders for %d fibers" % (len(got), len(ofibers)))
for g, f in zip(got, ofibers):
    want = list(f[0, :3]) + list(f[-1, :3]) + [f[:, 3].max()]
    check(g == want, "oriented_cylinders_list line %s, expected %s" % (g, want))

# The same tilted fibers are no z-parallel cylinders: refused by name, no file at all.
refused = os.path.join(tmp, "refused.ply")
w3 = FiberMeshWriter(Input=osource, FileName=refused, CylinderList=1)
catcher = ErrorCatcher(w3)
w3.UpdatePipeline()
check("CylinderList" in catcher.text() and "deviates" in catcher.text(), "tilted as z-aligned: %s" % catcher.text())
check(not os.path.exists(refused) and not os.path.exists(os.path.join(tmp, "refused.cylinders.txt")),
      "files written for a refused list")

# A bend of a known size: the middle point of fiber 1 (fiber_id 8) moved 0.05 µm off its chord.
bent = [zfibers[0].copy(), straight((0, 0, 0), (0, 0, 10), 3, [0.5, 0.5, 0.5])]
bent[1][1, 0] += 0.05
bsource = fiberpli.producer(fiberpli.from_arrays(bent, [7, 8], [0, 0]))
bpath = os.path.join(tmp, "bent.ply")
w4 = FiberMeshWriter(Input=bsource, FileName=bpath, CylinderList=2, StraightnessTolerance=0.01)
catcher = ErrorCatcher(w4)
w4.UpdatePipeline()
check("fiber 1 (id 8) deviates 0.05" in catcher.text(), "bent fiber: %s" % catcher.text())
check(not os.path.exists(bpath), "a mesh was written for a refused list")
catcher.clear()
w4.StraightnessTolerance = 0.06
w4.UpdatePipeline()
check(catcher.text() == "", "within 0.06 µm: %s" % catcher.text())
check(len(lines_of(os.path.join(tmp, "bent.cylinders.txt"))) == 2, "the bent model within tolerance")

# The default writes the mesh alone.
plain = os.path.join(tmp, "plain.ply")
w5 = FiberMeshWriter(Input=zsource, FileName=plain, NumberOfSides=6)
w5.UpdatePipeline()
check(os.path.exists(plain) and not os.path.exists(os.path.join(tmp, "plain.cylinders.txt")), "default list")
print("test_mesh_cylinders passed")
