#!/usr/bin/env python3
"""The message definition is the one source: a change to it changes the
generated header and the spec hash, and a malformed definition is refused
with file:line. Run by ctest as protocol_generator."""
import os
import subprocess
import sys
import tempfile

src = sys.argv[1]
gen = os.path.join(src, "protocol", "gen", "gp_gen.py")
definition = os.path.join(src, "protocol", "messages.def")
failures = []


def run(path, *args):
    return subprocess.run([sys.executable, gen, path, *args], capture_output=True, text=True)


checks = 0


def check(cond, what):
    global checks
    checks += 1
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


text = open(definition, encoding="utf-8").read()
base = run(definition, "--hash").stdout.strip()
with tempfile.TemporaryDirectory() as tmp:
    def variant(name, new_text):
        p = os.path.join(tmp, name)
        with open(p, "w", encoding="utf-8") as f:
            f.write(new_text)
        return p

    widened = variant("widened.def", text.replace("ch         u12[5]", "ch         u16[5]", 1)
                      .replace("flags      u12", "flags      u16", 1))
    r = run(widened, "--hash")
    check(r.returncode == 0 and r.stdout.strip() != base, "widening a SAMPLE field changes the hash")
    h1, h2 = os.path.join(tmp, "a.h"), os.path.join(tmp, "b.h")
    run(definition, "--header", h1)
    run(widened, "--header", h2)
    a, b = open(h1).read(), open(h2).read()
    check("#define GP_SAMPLE_LEN 15u" in a and "#define GP_SAMPLE_LEN 18u" in b,
          "the generated header follows the definition (SAMPLE 15 -> 18 bytes)")
    check("#define GP_SAMPLE_CH_COUNT 5u" in a and "#define GP_SAMPLE_CH_BITS 12u" in a
          and "#define GP_SAMPLE_CH_MAX 0xFFFu" in a and "#define GP_SAMPLE_CH_BITS 16u" in b
          and "#define GP_SAMPLE_CH_MAX 0xFFFFu" in b,
          "the channel count and ADC width come from the definition's SAMPLE.ch")
    renamed = variant("renamed.def", text.replace("  adc_bits       u8", "  adc_resolution u8", 1))
    check(run(renamed, "--hash").stdout.strip() != base, "renaming a field changes the hash")
    value = variant("value.def", text.replace("BAD_STATE       4", "BAD_STATE       6", 1))
    check(run(value, "--hash").stdout.strip() != base, "changing a named value changes the hash")
    comment = variant("comment.def", "# an added comment\n" + text)
    check(run(comment, "--hash").stdout.strip() == base, "comments do not change the hash")
    odd = variant("odd.def", text.replace("flags      u12", "flags      u11", 1))
    r = run(odd, "--hash")
    check(r.returncode != 0 and "not whole bytes" in r.stderr and "odd.def:" in r.stderr,
          "a message that is not whole bytes is refused with file:line")
    bad = variant("bad.def", text.replace("  seq        u16", "  seq        i16", 1))
    r = run(bad, "--hash")
    check(r.returncode != 0 and "bad.def:" in r.stderr and "expected" in r.stderr,
          "a malformed field is refused with file:line and what was expected")

# SPEC.md's message tables and stated hash agree with the definition.
sys.path.insert(0, os.path.dirname(gen))
import gp_gen  # noqa: E402
import re  # noqa: E402

proto, messages, enums = gp_gen.parse(definition)
spec = open(os.path.join(src, "protocol", "SPEC.md"), encoding="utf-8").read()
tables = {}
for block in re.split(r"^### ", spec, flags=re.M)[1:]:
    m = re.match(r"(\w+) \(0x([0-9A-F]{2})", block)
    if m:
        rows = re.findall(r"^\| (\w+) \| (u\d+(?:\[\d+\])?) \|", block, flags=re.M)
        tables[m.group(1)] = (int(m.group(2), 16), rows)
expected = {m["name"]: (m["id"], [(f["name"], f"u{f['bits']}" + (f"[{f['count']}]" if f["array"] else ""))
                                 for f in m["fields"]]) for m in messages}
check(tables == expected, "SPEC.md's message tables match messages.def")
check(f"Current spec hash: **{base}**" in spec, "SPEC.md states the current spec hash")

# SPEC.md's sample of the canonical text is the generator's, line for line
# ("..." skips lines), so a decoder written from the page derives our hash.
canon = gp_gen.canonical(proto, messages, enums).decode().splitlines()
sample = re.search(r"^```\n(protocol \d+\n.*?)^```", spec, flags=re.M | re.S)
pos, skip, in_order = 0, False, sample is not None
for line in (sample.group(1).splitlines() if sample else []):
    if line == "...":
        skip = True
        continue
    at = canon.index(line, pos) if line in canon[pos:] else -1
    if at < 0 or (at != pos and not skip):
        in_order = False
        break
    pos, skip = at + 1, False
check(in_order,
      "SPEC.md's sample of the canonical text matches the generator")

print(f"{checks - len(failures)} passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
