#!/usr/bin/env bash
# clang-format check and clang-tidy over the project's own sources.
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files 'core/*.cpp' 'core/*.hpp' 'hal/*.cpp' 'hal/*.hpp' \
                                  'sim/*.cpp' 'sim/*.hpp' 'host/*.cpp' 'host/*.hpp')
echo "lint: clang-format on ${#files[@]} files"
clang-format --dry-run --Werror "${files[@]}"
mapfile -t units < <(printf '%s\n' "${files[@]}" | grep '\.cpp$')
echo "lint: clang-tidy on ${#units[@]} translation units"
clang-tidy -p build --quiet "${units[@]}"
