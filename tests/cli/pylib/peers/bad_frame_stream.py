#!/usr/bin/env python3
"""Framed streams whose frames lie beyond what the stream's header allows, for the receiver.

usage: bad_frame_stream.py udp MODE PORT       sends to a receiver listening on PORT
       bad_frame_stream.py tcp MODE PORT_FILE  serves one client (its port written to PORT_FILE)
       bad_frame_stream.py free-udp-port       prints a UDP port free on loopback now

The stream: 2 s of noise at 4.092 Msps in 8192-byte ibyte frames. MODE seqjump: one extra
frame numbered 2^63 after frame 200; idxjump: frames from 200 on have index + 1e15.
"""
import os
import random
import socket
import struct
import sys
import time

SAMPLE_RATE_HZ = 4092000.0
FRAME_BYTES = 8192
SAMPLES_PER_FRAME = FRAME_BYTES // 2


def header(max_payload):
    return b"DNIF" + struct.pack("<HHBBHIddqiId", 1, 56, 0, 0, 0, max_payload, SAMPLE_RATE_HZ, 0.0, 0, 0, 0, 0.0)


def frame(sequence, first_sample, payload, flags=0):
    return b"DNFR" + struct.pack("<IQqI", len(payload), sequence, first_sample, flags) + payload


def frames(mode):
    rng = random.Random(1)
    payload = bytes(rng.getrandbits(8) for _ in range(FRAME_BYTES))
    out, first_sample = [], 0
    for sequence in range(1000):
        out.append(frame(sequence, first_sample + (10**15 if mode == "idxjump" and sequence >= 200 else 0), payload))
        if mode == "seqjump" and sequence == 200:
            out.append(frame(2**63, 10**6, payload))
        first_sample += SAMPLES_PER_FRAME
    out.append(frame(1000, first_sample, b"", 1))
    return out


def send_udp(mode, port):
    u = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    destination = ("127.0.0.1", port)
    for _ in range(10):  # until the receiver listens
        u.sendto(header(FRAME_BYTES), destination)
        time.sleep(0.1)
    for f in frames(mode):
        try:
            u.sendto(f, destination)
        except ConnectionRefusedError:
            break
        time.sleep(0.0002)


def serve_tcp(mode, port_file):
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    s.listen(1)
    with open(port_file + ".tmp", "w") as f:
        f.write(str(s.getsockname()[1]))
    os.rename(port_file + ".tmp", port_file)
    c, _ = s.accept()
    c.recv(16)
    try:
        c.sendall(header(FRAME_BYTES))
        for f in frames(mode):
            c.sendall(f)
    except (BrokenPipeError, ConnectionResetError):
        pass


def free_udp_port():
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", 0))
    print(s.getsockname()[1])


if sys.argv[1] == "free-udp-port":
    free_udp_port()
elif sys.argv[1] == "udp":
    send_udp(sys.argv[2], int(sys.argv[3]))
else:
    serve_tcp(sys.argv[2], sys.argv[3])
