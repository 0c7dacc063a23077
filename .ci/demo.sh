#!/usr/bin/env bash
# `make demo`: the most complete end-to-end run that exists today, headless-safe.
set -euo pipefail
cd "$(dirname "$0")/.."
echo "Twister Station demo"
echo "Only the foundation exists so far (build, test harness): there is no station,"
echo "simulator or bridge to run yet. Built programs:"
ls build/bin 2>/dev/null || echo "  (none)"
