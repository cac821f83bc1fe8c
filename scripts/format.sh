#!/usr/bin/env bash
# Checks that every C++ file is clang-formatted (.clang-format); `--fix` reformats instead.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

mode=(--dry-run --Werror)
if [[ "${1:-}" == "--fix" ]]; then
  mode=(-i)
fi
dirs=()
for dir in apps core scene kernels scheduler tests benchmarks; do
  [[ -d "$dir" ]] && dirs+=("$dir")
done
find "${dirs[@]}" -type f \( -name '*.cpp' -o -name '*.h' \) -print0 | sort -z |
  xargs -0 --no-run-if-empty clang-format "${mode[@]}"
