#!/usr/bin/env bash
# The built-in show (`make demo`): glove-gen plays a synthetic glove (its
# built-in motion, each finger a slow sine) on a pty, and `marionette run`
# reads it as it would read a real glove, through the control mapping, and
# draws the puppet. The show lasts as long as the scene's (sim.duration, 16 s
# for the humanoid), so the stage's curtain opens at its start and closes at
# its end. With a display it is in a window (keys: `marionette run --help`);
# without one it is drawn headless at 1280x720 into frames, an MP4 and a
# contact sheet under BUILD/demo/ (the sheet's first cell at 0 s, its last
# at the end), and a one-screen summary ends it. MR_DEMO_HEADLESS=1 asks
# for the headless show even with a display; MR_DEMO_SECONDS sets its
# length, MR_DEMO_SIZE its size.
set -euo pipefail

BUILD=${1:-build}
SRC=$(cd "$(dirname "$0")/.." && pwd)
GEN="$BUILD/tools/glove-gen/glove-gen"
RUN="$BUILD/host/app/marionette"
for t in "$GEN" "$RUN"; do
  [ -x "$t" ] || { echo "demo: $t not found; build first (make build)" >&2; exit 1; }
done

SCENE="$SRC/host/scenes/humanoid.yaml"
[ -f "$SCENE" ] || SCENE="$SRC/host/scenes/puppet.yaml"
OUT="$BUILD/demo"
tmp=$(mktemp -d)
gen_pid=""
cleanup() {
  [ -n "$gen_pid" ] && kill "$gen_pid" 2>/dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT

window=0
if [ -n "${DISPLAY:-}" ] && [ "${MR_DEMO_HEADLESS:-0}" != 1 ]; then window=1; fi
# The scene's sim.duration, whole seconds.
duration=$(sed -n '/^sim:/,/^[^ #]/s/^  duration: *\([0-9]*\).*/\1/p' "$SCENE" | head -n1)
secs=${MR_DEMO_SECONDS:-${duration:-16}}
size=${MR_DEMO_SIZE:-1280x720}

# The glove: a pty of its own, waiting for the show to open it. It plays
# longer than the show may take on a slow machine (a software renderer
# skips renders and gives up lag, so show time runs behind the clock) and
# is stopped when the show ends.
"$GEN" -o pty --path-file "$tmp/pty" --duration $((secs * 10 + 30)) --wait 30 --linger 0 -q \
  2>"$tmp/gen.err" &
gen_pid=$!
for _ in $(seq 100); do [ -s "$tmp/pty" ] && break; sleep 0.1; done
[ -s "$tmp/pty" ] || { echo "demo: glove-gen did not start:" >&2; cat "$tmp/gen.err" >&2; exit 1; }
glove="pty:$(head -n1 "$tmp/pty")"

if [ $window = 1 ]; then
  echo "== the built-in show: $(basename "$SCENE"), $secs s in a window, a synthetic glove on $glove =="
  echo "   (q quits, space pauses, drag to orbit; marionette run --help lists the keys)"
  "$RUN" run "$SCENE" --glove "$glove" --time "$secs" -o "$OUT" -q
  exit $?
fi

rm -rf "$OUT"
echo "== the built-in show: $(basename "$SCENE"), $secs s headless at $size (no display), a synthetic glove on $glove =="
set +e
"$RUN" run "$SCENE" --glove "$glove" --time "$secs" --headless -o "$OUT" --size "$size" -q \
  >"$tmp/run.out" 2>"$tmp/run.err"
rc=$?
set -e
if [ $rc -ne 0 ]; then
  echo "demo: marionette run failed (status $rc):" >&2
  cat "$tmp/run.err" >&2
  exit $rc
fi
field() { sed -n "s/^$1: //p" "$tmp/run.out" | head -n1; }
echo
printf '%-10s %s\n' "frames" "$(field 'frames simulated') simulated, $(field 'frames shown') drawn, $(field 'frames skipped') skipped (the paper's policy: renders skipped, show time kept on wall time)"
printf '%-10s %s\n' "physics" "$(field steps) steps, $(field resets) resets, latency p50 $(field 'latency p50'), p99 $(field 'latency p99')"
printf '%-10s %s\n' "glove" "$(field glove), $(field 'glove samples') samples, $(field 'glove losses') losses, $(field 'glove crc errors') crc errors"
printf '%-10s %s\n' "stage" "$(field stage)"
echo
echo "written:"
echo "  frames  $OUT/frame_*.png ($(ls "$OUT" | grep -c '^frame_'))"
[ -f "$OUT/show.mp4" ] && echo "  video   $OUT/show.mp4"
[ -f "$OUT/sheet.png" ] && echo "  sheet   $OUT/sheet.png (a contact sheet of the show)"
exit 0
