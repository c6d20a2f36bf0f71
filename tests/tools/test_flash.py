#!/usr/bin/env python3
"""`make flash` writes the glove's firmware into the Black Pill's flash
sector 0 through the STM32F411's ROM bootloader (USB DFU, 0483:df11,
alternate setting 0, 0x08000000, then leave DFU), and the dry run says
exactly that command without dfu-util or USB. Without an image, without
dfu-util or without a board in DFU mode it stops with one line saying
what to do, and a board in DFU mode gets exactly the dry run's command.

The last two cases need a USB board, which a test machine has not (and a
test must never flash a board someone left plugged in): there the test
puts a stand-in dfu-util first on PATH, which prints what dfu-util 0.11
lists for no board, a board it may not open, or a board in DFU mode, and
records the command lines it was given.

usage: test_flash.py SOURCE_DIR
"""
import os
import shutil
import subprocess
import sys
import tempfile

SRC = sys.argv[1]
FLASH = os.path.join(SRC, "tools", "flash.sh")
failures = []

# What dfu-util 0.11 lists with a Black Pill in its ROM bootloader.
FOUND = ('Found DFU: [0483:df11] ver=2200, devnum=7, cfg=1, intf=0, path="1-2", alt=0, '
         'name="@Internal Flash  /0x08000000/04*016Kg,01*064Kg,03*128Kg", serial="3677376C3430"')
DENIED = "Cannot open DFU device 0483:df11 found on devnum 7 (LIBUSB_ERROR_ACCESS)"


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL: " + what)


def run(argv, **kw):
    return subprocess.run(argv, capture_output=True, text=True, timeout=60, **kw)


def one_line(r, start):
    return r.stderr.count("\n") == 1 and r.stderr.startswith(start)


def path_with(tmp, listing):
    """A PATH with bash and grep only, and a stand-in dfu-util when listing
    is given: `dfu-util -l` prints the listing, anything else is written to
    calls.txt and succeeds."""
    bin_dir = os.path.join(tmp, "bin-%d" % len(os.listdir(tmp)))
    os.makedirs(bin_dir)
    for tool in ("bash", "grep"):
        os.symlink(shutil.which(tool), os.path.join(bin_dir, tool))
    if listing is not None:
        stand_in = os.path.join(bin_dir, "dfu-util")
        with open(stand_in, "w") as f:
            f.write("#!%s\n" % shutil.which("bash"))
            f.write('case " $* " in *" -l "*) printf "dfu-util 0.11\\n\\n%%s\\n" "%s";;\n'
                    % listing.replace('"', '\\"'))
            f.write('*) echo "$*" >> "%s/calls.txt";; esac\n' % tmp)
        os.chmod(stand_in, 0o755)
    return bin_dir


def main():
    tmp = tempfile.mkdtemp(prefix="mr-flash-test-")
    try:
        build = os.path.join(tmp, "build")
        for board in ("blackpill_f411", "blackpill_f411_8mhz"):
            os.makedirs(os.path.join(build, "firmware", board))
            with open(os.path.join(build, "firmware", board, "fw.bin"), "wb") as f:
                f.write(bytes(range(256)) * 8)
        image = os.path.join(build, "firmware", "blackpill_f411", "fw.bin")
        want = "dfu-util -d 0483:df11 -a 0 -s 0x08000000:leave -D %s" % image

        # The dry run, as the docs give it: make flash DRY_RUN=1.
        r = run(["make", "-s", "-C", SRC, "flash", "DRY_RUN=1", "BUILD=" + build])
        check(r.returncode == 0 and r.stdout == want + "\n" and r.stderr == "",
              "make flash DRY_RUN=1 prints exactly '%s' and exits 0: %r %r"
              % (want, r.stdout, r.stderr))
        r = run(["make", "-s", "-C", SRC, "flash", "DRY_RUN=1", "BUILD=" + build,
                 "BOARD=blackpill_f411_8mhz"])
        want_8mhz = want.replace("blackpill_f411", "blackpill_f411_8mhz")
        check(r.returncode == 0 and r.stdout == want_8mhz + "\n",
              "make flash BOARD=blackpill_f411_8mhz flashes the 8 MHz image: " + r.stdout)
        # The dry run needs no dfu-util: it never runs it.
        r = run([FLASH, "--dry-run", image], env=dict(os.environ, PATH=path_with(tmp, None)))
        check(r.returncode == 0 and r.stdout == want + "\n",
              "the dry run prints the command without dfu-util on PATH: %r %r"
              % (r.stdout, r.stderr))

        # No image: one line saying how to build one, and a non-zero exit.
        empty = os.path.join(tmp, "empty")
        r = run(["make", "-s", "-C", SRC, "flash", "DRY_RUN=1", "BUILD=" + empty])
        missing = os.path.join(empty, "firmware", "blackpill_f411", "fw.bin")
        check(r.returncode != 0 and r.stdout == "" and r.stderr.startswith(
            "flash: no firmware image at %s; build it with make firmware\n" % missing),
              "make flash without an image says how to build it and fails: " + r.stderr)
        r = run([FLASH, missing])
        check(r.returncode == 1 and one_line(r, "flash: no firmware image at %s; " % missing),
              "tools/flash.sh without an image gives one line and exit 1: " + r.stderr)

        # No dfu-util: one line pointing to make deps.
        r = run([FLASH, image], env=dict(os.environ, PATH=path_with(tmp, None)))
        check(r.returncode == 1 and r.stderr == "flash: dfu-util not found; install it with "
              "make deps\n", "without dfu-util, flashing says make deps: " + r.stderr)

        # No board in DFU mode, or one this user may not open: one line
        # each, and nothing flashed.
        calls = os.path.join(tmp, "calls.txt")
        r = run([FLASH, image], env=dict(os.environ, PATH=path_with(tmp, "")))
        check(r.returncode == 1 and one_line(r, "flash: no board in DFU mode (0483:df11) on "
                                             "USB; hold BOOT0, tap NRST, release BOOT0,"),
              "without a board in DFU mode, one line says how to enter it: " + r.stderr)
        other = FOUND.replace("[0483:df11]", "[1209:2444]")
        r = run([FLASH, image], env=dict(os.environ, PATH=path_with(tmp, other)))
        check(r.returncode == 1 and one_line(r, "flash: no board in DFU mode (0483:df11)"),
              "another device in DFU mode is not taken for the board: " + r.stderr)
        r = run([FLASH, image], env=dict(os.environ, PATH=path_with(tmp, DENIED)))
        check(r.returncode == 1 and one_line(r, "flash: the board is in DFU mode but this user "
                                             "may not open it; run sudo make flash"),
              "a board this user may not open gives one line naming sudo: " + r.stderr)
        check(not os.path.exists(calls), "nothing is flashed without a board")

        # A board in DFU mode gets the dry run's command, once.
        r = run([FLASH, image], env=dict(os.environ, PATH=path_with(tmp, FOUND)))
        flashed = open(calls).read() if os.path.exists(calls) else ""
        check(r.returncode == 0 and "dfu-util " + flashed == want + "\n",
              "a board in DFU mode is flashed with the dry run's command: %r %s"
              % (flashed, r.stderr))

        # Bad usage.
        r = run([FLASH, "--erase-all", image])
        check(r.returncode == 2 and one_line(r, "usage: tools/flash.sh"),
              "an unknown option is bad usage (exit 2): " + r.stderr)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    print("flash: the dry run's command, each error a line, the board flashed as printed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
