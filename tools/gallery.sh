#!/usr/bin/env bash
# The README's gallery (issue 21, item 6): every example scene on the set
# and every display mode (§3.3), one still each, drawn by the real
# `marionette render --frame T` at 640x360 into docs/pictures/ (SCENE.png
# for host/scenes/SCENE.yaml, mode-MODE.png for host/scenes/modes/MODE.yaml),
# each PNG checked to be 200 KB or less, so that the repository stays
# small. Each still is taken while the curtain is open (at least 1.5 s
# after the show starts and 1.5 s before it ends) and the puppets face the
# audience (humanoid-end.png is the README's "after" of the humanoid's
# last turn, beside before-humanoid.png, which an earlier build drew and
# no build draws again); the six examples with goldens (tests/pictures/pictures.h) are
# drawn at the goldens' frames, so a picture here is its golden's scene at
# twice the size. The same build draws the same pictures, byte for byte;
# commit them after looking at them.
#
#   tools/gallery.sh [BUILD [OUT]]     (default: build, docs/pictures)
#
# MR_GALLERY_SIZE=WxH draws another size; MR_GALLERY_BACKEND=egl|osmesa
# forces a backend (default: auto).
set -euo pipefail

BUILD=${1:-build}
SRC=$(cd "$(dirname "$0")/.." && pwd)
OUT=${2:-$SRC/docs/pictures}
RUN="$BUILD/host/app/marionette"
[ -x "$RUN" ] || { echo "gallery: $RUN not found; build first (make build)" >&2; exit 1; }
SIZE=${MR_GALLERY_SIZE:-640x360}
LIMIT=$((200 * 1024))
# The curtain's time to open at the start and to close at the end (s).
CURTAIN=1.5
mkdir -p "$OUT"

# name, scene under host/scenes/, the still's time in seconds
PICTURES=(
  "stick stick.yaml 5"
  "humanoid humanoid.yaml 6"
  "dragon dragon.yaml 8.5"
  "bird bird.yaml 5"
  "clash clash.yaml 7"
  "ghost ghost.yaml 5"
  "puppet puppet.yaml 6"
  "duet duet.yaml 4"
  "humanoid-end humanoid.yaml 14"
  "mode-particle modes/particle.yaml 2.5"
  "mode-link modes/link.yaml 2"
  "mode-rigid modes/rigid.yaml 3"
  "mode-freeform modes/freeform.yaml 3"
)

# Every example and every mode has its still: a new scene must be added
# above (and to README.md's gallery).
for f in "$SRC"/host/scenes/*.yaml "$SRC"/host/scenes/modes/*.yaml; do
  rel=${f#"$SRC"/host/scenes/}
  printf '%s\n' "${PICTURES[@]}" | awk '{print $2}' | grep -qx "$rel" ||
    { echo "gallery: $rel has no still in tools/gallery.sh" >&2; exit 1; }
done

failed=0
for p in "${PICTURES[@]}"; do
  read -r name scene t <<<"$p"
  path="$SRC/host/scenes/$scene"
  # The show's length, as `marionette sim` runs it; the still inside the
  # time the curtain is open.
  duration=$("$RUN" sim "$path" | sed -n 's/^simulated: \([0-9.]*\) s$/\1/p')
  if ! awk -v t="$t" -v d="$duration" -v c="$CURTAIN" 'BEGIN { exit !(t >= c && t <= d - c) }'; then
    echo "gallery: $scene at $t s is not between $CURTAIN s and $CURTAIN s before its end (${duration:-?} s)" >&2
    failed=1
    continue
  fi
  png="$OUT/$name.png"
  if ! "$RUN" render "$path" --frame "$t" --size "$SIZE" \
      --backend "${MR_GALLERY_BACKEND:-auto}" -q -o "$png" >/dev/null; then
    echo "gallery: $scene: marionette render failed" >&2
    failed=1
    continue
  fi
  size=$(stat -c %s "$png")
  if [ "$size" -gt "$LIMIT" ]; then
    echo "gallery: $png is $size bytes, over the $LIMIT allowed" >&2
    failed=1
  else
    printf '%-40s %7d bytes  (%s at %s s of %s s)\n' "${png#"$SRC"/}" "$size" "$scene" "$t" "$duration"
  fi
done
exit "$failed"
