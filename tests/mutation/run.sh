#!/usr/bin/env bash
# Mutation testing, by hand, not in CI: applies each mutant of tests/mutation/mutants.txt to a
# scratch copy of the working tree, rebuilds incrementally, runs the fast test labels and says
# whether the suite caught it (killed) or not (survived).
#   bash tests/mutation/run.sh [labels] [name-filter]
# labels default to unit|render|stats|image|extremes (all but sanitize, fuzz, mpi, cli, hostile).
set -euo pipefail
src="$(cd "$(dirname "$0")/../.." && pwd)"
labels="${1:-unit|render|stats|image|extremes}"
filter="${2:-}"
work="${RTIOW_MUTATION_DIR:-/tmp/rtiow-mutation}"

# A fresh copy of the working tree, every file touched: a build left by an interrupted run
# must not keep a mutant's objects.
rm -rf "$work/src" && mkdir -p "$work/src"
tar -C "$src" --exclude=./build --exclude=./.git -cf - . | tar -C "$work/src" -xf -
find "$work/src" -type f -exec touch {} +
cmake -S "$work/src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DRTIOW_SANITIZER_TESTS=OFF \
  -DRTIOW_FUZZ_TESTS=OFF -DRTIOW_MPI=OFF >/dev/null
# Only what the chosen labels run: most of a mutant's time is rebuilding, and a header of the
# hot path is included by every test binary.
targets=(rtiow)
for label in ${labels//|/ }; do
  case "$label" in
    unit | render | stats | image | extremes | cli | hostile) targets+=("${label}_tests") ;;
    *) targets=(all) && break ;;
  esac
done
build() { cmake --build "$work/build" -j"$(nproc)" --target "${targets[@]}" >"$work/build.log" 2>&1; }
suite() { ctest --test-dir "$work/build" -L "$labels" -j"$(nproc)" --stop-on-failure >"$work/test.log" 2>&1; }
build || { echo "the unmutated tree does not build" >&2; exit 1; }
suite || { echo "the unmutated tree fails its tests: see $work/test.log" >&2; exit 1; }

killed=0 survived=0
while IFS='|' read -r name file from to; do
  name="$(echo "$name" | xargs)"
  [[ -z "$name" || "$name" == \#* ]] && continue
  [[ -n "$filter" && "$name" != *$filter* ]] && continue
  file="$(echo "$file" | xargs)"
  target="$work/src/$file"
  cp "$target" "$target.orig"
  if ! python3 - "$target" "$from" "$to" <<'PY'
import sys
path, old, new = sys.argv[1], sys.argv[2].strip(), sys.argv[3].strip()
text = open(path).read()
if text.count(old) != 1:
    sys.exit(f"{path}: the text occurs {text.count(old)} times")
open(path, "w").write(text.replace(old, new))
PY
  then
    echo "SKIPPED  $name (text not found once)"; mv "$target.orig" "$target"; continue
  fi
  if ! build; then
    echo "KILLED   $name (does not compile)"; killed=$((killed + 1))
  elif suite; then
    echo "SURVIVED $name"; survived=$((survived + 1))
  else
    caught="$(grep -m1 -oE '[0-9]+ - [^ ]+' "$work/test.log" | head -1 || true)"
    echo "KILLED   $name by ${caught:-a failing test}"; killed=$((killed + 1))
  fi
  mv "$target.orig" "$target"
  touch "$target"
done <"$src/tests/mutation/mutants.txt"
build >/dev/null || true
echo "$killed killed, $survived survived"
