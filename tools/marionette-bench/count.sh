#!/bin/sh
# Stable figures for regressions (`make bench-count`): the instruction
# counts of fixed runs under callgrind, counted only inside each run
# (marionette-bench --count starts and stops the instrumentation), so the
# same build gives the same numbers on any machine.
#
#   tools/marionette-bench/count.sh [BUILD_DIR]
set -eu
build=${1:-build}
bench=$build/tools/marionette-bench/marionette-bench
[ -x "$bench" ] || { echo "bench-count: no $bench; build first" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "bench-count: valgrind is missing (make deps)" >&2; exit 2; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
echo "machine: $(uname -srm), $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1), $(nproc) cores"
echo "commit: $(git -C "$(dirname "$0")" rev-parse --short HEAD 2>/dev/null || echo unknown)"
for run in puppet decode; do
  case $run in
    puppet) what="host/scenes/puppet.yaml, 10 s" ;;
    decode) what="10 000 SAMPLE frames decoded" ;;
  esac
  valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file="$scratch/$run.out" \
    "$bench" --count $run >/dev/null 2>"$scratch/$run.log" ||
    { cat "$scratch/$run.log" >&2; exit 1; }
  total=$(sed -n 's/^totals: //p' "$scratch/$run.out" | head -1)
  printf '%-34s %15s instructions\n' "$what" "$total"
done
