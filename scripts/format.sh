#!/usr/bin/env bash
# scripts/format.sh [--check] -- clang-format (.clang-format) on every tracked C++
# source and header. --check changes nothing and exits 1, listing the files, when any
# is not formatted (.ci/run). clang-format comes from scripts/setup-debian.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.h' '*.hpp' | grep -v '/node_modules/')
if [ "${1:-}" = --check ]; then
  bad=()
  for f in "${files[@]}"; do
    clang-format --style=file "$f" | cmp -s - "$f" || bad+=("$f")
  done
  if [ ${#bad[@]} -gt 0 ]; then
    printf 'scripts/format.sh: not formatted (run scripts/format.sh):\n' >&2
    printf '  %s\n' "${bad[@]}" >&2
    exit 1
  fi
  exit 0
fi
clang-format --style=file -i "${files[@]}"
