"""pvpython: a CACTUS strand list keeps its box size through FiberReader (field data box_size) and
FiberWriter (line 1 of the .txt written back), a periodic cell's largest edge is the box of a cell,
and a box_size that is not one finite number is an error naming it."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager  # noqa: E402

load_plugin(globals())
tmp = option("-T")


def first_line(path):
    with open(path) as f:
        return f.readline().strip()


def box_of(poly):
    a = poly.GetFieldData().GetArray("box_size")
    return None if a is None else [a.GetValue(i) for i in range(a.GetNumberOfValues())]


# A strand list written by hand with an unusual box: 23.75 µm.
source = os.path.join(tmp, "box.txt")
with open(source, "w") as f:
    f.write("23.75\n2\n3\n0 0 0 0.5\n0 0.25 4 0.5\n0 0 8 0.6\n2\n3 1 0 0.7\n3 1 8 0.7\n")
reader = FiberReader(FileName=source)
read = servermanager.Fetch(reader)
check(box_of(read) == [23.75], "box_size read: %s" % box_of(read))
out = os.path.join(tmp, "box_again.txt")
writer = FiberWriter(Input=reader, FileName=out)
writer.UpdatePipeline()
Delete(writer)
check(first_line(out) == "23.75", "box size written back: %r" % first_line(out))
with open(source) as a, open(out) as b:
    check(a.read() == b.read(), "the strand list did not come back byte for byte")

# CACTUS's "no box" (-1) gives no field data and is written as -1 again.
none = os.path.join(tmp, "nobox.txt")
with open(none, "w") as f:
    f.write("-1\n1\n2\n0 0 0 1\n0 0 5 1\n")
r2 = FiberReader(FileName=none)
check(box_of(servermanager.Fetch(r2)) is None, "a box size of -1 became field data")
out2 = os.path.join(tmp, "nobox_again.txt")
w2 = FiberWriter(Input=r2, FileName=out2)
w2.UpdatePipeline()
Delete(w2)
check(first_line(out2) == "-1", "no box written as %r" % first_line(out2))

# A periodic cell is the box: its largest edge.
cube = FiberCubeSource(Populations=1, EdgeLength=12.0, Periodic=1, NumberOfFibers=4, FiberRadius=0.8, Seed=3)
cell = servermanager.Fetch(cube).GetFieldData().GetArray("periodic_cell")
edge = max(cell.GetValue(2 * a + 1) - cell.GetValue(2 * a) for a in range(3))
out3 = os.path.join(tmp, "cell.txt")
w3 = FiberWriter(Input=cube, FileName=out3)
w3.UpdatePipeline()
Delete(w3)
check(float(first_line(out3)) == edge, "cell box %r, largest edge %r" % (first_line(out3), edge))

# A box_size of two values is refused by name; nothing is written.
bad = ProgrammableFilter(Input=reader)
bad.Script = ("self.GetOutput().ShallowCopy(self.GetInput())\n"
              "from vtkmodules.vtkCommonCore import vtkDoubleArray\n"
              "a = vtkDoubleArray(); a.SetName('box_size'); a.InsertNextValue(1.0); a.InsertNextValue(2.0)\n"
              "self.GetOutput().GetFieldData().AddArray(a)\n")
out4 = os.path.join(tmp, "bad.txt")
w4 = FiberWriter(Input=bad, FileName=out4)
catcher = ErrorCatcher(w4.GetClientSideObject().GetWriter())  # the error of the write
outer = ErrorCatcher(w4)  # the parallel writer fails too
w4.UpdatePipeline()
check("box_size must be one finite number" in catcher.text(), "bad box: %s" % catcher.text())
check(not os.path.exists(out4), "a file was written for a bad box_size")
print("test_substrate_box passed")
