#!/usr/bin/env bash
# The README's pictures (issue 10, item 9): each example scene and each
# display mode (§3.3) drawn by `marionette render --frame` at 640x360 into
# docs/pictures/, each PNG checked to be 200 KB or less, so that the
# repository stays small. The frames are the goldens' (tests/pictures/
# test_pictures.c), so a picture here is the golden's scene at twice the
# size. The same build draws the same pictures, byte for byte; commit them
# after looking at them.
#
#   tools/pictures.sh [BUILD]        (default: build)
#
# MR_PICTURES_BACKEND=egl|osmesa forces a backend (default: auto).
set -euo pipefail

BUILD=${1:-build}
SRC=$(cd "$(dirname "$0")/.." && pwd)
RUN="$BUILD/host/app/marionette"
[ -x "$RUN" ] || { echo "pictures: $RUN not found; build first (make build)" >&2; exit 1; }
OUT="$SRC/docs/pictures"
LIMIT=$((200 * 1024))
mkdir -p "$OUT"

# name, scene under host/scenes/, the frame's time in seconds
PICTURES=(
  "stick stick.yaml 5"
  "humanoid humanoid.yaml 6"
  "dragon dragon.yaml 5"
  "bird bird.yaml 5"
  "clash clash.yaml 7"
  "ghost ghost.yaml 5"
  "mode-particle modes/particle.yaml 2.5"
  "mode-link modes/link.yaml 2"
  "mode-rigid modes/rigid.yaml 3"
  "mode-freeform modes/freeform.yaml 3"
)

failed=0
for p in "${PICTURES[@]}"; do
  read -r name scene t <<<"$p"
  png="$OUT/$name.png"
  if ! "$RUN" render "$SRC/host/scenes/$scene" --frame "$t" --size 640x360 \
      --backend "${MR_PICTURES_BACKEND:-auto}" -q -o "$png" >/dev/null; then
    echo "pictures: $scene: marionette render failed" >&2
    failed=1
    continue
  fi
  size=$(stat -c %s "$png")
  if [ "$size" -gt "$LIMIT" ]; then
    echo "pictures: $png is $size bytes, over the $LIMIT allowed" >&2
    failed=1
  else
    printf '%-40s %7d bytes  (%s at %s s)\n' "docs/pictures/$name.png" "$size" "$scene" "$t"
  fi
done
exit "$failed"
