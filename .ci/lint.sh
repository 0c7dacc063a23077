#!/usr/bin/env bash
# clang-format check and clang-tidy over the project's own sources (needs build/ for
# compile_commands.json). Runs both and fails if either finds something.
set -uo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files 'core/*.cpp' 'core/*.hpp' 'hal/*.cpp' 'hal/*.hpp' \
                                  'sim/*.cpp' 'sim/*.hpp' 'host/*.cpp' 'host/*.hpp')
status=0
echo "lint: clang-format on ${#files[@]} files"
clang-format --dry-run --Werror "${files[@]}" || status=1
mapfile -t units < <(printf '%s\n' "${files[@]}" | grep '\.cpp$')
echo "lint: clang-tidy on ${#units[@]} translation units"
printf '%s\n' "${units[@]}" | xargs -P "$(nproc)" -n 4 clang-tidy -p build --quiet || status=1
exit $status
