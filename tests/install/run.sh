#!/usr/bin/env bash
# tests/install/run.sh BUILD_DIR -- `cmake --install BUILD_DIR` into a temporary
# prefix, then configure, build and run the consumer project beside this script
# against it, in a temporary build folder. Exit 0 when the consumer ran and passed.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "$1" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/looptess_install.XXXXXX")
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
"$here/no_absolute_paths.sh" "$work/prefix"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S "$here" -B "$work/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/consumer"
