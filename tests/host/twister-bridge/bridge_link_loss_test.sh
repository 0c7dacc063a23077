#!/usr/bin/env bash
# Host link loss with real processes: twister-station (simulator, real time) keeps
# sculpting while its bridge goes away after the first commit; a new bridge that
# connects later gets the current mesh and the next commit, and ends with the
# station's exact mesh. Usage: bridge_link_loss_test.sh BUILD_DIR WORK_DIR
set -euo pipefail
build="$1"
work="$2"
here="$(cd "$(dirname "$0")" && pwd)"
rm -rf "$work"
mkdir -p "$work"
"$build/bin/twister" mesh sphere -n 80 --segments 128 --size 0.30 --center 0.55 0 0.10 \
  --out "$work/sphere.obj" > /dev/null
cat > "$work/station.toml" <<TOML
[station]
journal = "$work/journal.bin"
mesh = "$work/sphere.obj"
loop_timeout_ms = 5

[tracker]
backend = "sim"
left_station = 1
right_station = 2

[tracker.sim]
scenario_file = "$here/bridge_link_loss.scn"
time = "real"

[buttons]
backend = "stylus"
debounce_ms = 10

[systemd]
notify = false
watchdog = false
TOML
sock="$work/link.sock"
unset DISPLAY WAYLAND_DISPLAY
"$build/bin/twister-station" --config "$work/station.toml" --link "unix:$sock" --link-wait 20 \
  > "$work/station.log" 2>&1 &
station_pid=$!
trap 'kill "$station_pid" 2>/dev/null || true' EXIT
# No wait for the socket here: the bridge retries its connection (every 200 ms) until
# the station listens, within its --timeout.
# Bridge 1 leaves right after the first commit (the link drops mid-session).
"$build/bin/twister-bridge" --connect "unix:$sock" --offscreen --size 64x48 \
  --exit-after-commits 1 --timeout 30 -q 2> "$work/bridge1.log"
# Bridge 2 arrives while the station is between strokes.
"$build/bin/twister-bridge" --connect "unix:$sock" --offscreen --size 64x48 \
  --export "$work/final.obj" --exit-on-disconnect --timeout 30 2> "$work/bridge2.log"
wait "$station_pid"
trap - EXIT
cat "$work/station.log" "$work/bridge1.log" "$work/bridge2.log"
station_sum="$(sed -n 's/^twister-station: mesh checksum \([0-9a-f]*\)$/\1/p' "$work/station.log")"
bridge_sum="$(sed -n 's/^twister-bridge: exported mesh version [0-9]* (checksum \([0-9a-f]*\)).*/\1/p' "$work/bridge2.log")"
grep -q "strokes committed 2" "$work/station.log" || { echo "FAIL: station did not commit both strokes"; exit 1; }
grep -q "commit -> mesh version 3" "$work/bridge2.log" || { echo "FAIL: bridge 2 missed commit 3"; exit 1; }
[[ -n "$station_sum" && "$station_sum" == "$bridge_sum" ]] || { echo "FAIL: $station_sum != $bridge_sum"; exit 1; }
echo "link loss: new bridge synced to the station's mesh ($station_sum)"
