#!/usr/bin/env python3
"""Every C and C++ unit of the build is compiled with -ffp-contract=off as
the last word on contraction, and with no option that lets the compiler
reassociate, use reciprocals or assume finite values: a fused multiply-add
or a reordered sum moves the pinned state hashes, and then differently
under each compiler and on each machine.

usage: check_fp_flags.py BUILD_DIR/compile_commands.json
"""
import json
import shlex
import sys

LOOSE = ("-ffast-math", "-Ofast", "-funsafe-math-optimizations", "-fassociative-math",
         "-freciprocal-math", "-ffinite-math-only", "-fno-signed-zeros")


def words(entry):
    return entry["arguments"] if "arguments" in entry else shlex.split(entry["command"])


def main():
    units = json.load(open(sys.argv[1]))
    bad = []
    kinds = set()
    for u in units:
        w = words(u)
        kinds.add(u["file"].rsplit(".", 1)[-1])
        contract = [x for x in w if x.startswith("-ffp-contract=")]
        if not contract or contract[-1] != "-ffp-contract=off":
            bad.append("%s: contraction is %s" % (u["file"], contract[-1] if contract
                                                   else "the compiler's default"))
        loose = [x for x in w if x in LOOSE]
        if loose:
            bad.append("%s: %s" % (u["file"], " ".join(loose)))
    for b in bad:
        print("FAIL: " + b)
    # The check reached both languages: the C units and Eigen's C++ one.
    if not {"c", "cpp"} <= kinds:
        print("FAIL: expected C and C++ units in %s, found %s" % (sys.argv[1], sorted(kinds)))
        return 1
    if bad:
        return 1
    print("%d units, every one with -ffp-contract=off and no fast-math option" % len(units))
    return 0


if __name__ == "__main__":
    sys.exit(main())
