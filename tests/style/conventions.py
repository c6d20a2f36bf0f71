#!/usr/bin/env python3
"""Checks the API conventions of docs/conventions.md over the public headers.

Usage: conventions.py RULE SOURCE_DIR, RULE one of:
  extern-c   every public header (host/*/include/*.h) wraps its declarations
             in an extern "C" guard for C++ callers;
  status     every status enum (mr_*_status, mr_status) has its OK value 0,
             every failure (a name with ERR) below 0 and every other outcome
             above 0;
  cookie     every struct made by a default maker (mr_default_x_def(void))
             is named mr_x_def and starts with `uint32_t cookie`, its
             library stamps MR_DEF_COOKIE and compares cookies with it; no
             other cookie macro exists (each library's own tests show that
             the call taking a def refuses one not made by its maker);
  getters    no exported function ends in _get, and mr_object_get_noun is
             used only where mr_object_noun is a type's name;
  messages   a message comes back through `char *msg, size_t msg_size`, an
             error struct named mr_<lib>_error, or mr_<object>_last_error;
  used       every exported function is called somewhere outside its own
             definition and declaration (host/, tools/, tests/).
Each failure prints as FILE: what is wrong; the exit status is 1 when any.
"""
import pathlib
import re
import sys

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from function_length import strip  # noqa: E402  (comments and strings blanked)


def headers(root):
    return sorted(root.glob("host/*/include/*.h"))


def sources(root, dirs=("host", "tools", "tests")):
    out = []
    for d in dirs:
        for ext in ("*.c", "*.h", "*.cpp"):
            out += [p for p in (root / d).rglob(ext) if "build" not in p.parts]
    return sorted(out)


def check_extern_c(root):
    bad = []
    for h in headers(root):
        text = h.read_text()
        opens = re.search(r'#ifdef __cplusplus\s*\nextern "C" \{\s*\n#endif', text)
        closes = re.search(r"#ifdef __cplusplus\s*\n\}\s*(/\*.*\*/)?\s*\n#endif", text)
        if not (opens and closes):
            bad.append(f"{h.relative_to(root)}: no extern \"C\" guard")
    return bad


def enum_values(body):
    """(name, value) of an enum body, counting on from the last value."""
    out, nxt = [], 0
    for item in strip(body).split(","):
        item = item.strip()
        if not item:
            continue
        name, _, val = item.partition("=")
        if val.strip():
            nxt = int(val.strip(), 0)
        out.append((name.strip(), nxt))
        nxt += 1
    return out


def status_enums(root):
    for h in headers(root):
        text = h.read_text()
        for m in re.finditer(r"typedef enum (mr_(?:\w+_)?status) \{(.*?)\} \1;", text, re.S):
            yield h, m.group(1), enum_values(m.group(2))


def check_status(root):
    bad, seen = [], 0
    for h, name, values in status_enums(root):
        seen += 1
        where = f"{h.relative_to(root)}: {name}"
        if not values or not values[0][0].endswith("OK") or values[0][1] != 0:
            bad.append(f"{where}: the first value is not OK = 0")
        for v, n in values[1:]:
            if "_ERR_" in v and n >= 0:
                bad.append(f"{where}: failure {v} = {n} is not negative")
            if "_ERR_" not in v and n <= 0:
                bad.append(f"{where}: {v} = {n} is below 0 but not named _ERR_")
    if seen < 10:
        bad.append(f"only {seen} status enums found: the pattern no longer matches")
    return bad


def structs(text):
    """name -> body of each `typedef struct name { ... } name;`."""
    out = {}
    for m in re.finditer(r"typedef struct (mr_\w+) \{", text):
        depth, i = 1, m.end()
        while depth:
            depth += {"{": 1, "}": -1}.get(text[i], 0)
            i += 1
        out[m.group(1)] = text[m.end():i - 1]
    return out


def check_cookie(root):
    bad, all_structs = [], {}
    files = headers(root) + sorted(root.glob("host/app/*.h"))
    for h in files:
        all_structs.update({k: (h, v) for k, v in structs(strip(h.read_text())).items()})
    makers = 0
    for h in files:
        for m in re.finditer(r"\b(mr_\w+) mr_default_(\w+)\(void\);", strip(h.read_text())):
            typ, made = m.group(1), m.group(2)
            makers += 1
            where = f"{h.relative_to(root)}: mr_default_{made}()"
            if not made.endswith("_def") or typ != "mr_" + made:
                bad.append(f"{where} makes {typ}, not mr_{made} named *_def")
                continue
            body = all_structs.get(typ, (None, ""))[1]
            if not re.match(r"\s*uint32_t cookie;", body):
                bad.append(f"{where}: {typ} does not start with `uint32_t cookie;`")
            lib = h.parent.parent
            makes = re.compile(r"\b" + re.escape(typ) + r"\b")
            users = [p.read_text() for p in lib.rglob("*.c")]
            if not any(makes.search(t) and re.search(r"cookie = MR_DEF_COOKIE|\{\s*MR_DEF_COOKIE", t)
                       for t in users):
                bad.append(f"{where}: nothing in {lib.relative_to(root)} stamps MR_DEF_COOKIE")
            if not any(re.search(r"cookie\s*[!=]=\s*MR_DEF_COOKIE", t) for t in users):
                bad.append(f"{where}: nothing in {lib.relative_to(root)} compares a cookie "
                           "with MR_DEF_COOKIE")
    if makers < 20:
        bad.append(f"only {makers} default makers found: the pattern no longer matches")
    for p in sources(root, ("host", "tools")):
        for m in re.finditer(r"#define (MR_\w*COOKIE)\b", p.read_text()):
            if m.group(1) != "MR_DEF_COOKIE":
                bad.append(f"{p.relative_to(root)}: a second cookie macro {m.group(1)}")
    return bad


def exported(root):
    """(header, name) of every function a public header declares."""
    for h in headers(root):
        text = strip(h.read_text())
        for m in re.finditer(r"^[A-Za-z_][\w \*]*?\b(mr_\w+)\(", text, re.M):
            line = text[m.start():text.find("\n", m.start())]
            if line.startswith(("typedef", "#", "return")):
                continue
            yield h, m.group(1)


def check_getters(root):
    bad = []
    types = set()
    for h in headers(root):
        types |= set(re.findall(r"\}\s*(mr_\w+);", strip(h.read_text())))
    for h, f in exported(root):
        where = f"{h.relative_to(root)}: {f}"
        if f.endswith("_get"):
            bad.append(f"{where}: a getter says get before the noun, never after it")
        m = re.match(r"(mr_[a-z0-9]+)_get_(\w+)$", f)
        if m and f"{m.group(1)}_{m.group(2)}" not in types:
            bad.append(f"{where}: {m.group(1)}_{m.group(2)} names no type, so the getter "
                       f"is {m.group(1)}_{m.group(2)}")
    return bad


def check_messages(root):
    bad = []
    for h in headers(root):
        text = strip(h.read_text())
        rel = h.relative_to(root)
        for m in re.finditer(r"char \*(\w+), size_t (\w+)", text):
            if m.group(1) in ("msg", "err", "error", "errbuf", "message", "why", "reason"):
                if (m.group(1), m.group(2)) != ("msg", "msg_size"):
                    bad.append(f"{rel}: a message buffer named {m.group(1)}, {m.group(2)}, "
                               "not msg, msg_size")
        for m in re.finditer(r"\b(mr_\w*_err(?:or)?s?)\b(?!\()", text):
            name = m.group(1)
            if not re.fullmatch(r"mr_[a-z0-9]+_error", name):
                bad.append(f"{rel}: {name}: an error struct is named mr_<lib>_error")
        for s, body in structs(text).items():
            if s.endswith("_error") and not re.match(r"\s*mr_\w*status status;", body):
                bad.append(f"{rel}: {s} does not start with its status")
    return sorted(set(bad))


# Exported with no caller today, kept on purpose.
KEPT = {
    "mr_control_values": "the only view of the smoothing filter's state, for "
                         "the control tests that check it after odd inputs",
}


def check_used(root):
    bad = []
    decls = list(exported(root))
    names = {f for _, f in decls}
    uses = dict.fromkeys(names, 0)
    # A declaration or definition starts at column 0 with its return type;
    # anything else naming the function (a call, a pointer taken) is a use.
    own = re.compile(r"(static\s+inline\s+)?(const\s+)?[A-Za-z_]\w*[\s\*]+$")
    for p in sources(root):
        text = strip(p.read_text())
        for m in re.finditer(r"\bmr_\w+", text):
            if m.group() not in names:
                continue
            line_start = text[text.rfind("\n", 0, m.start()) + 1:m.start()]
            is_own = (own.fullmatch(line_start) and not line_start.startswith("return")
                      and text.startswith("(", m.end()))
            if not is_own:
                uses[m.group()] += 1
    for h, f in decls:
        if uses[f] == 0 and f not in KEPT:
            bad.append(f"{h.relative_to(root)}: {f} is exported but nothing calls it")
    if len(decls) < 200:
        bad.append(f"only {len(decls)} exported functions found: the pattern no longer matches")
    return bad


RULES = {"extern-c": check_extern_c, "status": check_status, "cookie": check_cookie,
         "getters": check_getters, "messages": check_messages, "used": check_used}


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in RULES:
        print(__doc__, file=sys.stderr)
        return 2
    root = pathlib.Path(sys.argv[2]).resolve()
    bad = RULES[sys.argv[1]](root)
    for b in bad:
        print(b)
    print(f"{sys.argv[1]}: {len(bad)} departures from docs/conventions.md")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
