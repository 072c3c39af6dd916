#!/usr/bin/env bash
# render_pins.sh BIN DIR: the outputs a refactoring must not change, rendered by BIN into DIR:
# the cover, passes, a crop, parts and their merges (plain, --stats-channels, --passes), a kept
# and resumed render and its checkpoint, adaptive renders, --like, an MPI render, denoised renders
# (one process, parts denoised by `rtiow denoise`, an adaptive one), and a render
# killed and resumed (checked against the uninterrupted one here). Render them with the binary
# before a change and after it, then compare with compare_pins.py OLD NEW.
set -u
BIN=$1; DIR=$2
[ -e "$DIR" ] && { echo "render_pins: $DIR exists: give a new directory" >&2; exit 2; }
mkdir -p "$DIR" && cd "$DIR" || exit 2
R() { "$BIN" "$@" -q 2>>log || echo "FAILED: $*" >> log; }
R render --scene cover --width 200 --spp 8 -o cover.png
R render --scene cover --width 160 --spp 4 --passes albedo,normal,depth -o passes.exr
R render --scene cover --width 160 --spp 4 --crop 40,30,50,40 --passes albedo,normal,depth -o crop.exr
R render --scene cover --width 160 --spp 6 --part 0/2 -o p0.exr
R render --scene cover --width 160 --spp 6 --part 1/2 -o p1.exr
R merge p0.exr p1.exr -o merged.exr
R render --scene cover --width 160 --spp 6 --stats-channels --part 0/2 -o ps0.exr
R render --scene cover --width 160 --spp 6 --stats-channels --part 1/2 -o ps1.exr
R merge --stats-channels ps0.exr ps1.exr -o merged-stats.exr
R render --scene cover --width 160 --spp 6 --passes albedo,normal,depth --part 0/2 -o pp0.exr
R render --scene cover --width 160 --spp 6 --passes albedo,normal,depth --part 1/2 -o pp1.exr
R merge pp0.exr pp1.exr -o merged-passes.exr
R render --scene materials --width 120 --spp 5 --keep-state -o kept.exr
cp kept.exr.rtiow-checkpoint kept.checkpoint 2>/dev/null
R render --scene materials --width 120 --spp 9 --resume -o kept.exr
R render --scene cover --width 120 --target-error 0.2 --spp 64 --stats-channels -o adaptive.exr
R render --scene cover --width 120 --image-error 0.05 --spp 64 --passes albedo --keep-state -o imgerr.exr
cp imgerr.exr.rtiow-checkpoint imgerr.checkpoint 2>/dev/null
R render --like cover.png -o like.png
R render --scene materials --width 160 --spp 16 --denoise -o denoised.exr
R render --scene defocus --width 150 --spp 16 --denoise --part 0/2 -o pd0.exr
R render --scene defocus --width 150 --spp 16 --denoise --part 1/2 -o pd1.exr
R denoise pd0.exr pd1.exr -o denoised-parts.exr
R render --scene cover --width 130 --spp 32 --adaptive --denoise -o denoised-adaptive.exr
mpirun --allow-run-as-root --oversubscribe -np 2 "$BIN" render -q --scene cover --width 160 --spp 6 --passes albedo,normal,depth --stats-channels -o mpi.exr 2>>log || echo "FAILED mpi" >> log
# Killed and resumed: must equal the uninterrupted render.
R render --scene cover --width 600 --spp 256 -o whole.png
( "$BIN" render -q --scene cover --width 600 --spp 256 --checkpoint 1 -o killed.png & pid=$!; sleep 5; kill -KILL $pid; wait $pid ) 2>/dev/null
R render --scene cover --width 600 --spp 256 --resume -o killed.png
idiff -q whole.png killed.png >/dev/null && echo "resumed = whole" >> log || echo "RESUMED DIFFERS" >> log
rm -f *.rtiow-checkpoint
sha256sum * | grep -v " log$" > sums.txt
