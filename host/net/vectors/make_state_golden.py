#!/usr/bin/env python3
"""Write host/net/vectors/state_golden.txt from STATE.md's rules, apart from
the C codec: this script packs the messages with Python's struct module,
reading only the spec hash from state.def through the generator. The C
tests decode every vector, check its fields and encode it back byte for
byte, so the two implementations keep each other honest.

Usage: make_state_golden.py host/net/state.def > host/net/vectors/state_golden.txt
"""
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "gen"))
import state_gen  # noqa: E402

FOREIGN = 0xDEADBEEF


def seal(type_id, spec_hash, body):
    raw = struct.pack("<BI", type_id, spec_hash) + body
    return raw + struct.pack("<I", state_gen.crc32c(raw))


def frame(spec_hash, scene_id, seq, t_us, sent_us, origin, step, pose, q):
    n_frames, n_points = len(pose) // 7, len(q) // 3
    body = struct.pack("<IIQQBH", scene_id, seq, t_us, sent_us, n_frames, n_points)
    body += struct.pack("<3f", *origin) + struct.pack("<3f", *step)
    body += struct.pack(f"<{len(pose)}f", *pose) + struct.pack(f"<{len(q)}H", *q)
    return seal(0x01, spec_hash, body)


def records(files):
    out = b""
    for name, data in files:
        out += struct.pack("<H", len(name)) + name.encode() + struct.pack("<I", len(data)) + data
    return out


def fnv1a64(data):
    h = 0xCBF29CE484222325
    for b in data:
        h = ((h ^ b) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def scene(spec_hash, fps, n_frames, n_points, files):
    recs = records(files)
    body = struct.pack("<QfBHHI", fnv1a64(recs), fps, n_frames, n_points, len(files), len(recs))
    return seal(0x02, spec_hash, body + recs), fnv1a64(recs)


def line(name, kind, spec_hash, wire, fields):
    vals = " ".join(f"{k}={','.join(str(x) for x in v) if isinstance(v, list) else v}"
                    for k, v in fields)
    return f"{name} {kind} 0x{spec_hash:08X} {wire.hex()} {vals}".rstrip()


def main():
    version, messages = state_gen.parse(sys.argv[1])
    spec = state_gen.crc32c(state_gen.canonical(version, messages))
    out = [f"# Golden vectors of the show-state messages, spec hash 0x{spec:08X}.",
           "# Written by host/net/vectors/make_state_golden.py (STATE.md's rules, apart from",
           "# the C codec). Columns: NAME TYPE SPEC_HASH WIRE_HEX FIELD=VALUE...",
           "# (pose values are floats; the last vector comes from another definition)."]
    pose = [0.0, 1.5, -0.25, 1.0, 0.0, 0.0, 0.0]
    q = [0, 0, 0, 65535, 65535, 65535, 1, 2, 3]
    f1 = [("scene_id", 0x12345678), ("seq", 7), ("t_us", 116667), ("sent_us", 1764158400000000),
          ("n_frames", 1), ("n_points", 3), ("q", q)]
    out.append(line("frame_one_puppet", "FRAME", spec,
                    frame(spec, 0x12345678, 7, 116667, 1764158400000000, [-1.0, 0.0, -0.5],
                          [0.25, 0.125, 0.0], pose, q), f1))
    out.append(line("frame_empty", "FRAME", spec, frame(spec, 1, 0, 0, 0, [0, 0, 0], [0, 0, 0], [], []),
                    [("scene_id", 1), ("seq", 0), ("t_us", 0), ("sent_us", 0), ("n_frames", 0),
                     ("n_points", 0)]))
    files = [("show.yaml", b"name: tiny\n"), ("models/a.obj", b"mtllib a.mtl\n"), ("models/a.mtl", b"")]
    wire, h = scene(spec, 60.0, 2, 40, files)
    out.append(line("scene_three_files", "SCENE", spec, wire,
                    [("scene_hash", h), ("n_frames", 2), ("n_points", 40), ("n_files", 3)]))
    out.append(line("frame_foreign", "FRAME", FOREIGN,
                    frame(FOREIGN, 1, 1, 0, 0, [0, 0, 0], [0, 0, 0], [], []), [("seq", 1)]))
    print("\n".join(out))


if __name__ == "__main__":
    main()
