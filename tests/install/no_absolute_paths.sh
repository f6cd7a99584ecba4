#!/usr/bin/env bash
# tests/install/no_absolute_paths.sh PREFIX -- exit 1, naming the file and line, when
# an installed looptess targets file (PREFIX/lib/cmake/looptess/looptess_*Targets*.cmake)
# names an absolute path: the package must work wherever it is copied. CMake's own
# `if(_IMPORT_PREFIX STREQUAL "/")` is not one.
set -euo pipefail
status=0
for f in "$1"/lib/cmake/looptess/looptess_*Targets*.cmake; do
  if grep -n -E "\"/|;/|=/" "$f" | grep -v -F 'STREQUAL "/")'; then
    echo "$(basename "$f") names an absolute path (above)" >&2
    status=1
  fi
done
exit $status
