#!/usr/bin/env bash
# rtiow's render loop against the lean tracer (lean_tracer.cpp) at 1, 4, 8 and 16 threads, and
# at depth 1 (camera rays and their first scatter only), in alternating rounds, medians; then
# the command against its loop, and a million-sphere file's load against the same scene made
# in memory, at 1 to 16 threads. For a many-core machine (docs/performance.md, "On a 16-core
# Xeon"); a few minutes there.
#   bash tests/bench/many_cores.sh [build dir=build] [scale=1: the image's side, x 800x450]
set -u
bin=${1:-build}/bin
scale=${2:-1}
width=$(awk -v s="$scale" 'BEGIN {print int(800 * s)}')
height=$(awk -v s="$scale" 'BEGIN {print int(450 * s)}')
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

rate() { grep -o '"mrays_per_second":[0-9.]*' | tail -1 | cut -d: -f2; }
median() { tr ' ' '\n' | grep . | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
seconds() {
  local start
  start=$(date +%s.%N)
  "$@" >/dev/null 2>&1 || echo "failed: $*" >&2
  awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.3f", b - a}'
}

# threads rounds depth: rtiow, the lean tracer (double test), --float, --robust-offset
against_lean() {
  local threads=$1 rounds=$2 depth=$3 rtiow="" lean="" float="" robust=""
  local job=(--width "$width" --height "$height" --spp 64 --depth "$depth" --threads "$threads"
    --repeat 1)
  for ((round = 0; round < rounds; ++round)); do
    rtiow+=" $("$bin/rtiow" bench-point --scene cover "${job[@]}" 2>/dev/null | rate)"
    lean+=" $("$bin/rtiow_lean_tracer" "${job[@]}" 2>/dev/null | rate)"
    if ((depth > 1)); then
      float+=" $("$bin/rtiow_lean_tracer" "${job[@]}" --float 2>/dev/null | rate)"
      robust+=" $("$bin/rtiow_lean_tracer" "${job[@]}" --robust-offset 2>/dev/null | rate)"
    fi
  done
  echo "threads $threads, depth $depth, ${width}x${height}x64: rtiow$rtiow | lean$lean" \
    "| lean --float$float | lean --robust-offset$robust"
  awk -v r="$(echo "$rtiow" | median)" -v l="$(echo "$lean" | median)" \
    -v f="$(echo "$float" | median)" -v o="$(echo "$robust" | median)" \
    -v t="$threads" -v d="$depth" 'BEGIN {
      printf "  medians (Mrays/s): rtiow %.2f, lean %.2f: %.3fx", r, l, r / l
      if (f > 0) printf "; lean --float %.2f: %.3fx; lean --robust-offset %.2f: %.3fx", f, r / f, o, r / o
      printf "\n" }'
}

echo "== the render loop against the lean tracer (Mrays/s)"
against_lean 1 3 50
against_lean 4 5 50
against_lean 8 5 50
against_lean 16 7 50
echo "== camera rays only (depth 1)"
against_lean 1 3 1
against_lean 8 5 1

echo "== the command (scene from a file, checkpoint on, PNG) against its loop, the book's job"
"$bin/rtiow" scene cover -o "$work/cover.json"
for threads in 16 4; do
  command="" loop=""
  for round in 1 2 3 4 5; do
    command+=" $(seconds "$bin/rtiow" render "$work/cover.json" --width 400 --height 225 --spp 100 \
      --depth 50 --sampler independent --seed 0 -q --threads "$threads" -o "$work/cover.png")"
    loop+=" $(seconds "$bin/rtiow" bench-point --scene cover --width 400 --height 225 --spp 100 \
      --depth 50 --repeat 1 --threads "$threads")"
  done
  awk -v c="$(echo "$command" | median)" -v l="$(echo "$loop" | median)" -v t="$threads" \
    'BEGIN {printf "threads %d: command %.3f s, loop %.3f s: %.3fx\n", t, c, l, l / c}'
done

echo "== a million spheres from a file against the same made in memory, 8x8, 1 spp (seconds)"
"$bin/rtiow" scene spheres:1000000 -o "$work/s1m.json"
for threads in 1 2 4 8 16; do
  file="" memory=""
  for round in 1 2 3; do
    file+=" $(seconds "$bin/rtiow" render "$work/s1m.json" --width 8 --height 8 --spp 1 \
      --threads "$threads" -o "$work/file.png")"
    memory+=" $(seconds "$bin/rtiow" render --scene spheres:1000000 --width 8 --height 8 --spp 1 \
      --threads "$threads" -o "$work/memory.png")"
  done
  awk -v f="$(echo "$file" | median)" -v m="$(echo "$memory" | median)" -v t="$threads" \
    'BEGIN {printf "threads %d: file %.3f, memory %.3f, the load %.3f more\n", t, f, m, f - m}'
done
