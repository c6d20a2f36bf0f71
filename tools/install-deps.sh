#!/usr/bin/env bash
# Installs the Debian packages the project needs, and only those that are
# missing, so that `make` works on a fresh Debian machine. Uses sudo when not
# root. The package list is the one place that says what the project needs.
#   tools/install-deps.sh [--log FILE]
# With --log (what `make deps` passes, build/deps.log; V=1 leaves it out)
# apt's output goes to FILE and one line says what is being done; if apt
# fails, its last lines and the log's path are printed. Without --log
# apt's output comes to the screen.
set -euo pipefail

log=""
case "${1:-}" in
  --log) [ $# -eq 2 ] && log=$2 || { echo "usage: tools/install-deps.sh [--log FILE]" >&2; exit 2; } ;;
  "") ;;
  *) echo "usage: tools/install-deps.sh [--log FILE]" >&2; exit 2 ;;
esac

PACKAGES=(
  # clang: the second compiler, whose build (make test-clang) must pin the
  # same state hashes as GCC's, and libFuzzer with its runtime.
  build-essential cmake pkg-config python3 clang libclang-rt-14-dev
  libcmocka-dev libserialport-dev libfyaml-dev libeigen3-dev
  # cJSON: the JSON of marionette export's glTF files.
  libcjson-dev
  gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi
  qemu-system-arm clang-format groff-base
  # The stage: an SDL2 window, OSMesa and EGL surfaceless with Mesa's
  # software rasteriser, Assimp for models, cglm for the render maths, stb
  # for images and the on-screen font, Xvfb for the window's tests, ffmpeg
  # for video.
  libsdl2-dev libosmesa6-dev libegl-dev libegl-mesa0 libgl1-mesa-dri
  libassimp-dev libcglm-dev libstb-dev fonts-dejavu-core xvfb xauth ffmpeg
  # Gloves over the network (host/net): libmosquitto, the MQTT v5 client
  # with TLS; mosquitto, the broker the tests start (its service is not
  # needed: tests run their own on free loopback ports); openssl, which
  # makes the tests' throwaway certificates; Xlib, with which the watcher's
  # window test presses its keys.
  libmosquitto-dev mosquitto openssl libx11-dev
  # marionette-bench: its plots (SVG and PNG), and the instruction counts
  # of `make bench-count`.
  gnuplot-nox valgrind
  # make flash: the firmware goes to the glove's board over USB DFU.
  dfu-util
  # The theater box's unit is checked with systemd-analyze verify, which a
  # container or a minimal install lacks.
  systemd
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#PACKAGES[@]} packages are installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
# Recommends are left out: they pulled in 466 packages (about 4.5 GB, most of
# it documentation and GUI bits) where the build needs a fraction of that.
# (&&: set -e does not stop a function that runs as an if's condition.)
apt_steps() {
  $SUDO apt-get update &&
    $SUDO apt-get install -y --no-install-recommends -o Dpkg::Progress-Fancy=0 \
      -o APT::Color=0 "${missing[@]}"
}
if [ -z "$log" ]; then
  echo "deps: installing ${missing[*]}"
  apt_steps
else
  mkdir -p "$(dirname "$log")"
  echo "deps: installing ${missing[*]}" >"$log"
  n=${#missing[@]}
  echo "deps: installing $n package$([ "$n" = 1 ] || echo s) (log: $log)..."
  # sudo asks for a password on the terminal itself, not on the log.
  if ! apt_steps >>"$log" 2>&1; then
    echo "deps: apt-get failed; the last lines of $log:" >&2
    tail -n 15 "$log" >&2
    echo "deps: the whole log: $log" >&2
    exit 1
  fi
fi
echo "deps: done, ${#missing[@]} installed"
