#!/usr/bin/env python3
"""Print a firmware image's flash, static RAM and worst-case stack use, and
fail when any exceeds its budget.

Flash is what the image stores (vectors, code, constants, .data's initial
values); static RAM is .data + .bss. The stack bound comes from two sources:
the per-function frame sizes GCC writes with -fstack-usage (.su files), and
the call graph read from the linked image's disassembly (every bl/b to a
function symbol), which also catches calls the compiler adds on its own
(memcpy, libgcc). The bound is the deepest chain from Reset_Handler plus, for
each interrupt handler, its deepest chain and the 32-byte exception frame,
as if every handler nested on top of the main loop at its deepest point: an
over-estimate, never an under-estimate. The script refuses to give a bound
(and fails the build) when it cannot: recursion, an indirect call, a
function whose frame is dynamic, or one whose frame size is unknown.
"""
import argparse
import glob
import os
import re
import subprocess
import sys

EXC_FRAME = 32  # r0-r3, r12, lr, pc, xpsr (no FPU context: soft float)


def fail(msg):
    print(f"budget: {msg}", file=sys.stderr)
    sys.exit(1)


def section_sizes(size_tool, elf):
    out = subprocess.run([size_tool, "-A", elf], check=True, capture_output=True, text=True).stdout
    sizes = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 3 and parts[0].startswith(".") and parts[1].isdigit():
            sizes[parts[0]] = int(parts[1])
    return sizes


def stack_frames(obj_dir):
    frames = {}
    for su in glob.glob(os.path.join(obj_dir, "*.su")):
        with open(su, encoding="utf-8") as f:
            for line in f:
                loc, size, kind = line.rstrip("\n").split("\t")
                name = loc.rsplit(":", 1)[1]
                if kind.strip() != "static":
                    fail(f"{loc}: stack frame is {kind.strip()}, cannot bound it")
                # Static functions of the same name in two files: keep the larger.
                frames[name] = max(frames.get(name, 0), int(size))
    return frames


def disassembly(objdump, elf):
    out = subprocess.run([objdump, "-d", "--no-show-raw-insn", elf], check=True,
                         capture_output=True, text=True).stdout
    funcs, calls, prologue = {}, {}, {}
    cur = None
    head = re.compile(r"^([0-9a-f]+) <([^>]+)>:$")
    branch = re.compile(r"^\s*[0-9a-f]+:\s+(bl|blx|b)(?:eq|ne|cs|cc|hs|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le)?(?:\.[wn])?\s+([0-9a-f]+|r\d+|lr|ip)(?:\s+<([^>]+)>)?")
    for line in out.splitlines():
        m = head.match(line)
        if m:
            cur = m.group(2)
            funcs[cur] = int(m.group(1), 16)
            calls.setdefault(cur, set())
            prologue[cur] = 0
            continue
        if cur is None:
            continue
        ins = line.split("\t")
        text = " ".join(ins[1:]).strip() if len(ins) > 1 else ""
        # Frame of functions without a .su file (libgcc): push + sub sp.
        pm = re.match(r"push(?:\.w)?\s+\{([^}]*)\}", text)
        if pm:
            prologue[cur] += 4 * len([r for r in pm.group(1).split(",") if r.strip()])
        sm = re.match(r"sub(?:\.w)?\s+sp,\s*(?:sp,\s*)?#(\d+)", text)
        if sm:
            prologue[cur] += int(sm.group(1))
        bm = branch.match(line)
        if not bm:
            continue
        op, target, sym = bm.group(1), bm.group(2), bm.group(3)
        if op == "blx" and target.startswith("r"):
            fail(f"{cur}: indirect call ({text}), cannot bound the stack")
        if sym is None or "+" in sym or sym == cur:
            continue  # a branch inside the function
        calls[cur].add(sym)
    return funcs, calls, prologue


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--board", required=True)
    ap.add_argument("--elf", required=True)
    ap.add_argument("--size", default="arm-none-eabi-size")
    ap.add_argument("--flash", type=int, required=True)
    ap.add_argument("--ram", type=int, required=True)
    ap.add_argument("--stack", type=int, required=True)
    ap.add_argument("obj_dir")
    a = ap.parse_args()

    s = section_sizes(a.size, a.elf)
    flash = sum(s.get(k, 0) for k in (".isr_vector", ".text", ".ARM.exidx", ".data"))
    ram = s.get(".data", 0) + s.get(".bss", 0)

    frames = stack_frames(a.obj_dir)
    objdump = a.size[: -len("size")] + "objdump"
    funcs, calls, prologue = disassembly(objdump, a.elf)

    depth, path = {}, {}

    def visit(fn, stack):
        if fn in depth:
            return depth[fn]
        if fn in stack:
            fail(f"recursion through {' -> '.join(stack + [fn])}, cannot bound the stack")
        if fn in frames:
            own = frames[fn]
        elif fn in prologue:
            own = prologue[fn]
        else:
            fail(f"{fn}: no frame size known")
        best, best_path = 0, []
        for callee in sorted(calls.get(fn, ())):
            d = visit(callee, stack + [fn])
            if d > best:
                best, best_path = d, path[callee]
        depth[fn] = own + best
        path[fn] = [fn] + best_path
        return depth[fn]

    called = set().union(*calls.values()) if calls else set()
    roots = sorted(f for f in funcs if f not in called and f != "Reset_Handler"
                   and (f.endswith("_Handler") or f.endswith("_IRQHandler") or f == "fw_default_handler"))
    if "Reset_Handler" not in funcs:
        fail("no Reset_Handler in the image")
    main_depth = visit("Reset_Handler", [])
    isr = [(r, visit(r, []) + EXC_FRAME) for r in roots]
    total = main_depth + sum(d for _, d in isr)

    print(f"{a.board}: flash {flash} / {a.flash} bytes ({100.0 * flash / a.flash:.1f} %), "
          f"static RAM {ram} / {a.ram} bytes ({100.0 * ram / a.ram:.1f} %)")
    print(f"{a.board}: stack, deepest chain from reset {main_depth} bytes: {' > '.join(path['Reset_Handler'])}")
    for r, d in isr:
        if d > EXC_FRAME:
            print(f"{a.board}: stack, {r} {d} bytes with its exception frame: {' > '.join(path[r])}")
    print(f"{a.board}: stack, worst case with every handler nested {total} / {a.stack} bytes")
    bad = []
    if flash > a.flash:
        bad.append(f"flash {flash} > {a.flash}")
    if ram > a.ram:
        bad.append(f"static RAM {ram} > {a.ram}")
    if total > a.stack:
        bad.append(f"stack {total} > {a.stack}")
    if bad:
        fail(f"{a.board}: over budget: {', '.join(bad)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
