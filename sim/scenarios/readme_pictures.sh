#!/usr/bin/env bash
# The README's scenario pictures (docs/pictures/), 400x300: the spork step by step and
# the twisted and bent box as the model alone (--plain), one live warp of the spork
# with the display's cues (no heads-up text).
#   sim/scenarios/readme_pictures.sh [BUILD_DIR] [OUT_DIR]   # defaults: build docs/pictures
set -euo pipefail
cd "$(dirname "$0")/../.."
build="${1:-build}"
out="${2:-docs/pictures}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
run() {  # NAME OUT_NAME OPTION
  python3 sim/scenarios/run_scenario.py "sim/scenarios/$1.scn" --bin "$build/bin" \
    --out "$work/$2" --bridge --size 400x300 "$3" > "$work/$2.txt"
}
run spork spork --plain
pics="$work/spork/pictures"
cp "$pics/rest.png" "$out/spork-0-sphere.png"
for k in 1 2 3 4 5; do cp "$pics/commit-$((k + 1)).png" "$out/spork-$k.png"; done
run spork spork-cues --no-hud
cp "$work/spork-cues/pictures/live-5.png" "$out/spork-live-4.png"
for box in box_twist box_bend; do
  run "$box" "$box" --plain
  last="$(ls "$work/$box/pictures" | grep -E '^(commit|mesh)-' | sort -t- -k2 -n | tail -1)"
  cp "$work/$box/pictures/$last" "$out/$box.png"
done
echo "README pictures in $out/"
