#!/usr/bin/env bash
# The protocol demo (`make demo` runs it until the theater exists): a few
# seconds of a synthetic glove stream, in real time and with faults injected,
# piped from glove-gen into glove-dump; then the decoder's counters beside
# what glove-gen says it injected. They must be equal.
set -euo pipefail

BUILD=${1:-build}
GEN="$BUILD/tools/glove-gen/glove-gen"
DUMP="$BUILD/tools/glove-dump/glove-dump"
for t in "$GEN" "$DUMP"; do
  [ -x "$t" ] || { echo "demo: $t not found; build first (make build)" >&2; exit 1; }
done

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "== glove-gen | glove-dump: 6 s at 30 frames/s, real time, with faults =="
echo "   (one line per frame; '!' lines are the faults as the decoder saw them)"
echo
# Every fault kind but wrong-hash, which would end the dump as a spec
# mismatch; tools/README.md shows that one on its own.
timeout 30 "$GEN" --rate 30 --duration 6 --seed 42 \
    --drop 0.03 --dup 0.03 --reorder 0.03 --flip 0.03 --truncate 0.03 \
    --garbage 0.02 --unknown 0.02 --stall 0.01 --stall-frames 3:8 \
    --truth "$tmp/truth.txt" \
  | timeout 30 "$DUMP" --counters "$tmp/counters.txt" 2>"$tmp/dump.err"

echo
printf '%-16s %12s %12s\n' counter injected decoded
status=0
for k in frames crc_errors framing_errors oversize unknown_type spec_mismatch \
         lost duplicates reordered seq_restarts bytes; do
  want=$(sed -n "s/^$k=//p" "$tmp/truth.txt")
  got=$(sed -n "s/^$k=//p" "$tmp/counters.txt")
  mark=""
  [ "$want" = "$got" ] || { mark="  <- differs"; status=1; }
  printf '%-16s %12s %12s%s\n' "$k" "$want" "$got" "$mark"
done
echo
if [ $status -eq 0 ]; then
  echo "every counter equals what was injected"
else
  echo "demo: the decoder's counters differ from what was injected" >&2
fi
exit $status
