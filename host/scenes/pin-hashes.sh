#!/bin/sh
# Re-pins determinism: writes the state hash each hard case ends with into
# its `expect: state_hash:` line, and regenerates the sample output in
# FORMAT.md. Run it after a change that is meant to move the numbers, then
# review the diff: every hash that moved is a state that changed.
#
#   host/scenes/pin-hashes.sh [path/to/marionette]   (default build/host/app/marionette)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
bin=${1:-$root/build/host/app/marionette}
[ -x "$bin" ] || { echo "pin-hashes: no program at $bin; build it first" >&2; exit 2; }

for f in "$here"/hard/*.yaml; do
  grep -q '^  state_hash:' "$f" || continue
  line=$("$bin" sim --print-hash "$f")
  sed -i "s/^  state_hash: .*/  $line/" "$f"
  echo "$(basename "$f"): $line"
done

# The sample between the markers in FORMAT.md is this very command's output.
cd "$root"
sample=$(mktemp)
trap 'rm -f "$sample"' EXIT
"$bin" sim host/scenes/puppet.yaml >"$sample"
awk -v sample="$sample" '
  /^<!-- sample: begin -->$/ { print; print "```"; while ((getline l < sample) > 0) print l; print "```"; skip = 1; next }
  /^<!-- sample: end -->$/   { skip = 0 }
  !skip { print }
' host/scenes/FORMAT.md >"$sample.md"
mv "$sample.md" host/scenes/FORMAT.md
echo "FORMAT.md: sample regenerated"
