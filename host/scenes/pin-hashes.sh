#!/bin/sh
# Re-pins determinism: writes the state hash each hard case ends with into
# its `expect: state_hash:` line, and regenerates the sample output in
# FORMAT.md and the table of runs in hard/README.md. Run it after a change that is meant to move the numbers, then
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

# Replaces the lines between <!-- NAME: begin --> and <!-- NAME: end --> in
# FILE with the contents of BODY.
splice() {
  awk -v name="$1" -v body="$3" '
    $0 == "<!-- " name ": begin -->" { print; while ((getline l < body) > 0) print l; skip = 1; next }
    $0 == "<!-- " name ": end -->"   { skip = 0 }
    !skip { print }
  ' "$2" >"$2.tmp" && mv "$2.tmp" "$2"
}

cd "$root"
body=$(mktemp)
trap 'rm -f "$body"' EXIT

# The sample in FORMAT.md is this very command's output.
{ echo '```'; "$bin" sim host/scenes/puppet.yaml; echo '```'; } >"$body"
splice sample host/scenes/FORMAT.md "$body"
echo "FORMAT.md: sample regenerated"

# One row per hard case that runs, in the order test_scene_hard.c builds it.
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
splice measured host/scenes/hard/README.md "$body"
echo "hard/README.md: table regenerated"
