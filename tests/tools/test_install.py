#!/usr/bin/env python3
"""`make install` puts the programs (marionette's run and render in the
stage program under libexec), their man pages and the udev rule in place
under DESTDIR; each man page renders without warnings and names every
option its program's --help lists; the installed theater unit passes
systemd-analyze verify, and its command lines run against the installed
tree and play a show from a glove (check_unit_runs); the Makefile hands
PREFIX and the udev folder to the install, keeps the build log off the screen, runs the
benchmark for make bench and the clang build's tests for make test.

usage: test_install.py SOURCE_DIR BUILD_DIR
"""
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

SRC, BUILD = sys.argv[1], sys.argv[2]
PREFIX = "/usr"
PROGRAMS = {"marionette": [["--help"], ["sim", "--help"], ["run", "--help"],
                           ["render", "--help"], ["list-ports", "--help"],
                           ["take", "--help"], ["watch", "--help"]],
            "glove-gen": [["--help"]],
            "glove-dump": [["--help"]]}
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL: " + what)


def run(argv, timeout=120, **kw):
    return subprocess.run(argv, capture_output=True, text=True, timeout=timeout, **kw)


def help_options(text):
    """The options a --help lists: the first column of its option lines."""
    opts = set()
    for line in text.splitlines():
        m = re.match(r"^\s+(-[A-Za-z0-9])?(?:,\s*)?(--[a-z][a-z0-9-]*)?", line)
        if m:
            opts.update(o for o in m.groups() if o)
    return opts


def render(page):
    """The page as plain text, and what the formatter warned about."""
    if shutil.which("groff"):
        warn = run(["groff", "-man", "-Tascii", "-ww", "-z", page]).stderr
        text = run(["groff", "-man", "-Tascii", "-P-cbou", page]).stdout
        return text, warn
    if shutil.which("mandoc"):
        warn = run(["mandoc", "-Tlint", "-Wwarning", page]).stdout
        return run(["mandoc", "-Tascii", page]).stdout, warn
    # No formatter: every request must be one the man macros know.
    known = {"TH", "SH", "SS", "TP", "PP", "IP", "B", "I", "BI", "IB", "BR", "RB",
             "IR", "RI", "EX", "EE", "br"}
    bad = [ln for ln in open(page) if ln.startswith(".") and ln[1:].split()[0] not in known]
    text = re.sub(r"\\f[BIRP]|\\\(..|\\~", "", open(page).read()).replace("\\-", "-")
    return text, "".join("unknown request: " + ln for ln in bad)


def check_front_door():
    """The Makefile's promises, read from what it would run (make -n): the
    build's and apt's output go to logs in the build folder (V=1: to the
    screen), sub-makes print no directory lines, and make bench runs the
    benchmark. tools_deps runs the quiet steps themselves."""
    n = run(["make", "-n", "firmware"], cwd=SRC).stdout
    check("Entering directory" not in n, "make firmware prints no 'Entering directory' lines")
    n = run(["make", "-n", "build", "BUILD=b"], cwd=SRC).stdout
    steps = [l for l in n.splitlines() if re.match(r"(mkdir -p b && )?cmake (-S|--build)", l)]
    check(len(steps) == 2 and ">b/build.log 2>&1" in steps[0].split("||")[0]
          and ">>b/build.log 2>&1" in steps[1].split("||")[0]
          and all("tail -n 25 b/build.log" in l and "the whole log: b/build.log" in l
                  for l in steps),
          "make build keeps CMake's output in BUILD/build.log, and a failed step prints its "
          "last lines and the log's path: " + " / ".join(steps))
    check("make: building b/ (log: b/build.log" in n, "make build names its log: " + n)
    n = run(["make", "-n", "build", "V=1"], cwd=SRC).stdout
    check("build.log" not in n and "cmake --build build" in n, "make build V=1 shows the build log")
    n = run(["make", "-n", "deps", "BUILD=b"], cwd=SRC).stdout
    check(n.strip() == "tools/install-deps.sh --log b/deps.log",
          "make deps keeps apt's output in BUILD/deps.log: " + n)
    n = run(["make", "-n", "deps", "V=1"], cwd=SRC).stdout
    check(n.strip() == "tools/install-deps.sh", "make deps V=1 shows apt's output: " + n)
    n = run(["make", "-n", "bench"], cwd=SRC).stdout
    check("tools/protocol-bench/protocol-bench" in n, "make bench runs protocol-bench")
    n = run(["make", "-n", "test"], cwd=SRC).stdout
    check("-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++" in n and "--target numbers_tests" in n
          and re.search(r"cd build-clang && ctest .*-L numbers", n) is not None,
          "make test builds the numbers tests with clang in build-clang/ and runs them")


def verify_unit(dest, unit):
    """systemd-analyze verify, over the DESTDIR tree as the box's root, so
    that it finds the installed program; the tree is given the /bin/sh
    that ExecStartPre runs, as every box has one."""
    check(shutil.which("systemd-analyze") is not None,
          "systemd-analyze is installed (make deps brings it) to verify the unit")
    if not shutil.which("systemd-analyze"):
        return
    os.makedirs(dest + "/bin", exist_ok=True)
    shutil.copy("/bin/sh", dest + "/bin/sh")
    r = run(["systemd-analyze", "verify", "--man=no", "--recursive-errors=no", "--root=" + dest,
             unit])
    check(r.returncode == 0 and r.stderr.strip() == "" and r.stdout.strip() == "",
          "systemd-analyze verify accepts the installed unit: " + (r.stderr + r.stdout).strip())


def on_box(arg, dest):
    """An argument of the unit's, with its paths under PREFIX and /dev moved
    into the DESTDIR tree, the box's root here."""
    return re.sub(r"(?<![\w.-])(%s/|/dev/)" % re.escape(PREFIX), lambda m: dest + m.group(1), arg)


def run_show(argv, env, secs):
    """argv started, let run secs seconds after its first status line (the
    show's first frame), then stopped with SIGTERM as systemctl stop does.
    Its exit status, stdout and stderr; status None when it never showed a
    frame within a minute (it is then killed)."""
    try:
        p = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True)
    except OSError as e:
        return None, "", str(e)
    out, err = [], []
    readers = [threading.Thread(target=lambda f=f, to=to: to.extend(iter(f.readline, "")))
               for f, to in ((p.stdout, out), (p.stderr, err))]
    for t in readers:
        t.start()
    end = time.monotonic() + 60
    while p.poll() is None and not out and time.monotonic() < end:
        time.sleep(0.05)
    started = bool(out)
    if started and p.poll() is None:
        time.sleep(secs)
        p.send_signal(signal.SIGTERM)
    try:
        p.wait(timeout=60)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()
        started = False
    for t in readers:
        t.join()
    return (p.returncode if started or p.returncode != 0 else None), "".join(out), "".join(err)


def summary(out, key):
    """A number from the show's summary (key: N ...), or -1."""
    m = re.search(r"^%s: .*?(\d+)" % re.escape(key), out, re.M)
    return int(m.group(1)) if m else -1


def check_unit_runs(dest, text):
    """The installed unit's own command lines, run against the installed
    tree: %i is a glove serial number, and the glove's adapter, which the
    udev rule links at /dev/marionette-glove-<serial>, is a link under
    DESTDIR/dev to the pty of the installed glove-gen. ExecStartPre waits
    for that link and returns once it is there. ExecStart asks for
    --fullscreen, a screen through X, Wayland or KMS, which a test machine
    has not: run as the unit runs it (no DISPLAY, no WAYLAND_DISPLAY), it
    ends with one line and exit 1, which the unit restarts (or, on a
    machine whose console it can take, it plays). Then the same command
    line with --headless plays the show offscreen: it reads the glove over
    the serial path, draws frames, and SIGTERM after 2 s (systemctl stop)
    ends it with exit 0, which systemd counts as a clean stop.
    The unit names no scene, so the program plays /etc/marionette/show.yaml,
    else the default show at the build's prefix, which is not where DESTDIR
    put it: the test names the installed default show (in DESTDIR) as the
    scene. That the program picks it by itself is checked in
    check_model_search."""
    pre = [ln[len("ExecStartPre="):] for ln in text.splitlines() if ln.startswith("ExecStartPre=")]
    start = [ln[len("ExecStart="):] for ln in text.splitlines() if ln.startswith("ExecStart=")]
    if len(pre) != 1 or len(start) != 1:
        check(False, "the unit has one ExecStartPre and one ExecStart line")
        return
    serial = "E66138935F2D3C28"
    box = lambda line: [on_box(a.replace("%i", serial), dest) for a in shlex.split(line)]
    os.makedirs(dest + "/dev", exist_ok=True)
    try:
        run(box(pre[0]), timeout=1.5)
        check(False, "ExecStartPre waits while the glove's adapter is not plugged in")
    except subprocess.TimeoutExpired:
        pass
    pty = dest + "/glove.pty"
    gen = subprocess.Popen([dest + PREFIX + "/bin/glove-gen", "-o", "pty", "--path-file", pty,
                            "--duration", "120", "--wait", "60", "--linger", "0", "-q"],
                           stderr=subprocess.DEVNULL)
    try:
        end = time.monotonic() + 10
        while not (os.path.exists(pty) and open(pty).read().strip()) and time.monotonic() < end:
            time.sleep(0.05)
        os.symlink(open(pty).readline().strip(), dest + "/dev/marionette-glove-" + serial)
        try:
            ok = run(box(pre[0]), timeout=10).returncode == 0
        except subprocess.TimeoutExpired:
            ok = False
        check(ok, "ExecStartPre returns once the glove's adapter is there")
        argv = box(start[0]) + [dest + PREFIX + "/share/marionette/scenes/humanoid.yaml"]
        env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
        rc, out, err = run_show(argv, env, 2)
        played = rc == 0 and summary(out, "frames shown") > 0
        check((rc == 1 and err.count("\n") == 1 and "no screen" in err) or played,
              "the unit's command line without a screen ends with one line and exit 1, or "
              "plays: %s %s" % (rc, err.strip()))
        rc, out, err = run_show(argv + ["--headless"], env, 2)
        check(rc == 0 and summary(out, "frames shown") > 0 and summary(out, "glove samples") > 0
              and re.search(r"^stage: headless .* [1-9]\d* frames drawn", out, re.M),
              "the unit's command line with --headless plays the show from the glove, drawing "
              "frames, and SIGTERM ends it with exit 0: status %s %s %s" % (rc, out, err))
    finally:
        gen.kill()
        gen.wait()


def check_model_search(dest):
    """An installed example scene copied alone to a new folder finds its
    models in the installed tree along MARIONETTE_PATH (after a folder that
    does not exist); with the models nowhere, the one-line error names the
    scene's folder, each MARIONETTE_PATH folder and the installed one."""
    share = dest + PREFIX + "/share/marionette/scenes"
    show = dest + "/show"
    os.makedirs(show)
    shutil.copy(share + "/humanoid.yaml", show + "/show.yaml")
    exe = dest + PREFIX + "/bin/marionette"
    argv = [exe, "render", show + "/show.yaml", "--frame", "1", "-o", dest + "/pictures"]
    env = dict(os.environ, MARIONETTE_PATH=dest + "/nowhere:" + share)
    r = run(argv, env=env)
    check(r.returncode == 0 and os.path.isfile(dest + "/pictures/frame_1.000.png"),
          "a copied scene finds its models in the installed tree along MARIONETTE_PATH: "
          + r.stderr.strip())
    cache = open(BUILD + "/CMakeCache.txt").read()
    built = re.search(r"^CMAKE_INSTALL_PREFIX:PATH=(.*)$", cache, re.M).group(1)
    places = [show + "/models/humanoid_head.obj", dest + "/a/models/humanoid_head.obj",
              dest + "/b/models/humanoid_head.obj",
              built + "/share/marionette/scenes/models/humanoid_head.obj"]
    if os.path.exists(places[-1]):
        print("note: the scenes are installed in %s here; the missing model is not tried" % built)
        return
    # marionette run without a scene: the box's show, else the default show.
    default = built + "/share/marionette/scenes/humanoid.yaml"
    if not os.path.exists("/etc/marionette/show.yaml") and not os.path.exists(default):
        r = run([exe, "run", "--glove", "tcp:127.0.0.1:9", "-o", dest + "/run"])
        check(r.returncode == 1 and r.stderr.startswith("marionette: %s: " % default),
              "marionette run without a scene plays the installed default show: " + r.stderr)
    r = run(argv, env=dict(os.environ, MARIONETTE_PATH=dest + "/a::" + dest + "/b"))
    err = r.stderr.strip()
    at = [err.find(p) for p in places]
    check(r.returncode == 1 and err.count("\n") == 0 and -1 not in at and at == sorted(at),
          "a missing model's one-line error names, in order, every place searched: " + err)


def main():
    dest = tempfile.mkdtemp(prefix="mr-install-test-")
    try:
        env = {k: v for k, v in os.environ.items() if k != "MR_UDEV_RULES_DIR"}
        env["DESTDIR"] = dest
        r = run(["cmake", "--install", BUILD, "--prefix", PREFIX], env=env)
        check(r.returncode == 0, "cmake --install exits 0: " + r.stderr.strip())
        root = dest + PREFIX
        rule = open(SRC + "/hardware/99-marionette-glove.rules").read()
        udev = dest + PREFIX + "/lib/udev/rules.d/99-marionette-glove.rules"
        check(os.path.isfile(udev) and open(udev).read() == rule,
              "by default the udev rule is installed at PREFIX/lib/udev/rules.d")
        # The folder make install picks for /usr/local, where udev reads it.
        env["MR_UDEV_RULES_DIR"] = "/etc/udev/rules.d"
        r = run(["cmake", "--install", BUILD, "--prefix", PREFIX], env=env)
        udev = dest + "/etc/udev/rules.d/99-marionette-glove.rules"
        check(r.returncode == 0 and os.path.isfile(udev) and open(udev).read() == rule,
              "MR_UDEV_RULES_DIR=/etc/udev/rules.d puts the rule there, under DESTDIR")
        listing = run(["find", dest, "-type", "f"]).stdout.split()
        share = root + "/share/marionette/scenes"
        scenes = sorted(f for f in os.listdir(SRC + "/host/scenes") if f.endswith(".yaml"))
        models = sorted(os.listdir(SRC + "/host/scenes/models"))
        check(os.path.isdir(share) and sorted(f for f in os.listdir(share) if f.endswith(".yaml"))
              == scenes, "the example scenes (not the hard cases) are installed in "
              "PREFIX/share/marionette/scenes")
        check(os.path.isdir(share + "/models") and sorted(os.listdir(share + "/models")) == models,
              "the example scenes' models are installed in PREFIX/share/marionette/scenes/models")
        check(len(listing) == 12 + len(scenes) + len(models),
              "install puts exactly 3 programs, the stage, export and glove programs, 3 man pages, "
              "the systemd unit, the rule (twice here), the scenes and their models: "
              + " ".join(sorted(listing)))
        stage = dest + PREFIX + "/libexec/marionette/marionette-stage"
        check(os.access(stage, os.X_OK), "the stage program (run, render) is installed in "
              "PREFIX/libexec/marionette, off PATH")
        export = dest + PREFIX + "/libexec/marionette/marionette-export"
        check(os.access(export, os.X_OK), "the export program (export) is installed in "
              "PREFIX/libexec/marionette, off PATH")
        glove = dest + PREFIX + "/libexec/marionette/marionette-glove"
        check(os.access(glove, os.X_OK), "the glove program (list-ports, calibrate) is installed "
              "in PREFIX/libexec/marionette, off PATH")
        unit = dest + PREFIX + "/lib/systemd/system/marionette-theater@.service"
        text = open(unit).read() if os.path.isfile(unit) else ""
        check("\nExecStart=%s/bin/marionette run " % PREFIX in text and "@" not in
              text.split("ExecStart=")[1].split()[0],
              "the theater box's systemd unit is installed in PREFIX/lib/systemd/system and "
              "starts PREFIX/bin/marionette (DESTDIR left out): " + text.split("ExecStart=")[-1][:60])
        check("ExecStartPre=" in text and "RestartPreventExitStatus=2 3" in text,
              "the unit still waits for the glove's adapter and does not retry exit 2 or 3")
        verify_unit(dest, unit)
        check_unit_runs(dest, text)
        check_model_search(dest)
        for prog, helps in PROGRAMS.items():
            exe = os.path.join(root, "bin", prog)
            page = os.path.join(root, "share/man/man1", prog + ".1")
            check(os.access(exe, os.X_OK), prog + " is installed executable in bin/")
            check(os.path.isfile(page), prog + ".1 is installed in share/man/man1/")
            if not (os.access(exe, os.X_OK) and os.path.isfile(page)):
                continue
            text, warn = render(page)
            check(warn.strip() == "", prog + ".1 renders without warnings: " + warn.strip())
            check(prog in text and "EXIT STATUS" in text, prog + ".1 renders to text")
            for args in helps:
                h = run([exe] + args)
                check(h.returncode == 0, "installed %s %s exits 0" % (prog, " ".join(args)))
                opts = help_options(h.stdout)
                check(len(opts) >= 2, "%s %s lists options" % (prog, " ".join(args)))
                for o in sorted(opts):
                    check(re.search(r"(?<![\w-])%s(?![\w-])" % re.escape(o), text) is not None,
                          "%s.1 describes %s (from %s %s)" % (prog, o, prog, " ".join(args)))
        # The Makefile's install target passes PREFIX and picks the udev folder.
        for prefix, want in (("/usr", "/usr/lib/udev/rules.d"),
                             ("/usr/local", "/etc/udev/rules.d"),
                             ("/opt/mr", "/opt/mr/lib/udev/rules.d")):
            n = run(["make", "-s", "-n", "-C", SRC, "install", "PREFIX=" + prefix])
            check("--prefix " + prefix in n.stdout and "MR_UDEV_RULES_DIR=%s cmake" % want in n.stdout
                  and "cmake -S" not in n.stdout,
                  "make install PREFIX=%s installs under %s, the rule in %s, and builds nothing"
                  % (prefix, prefix, want))
        check_front_door()
    finally:
        shutil.rmtree(dest, ignore_errors=True)
    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    print("install: programs, man pages and udev rule in place; every --help option documented")
    return 0


if __name__ == "__main__":
    sys.exit(main())
