#!/usr/bin/env bash
# twister-bridge checks --export at start: a folder that does not exist, a folder
# that is a file, or an unknown format exits 2 at once (the bridge is given a long
# timeout: a check at exit would wait for it), naming the problem; a good .glb path
# passes the check (the run then ends at its short timeout, with no mesh to export);
# a crease angle outside 0..180 is refused at start too.
# Usage: bridge_export_check_test.sh BUILD_DIR WORK_DIR
set -euo pipefail
build="$1"
work="$2"
rm -rf "$work"
mkdir -p "$work"
unset DISPLAY WAYLAND_DISPLAY
bridge() { "$build/bin/twister-bridge" --offscreen --size 64x48 --connect "unix:$work/absent.sock" "$@"; }
fail() { echo "FAIL: $*"; exit 1; }
touch "$work/file"
for bad in "$work/no/such/dir/final.glb" "$work/file/final.glb" "$work/final.xyz" "$work/final"; do
  start=$(date +%s%N)
  rc=0
  bridge --timeout 30 --export "$bad" 2> "$work/err.log" || rc=$?
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  [[ $rc -eq 2 ]] || fail "$bad: exit $rc, want 2"
  (( ms < 5000 )) || fail "$bad: refused after $ms ms, not at start"
  grep -q "error: options: --export: " "$work/err.log" || fail "$bad: $(cat "$work/err.log")"
done
bridge --timeout 0.2 --export "$work/final.glb" 2> "$work/ok.log" || true
grep -q "no mesh received" "$work/ok.log" || fail "a good path: $(cat "$work/ok.log")"
grep -q "options:" "$work/ok.log" && fail "a good path refused: $(cat "$work/ok.log")"
# The crease angle is a range: outside it the bridge refuses at start (exit 2).
for bad in 181 -1 x; do
  rc=0
  bridge --timeout 30 --crease-angle "$bad" 2> "$work/err.log" || rc=$?
  [[ $rc -eq 2 ]] || fail "--crease-angle $bad: exit $rc, want 2"
done
bridge --timeout 0.2 --crease-angle 30 --no-live-refine 2> "$work/crease.log" || true
grep -q "options:" "$work/crease.log" && fail "--crease-angle 30 refused: $(cat "$work/crease.log")"
echo "crease angle checked at start: ok"
echo "export paths checked at start: ok"
