#!/usr/bin/env python3
"""Fails when a C or C++ function in the given folders is longer than a limit.

The house rule (STYLE.md) is that a function past about 80 lines probably
holds two things. Usage: function_length.py LIMIT DIR... ; prints the longest
functions, and every one over the limit as file:line: name (N lines).
"""
import pathlib
import re
import sys

SOURCE = {".c", ".h", ".cpp", ".hpp"}


def strip(text):
    """Blanks comments, strings and character literals, keeping newlines."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + re.sub(r"[^\n]", " ", text[i + 1:j]) + c)
            i = j + 1
        elif c == "#":  # preprocessor line, with continuations
            j = i
            while True:
                k = text.find("\n", j)
                if k < 0:
                    k = n
                    break
                if text[k - 1] != "\\":
                    break
                j = k + 1
            out.append(re.sub(r"[^\n]", " ", text[i:k]))
            i = k
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path):
    text = strip(path.read_text(errors="replace"))
    depth, start, found = 0, None, []
    for m in re.finditer(r"[{}]", text):
        if m.group() == "{":
            if depth == 0 or (depth == 1 and start is None):
                head = text[:m.start()].rstrip()
                # A function body follows a parameter list (maybe with const,
                # noexcept or an initialiser list); a namespace or extern "C"
                # block does not count as a level.
                if re.search(r"\)\s*(const|noexcept|override)?\s*$", head) and not re.search(r"=\s*$", head):
                    name = re.findall(r"([A-Za-z_]\w*)\s*\([^()]*(?:\([^()]*\)[^()]*)*\)\s*(?:const|noexcept|override)?\s*$", head)
                    start = (m.start(), name[-1] if name else "?", depth)
            depth += 1
        else:
            depth -= 1
            if start is not None and depth == start[2]:
                first = text.count("\n", 0, start[0]) + 1
                last = text.count("\n", 0, m.start()) + 1
                found.append((last - first + 1, f"{path}:{first}", start[1]))
                start = None
            if depth < 0:
                depth = 0
    return found


def main(argv):
    if len(argv) < 3:
        print("usage: function_length.py LIMIT DIR...", file=sys.stderr)
        return 2
    limit = int(argv[1])
    found = []
    for root in argv[2:]:
        for p in sorted(pathlib.Path(root).rglob("*")):
            if p.suffix in SOURCE and p.is_file():
                found += functions(p)
    found.sort(key=lambda f: -f[0])
    over = [f for f in found if f[0] > limit]
    print(f"{len(found)} functions; the longest:")
    for n, where, name in found[:5]:
        print(f"  {where}: {name} ({n} lines)")
    for n, where, name in over:
        print(f"{where}: {name} is {n} lines, over the limit of {limit}", file=sys.stderr)
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
