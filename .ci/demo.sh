#!/usr/bin/env bash
# `make demo`: the paper's Figure 1, a sphere sculpted into a spork in five two-hand
# strokes, through the real programs, headless-safe.
#  1. twister-station plays sim/scenarios/spork.scn (the simulated Fastrak with
#     scripted buttons for both hands, in real time: 120 Hz) and serves the display
#     link; twister-bridge shows it (a window when $DISPLAY works, else offscreen),
#     writes PNG snapshots and exports the final mesh. Progress: stroke k of 5.
#     Checked: the station's final mesh = the display's = `twister replay` of the
#     journal (checksums).
#  2. The same chain with twister-sim on a pseudo-terminal: the tracker's bytes go
#     over a serial line to the station (stylus strokes: the Fastrak line carries only
#     the stylus button, so the two-hand scenarios use the in-process simulator).
#  3. The paper's Figure 8 comparison of the three warp methods.
# Nothing is left running: every process is waited for or killed.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/bin
out=build/demo
rm -rf "$out"
mkdir -p "$out"

window=()
if [[ -n "${DISPLAY:-}" ]] && command -v xdpyinfo > /dev/null && xdpyinfo > /dev/null 2>&1; then
  window=(--window)
  echo "== display: a window on $DISPLAY (snapshots are written too)"
else
  echo "== display: offscreen (no usable \$DISPLAY): snapshots only"
fi

echo "== 1. the spork (paper, Figure 1): twister-station -> link -> twister-bridge"
python3 sim/scenarios/run_scenario.py sim/scenarios/spork.scn --bin "$bin" \
  --out "$out/spork" --bridge --time real --progress 5 --size 800x600 "${window[@]}" \
  | tee "$out/spork.txt"
sums="$(sed -n 's/^\(station\|display\|replay\) \([0-9a-f]*\)$/\2/p' "$out/spork.txt" | sort -u)"
if [[ "$(wc -l <<< "$sums")" != 1 || -z "$sums" ]]; then
  echo "demo: station, display and replay disagree:" >&2
  cat "$out/spork.txt" >&2
  exit 1
fi
echo "demo: station = display = replay (checksum $sums)"
pics="$out/spork/pictures"
steps=("$pics/rest.png")
for v in 2 3 4 5 6; do steps+=("$pics/commit-$v.png"); done
for p in "${steps[@]}"; do
  [[ -s "$p" ]] || { echo "demo: missing snapshot $p" >&2; exit 1; }
done

echo
echo "== 2. over a serial line: twister-sim on a PTY -> twister-station -> twister-bridge"
python3 tests/e2e/pty_chain_test.py --bin "$bin" --scenario sim/scenarios/stylus_strokes.scn \
  --out "$out/pty" --commits 3 | tail -2

echo
echo "== 3. Figure 8 of the paper: self-intersections per method and angle"
"$bin/twister" figure8 --svg "$out/figure8.svg" --png "$out/figure8.png" | head -12

echo
echo "Spork, step by step (sphere, then after each of the five strokes):"
printf '  %s\n' "${steps[@]}"
echo "Live warps (hands' weights in red and green): $pics/live-*.png"
echo "Final mesh: $out/spork/final.glb (glTF, as the display holds it) and $out/spork/replayed.obj (OBJ, rebuilt from the journal)"
echo "Journal: $out/spork/journal.twj"
echo "Logs: $out/spork/station.log, $out/spork/bridge.log"
