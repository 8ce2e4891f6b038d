#!/usr/bin/env bash
# Installs the dependencies, builds in build/ and runs the whole test suite under Xvfb.
# The exit code is ctest's.
set -euo pipefail
cd "$(dirname "$0")/.."
# ctest -j2 runs multi-threaded tests side by side on 2 cores: spinning OpenMP threads then wait
# for descheduled ones and a 0.5 s solve can take 20 s. Passive waiting keeps them robust.
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-PASSIVE}"
bash scripts/install-deps.sh
bash scripts/build.sh

# One HDF5 in the process: our libraries must link ParaView's libhdf5_openmpi only (docs/architecture.md §5).
libs=$(find build/lib -name 'FiberPLI*.so*' -o -name 'libFiberPLI*.so*' | sort)
linked=$(ldd $libs)
if grep -q 'libhdf5_serial' <<<"$linked"; then
  echo "FiberPLI links the serial HDF5 library beside ParaView's libhdf5_openmpi:" >&2
  grep hdf5 <<<"$linked" >&2
  exit 1
fi

cd build
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure -j2
