"""pvpython: SaveData of an .h5 onto a full file system fails with an error naming the file, keeps
the file that was there, leaves no temporary file, and pvpython still exits cleanly (it used to
segfault at exit in HDF5's teardown). The full file system is a 64 KiB tmpfs when this process may
mount one (root), else RLIMIT_FSIZE, which fails writes the same way (EFBIG instead of ENOSPC)."""
import os
import resource
import signal
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fiberpli_test import ErrorCatcher, check, load_plugin, option  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402

load_plugin(globals())
tmp = option("-T")
full = os.path.join(tmp, "full")
os.makedirs(full, exist_ok=True)
subprocess.call(["umount", full], stderr=subprocess.DEVNULL)  # left over from an interrupted run
for name in os.listdir(full):
    os.remove(os.path.join(full, name))
mounted = subprocess.call(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", full],
                          stderr=subprocess.DEVNULL) == 0
print("test_h5_full_disk: " + ("64 KiB tmpfs" if mounted else "cannot mount a tmpfs here, using RLIMIT_FSIZE"))

small = FiberCubeSource(Populations=1, NumberOfFibers=2, EdgeLength=10.0, FiberRadius=0.8, SegmentLength=2.0,
                        Seed=1)
big = FiberCubeSource(Populations=3, NumberOfFibers=600, EdgeLength=40.0, FiberRadius=0.8, SegmentLength=1.0,
                      Seed=2)
target = os.path.join(full, "fibers.h5")
SaveData(target, proxy=small)
with open(target, "rb") as f:
    before = f.read()
check(len(before) > 0, "the small file was not written")

saved_limit = resource.getrlimit(resource.RLIMIT_FSIZE)
if not mounted:
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (64 * 1024, saved_limit[1]))
try:
    writer = CreateWriter(target, big)
    catcher = ErrorCatcher(writer.GetClientSideObject().GetWriter())  # the error of the write
    outer = ErrorCatcher(writer)  # the parallel writer fails too (its executive reports it)
    writer.UpdatePipeline()
finally:
    resource.setrlimit(resource.RLIMIT_FSIZE, saved_limit)
text = catcher.text()
check(target in text, "the error must name the file: %r" % text)
check("No space left" in text or "File too large" in text, "the error must give the cause: %r" % text)
with open(target, "rb") as f:
    check(f.read() == before, "the existing file was changed")
check(os.listdir(full) == ["fibers.h5"], "left behind: %s" % os.listdir(full))
Delete(writer)

# HDF5 is still usable: the old file reads back.
reader = OpenDataFile(target)
reader.UpdatePipeline()
check(reader.GetDataInformation().GetNumberOfCells() == 2, "the old file no longer reads")
Delete(reader)
if mounted:
    subprocess.call(["umount", full])
print("test_h5_full_disk passed")
