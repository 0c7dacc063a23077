#!/usr/bin/env bash
# The 16-bit packed format end to end through the programs (issue 15): twister-sim
# --binary16 (an Isotrak-style unit whose `f` is the packed format) on a PTY link,
# `twister fastrak-dump LINK --binary16` configuring it like VRPN's Isotrak driver
# (O s,2,11: 20-byte records) and printing poses. Also: --command-time and --port
# are accepted, bad values refused.
# Usage: fastrak_dump_binary16_test.sh TWISTER_SIM TWISTER WORK_DIR
set -euo pipefail
sim="$1"
twister="$2"
work="$3"
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }

cat > "$work/hands.scn" <<SCN
receivers 2
key 0 1 10 -4 2 90 0 0
key 0 2 12 4 -3 0 0 0
SCN
mkfifo "$work/sim.out"
"$sim" --scenario "$work/hands.scn" --binary16 --reset-time 0.2 --port fixed \
  --command-time x=0.5 --link "$work/link" --duration 20 > "$work/sim.out" 2> "$work/sim.log" &
sim_pid=$!
trap 'kill "$sim_pid" 2>/dev/null || true' EXIT
# The device path is the simulator's first line: wait for it (blocking read, 5 s).
first=""
read -r -t 5 first < "$work/sim.out" || true
[[ "$first" == "$work/link" ]] || fail "no link line: '$first' $(cat "$work/sim.log")"

"$twister" fastrak-dump "$work/link" --binary16 -O 1,2,11 -O 2,2,11 --quick --count 60 \
  --seconds 15 > "$work/dump.out" 2> "$work/dump.log" || fail "dump: $(cat "$work/dump.log")"
lines=$(wc -l < "$work/dump.out")
[[ $lines -eq 60 ]] || fail "want 60 poses, got $lines: $(tail -n 3 "$work/dump.log")"
# Station 1 rests at (10, -4, 2) turned 90 degrees about z: U = (0, 1, 0); station 2
# at (12, 4, -3); one count is 0.002 in.
awk '$1 == 1 && (($2 - 10) ^ 2 > 1e-5 || ($3 + 4) ^ 2 > 1e-5 || ($6 - 1) ^ 2 > 1e-6) { bad = 1 }
     $1 == 2 && (($2 - 12) ^ 2 > 1e-5 || ($4 + 3) ^ 2 > 1e-5) { bad = 1 }
     NF != 13 { bad = 1 } END { exit bad }' "$work/dump.out" ||
  fail "poses off: $(head -n 4 "$work/dump.out")"
grep -q "error" "$work/dump.out" && fail "error lines: $(grep error "$work/dump.out" | head -n 3)"

rc=0
"$sim" --command-time O 2> /dev/null || rc=$?
[[ $rc -eq 2 ]] || fail "--command-time O: exit $rc, want 2"
rc=0
"$sim" --port serial 2> /dev/null || rc=$?
[[ $rc -eq 2 ]] || fail "--port serial: exit $rc, want 2"
echo "fastrak-dump binary16 on twister-sim: ok"
