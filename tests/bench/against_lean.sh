#!/usr/bin/env bash
# rtiow's render loop against the lean tracer (lean_tracer.cpp) on the book's job, in
# alternating rounds on this machine, and the ratio of their medians; also against the lean
# tracer with rtiow's kind of spawn (--robust-offset), which prices the robust offsets. rtiow
# traces the same paths (--roulette off): its roulette saves rays that cost more than the
# average one, which would flatter its rate by about 2%:
#   bash tests/bench/against_lean.sh [rounds=5] [threads=2] [build dir=build]
set -euo pipefail
rounds=${1:-5}
threads=${2:-2}
bin=${3:-build}/bin
job=(--width 400 --height 225 --spp 100 --depth 50 --threads "$threads")

rate() { grep -o '"mrays_per_second":[0-9.]*' | cut -d: -f2; }
median() { sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }

rtiow_rates=() lean_rates=() robust_rates=()
for ((round = 1; round <= rounds; ++round)); do
  rtiow_rates+=("$("$bin/rtiow" bench-point --scene cover "${job[@]}" --repeat 1 --roulette off | tail -1 | rate)")
  lean_rates+=("$("$bin/rtiow_lean_tracer" "${job[@]}" --repeat 1 | rate)")
  robust_rates+=("$("$bin/rtiow_lean_tracer" "${job[@]}" --repeat 1 --robust-offset | rate)")
done
rtiow_median=$(printf '%s\n' "${rtiow_rates[@]}" | median)
lean_median=$(printf '%s\n' "${lean_rates[@]}" | median)
robust_median=$(printf '%s\n' "${robust_rates[@]}" | median)
echo "rtiow bench-point (Mrays/s): ${rtiow_rates[*]}"
echo "lean tracer       (Mrays/s): ${lean_rates[*]}"
echo "lean, robust spawn (Mrays/s): ${robust_rates[*]}"
awk -v r="$rtiow_median" -v l="$lean_median" -v o="$robust_median" -v t="$threads" \
  'BEGIN {printf "medians: rtiow %.2f, lean %.2f Mrays/s, %d threads: rtiow at %.3fx the lean tracer\n", r, l, t, r / l
          printf "against the lean tracer with the robust spawn (%.2f Mrays/s): %.3fx\n", o, r / o}'
