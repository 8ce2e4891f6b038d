#!/usr/bin/env bash
# Installs the dependencies, builds in build/ and runs the demo (Examples/demo.py) with pvbatch
# under Xvfb: a dense two-population periodic cell solved to zero overlaps, measured by
# FiberMetrics, tubes coloured by population, PLISimulation -> PLIAnalysis -> FOM with its legend;
# writes demo.png (all views in one picture), demo_tubes.vtp and demo_fibers.h5 into the printed
# folder and prints fibers, steps, collisions, volume fraction and seconds (a few seconds after the
# build; README "FiberPLI" says what the time depends on).
set -euo pipefail
cd "$(dirname "$0")/.."
# ctest -j2 runs multi-threaded tests side by side on 2 cores: spinning OpenMP threads then wait
# for descheduled ones and a 0.5 s solve can take 20 s. Passive waiting keeps them robust.
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-PASSIVE}"
bash scripts/install-deps.sh
bash scripts/build.sh
out="${FIBERPLI_DEMO_OUT:-$PWD/build/demo}"
mkdir -p "$out"
plugin=$(find "$PWD/build/lib" -name FiberPLI.so | head -n 1)
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvbatch --dr Examples/demo.py "$plugin" "$out"
echo "Demo output written to: $out"
