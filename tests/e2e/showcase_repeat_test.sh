#!/usr/bin/env bash
# Issue 27: live pictures are deterministic in virtual time. Two runs of the spork at
# the same time (each slowing the other) must write the same pictures, byte for byte:
# the station waits for its display before its clock steps on, so the display sees the
# same messages and pictures each live warp at the same instant.
#   showcase_repeat_test.sh BUILD_DIR OUT_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="$1"
out="$2"
rm -rf "$out"
mkdir -p "$out"
pids=()
for run in a b; do
  python3 "$here/../../sim/scenarios/run_scenario.py" "$here/../../sim/scenarios/spork.scn" \
    --bin "$build/bin" --out "$out/$run" --bridge --size 320x240 > "$out/$run.txt" &
  pids+=($!)
done
failed=0
for pid in "${pids[@]}"; do wait "$pid" || failed=1; done
if (( failed )); then
  cat "$out"/a.txt "$out"/b.txt >&2
  echo "repeat: a run failed" >&2
  exit 1
fi
(cd "$out/a/pictures" && sha256sum -- *.png) > "$out/a.sums"
(cd "$out/b/pictures" && sha256sum -- *.png) > "$out/b.sums"
if ! diff "$out/a.sums" "$out/b.sums" >&2; then
  echo "repeat: the two runs wrote different pictures" >&2
  exit 1
fi
grep -q 'live-6.png' "$out/a.sums" || { echo "repeat: live-6.png missing" >&2; exit 1; }
echo "repeat: $(wc -l < "$out/a.sums") pictures, the same in both runs"
