#!/usr/bin/env bash
# twister-bridge's --log-level: errors show at every level (a bad link address at
# --log-level error), notices show by default and not at --log-level warning or with
# -q, info lines only at info; picture paths stay on stdout. No station is needed:
# the bridge runs offscreen against an absent socket until its timeout.
# Usage: bridge_log_level_test.sh BUILD_DIR WORK_DIR
set -euo pipefail
build="$1"
work="$2"
rm -rf "$work"
mkdir -p "$work"
unset DISPLAY WAYLAND_DISPLAY
export EGL_PLATFORM=surfaceless
bridge() { "$build/bin/twister-bridge" --offscreen --size 64x48 "$@"; }
fail() { echo "FAIL: $*"; exit 1; }
absent="unix:$work/absent.sock"

rc=0
bridge --connect "bogus" --log-level error 2> "$work/error.log" || rc=$?
[[ $rc -eq 2 ]] || fail "bad address: exit $rc, want 2"
grep -qx "twister-bridge: error: options: bad link address bogus (unix:PATH | tcp:HOST:PORT | serial:DEVICE)" \
  "$work/error.log" || fail "bad address at --log-level error: $(cat "$work/error.log")"

bridge --connect "$absent" --timeout 0.2 2> "$work/notice.log"
grep -q "^twister-bridge: summary: mesh version 0;" "$work/notice.log" ||
  fail "default level shows no summary: $(cat "$work/notice.log")"

for quiet in "--log-level warning" "-q"; do
  # shellcheck disable=SC2086  # two words on purpose
  bridge --connect "$absent" --timeout 0.2 $quiet 2> "$work/warning.log"
  [[ ! -s "$work/warning.log" ]] || fail "$quiet still shows: $(cat "$work/warning.log")"
done

rc=0
bridge --connect "$absent" --log-level verbose 2> "$work/bad_level.log" || rc=$?
[[ $rc -eq 2 ]] || fail "unknown level: exit $rc, want 2"
echo "twister-bridge log levels: ok"
