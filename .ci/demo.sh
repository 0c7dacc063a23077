#!/usr/bin/env bash
# `make demo`: the most complete end-to-end run that exists, headless-safe.
# Today: the station with the in-process simulated Fastrak and stylus commits a
# scripted stroke to its journal; the journal is replayed onto a sphere and written
# as OBJ; the Figure 8 comparison is drawn. The display (twister-bridge) is not built
# yet, so no live picture of the sculpture is shown.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/bin
out=build/demo
rm -rf "$out" && mkdir -p "$out"

echo "== 1. twister-station, simulated tracker and buttons (virtual time)"
"$bin/twister-station" --config hal/station/deploy/sim.toml --journal "$out/journal.bin"

echo
echo "== 2. replay the station's journal onto a sphere (the imposter -> model workflow)"
"$bin/twister" mesh sphere -n 64 --segments 128 --size 0.25 --out "$out/sphere.obj"
"$bin/twister" replay "$out/journal.bin" --mesh "$out/sphere.obj" --out "$out/sculpted.obj"

echo
echo "== 3. Figure 8 of the paper: self-intersections per method and angle"
"$bin/twister" figure8 --svg "$out/figure8.svg" --png "$out/figure8.png"

echo
echo "Demo output in $out/: journal.bin, sphere.obj, sculpted.obj, figure8.svg, figure8.png"
echo "Not shown: the live display (twister-bridge), which does not exist yet."
