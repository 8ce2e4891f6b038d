"""pvpython: CATERPillar .csv and CACTUS .txt through FiberWriter and FiberReader: points, radii, inner radii and bundles come back point by point; an ordinary CSV
stays with ParaView's CSV reader; a strand file whose count lies is refused naming file and line."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())
tmp = option("-T")
cube = FiberCubeSource(Populations=2, NumberOfFibers=12, EdgeLength=20.0, FiberRadius=0.8,
                       SegmentLength=2.0, Displacement=0.5, Seed=4, GRatio=0.7)
original = servermanager.Fetch(cube)


def fibers(poly):
    """Per line cell: (fiber_id, bundle_id, [(x, y, z, r, inner)])."""
    radius = poly.GetPointData().GetArray("radius")
    inner = poly.GetPointData().GetArray("inner_radius")
    ids = poly.GetCellData().GetArray("fiber_id")
    bundles = poly.GetCellData().GetArray("bundle_id")
    out = []
    for c in range(poly.GetNumberOfCells()):
        cell = poly.GetCell(c)
        pts = []
        for k in range(cell.GetNumberOfPoints()):
            i = cell.GetPointId(k)
            x, y, z = poly.GetPoint(i)
            pts.append((x, y, z, radius.GetValue(i), inner.GetValue(i) if inner else None))
        out.append((ids.GetValue(c), bundles.GetValue(c), pts))
    return out


probe = FiberReader()


def fiber_reader_claims(path):
    """vtkFiberReader::CanReadFile, what ParaView's reader factory asks."""
    return bool(servermanager.vtkSMReaderFactory.CanReadFile(path, probe.SMProxy))


before = fibers(original)
for ext in ("csv", "txt"):
    path = os.path.join(tmp, "cube." + ext)
    if os.path.exists(path):
        os.remove(path)
    # SaveData would pick ParaView's own CSV writer for .csv: name the writer.
    writer = FiberWriter(Input=cube, FileName=path)
    writer.UpdatePipeline()
    Delete(writer)
    # ParaView's CSV reader takes any .csv and .txt, so OpenDataFile may pick it (the GUI asks);
    # FiberReader must be among the readers offered.
    check(fiber_reader_claims(path), "FiberReader does not offer to read ." + ext)
    reader = FiberReader(FileName=path)
    after = fibers(servermanager.Fetch(reader))
    check(len(after) == len(before), ".%s: %d fibers read back" % (ext, len(after)))
    for (fid, bundle, pts), (fid2, bundle2, pts2) in zip(before, after):
        if ext == "txt":  # CACTUS: ids are positions, no bundles, no inner radii; points exact
            check([p[:4] for p in pts] == [p[:4] for p in pts2], ".txt fiber %d differs" % fid)
            continue
        check((fid, bundle) == (fid2, bundle2), ".csv ids %s != %s" % ((fid, bundle), (fid2, bundle2)))
        # CATERPillar: every point comes back bit for bit, in order, among the extra spheres.
        j = 0
        for p in pts:
            while j < len(pts2) and pts2[j][:3] != p[:3]:
                j += 1
            check(j < len(pts2), ".csv fiber %d lost point %s" % (fid, p[:3]))
            check(pts2[j] == p, ".csv fiber %d point %s: %s" % (fid, p, pts2[j]))
        check(len(pts2) >= len(pts), ".csv spheres")
    Delete(reader)

plain = os.path.join(tmp, "table.csv")
with open(plain, "w") as f:
    f.write("a,b,c\n1,2,3\n4,5,6\n")
check(not fiber_reader_claims(plain), "FiberReader claimed an ordinary CSV")
table = OpenDataFile(plain)
check(table is not None and table.GetXMLName() == "CSVReader", "an ordinary CSV is not opened as a table")

liar = os.path.join(tmp, "liar.txt")
with open(liar, "w") as f:
    f.write("20\n3\n2\n0 0 0 1.0\n0 0 5 1.0\n")
bad = FiberReader(FileName=liar)
catcher = ErrorCatcher(bad)
bad.UpdatePipeline()
check("liar.txt line 6: strand 1 of 3" in catcher.text(), "lying count: %s" % catcher.text())
print("test_substrate_io passed")
