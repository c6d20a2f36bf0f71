#!/usr/bin/env python3
"""The READMEs' fault-accounting examples work as written, with the programs
on the PATH as `make install` puts them: the check each shows prints
nothing, and what it compares is really there (a decoder counter line that
matched nothing would make it print).

usage: test_readme.py SOURCE_DIR GLOVE_GEN GLOVE_DUMP
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

SRC, GEN, DUMP = sys.argv[1:4]


def block_with(doc, needle):
    for m in re.finditer(r"```sh\n(.*?)```", open(os.path.join(SRC, doc)).read(), re.S):
        if needle in m.group(1):
            return m.group(1)
    sys.exit("FAIL: %s has no sh example with %r" % (doc, needle))


def run_example(name, script):
    tmp = tempfile.mkdtemp(prefix="mr-readme-test-")
    try:
        bindir = os.path.join(tmp, "bin")
        os.mkdir(bindir)
        os.symlink(GEN, os.path.join(bindir, "glove-gen"))
        os.symlink(DUMP, os.path.join(bindir, "glove-dump"))
        env = dict(os.environ, PATH=bindir + ":" + os.environ["PATH"])
        r = subprocess.run(["bash", "-c", script], cwd=tmp, env=env, capture_output=True,
                           text=True, timeout=300)
        counters = [l for f in os.listdir(tmp) if f.endswith(".txt") and "truth" not in f
                    for l in open(os.path.join(tmp, f)) if "=" in l]
        ok = r.stdout == "" and len(counters) >= 11
        print("%s: %s (%d counter lines compared)" % (name, "ok" if ok else "FAIL",
                                                     len(counters)))
        if not ok:
            print("stdout:\n" + r.stdout + "\nstderr:\n" + r.stderr[-2000:])
        return ok
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


readme = block_with("README.md", "glove-gen --fast -n 100000")
recipe = block_with("tools/README.md", "--faults 0.1 --seed 7")
# The recipe's first paragraph, with the G and D of the quick start.
recipe = "G=glove-gen D=glove-dump\n" + recipe.split("\n\n")[0]
ok = run_example("README.md, Testers", readme)
ok = run_example("tools/README.md, Recipes", recipe) and ok
sys.exit(0 if ok else 1)
