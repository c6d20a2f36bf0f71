#!/usr/bin/env python3
"""The seed corpus of fuzz_firmware, made from the golden vectors.

Each golden frame of a host command (protocol/messages.def: direction
"host") becomes one seed, and a few sessions join them: every command in a
row, a calibration with ticks between CAL_START and CAL_SAVE (each 0x00 is an
idle delimiter, and the glove reads at most 32 bytes a tick), and one of the
glove's own frames echoed back. One more seed, frames_every_command, holds
the commands in the target's second reading of an input: a length byte, then
type and payload, the CRC and framing left to the target.

  firmware_corpus.py ROOT          writes ROOT/tests/fuzz/corpus/firmware/
  firmware_corpus.py ROOT --check  exits 1, naming the file, if the committed
                                   corpus differs from what it would write
"""
import os
import sys


def host_types(defn):
    names = set()
    for line in open(defn, encoding="utf-8"):
        words = line.split("#", 1)[0].split()
        if len(words) >= 4 and words[0] == "message" and words[3] == "host":
            names.add(words[1])
    return names


def golden(path):
    vectors = {}
    for line in open(path, encoding="utf-8"):
        if line.startswith("#") or not line.strip():
            continue
        name, mtype, spec_hash, wire = line.split()[:4]
        vectors[name] = (mtype, spec_hash, bytes.fromhex(wire))
    return vectors


def cobs_decode(block):
    out, i = bytearray(), 0
    while i < len(block):
        code = block[i]
        out += block[i + 1:i + code]
        i += code
        if code < 0xFF and i < len(block):
            out.append(0)
    return bytes(out)


def corpus(root):
    hosts = host_types(os.path.join(root, "protocol", "messages.def"))
    vectors = golden(os.path.join(root, "protocol", "vectors", "golden.txt"))
    ours = {n: v for n, v in vectors.items() if not n.startswith("mismatch_")}
    seeds = {n: w for n, (t, _, w) in ours.items() if t in hosts}
    if not seeds:
        raise SystemExit("firmware_corpus.py: no host command among the golden vectors")
    seeds["session_every_command"] = b"".join(seeds[n] for n in sorted(seeds))
    idle = b"\x00" * 320
    seeds["session_calibration"] = seeds["cal_start"] + idle + seeds["cal_save"] + seeds["get_status"]
    seeds["session_echo"] = ours["sample_basic"][2] + seeds["ping"]
    bodies = [cobs_decode(seeds[n][:-1])[:-4] for n in sorted(seeds) if not n.startswith("session_")]
    seeds["frames_every_command"] = b"".join(bytes([len(b)]) + b for b in bodies)
    return seeds


def main(argv):
    if len(argv) not in (2, 3) or (len(argv) == 3 and argv[2] != "--check"):
        sys.stderr.write("usage: firmware_corpus.py ROOT [--check]\n")
        return 2
    root = argv[1]
    out = os.path.join(root, "tests", "fuzz", "corpus", "firmware")
    seeds = corpus(root)
    if len(argv) == 3:
        have = set(os.listdir(out)) if os.path.isdir(out) else set()
        for name in sorted(have | set(seeds)):
            path = os.path.join(out, name)
            if name not in seeds or name not in have or open(path, "rb").read() != seeds[name]:
                sys.stderr.write(f"{path}: differs from the golden vectors; "
                                 "run tests/fuzz/firmware_corpus.py to write it again\n")
                return 1
        return 0
    os.makedirs(out, exist_ok=True)
    for name in os.listdir(out):
        if name not in seeds:
            os.remove(os.path.join(out, name))
    for name, data in seeds.items():
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
