#!/usr/bin/env bash
# twister-sim's --log-level: an unreadable scenario is an error line even at
# --log-level error; the exit summary is a notice (shown by default, not at
# --log-level warning); the device path stays the first line of stdout.
# Usage: sim_log_level_test.sh TWISTER_SIM WORK_DIR
set -euo pipefail
sim="$1"
work="$2"
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }

rc=0
"$sim" --scenario "$work/absent.scn" --log-level error 2> "$work/error.log" || rc=$?
[[ $rc -eq 2 ]] || fail "absent scenario: exit $rc, want 2"
grep -q "^twister-sim: error: scenario: " "$work/error.log" ||
  fail "absent scenario at --log-level error: $(cat "$work/error.log")"

"$sim" --duration 0.2 --reset-time 0 > "$work/notice.out" 2> "$work/notice.log"
grep -q "^/dev/pts/" <(head -n 1 "$work/notice.out") || fail "stdout: $(cat "$work/notice.out")"
grep -q "^twister-sim: summary: records=" "$work/notice.log" ||
  fail "default level shows no summary: $(cat "$work/notice.log")"

"$sim" --duration 0.2 --reset-time 0 --log-level warning > /dev/null 2> "$work/warning.log"
[[ ! -s "$work/warning.log" ]] || fail "--log-level warning still shows: $(cat "$work/warning.log")"

rc=0
"$sim" --log-level verbose 2> /dev/null || rc=$?
[[ $rc -eq 2 ]] || fail "unknown level: exit $rc, want 2"
echo "twister-sim log levels: ok"
