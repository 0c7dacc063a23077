#!/usr/bin/env bash
# The README's pictures of the paper's Figure 6: a twisted box and a bent box, made
# by the real programs. twister-station (simulator, virtual time, scripted buttons)
# plays host/twister-bridge/figure6/{twist,bend}.scn on a subdivided bar; the
# display (twister-bridge --offscreen) pictures the live warp just before the
# stroke commits: weights, hand glyphs, screw axes and trajectories, HUD.
# Usage: host/twister-bridge/figure6.sh [BUILD_DIR] [OUT_DIR]
#   writes OUT_DIR/figure6-twist.png and OUT_DIR/figure6-bend.png (default OUT_DIR:
#   docs/pictures). Fails unless each run ends with the display's mesh equal to the
#   station's (checksums).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../../build}"
out="${2:-$here/../../docs/pictures}"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
work="$(mktemp -d)"
trap '[[ -n "${TWISTER_KEEP:-}" ]] || rm -rf "$work"' EXIT
export EGL_PLATFORM=surfaceless
unset DISPLAY WAYLAND_DISPLAY

# A bar 0.10 x 0.48 x 0.10 m centred at (0.55, 0, 0.10) m, its six faces cut into
# squares of 1 cm (shared vertices along the edges): enough for a smooth twist.
awk 'BEGIN {
  nx = 10; ny = 48; nz = 10; x0 = 0.50; y0 = -0.24; z0 = 0.05; h = 0.01;
  # vertex ids on the surface of the (nx+1) x (ny+1) x (nz+1) lattice
  for (i = 0; i <= nx; i++) for (j = 0; j <= ny; j++) for (k = 0; k <= nz; k++) {
    if (i > 0 && i < nx && j > 0 && j < ny && k > 0 && k < nz) continue;
    id[i, j, k] = ++n;
    printf "v %.4f %.4f %.4f\n", x0 + i * h, y0 + j * h, z0 + k * h;
  }
  # faces, outward (counter-clockwise seen from outside)
  for (j = 0; j < ny; j++) for (k = 0; k < nz; k++) {
    quad(id[0, j, k], id[0, j, k + 1], id[0, j + 1, k + 1], id[0, j + 1, k]);
    quad(id[nx, j, k], id[nx, j + 1, k], id[nx, j + 1, k + 1], id[nx, j, k + 1]);
  }
  for (i = 0; i < nx; i++) for (k = 0; k < nz; k++) {
    quad(id[i, 0, k], id[i + 1, 0, k], id[i + 1, 0, k + 1], id[i, 0, k + 1]);
    quad(id[i, ny, k], id[i, ny, k + 1], id[i + 1, ny, k + 1], id[i + 1, ny, k]);
  }
  for (i = 0; i < nx; i++) for (j = 0; j < ny; j++) {
    quad(id[i, j, 0], id[i, j + 1, 0], id[i + 1, j + 1, 0], id[i + 1, j, 0]);
    quad(id[i, j, nz], id[i + 1, j, nz], id[i + 1, j + 1, nz], id[i, j + 1, nz]);
  }
}
function quad(a, b, c, d) { printf "f %d %d %d\nf %d %d %d\n", a, b, c, a, c, d }' \
  > "$work/bar.obj"

cat > "$work/camera.toml" <<TOML
[camera]
azimuth_deg = 35.0
elevation_deg = 30.0
zoom = 1.25
TOML

for stroke in twist bend; do
  cat > "$work/$stroke.toml" <<TOML
[station]
journal = "$work/$stroke-journal.bin"
mesh = "$work/bar.obj"
loop_timeout_ms = 10

[tracker]
backend = "sim"
left_station = 1
right_station = 2

[tracker.sim]
scenario_file = "$here/figure6/$stroke.scn"
time = "virtual"

[buttons]
backend = "sim"
debounce_ms = 10

[systemd]
notify = false
watchdog = false
TOML
  "$build/bin/twister-station" --config "$work/$stroke.toml" --link "unix:$work/$stroke.sock" \
    --link-wait 30 > "$work/$stroke-station.log" 2>&1 &
  station_pid=$!
  mkdir -p "$work/$stroke"
  rc=0
  "$build/bin/twister-bridge" --connect "unix:$work/$stroke.sock" --offscreen --size 960x720 \
    --camera "$work/camera.toml" --snapshots "$work/$stroke" --export "$work/$stroke.obj" \
    --exit-on-disconnect --timeout 50 > /dev/null 2> "$work/$stroke-bridge.log" || rc=$?
  wait "$station_pid" || rc=$?
  if [[ $rc -ne 0 ]]; then
    cat "$work/$stroke-station.log" "$work/$stroke-bridge.log" >&2
    echo "figure6: $stroke failed" >&2
    exit 1
  fi
  station_sum="$(sed -n 's/^twister-station: mesh checksum \([0-9a-f]*\)$/\1/p' "$work/$stroke-station.log")"
  bridge_sum="$(sed -n 's/^twister-bridge: exported mesh version [0-9]* (checksum \([0-9a-f]*\)).*/\1/p' "$work/$stroke-bridge.log")"
  if [[ -z "$station_sum" || "$station_sum" != "$bridge_sum" ]]; then
    echo "figure6: $stroke: the display's mesh differs from the station's" >&2
    exit 1
  fi
  # The end face under hand 1 turned by the hand's angle (measured on the display's
  # final mesh; sim/scenarios/run_scenario.py's @expect-turn).
  case "$stroke" in
    twist) expect="0.55 -0.24 0.10 -> 0.54991 -0.26035 0.100076 y 70 12" ;;
    bend) expect="0.55 -0.24 0.10 -> 0.62611 -0.22479 0.100076 z 35 12" ;;
  esac
  PYTHONPATH="$here/../../sim/scenarios" python3 -c '
import sys, run_scenario
sys.exit(1 if run_scenario.check_expectations([("expect-turn", sys.argv[1])], sys.argv[2], sys.argv[3]) else 0)
' "$expect" "$work/bar.obj" "$work/$stroke.obj" >&2 || { echo "figure6: $stroke: the end face did not turn as the hand did" >&2; exit 1; }
  cp "$work/$stroke/live-2.png" "$out/figure6-$stroke.png"
  echo "$out/figure6-$stroke.png"
done
