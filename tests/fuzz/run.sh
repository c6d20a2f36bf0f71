#!/usr/bin/env bash
# Runs every built fuzz target for a bounded time over a scratch copy of its
# committed seed corpus. Usage: run.sh BUILD_DIR SECONDS (0: each seed once)
set -euo pipefail
build=$1
secs=$2
here=$(cd "$(dirname "$0")" && pwd)
status=0
# A leak inside libfyaml, with its upstream report: tests/lsan.supp.
export LSAN_OPTIONS="suppressions=$here/../lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
for target in "$build"/tests/fuzz/fuzz_*; do
  [ -x "$target" ] || continue
  name=${target##*/fuzz_}
  work=$(mktemp -d)
  cp "$here/corpus/$name"/* "$work"/
  # The scene target also starts from every scene the repository ships.
  if [ "$name" = scene ]; then
    root=$(cd "$here/../.." && pwd)
    for f in "$root"/host/scenes/*.yaml "$root"/host/scenes/hard/*.yaml; do
      cp "$f" "$work/repo-${f##*/}"
    done
  fi
  log="$build/fuzz-$name.log"
  echo "fuzz: $name for ${secs}s over $(ls "$here/corpus/$name" | wc -l) seeds"
  # 0 seconds: every seed once and no fuzzing (the sanitizer builds' pass).
  if [ "$secs" = 0 ]; then limit=-runs=0; else limit=-max_total_time="$secs"; fi
  if "$target" "$limit" -print_final_stats=1 -artifact_prefix="$build/" \
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
