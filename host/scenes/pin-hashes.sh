#!/bin/sh
# Re-pins determinism: writes the state hash each hard case ends with into
# its `expect: state_hash:` line, and regenerates the sample output in
# FORMAT.md and the table of runs in hard/README.md. Run it after a change
# that is meant to move the numbers, then review the diff: every hash that
# moved is a state that changed.
#
#   host/scenes/pin-hashes.sh [--check] [path/to/marionette]
#
# The program defaults to build/host/app/marionette. With --check nothing is
# written: the files are regenerated in a scratch folder and compared, and
# the exit status is 1 when a pin or a sample is not what the program gives.
set -eu
check=0
if [ "${1:-}" = "--check" ]; then
  check=1
  shift
fi
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
bin=${1:-$root/build/host/app/marionette}
[ -x "$bin" ] || { echo "pin-hashes: no program at $bin; build it first" >&2; exit 2; }

cd "$root"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
body=$scratch/body
# Where the regenerated files go: the tree itself, or a copy of its part.
out=$root
if [ $check = 1 ]; then
  out=$scratch/tree
  mkdir -p "$out/host/scenes/hard"
  cp host/scenes/FORMAT.md "$out/host/scenes/"
  cp host/scenes/hard/*.yaml host/scenes/hard/README.md "$out/host/scenes/hard/"
fi
say() { [ $check = 1 ] || echo "$@"; }

for f in host/scenes/hard/*.yaml; do
  grep -q '^  state_hash:' "$f" || continue
  line=$("$bin" sim --print-hash "$f")
  sed -i "s/^  state_hash: .*/  $line/" "$out/$f"
  say "$(basename "$f"): $line"
done

# Replaces the lines between <!-- NAME: begin --> and <!-- NAME: end --> in
# FILE with the contents of BODY.
splice() {
  awk -v name="$1" -v body="$3" '
    $0 == "<!-- " name ": begin -->" { print; while ((getline l < body) > 0) print l; skip = 1; next }
    $0 == "<!-- " name ": end -->"   { skip = 0 }
    !skip { print }
  ' "$2" >"$2.tmp" && mv "$2.tmp" "$2"
}

# The sample in FORMAT.md is this very command's output.
{ echo '```'; "$bin" sim host/scenes/puppet.yaml; echo '```'; } >"$body"
splice sample "$out/host/scenes/FORMAT.md" "$body"
say "FORMAT.md: sample regenerated"

# One row per hard case that runs, as tests/scene/test_hard.c builds it.
{
  echo '| scene | simulated | steps | rejected | mean Δt | at upper bound | max deviation | resets |'
  echo '|---|---|---|---|---|---|---|---|'
  for f in host/scenes/hard/*.yaml; do
    grep -q '^  state_hash:' "$f" || continue
    "$bin" sim "$f" | awk -F': ' -v name="$(basename "$f" .yaml)" '
      { v[$1] = $2 }
      END { printf "| `%s` | %s | %s | %s | %s | %s | %s | %s |\n", name, v["simulated"],
            v["steps"], v["rejected"], v["dt mean"], v["at upper bound"], v["deviation max"],
            v["resets"] }'
  done
} >"$body"
splice measured "$out/host/scenes/hard/README.md" "$body"
say "hard/README.md: table regenerated"

if [ $check = 1 ]; then
  # wall: is the one line that depends on the machine.
  stale=0
  for f in host/scenes/FORMAT.md host/scenes/hard/README.md host/scenes/hard/*.yaml; do
    diff -u -I '^wall: ' "$f" "$out/$f" >&2 || stale=1
  done
  if [ $stale = 1 ]; then
    echo "pin-hashes: the pins or samples above are stale; run host/scenes/pin-hashes.sh" >&2
    exit 1
  fi
  echo "pin-hashes: every pin and sample is current"
fi
