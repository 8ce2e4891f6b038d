#!/usr/bin/env bash
# A push rule over many inputs of one workload (bench/README.md "Push schedule on heavily
# overlapping input"): the final φ of one input moves by ±2 points with the last bit of the push,
# so a rule is judged by its mean over seeds and by its paired difference to the baseline (the
# same seed = the same input). Runs fiberpli_solver_bench on one thread per seed, once with the
# rule's flags and once with the baseline's, and prints per seed steps / φ of both, then the
# means, the mean paired difference of φ and of the steps with their standard errors. Never run
# by ctest; long, so run it under `nice -n 19` on a shared machine.
#   bash bench/push_seeds.sh <build dir> [--workload dense-b] [--seeds 1-16] [--samples 300000]
#        [--baseline "FLAGS"] [--baseline-build DIR] [--cache DIR] [--tag TEXT] -- RULE FLAGS...
# FLAGS are solver_bench knobs (e.g. --push-boost 2, --separation-speed 0.05); the baseline is
# the defaults unless given, run by the same build unless --baseline-build names another one (a
# code change judged against main's build). --cache DIR keeps each run's row keyed by the bench
# binary, workload, flags, seed and --tag (a label for what the flags do not show, e.g. the
# environment), so a baseline is run once for all rules compared against it.
set -euo pipefail
build=$(cd "$1" && pwd); shift
workload=dense-b seeds=1-16 samples=300000 baseline="" cache="" tag="" baseBuild=$build
while [ $# -gt 0 ]; do
  case "$1" in
    --workload) workload=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --samples) samples=$2; shift 2 ;;
    --baseline) baseline=$2; shift 2 ;;
    --baseline-build) baseBuild=$(cd "$2" && pwd); shift 2 ;;
    --cache) cache=$2; shift 2 ;;
    --tag) tag=$2; shift 2 ;;
    --) shift; break ;;
    *) echo "push_seeds.sh: unknown argument '$1' (rule flags go after --)" >&2; exit 2 ;;
  esac
done
rule="$*"
for b in "$build" "$baseBuild"; do
  [ -x "$b/bin/fiberpli_solver_bench" ] || { echo "push_seeds.sh: no $b/bin/fiberpli_solver_bench (build the bench first)" >&2; exit 2; }
done
first=${seeds%-*} last=${seeds#*-}
[ -n "$cache" ] && mkdir -p "$cache"

# One run: "steps phi solved" (phi in %), from the bench's table row.
run() { # build flags seed tag
  local bench="$1/bin/fiberpli_solver_bench" key file row
  shift
  key=$(echo "$(md5sum < "$bench") $workload $samples $1 seed $2 tag $3" | md5sum | cut -c1-16)
  file="$cache/$key"
  if [ -n "$cache" ] && [ -s "$file" ]; then cat "$file"; return; fi
  # shellcheck disable=SC2086
  row=$("$bench" "$workload" --threads 1 --samples "$samples" --seed "$2" $1 | grep "^| $workload ")
  row=$(echo "$row" | awk -F'|' '{ s = $5; p = $15; gsub(/[ %]/, "", s); gsub(/[ %]/, "", p);
    solved = $12; gsub(/ /, "", solved); print s, p, solved }')
  [ -n "$cache" ] && echo "$row" > "$file"
  echo "$row"
}

echo "workload $workload, seeds $seeds, rule '${rule:-defaults}'${tag:+ ($tag)} vs baseline '${baseline:-defaults}' (1 thread, MC $samples)"
echo "| seed | rule steps | rule φ | baseline steps | baseline φ | Δφ [points] |"
echo "|---|---|---|---|---|---|"
rows=""
for ((seed = first; seed <= last; ++seed)); do
  read -r rs rp rsolved < <(run "$build" "$rule" "$seed" "$tag")
  read -r bs bp bsolved < <(run "$baseBuild" "$baseline" "$seed" "")
  [ "$rsolved" = 1 ] || rs="$rs (unsolved)"
  [ "$bsolved" = 1 ] || bs="$bs (unsolved)"
  printf '| %d | %s | %.1f %% | %s | %.1f %% | %+.2f |\n' "$seed" "$rs" "$rp" "$bs" "$bp" "$(echo "$rp - $bp" | bc -l)"
  rows+="${rs%% *} $rp ${bs%% *} $bp"$'\n'
done
# Means and standard errors of the means (sample standard deviation / √n).
echo -n "$rows" | awk '
  { n++; rs += $1; rp += $2; bs += $3; bp += $4; d = $2 - $4; dd += d; dd2 += d * d;
    e = $1 - $3; de += e; de2 += e * e; r = $1 / $3; lr += log(r) }
  END {
    if (n < 2) { print "need >= 2 seeds"; exit 1 }
    md = dd / n; sd = sqrt((dd2 - n * md * md) / (n - 1)) / sqrt(n);
    me = de / n; se = sqrt((de2 - n * me * me) / (n - 1)) / sqrt(n);
    printf "| mean (%d seeds) | %.0f | %.2f %% | %.0f | %.2f %% | %+.2f ± %.2f |\n", n, rs / n, rp / n, bs / n, bp / n, md, sd;
    printf "paired: Δφ = %+.2f ± %.2f points (mean ± standard error), Δsteps = %+.0f ± %.0f, steps rule/baseline geometric mean %.2f\n",
      md, sd, me, se, exp(lr / n) }'
