#!/usr/bin/env bash
# source-files.sh PATTERN...: the project's files matching git-style path patterns
# ('core/*.cpp', '*.py'; `*` also matches `/`), one per line, relative to the root.
# In a git checkout: `git ls-files`. Without .git (an unpacked source archive): the
# tree on disk, build trees (build*/), .git and .cache skipped.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ -e .git ]]; then
  exec git ls-files -- "$@"
fi
match=(-false)
for p in "$@"; do match+=(-o -path "./$p"); done
find . \( -path './build*' -o -path './.git' -o -path './.cache' \) -prune \
  -o -type f \( "${match[@]}" \) -print |
  sed 's|^\./||' | LC_ALL=C sort
