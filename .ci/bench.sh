#!/usr/bin/env bash
# Runs every benchmark program of the release build; JSON copies go to build/bench/.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p build/bench
found=0
for b in build/bin/*_bench; do
  [ -x "$b" ] || continue
  found=1
  name=$(basename "$b")
  echo "== $name"
  "$b" --benchmark_out="build/bench/$name.json" --benchmark_out_format=json "$@"
done
[ "$found" -eq 1 ] || { echo "bench: no benchmark programs were built" >&2; exit 1; }
# Latency by stage, tracker record -> presented frame (docs/performance.md).
if [ -x build/bin/latency_probe ]; then
  echo "== latency_probe"
  build/bin/latency_probe | tee build/bench/latency_probe.txt
fi
# Latency by stage, tracker record -> presented frame (docs/performance.md).
if [ -x build/bin/latency_probe ]; then
  echo "== latency_probe"
  build/bin/latency_probe | tee build/bench/latency_probe.txt
fi
