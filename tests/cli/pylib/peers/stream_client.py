#!/usr/bin/env python3
"""A client of `deepnav serve` that waits for the end-of-stream frame.

usage: stream_client.py tcp|udp PORT READY_FILE

Subscribes, reads the header and two frames, creates READY_FILE, then reads until the
end-of-stream frame (prints "end of stream", exits 0) or until the connection drops or 10 s
of silence (prints what happened, exits 1).
"""
import socket
import struct
import sys
import time

kind, port, ready = sys.argv[1], int(sys.argv[2]), sys.argv[3]
request = b"DNRQ" + struct.pack("<HHq", 1, 0, 0)
frames = 0


def frame_seen(header):
    """Counts a data frame (and signals READY_FILE at the second); exits at end of stream.
    Returns the payload's length."""
    global frames
    assert header[:4] == b"DNFR", header[:4]
    length, _sequence, _first_sample, flags = struct.unpack("<IQqI", header[4:28])
    if flags & 1:
        print(f"{kind}: end of stream after {frames} frames")
        sys.exit(0)
    frames += 1
    if frames == 2:
        open(ready, "w").close()
    return length


def read_tcp():
    s = socket.create_connection(("127.0.0.1", port), timeout=10)
    s.sendall(request)

    def exact(n):
        data = b""
        while len(data) < n:
            part = s.recv(n - len(data))
            if not part:
                print(f"{kind}: connection closed without an end-of-stream frame after {frames} frames")
                sys.exit(1)
            data += part
        return data

    assert exact(56)[:4] == b"DNIF"
    while True:
        exact(frame_seen(exact(28)))


def read_udp():
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.settimeout(0.5)
    last_request, silent_since = 0.0, time.time()
    while time.time() - silent_since < 10:
        if time.time() - last_request > 1:  # subscribe, then keep alive
            s.sendto(request, ("127.0.0.1", port))
            last_request = time.time()
        try:
            d = s.recv(65536)
        except socket.timeout:
            continue
        silent_since = time.time()
        if d[:4] == b"DNFR":
            frame_seen(d[:28])
    print(f"{kind}: no end-of-stream frame after {frames} frames (10 s of silence)")
    sys.exit(1)


if kind == "tcp":
    read_tcp()
else:
    read_udp()
