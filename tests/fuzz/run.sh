#!/usr/bin/env bash
# Runs every built fuzz target for a bounded time over a scratch copy of its
# committed seed corpus. Usage: run.sh BUILD_DIR SECONDS
set -euo pipefail
build=$1
secs=$2
here=$(cd "$(dirname "$0")" && pwd)
status=0
for target in "$build"/tests/fuzz/fuzz_*; do
  [ -x "$target" ] || continue
  name=${target##*/fuzz_}
  work=$(mktemp -d)
  cp "$here/corpus/$name"/* "$work"/
  log="$build/fuzz-$name.log"
  echo "fuzz: $name for ${secs}s over $(ls "$here/corpus/$name" | wc -l) seeds"
  if "$target" -max_total_time="$secs" -print_final_stats=1 -artifact_prefix="$build/" \
       "$work" >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    echo "fuzz: $name clean after $runs runs"
  else
    echo "fuzz: $name FAILED (log: $log)" >&2
    tail -n 40 "$log" >&2
    status=1
  fi
  rm -rf "$work"
done
exit $status
