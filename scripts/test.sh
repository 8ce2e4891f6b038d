#!/usr/bin/env bash
# Installs the dependencies, builds in build/ and runs the whole test suite under Xvfb.
# The exit code is ctest's.
set -euo pipefail
cd "$(dirname "$0")/.."
# ctest -j2 runs multi-threaded tests side by side on 2 cores: spinning OpenMP threads then wait
# for descheduled ones and a 0.5 s solve can take 20 s. Passive waiting keeps them robust.
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-PASSIVE}"
bash scripts/install-deps.sh
# Every C/C++ file as .clang-format (VTK's style) says, before anything is built.
bash scripts/check_format.sh >/dev/null || { bash scripts/check_format.sh | grep -v 'file(s) checked' >&2; exit 1; }
bash scripts/build.sh

# One HDF5 for our code: our libraries must link ParaView's libhdf5_openmpi only (docs/architecture.md §5).
# The non-GUI libraries (Core, Conversion, Filters, Readers) are checked with everything they pull in;
# the plugin module also links ParaView's pqCore for its GUI part, which itself pulls in NetCDF and
# GDAL and with them the serial HDF5 (as pvpython and pvbatch already do), so for the plugin only
# its own direct dependencies are checked.
libs=$(find build/lib -name 'libFiberPLI*.so*' | sort)
linked=$(ldd $libs)
plugin=$(find build/lib -name 'FiberPLI.so' | head -1)
direct=$(readelf -d "$plugin" | grep NEEDED)
if grep -q 'libhdf5_serial' <<<"$linked$direct"; then
  echo "FiberPLI links the serial HDF5 library beside ParaView's libhdf5_openmpi:" >&2
  grep hdf5 <<<"$linked$direct" >&2
  exit 1
fi
grep -q 'libhdf5_openmpi' <<<"$linked" || { echo "FiberPLI's readers do not link libhdf5_openmpi" >&2; exit 1; }

cd build
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure -j2
