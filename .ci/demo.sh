#!/usr/bin/env bash
# `make demo`: the simulated station -> bridge -> display demo, headless-safe.
#  1. twister-station on the in-process simulated Fastrak sculpts a sphere with a
#     scripted stroke sequence and serves the display link; twister-bridge renders
#     it offscreen (EGL surfaceless, no display needed) to PNG snapshots and exports
#     the final mesh; the demo fails unless both hold the same mesh, bit for bit.
#  2. The station's journal is replayed onto the same sphere by `twister replay`
#     (what happens after a power loss, or on a finer model).
#  3. The paper's Figure 8 comparison of the three warp methods.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/bin
out=build/demo

echo "== 1. simulated station -> twister-bridge (offscreen display)"
host/twister-bridge/demo.sh build "$out"

echo
echo "== 2. replay the station's journal onto the initial sphere"
"$bin/twister" replay "$out/journal.bin" --mesh "$out/sphere.obj" --out "$out/replayed.obj" \
  | tee "$out/replay.txt"
station_sum="$(sed -n 's/^twister-station: mesh checksum \([0-9a-f]*\)$/\1/p' "$out/station.log")"
replay_sum="$(sed -n 's/^mesh .* checksum \([0-9a-f]*\)$/\1/p' "$out/replay.txt")"
if [[ -z "$station_sum" || "$station_sum" != "$replay_sum" ]]; then
  echo "demo: replay gives mesh $replay_sum, the station had $station_sum" >&2
  exit 1
fi
echo "demo: the replayed journal rebuilds the station's mesh exactly (checksum $replay_sum)"

echo
echo "== 3. Figure 8 of the paper: self-intersections per method and angle"
"$bin/twister" figure8 --svg "$out/figure8.svg" --png "$out/figure8.png" | head -12

echo
echo "Demo output in $out/: pictures/*.png (rest, live warp, committed), final.obj,"
echo "replayed.obj, journal.bin, figure8.png/svg, station.log, bridge.log"
