#!/usr/bin/env bash
# Fails when a C or C++ file of the tree differs from what .clang-format makes
# of it, naming each such file; `make format` rewrites them.
# Usage: check_format.sh SOURCE_DIR
set -euo pipefail
cd "$1"
command -v clang-format >/dev/null || { echo "check_format: clang-format is not installed (make deps)" >&2; exit 1; }
mapfile -t files < <(find protocol firmware host tools tests \
  \( -name '*.c' -o -name '*.h' -o -name '*.cpp' \) -type f | sort)
bad=0
for f in "${files[@]}"; do
  if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "$f: not in the house format (make format)" >&2
    bad=$((bad + 1))
  fi
done
echo "${#files[@]} files checked, $bad not in the house format"
[ "$bad" -eq 0 ]
