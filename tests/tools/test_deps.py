#!/usr/bin/env python3
"""`make deps` is quiet: with nothing missing it says so in one line; with
packages missing it prints one line naming the count and the log, keeps
apt's output in BUILD/deps.log, installs exactly what is missing, and ends
with one line; when apt fails it prints the log's last lines and its path
and exits non-zero; V=1 puts apt's output on the screen. A build whose
configure step fails prints the log's last lines and its path too.

A test must not install packages, so the script runs for real with
stand-ins first on PATH for the package tools only: dpkg-query (which
says the packages listed in missing.txt are not installed), apt-get
(which records its command line, prints 400 lines as a download would,
and fails where fail.txt says so) and sudo (which runs its command).

usage: test_deps.py SOURCE_DIR
"""
import os
import shutil
import subprocess
import sys
import tempfile

SRC = sys.argv[1]
DEPS = os.path.join(SRC, "tools", "install-deps.sh")
failures = []

STAND_INS = {
    "dpkg-query": """
pkg=${@: -1}
echo "$pkg" >> "$T/queried.txt"
grep -qx "$pkg" "$T/missing.txt" && exit 1
printf 'install ok installed'
""",
    "apt-get": """
echo "apt-get $*" >> "$T/apt.txt"
for i in $(seq 400); do echo "Get:$i http://deb.debian.org/debian bookworm/main amd64 pkg$i"; done
if grep -qx "$1" "$T/fail.txt"; then
  echo "E: Unable to locate package no-such-package" >&2
  exit 100
fi
""",
    "sudo": 'exec "$@"\n',
}


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL: " + what)


def lines(text):
    return text.splitlines()


class Box:
    """A scratch folder with the stand-ins, and the calls they saw."""

    def __init__(self, tmp, missing, fail=()):
        self.dir = tempfile.mkdtemp(dir=tmp)
        bin_dir = os.path.join(self.dir, "bin")
        os.makedirs(bin_dir)
        for name, body in STAND_INS.items():
            path = os.path.join(bin_dir, name)
            with open(path, "w") as f:
                f.write("#!%s\nT=%s\n%s" % (shutil.which("bash"), self.dir, body))
            os.chmod(path, 0o755)
        for name, words in (("missing.txt", missing), ("fail.txt", fail)):
            with open(os.path.join(self.dir, name), "w") as f:
                f.write("".join(w + "\n" for w in words))
        self.env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ["PATH"])

    def run(self, argv):
        return subprocess.run(argv, capture_output=True, text=True, timeout=60, env=self.env,
                              cwd=SRC)

    def read(self, name):
        path = os.path.join(self.dir, name)
        return lines(open(path).read()) if os.path.exists(path) else []


def main():
    tmp = tempfile.mkdtemp(prefix="mr-deps-test-")
    try:
        # Nothing missing: one line, and no apt-get.
        box = Box(tmp, [])
        r = box.run([DEPS, "--log", box.dir + "/deps.log"])
        n = len(box.read("queried.txt"))
        check(r.returncode == 0 and r.stdout == "deps: all %d packages are installed\n" % n
              and r.stderr == "" and n > 20 and box.read("apt.txt") == [],
              "with nothing missing, deps says so in one line: %r %r" % (r.stdout, r.stderr))

        # Two missing, through make: one line before and one after, apt's
        # output in BUILD/deps.log.
        box = Box(tmp, ["dfu-util", "cmake"])
        build = box.dir + "/build"
        r = box.run(["make", "-s", "deps", "BUILD=" + build])
        log = build + "/deps.log"
        check(r.returncode == 0 and lines(r.stdout) == [
            "deps: installing 2 packages (log: %s)..." % log,
            "deps: done, 2 installed"] and r.stderr == "",
              "make deps installs quietly, naming its log: %r %r" % (r.stdout, r.stderr))
        apt = box.read("apt.txt")
        check(len(apt) == 2 and apt[0] == "apt-get update" and apt[1].startswith("apt-get install")
              and apt[1].split()[-2:] == ["cmake", "dfu-util"],
              "apt-get updates, then installs exactly the missing packages: %r" % apt)
        logged = open(log).read() if os.path.exists(log) else ""
        check(logged.count("Get:") == 800 and "pkg400" in logged,
              "apt's output is kept in the log, all of it: %d lines" % len(lines(logged)))

        # V=1: apt's output on the screen, no log.
        box = Box(tmp, ["dfu-util"])
        r = box.run(["make", "-s", "deps", "V=1", "BUILD=" + box.dir + "/build"])
        check(r.returncode == 0 and r.stdout.count("Get:") == 800
              and not os.path.exists(box.dir + "/build/deps.log"),
              "make deps V=1 shows apt's output: %d lines" % len(lines(r.stdout)))

        # apt fails: its last lines and the log's path, and a non-zero exit.
        for step in ("update", "install"):
            box = Box(tmp, ["dfu-util"], fail=[step])
            log = box.dir + "/deps.log"
            r = box.run([DEPS, "--log", log])
            err = lines(r.stderr)
            check(r.returncode != 0 and lines(r.stdout) == [
                "deps: installing 1 package (log: %s)..." % log]
                  and len(err) <= 20 and "E: Unable to locate package no-such-package" in err
                  and err[-1] == "deps: the whole log: %s" % log,
                  "a failed apt-get %s shows the log's last lines and its path, and fails: %s"
                  % (step, r.stderr))
            check(len(box.read("apt.txt")) == (1 if step == "update" else 2),
                  "nothing runs after a failed apt-get %s" % step)

        # A build that cannot configure: the log's last lines and its path.
        build = os.path.join(tmp, "stale")
        os.makedirs(build)
        with open(build + "/CMakeCache.txt", "w") as f:
            f.write("CMAKE_HOME_DIRECTORY:INTERNAL=/nowhere\n"
                    "CMAKE_CACHEFILE_DIR:INTERNAL=/elsewhere\n")
        r = subprocess.run(["make", "-s", "-o", "deps", "build", "BUILD=" + build], cwd=SRC,
                           capture_output=True, text=True, timeout=120)
        check(r.returncode != 0 and r.stdout == "" and "CMake Error" in r.stderr
              and "make: configuring %s/ failed; the whole log: %s/build.log" % (build, build)
              in r.stderr and os.path.exists(build + "/build.log")
              and "CMake Error" in open(build + "/build.log").read(),
              "a build that cannot configure shows the log's end and its path: " + r.stderr)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    print("deps: quiet, logged, failures shown with the log's path")
    return 0


if __name__ == "__main__":
    sys.exit(main())
