#!/usr/bin/env python3
"""A second decoder, written from protocol/SPEC.md alone: the spec hash, the
largest wire frame, every message's type id, payload length and field bit
positions are read from the page, and the receiver rules of its section 9
are followed as written. It must read every golden vector as its stated
meaning, and count every glove-gen fault stream exactly as the C decoder
(glove-dump) and the injected truth do. If the page and the code drift
apart, a stranger's decoder would too, and this fails.
Run by ctest as tools_spec_decoder: test_spec_decoder.py SRC GLOVE_GEN GLOVE_DUMP."""
import os
import re
import subprocess
import sys
import tempfile

src, glove_gen, glove_dump = sys.argv[1:4]
spec = open(os.path.join(src, "protocol", "SPEC.md"), encoding="utf-8").read()
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


# --- what the page says ----------------------------------------------------
HASH = int(re.search(r"Current spec hash: \*\*0x([0-9A-F]{8})\*\*", spec).group(1), 16)
MAX_WIRE = int(re.search(r"\*\*(\d+) bytes\*\* \(`GP_MAX_WIRE`\)", spec).group(1))
MESSAGES = {}  # type id -> (name, payload bytes, unseeded, [(field, first bit, bits, count)])
for block in re.split(r"^### ", spec, flags=re.M)[1:]:
    head = re.match(r"(\w+) \(0x([0-9A-F]{2}), ([^)]*)\) — (\d+)-byte payload", block)
    if not head:
        continue
    fields = []
    for name, typ, lo in re.findall(r"^\| (\w+) \| (u\d+(?:\[\d+\])?) \| \d+ \| (\d+)–\d+ \|",
                                    block, flags=re.M):
        m = re.match(r"u(\d+)(?:\[(\d+)\])?$", typ)
        fields.append((name, int(lo), int(m.group(1)), int(m.group(2) or 0)))
    MESSAGES[int(head.group(2), 16)] = (head.group(1), int(head.group(4)),
                                        "unseeded" in head.group(3), fields)
UNSEEDED = [t for t, m in MESSAGES.items() if m[2]]
MAX_FRAME = int(re.search(r"\*\*(\d+) bytes\*\* \(`GP_MAX_FRAME`\)", spec).group(1))
START = int(re.search(r"^\| GP_SAMPLE_F_START \| 0x([0-9A-Fa-f]+) \|", spec, flags=re.M).group(1), 16)
check(len(MESSAGES) >= 14 and UNSEEDED == [0x02], "SPEC.md lists the messages, INFO unseeded")

TABLE = []
for i in range(256):
    c = i
    for _ in range(8):
        c = (c >> 1) ^ (0x82F63B78 if c & 1 else 0)
    TABLE.append(c)


def crc32c(data):
    c = 0xFFFFFFFF
    for b in data:
        c = TABLE[(c ^ b) & 0xFF] ^ (c >> 8)
    return c ^ 0xFFFFFFFF


check(crc32c(b"123456789") == 0xE3069283, "CRC-32/ISCSI check value")


def le(b):
    return int.from_bytes(b, "little")


def cobs_decode(block):
    out, i = bytearray(), 0
    while i < len(block):
        code = block[i]
        i += 1
        if code == 0 or i + code - 1 > len(block):
            return None
        out += block[i:i + code - 1]
        i += code - 1
        if code != 0xFF and i < len(block):
            out.append(0)
    return bytes(out)


def unpack(t, payload):
    """Fields by their payload bits: bit b is bit (b mod 8) of byte (b div 8)."""
    bits = le(payload)
    out = {}
    for name, lo, width, count in MESSAGES[t][3]:
        vals = [(bits >> (lo + k * width)) & ((1 << width) - 1) for k in range(max(count, 1))]
        out[name] = vals if count else vals[0]
    return out


class Decoder:
    """SPEC.md section 9, rule by rule."""

    def __init__(self, our_hash):
        self.hash = our_hash
        self.peer = None
        self.high = None
        self.seen = set()  # sequence numbers seen, high and the 63 below it
        self.buf = bytearray()
        self.discarding = False
        self.following = False  # rule 2's exception: a long run that may be foreign
        self.in_step = False  # a 0x00 has been seen (rule 1)
        self.high_start = None  # (t_us) of the frame at high, if it carried START
        self.c = dict.fromkeys(("frames crc_errors framing_errors oversize unknown_type "
                                "spec_mismatch lost duplicates reordered seq_restarts "
                                "bytes").split(), 0)

    def feed(self, data):
        events = []
        for b in data:
            self.c["bytes"] += 1
            if b:
                if self.discarding:
                    continue
                if len(self.buf) == MAX_WIRE and not self.following:  # rule 2
                    if (self.buf[0] >= 2 and self.buf[1] in UNSEEDED) or self.peer is not None:
                        self.following = True
                        self.buf.append(b)
                        continue
                    self.discarding, self.buf = True, bytearray()
                    self.c["oversize"] += 1
                    events.append(("oversize", None))
                    continue
                self.buf.append(b)
                continue
            if self.discarding:
                self.discarding = False
            elif self.following:
                self.following = False
                ev = self.frame(bytes(self.buf))
                if ev[0] != "spec_mismatch":
                    self.c[ev[0]] -= 1
                    ev = self.count("oversize")
                events.append(ev)
                self.buf = bytearray()
            elif self.buf:  # rule 1: empty frames are ignored
                ev = self.frame(bytes(self.buf))
                if not self.in_step and ev[0] in ("framing_errors", "crc_errors"):
                    self.c[ev[0]] -= 1  # rule 1: the tail of a frame joined mid-way
                else:
                    events.append(ev)
                self.buf = bytearray()
            self.in_step = True
        return events

    def count(self, what, msg=None):
        self.c[what] += 1
        return (what, msg)

    def frame(self, block):
        raw = cobs_decode(block)
        if raw is None or len(raw) < 5:  # rule 3
            return self.count("framing_errors")
        t, body, crc = raw[0], raw[:-4], le(raw[-4:])
        known = MESSAGES.get(t)
        unseeded = t in UNSEEDED
        ours = crc32c((b"" if unseeded else self.hash.to_bytes(4, "little")) + body) == crc
        if unseeded and len(raw) >= 10 and ours and le(raw[2:6]) != self.hash:  # rule 4
            self.peer = le(raw[2:6])
            return self.count("spec_mismatch")
        if not ours and not unseeded and self.peer is not None and \
                crc32c(self.peer.to_bytes(4, "little") + body) == crc:  # rule 5
            return self.count("spec_mismatch")
        if len(raw) > MAX_FRAME or (known and len(raw) != 1 + known[1] + 4):  # rule 6
            return self.count("framing_errors")
        if not ours:  # rule 7
            return self.count("crc_errors")
        if not known:  # rule 8
            return self.count("unknown_type")
        msg = (t, unpack(t, raw[1:-4]))
        if known[0] == "SAMPLE":
            return self.sequence(msg)
        return self.count("frames", msg)

    def sequence(self, msg):
        seq, start = msg[1]["seq"], msg[1]["flags"] & START
        d = None
        if self.high is not None:
            d = (seq - self.high) & 0xFFFF
            d = d - 0x10000 if d >= 0x8000 else d
        if d is not None and start:
            if d == 0 and self.high_start == msg[1]["t_us"]:
                return self.count("duplicates", msg)
            self.c["seq_restarts"] += 1
            self.high = seq
            self.seen = set()
        elif d is None or d > 0:
            if d is not None:
                self.c["lost"] += d - 1
            self.high = seq
        elif d == 0 or (-64 < d < 0 and seq in self.seen):
            return self.count("duplicates", msg)
        elif -64 < d < 0:
            self.seen.add(seq)
            self.c["reordered"] += 1
            self.c["lost"] = max(0, self.c["lost"] - 1)
            return self.count("frames", msg)
        else:
            self.c["seq_restarts"] += 1
            self.high = seq
            self.seen = set()
        self.high_start = msg[1]["t_us"] if start else None
        self.seen.add(seq)
        self.seen = {s for s in self.seen if (self.high - s) & 0xFFFF < 64}
        return self.count("frames", msg)


# --- the golden vectors, read through the page's tables ---------------------
golden = os.path.join(src, "protocol", "vectors", "golden.txt")
names = {m[0]: t for t, m in MESSAGES.items()}
n_vectors = 0
for line in open(golden, encoding="utf-8"):
    cols = line.split("#", 1)[0].split()
    if not cols:
        continue
    name, typ, hash_hex, wire = cols[:4]
    want = {k: ([int(x) for x in v.split(",")] if "," in v else int(v))
            for k, v in (kv.split("=", 1) for kv in cols[4:])}
    d = Decoder(HASH)
    if name.startswith("mismatch_"):
        d.peer = int(hash_hex, 16)
    events = d.feed(bytes.fromhex(wire))
    n_vectors += 1
    if name.startswith("mismatch_"):
        ok = events == [("spec_mismatch", None)]
        if typ == "INFO":
            ok = ok and d.peer == int(hash_hex, 16)
    else:
        ok = len(events) == 1 and events[0][0] == "frames" and \
            events[0][1] == (names[typ], want)
    if not ok:
        check(False, f"golden vector {name} decodes from SPEC.md's tables to its meaning")
check(n_vectors >= 15 and not failures, f"{n_vectors} golden vectors read through SPEC.md's tables")

# --- sequence numbers at the window's edges, the wrap and restarts --------


def cobs_encode(raw):
    out, run = bytearray(), bytearray()
    for b in raw:
        if b == 0 or len(run) == 254:
            out += bytes([len(run) + 1]) + run
            run = bytearray()
            if b == 0:
                continue
        run.append(b)
    return bytes(out + bytes([len(run) + 1]) + run + b"\0")


def sample(seq, flags=0, t_us=0):
    t = names["SAMPLE"]
    bits = 0
    for name, lo, width, count in MESSAGES[t][3]:
        bits |= {"seq": seq, "flags": flags, "t_us": t_us}.get(name, 0) << lo
    body = bytes([t]) + bits.to_bytes(MESSAGES[t][1], "little")
    return cobs_encode(body + crc32c(HASH.to_bytes(4, "little") + body).to_bytes(4, "little"))


seqs = [9, 8, 10, 11, 13, 12, 12, 11, 100, 37, 36, 200, 137, 138, 136, 65534, 65535, 1, 0,
        0, 2, 65535, 400, 401, 336, 337, 402, 500, 436, 437, 3, 4, 2, 60, 5, 4, 6,
        (0, 7), (0, 7), 1, 2, 30, (0, 8), 1, 100, (0, 9), 40000, (0, 10), 65535, (0, 11), 1]
with tempfile.TemporaryDirectory() as tmp:
    path, counters = os.path.join(tmp, "seq.bin"), os.path.join(tmp, "seq.c")
    with open(path, "wb") as f:
        f.write(b"".join(sample(q[0], START, q[1]) if isinstance(q, tuple) else sample(q)
                         for q in seqs))
    subprocess.run([glove_dump, "-q", "--counters", counters, path], capture_output=True)
    got = {k: int(v) for k, v in re.findall(r"^(\w+)=(\d+)$", open(counters).read(), re.M)}
    d = Decoder(HASH)
    d.feed(open(path, "rb").read())
    check(got == d.c and d.c["seq_restarts"] >= 8 and d.c["reordered"] >= 5
          and d.c["duplicates"] >= 3,
          f"sequence edge cases count as the page says: {d.c}")

# --- another definition's frames of any length, past the wire limit too -----


def foreign_frame(t, payload, seed_hash):
    body = bytes([t]) + payload
    seed = b"" if t in UNSEEDED else seed_hash.to_bytes(4, "little")
    return cobs_encode(body + crc32c(seed + body).to_bytes(4, "little"))


FOREIGN = 0x0BADF00D
prefix = bytes([1]) + FOREIGN.to_bytes(4, "little")
stream = b"\0" + b"".join(
    foreign_frame(names["INFO"], prefix + bytes(range(n % 256)) * (1 + n // 256), FOREIGN)
    for n in (5, 53, 54, 300, 700))
stream += b"".join(foreign_frame(names["SAMPLE"], bytes([7]) * n, FOREIGN) for n in (0, 15, 60, 400))
stream += b"\xff" + bytes([names["INFO"]]) + b"\x37" * 300 + b"\0"  # long, foreign to nobody
stream += sample(5) + sample(6)
with tempfile.TemporaryDirectory() as tmp:
    path, counters = os.path.join(tmp, "long.bin"), os.path.join(tmp, "long.c")
    with open(path, "wb") as f:
        f.write(stream)
    r = subprocess.run([glove_dump, "-q", "--keep-going", "--counters", counters, path],
                       capture_output=True)
    got = {k: int(v) for k, v in re.findall(r"^(\w+)=(\d+)$", open(counters).read(), re.M)}
    d = Decoder(HASH)
    d.feed(stream)
    check(got == d.c and d.c["spec_mismatch"] == 9 and d.c["oversize"] == 1
          and d.c["frames"] == 2 and d.c["framing_errors"] + d.c["crc_errors"] == 0,
          f"another definition's INFO and SAMPLE of any length are spec mismatches: {d.c}")

# --- fault streams: the page's decoder, the C decoder and the truth agree ---
with tempfile.TemporaryDirectory() as tmp:
    for seed in ("3", "4"):
        stream, truth, counters = (os.path.join(tmp, f"{seed}.{x}") for x in ("bin", "truth", "c"))
        subprocess.run([glove_gen, "--fast", "-q", "-n", "20000", "--faults", "0.2",
                        "--stall-frames", "1:20", "--seed", seed, "-o", "file:" + stream,
                        "--truth", truth], check=True)
        r = subprocess.run([glove_dump, "-q", "--keep-going", "--counters", counters, stream],
                           capture_output=True, text=True)
        d = Decoder(HASH)
        d.feed(open(stream, "rb").read())

        def kv(path):
            return {k: int(v) for k, v in re.findall(r"^(\w+)=(\d+)$", open(path).read(), re.M)}

        c_counts, truth_counts = kv(counters), kv(truth)
        mine = {k: v for k, v in d.c.items()}
        check(r.returncode == 3 and mine == c_counts,
              f"seed {seed}: SPEC.md's decoder counts as glove-dump does {mine}")
        check(all(truth_counts[k] == v for k, v in mine.items()),
              f"seed {seed}: and as glove-gen injected")
        check(all(mine[k] > 0 for k in mine if k != "seq_restarts"),
              f"seed {seed}: every kind of fault occurred")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
