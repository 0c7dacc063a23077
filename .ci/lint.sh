#!/usr/bin/env bash
# `make lint`: the project's code rules, all of them, failing if any breaks:
#   clang-format    layout (.clang-format)
#   clang-tidy      naming, bug finders, no function over 80 lines (.clang-tidy;
#                   needs build/ for compile_commands.json)
#   file length     no code file over 400 lines (tests and benchmarks included)
set -uo pipefail
cd "$(dirname "$0")/.."
max_lines=400
# (.ci/source-files.sh: git's list, or the tree on disk without .git)
mapfile -t files < <(.ci/source-files.sh 'core/*.cpp' 'core/*.hpp' 'hal/*.cpp' 'hal/*.hpp' \
                                         'sim/*.cpp' 'sim/*.hpp' 'host/*.cpp' 'host/*.hpp')
status=0
echo "lint: clang-format on ${#files[@]} files"
clang-format --dry-run --Werror "${files[@]}" || status=1
mapfile -t units < <(printf '%s\n' "${files[@]}" | grep '\.cpp$')
echo "lint: clang-tidy on ${#units[@]} translation units"
printf '%s\n' "${units[@]}" | xargs -P "$(nproc)" -n 4 clang-tidy -p build --quiet || status=1
mapfile -t code < <(.ci/source-files.sh '*.cpp' '*.hpp' '*.h' '*.py' '*.sh')
echo "lint: file length (at most $max_lines lines) on ${#code[@]} files"
long=$(wc -l "${code[@]}" | awk -v max="$max_lines" '$2 != "total" && $1 > max {print "  " $2 ": " $1 " lines"}')
if [[ -n "$long" ]]; then
  echo "lint: files over $max_lines lines (split them by concept):"
  echo "$long"
  status=1
fi
exit $status
