#!/usr/bin/env bash
# Runs bench/mpi_solver_bench.py for 1 rank x 1 and 2 threads and 2 ranks x 1 thread on every
# workload given (default: cube-a cube-b cube-c cell) and prints the rows of the table in
# bench/README.md "Distributed solver". Never run by ctest.
#   bash bench/mpi_solver_bench.sh <build dir> [--max-steps N] [workload...]
set -euo pipefail
build=$(cd "$1" && pwd); shift
steps=()
if [ "${1:-}" = "--max-steps" ]; then steps=(--max-steps "$2"); shift 2; fi
workloads=("$@"); [ ${#workloads[@]} -gt 0 ] || workloads=(cube-a cube-b cube-c cell)
here=$(cd "$(dirname "$0")" && pwd)
plugin=$(find "$build" -name FiberPLI.so | head -1)
pvbatch=$(command -v pvbatch)
# --bind-to none: Open MPI binds each of up to 2 ranks to one core by default, which would run a
# rank's threads on that one core. Waiting ranks yield the core (the default busy poll starves the others on a loaded machine).
export OMP_WAIT_POLICY=PASSIVE OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_mpi_yield_when_idle=1
echo "| workload | ranks | threads | steps | wall [s] | s/step | collisions left | per rank: fibers/peak points/halo links/held links/halo bytes per step | per rank: peak RSS / RSS before the solve | per rank: CPU [s] | hash |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for w in "${workloads[@]}"; do
  for run in "1 1" "1 2" "2 1"; do
    set -- $run
    mpiexec --allow-run-as-root --oversubscribe --bind-to none -n "$1" "$pvbatch" --dr "$here/mpi_solver_bench.py" "$plugin" "$w" \
      --threads "$2" "${steps[@]}" 2>/dev/null | grep '^| '
  done
done
