#!/usr/bin/env python3
"""Write protocol/vectors/golden.txt from SPEC.md's rules, independently of
the C codec: this script packs, checksums and frames in Python, reading only
the layouts from messages.def. The C tests then check the codec against the
file, so the two implementations keep each other honest.

Usage: make_golden.py protocol/messages.def > protocol/vectors/golden.txt
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "gen"))
import gp_gen  # noqa: E402

FOREIGN = 0xDEADBEEF


def pack(msg, fields):
    bits, off = 0, 0
    for f in msg["fields"]:
        vals = fields[f["name"]]
        vals = vals if isinstance(vals, list) else [vals]
        assert len(vals) == f["count"], f["name"]
        for v in vals:
            assert 0 <= v < (1 << f["bits"]), (f["name"], v)
            bits |= v << off
            off += f["bits"]
    return bits.to_bytes(msg["bytes"], "little")


def cobs(data):
    out, block = bytearray(), bytearray()
    for b in data:
        if b == 0:
            out += bytes([len(block) + 1]) + block
            block = bytearray()
        else:
            block.append(b)
            if len(block) == 254:
                out += b"\xff" + block
                block = bytearray()
    return bytes(out + bytes([len(block) + 1]) + block)


def wire(msg, fields, spec_hash):
    body = bytes([msg["id"]]) + pack(msg, fields)
    seed = b"" if msg["unseeded"] else spec_hash.to_bytes(4, "little")
    crc = gp_gen.crc32c(seed + body)
    return cobs(body + crc.to_bytes(4, "little")) + b"\x00"


def main():
    proto, messages, enums = gp_gen.parse(sys.argv[1])
    spec = gp_gen.crc32c(gp_gen.canonical(proto, messages, enums))
    by = {m["name"]: m for m in messages}
    info = dict(proto_major=proto, spec_hash=spec, fw_major=1, fw_minor=2, fw_patch=3,
                uid=[0x00470031, 0x3233510A, 0x37383939], hand=1, n_channels=5,
                adc_bits=12, sample_rate_hz=1000, frame_rate_hz=250, baud=115200,
                cal_state=1, cal_min=[310, 295, 402, 350, 288],
                cal_max=[3710, 3655, 3802, 3590, 3499])
    vectors = [
        ("sample_basic", "SAMPLE", spec, dict(seq=1, t_us=4000, ch=[100, 200, 300, 400, 500], flags=1)),
        ("sample_zeros", "SAMPLE", spec, dict(seq=0, t_us=0, ch=[0, 0, 0, 0, 0], flags=0)),
        ("sample_start", "SAMPLE", spec, dict(seq=0, t_us=1000, ch=[2048] * 5, flags=0x10)),
        ("sample_full_scale", "SAMPLE", spec, dict(seq=65535, t_us=0xFFFFFFFF, ch=[4095] * 5, flags=31)),
        ("sample_mid", "SAMPLE", spec, dict(seq=4660, t_us=123456789, ch=[2048, 1, 4094, 3000, 17], flags=2)),
        ("info_right_calibrated", "INFO", spec, info),
        ("status_counters", "STATUS", spec, dict(t_us=1000000, frames_sent=250, overruns=1,
                                                dropped_frames=2, cmd_errors=3, adc_timeouts=4)),
        ("ack_ping", "ACK", spec, dict(tag=7, cmd=by["PING"]["id"])),
        ("nack_bad_argument", "NACK", spec, dict(tag=9, cmd=by["SET_RATE"]["id"], reason=3)),
        ("ping", "PING", spec, dict(tag=7)),
        ("get_info", "GET_INFO", spec, dict(tag=1)),
        ("set_rate_1000hz_921600", "SET_RATE", spec, dict(tag=2, frame_rate_hz=1000, baud=921600)),
        ("stream_on", "STREAM_ON", spec, dict(tag=3)),
        ("stream_off", "STREAM_OFF", spec, dict(tag=4)),
        ("cal_start", "CAL_START", spec, dict(tag=5)),
        ("cal_save", "CAL_SAVE", spec, dict(tag=6)),
        ("cal_clear", "CAL_CLEAR", spec, dict(tag=8)),
        ("get_status", "GET_STATUS", spec, dict(tag=10)),
        ("mismatch_info", "INFO", FOREIGN, dict(info, spec_hash=FOREIGN)),
        ("mismatch_sample", "SAMPLE", FOREIGN, dict(seq=2, t_us=8000, ch=[100, 200, 300, 400, 500], flags=1)),
    ]
    print("# Golden vectors of the glove protocol, spec hash 0x%08X." % spec)
    print("# Written by protocol/vectors/make_golden.py (an implementation of SPEC.md")
    print("# independent of the C codec). Columns: NAME TYPE SPEC_HASH WIRE_HEX FIELD=VALUE...")
    print("# mismatch_* vectors come from a device built from another spec (hash 0x%08X);" % FOREIGN)
    print("# mismatch_info announces it, mismatch_sample is CRC-seeded with it.")
    for name, typ, h, fields in vectors:
        w = wire(by[typ], fields, h)
        vals = " ".join(f"{k}={','.join(map(str, v)) if isinstance(v, list) else v}"
                        for k, v in fields.items())
        print(f"{name} {typ} 0x{h:08X} {w.hex()} {vals}")


if __name__ == "__main__":
    main()
