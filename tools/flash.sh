#!/usr/bin/env bash
# Flashes a glove firmware image (a raw .bin from `make firmware`) into the
# Black Pill over USB DFU, through the STM32F411's own ROM bootloader:
#   tools/flash.sh [--dry-run] IMAGE
# `make flash` runs it with build/firmware/$(BOARD)/fw.bin, and
# `make flash DRY_RUN=1` passes --dry-run: the dfu-util command is printed
# on stdout, and nothing else is done (no USB, no dfu-util needed).
#
# The ROM bootloader's facts, from ST's application notes:
# - AN2606 ("STM32 microcontroller system memory boot mode"), the STM32F411
#   section: with BOOT0 high at reset the chip runs its system-memory
#   bootloader, which offers USB DFU on PA11/PA12 (the Black Pill's USB-C
#   port) as USB device 0483:df11 (STMicroelectronics' vendor id, its DFU
#   product id).
# - AN3156 ("USB DFU protocol used in the STM32 bootloader"): alternate
#   setting 0 is the internal flash, addressed from 0x08000000, written
#   with ST's DfuSe extension (dfu-util -s ADDRESS), which erases the pages
#   it writes; ":leave" makes the bootloader start the new firmware.
# The image is linked at 0x08000000 and fits flash sector 0
# (firmware/boards/blackpill_f411/link.ld), so sector 1 and the
# calibration stored there are left as they are.
set -euo pipefail

DFU_ID=0483:df11
DFU_ALT=0
ADDRESS=0x08000000

usage() {
  echo "usage: tools/flash.sh [--dry-run] IMAGE" >&2
  exit 2
}

dry=0
image=""
for a in "$@"; do
  case "$a" in
    --dry-run) dry=1 ;;
    -*) usage ;;
    *) [ -z "$image" ] || usage; image=$a ;;
  esac
done
[ -n "$image" ] || usage

if [ ! -f "$image" ]; then
  echo "flash: no firmware image at $image; build it with make firmware" >&2
  exit 1
fi

cmd=(dfu-util -d "$DFU_ID" -a "$DFU_ALT" -s "$ADDRESS:leave" -D "$image")
if [ $dry = 1 ]; then
  echo "${cmd[*]}"
  exit 0
fi

if ! command -v dfu-util >/dev/null; then
  echo "flash: dfu-util not found; install it with make deps" >&2
  exit 1
fi
# dfu-util -l lists what is in DFU mode now; without the board the flash
# would only end in "No DFU capable USB device available".
found=$(dfu-util -l -d "$DFU_ID" 2>&1 || true)
if grep -qi "Cannot open DFU device $DFU_ID" <<<"$found"; then
  echo "flash: the board is in DFU mode but this user may not open it; run sudo make flash" \
    "(hardware/troubleshooting.md, \"The board does not enter DFU mode\")" >&2
  exit 1
fi
if ! grep -qi "Found DFU: \[$DFU_ID\]" <<<"$found"; then
  echo "flash: no board in DFU mode ($DFU_ID) on USB; hold BOOT0, tap NRST, release BOOT0," \
    "then run make flash again (hardware/troubleshooting.md)" >&2
  exit 1
fi
echo "flash: ${cmd[*]}"
"${cmd[@]}"
