#!/usr/bin/env python3
"""Writes the binary seeds of the stream and sample-converter harnesses (corpus/stream_tcp,
corpus/stream_udp, corpus/sample_converter): valid streams in the layouts of docs/streaming.md,
"Protocol", tables, so that fuzzing starts from inputs that reach the frame checks.
Run from anywhere: python3 tests/fuzz/make_seeds.py"""
import os
import random
import struct

here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
rng = random.Random(1)


def header(fmt=0, max_payload=64, fs=4092000.0, start=0, week=2190, sow=7200.0, flags=1):
    return b"DNIF" + struct.pack("<HHBBHIddqiId", 1, 56, fmt, flags, 0, max_payload, fs, 0.0, start, week, 0, sow)


def frame(seq, first, payload, end=False):
    return b"DNFR" + struct.pack("<IQqI", len(payload), seq, first, 1 if end else 0) + payload


def request(resume=0, stop=False):
    return b"DNRQ" + struct.pack("<HHq", 1, 1 if stop else 0, resume)


def noise(n):
    return bytes(rng.getrandbits(8) for _ in range(n))


def write(harness, name, data):
    os.makedirs(os.path.join(here, harness), exist_ok=True)
    with open(os.path.join(here, harness, name), "wb") as f:
        f.write(data)


def stream(fmt=0, bytes_per_sample=2, frames=3, start=0, lost=()):
    out, index = [], start
    for seq in range(frames):
        payload = noise(64)
        if seq not in lost:
            out.append(frame(seq, index, payload))
        index += 64 // bytes_per_sample
    out.append(frame(frames, index, b"", end=True))
    return header(fmt, 64, start=start), out


# TCP: the first byte is the size of the pieces the stream arrives in (0: all at once).
for piece, fmt, bps in ((0, 0, 2), (7, 1, 4), (1, 4, 2), (100, 2, 8)):
    h, frames = stream(fmt, bps)
    write("stream_tcp", f"fmt{fmt}_piece{piece}.bin", bytes([piece]) + h + b"".join(frames))

# UDP: datagrams, each after a length byte (0: a 16-byte request, 255: a 56-byte header).
def datagrams(items):
    out = b""
    for d in items:
        code = 0 if len(d) == 16 else 255 if len(d) == 56 else len(d)
        assert code < 255 or len(d) == 56
        out += bytes([code]) + d
    return out

h, frames = stream(lost=(1,))
write("stream_udp", "lost_frame.bin", datagrams([request(), h] + frames))
h, frames = stream(frames=4)
write("stream_udp", "reordered_duplicated.bin", datagrams([h, frames[1], frames[0], frames[0], frames[3], frames[2], frames[4]]))
h, frames = stream(start=1000)
write("stream_udp", "resumed_session.bin", datagrams([h] + frames[:2] + [request(1064, True), header(0, 64, start=0)] + frames))

# Sample converter: three selector bytes (kind, packed layout a, b; bit 7 of b: inverted
# spectrum), then samples.
for kind in range(5):
    write("sample_converter", f"kind{kind}.bin", bytes([kind, 0, 0]) + noise(96))
for a, b in ((0x00, 0x00), (0x05, 0x05), (0x1e, 0x15), (0x2a, 0x92), (0x0c, 0x08)):
    write("sample_converter", f"packed_{a:02x}_{b:02x}.bin", bytes([5, a, b]) + noise(96))
