"""pvpython: a fastPLI .dat with one bad line, opened like File -> Open does (OpenDataFile), lands in
FiberReader and gives its error naming the file and the line, not the Tecplot reader's."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402

load_plugin(globals())
tmp = option("-T")
good = ["%d %d 0 0.5" % (i, i % 3) for i in range(40)]
for bad_line, text in ((1, "1.0 2.0 abc 0.5"), (3, "1 2 3"), (25, "1 2 3 -0.5")):
    lines = list(good)
    lines[bad_line - 1] = text
    path = os.path.join(tmp, "broken_%d.dat" % bad_line)
    with open(path, "w") as f:
        f.write("\n".join(lines[:20]) + "\n\n" + "\n".join(lines[20:]) + "\n")
    reader = OpenDataFile(path)
    check(reader is not None and reader.GetXMLName() == "FiberReader",
          "line %d: OpenDataFile chose %s" % (bad_line, reader and reader.GetXMLName()))
    errors = ErrorCatcher(reader)
    reader.UpdatePipeline()
    # lines after the blank line are one further down in the file
    expected = "broken_%d.dat line %d:" % (bad_line, bad_line if bad_line <= 20 else bad_line + 1)
    check(expected in errors.text(), "line %d: %r" % (bad_line, errors.text()))
    Delete(reader)
# The fiber file with no bad line still reads.
path = os.path.join(tmp, "good.dat")
with open(path, "w") as f:
    f.write("\n".join(good) + "\n")
reader = OpenDataFile(path)
reader.UpdatePipeline()
check(reader.GetDataInformation().GetNumberOfPoints() == 40, "good file")
check("Group" in reader.ListProperties(), "FiberReader has no Group property")
print("broken .dat files reach FiberReader")
