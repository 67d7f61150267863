#!/usr/bin/env python3
"""A small rtl_tcp-protocol server for the tests (loopback only).

Serves a cu8 file as an rtl_tcp server serves a dongle: on a connection it sends the
12-byte dongle header ("RTL0", tuner type, gain steps, big-endian), records the 5-byte
commands the client sends (one line each: command byte and parameter, to --commands), and
streams the file's bytes paced at the sample rate in real time, in buffers as a dongle
delivers them. --drop-at S --drop-seconds D leaves out D seconds of samples at S seconds
(the server keeps its real-time schedule, as rtl_tcp does when it drops buffers), and logs
the samples it left out. One session, then it exits.

The roles of a server that is not a dongle: --pace F sends at F times real time (0.5: a
file replayed at half speed; 0.001 with --buffer-bytes 2000: a trickle of 2000 bytes every
half second), --seconds S serves only the file's first S seconds, --stop-after S closes the
connection after S seconds however much was sent, and --close-after-header sends the dongle
header, takes the tuning commands and closes without a sample.

usage: rtltcp_server.py FILE --rate HZ --port-file F [--commands F] [--drop-at S --drop-seconds D]
                        [--pace F] [--seconds S] [--stop-after S] [--close-after-header]
"""
import argparse
import os
import socket
import struct
import sys
import threading
import time

NAMES = {1: "frequency", 2: "sample_rate", 3: "gain_mode", 4: "gain", 5: "freq_correction", 6: "if_gain",
         7: "test_mode", 8: "agc_mode", 9: "direct_sampling", 10: "offset_tuning", 11: "rtl_xtal",
         12: "tuner_xtal", 13: "gain_by_index", 14: "bias_tee"}


def read_commands(conn, out_path, stop):
    buf = b""
    lines = []
    conn.settimeout(0.2)
    while not stop.is_set():
        try:
            chunk = conn.recv(64)
        except socket.timeout:
            continue
        except OSError:
            break
        if not chunk:
            break
        buf += chunk
        while len(buf) >= 5:
            cmd, param = struct.unpack(">BI", buf[:5])
            buf = buf[5:]
            lines.append(f"{NAMES.get(cmd, hex(cmd))} {param}")
            if out_path:
                with open(out_path, "w") as f:
                    f.write("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("file")
    ap.add_argument("--rate", type=float, required=True, help="samples/s of the file (pacing)")
    ap.add_argument("--port-file", required=True)
    ap.add_argument("--commands", default="")
    ap.add_argument("--drop-at", type=float, default=-1.0)
    ap.add_argument("--drop-seconds", type=float, default=0.0)
    ap.add_argument("--buffer-bytes", type=int, default=32768, help="bytes a dongle buffer (sent at once)")
    ap.add_argument("--tuner", type=int, default=5, help="tuner type (5: R820T)")
    ap.add_argument("--gains", type=int, default=29, help="gain steps")
    ap.add_argument("--pace", type=float, default=1.0, help="multiple of real time the samples are sent at")
    ap.add_argument("--seconds", type=float, default=-1.0, help="serve only the file's first S seconds")
    ap.add_argument("--stop-after", type=float, default=-1.0, help="close after S seconds of sending")
    ap.add_argument("--close-after-header", action="store_true", help="send the dongle header, then close")
    a = ap.parse_args()

    data = open(a.file, "rb").read()
    if a.seconds >= 0:
        data = data[:int(a.seconds * a.rate) * 2]
    srv = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    srv.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    srv.bind(("127.0.0.1", 0))
    srv.listen(1)
    with open(a.port_file + ".tmp", "w") as f:
        f.write(f"{srv.getsockname()[1]}\n")
    os.replace(a.port_file + ".tmp", a.port_file)
    srv.settimeout(30)
    conn, _ = srv.accept()
    conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    conn.sendall(b"RTL0" + struct.pack(">II", a.tuner, a.gains))
    if a.close_after_header:
        conn.settimeout(0.5)
        try:
            conn.recv(4096)  # the tuning commands: the client sends them before reading samples
        except socket.timeout:
            pass
        conn.close()
        print("rtltcp_server: sent the dongle header and closed", file=sys.stderr)
        return
    stop = threading.Event()
    reader = threading.Thread(target=read_commands, args=(conn, a.commands, stop), daemon=True)
    reader.start()

    bytes_per_s = 2.0 * a.rate  # of signal: --drop-at and --drop-seconds are in seconds of signal
    drop_from = int(a.drop_at * bytes_per_s) // a.buffer_bytes * a.buffer_bytes if a.drop_at >= 0 else -1
    drop_to = drop_from + int(round(a.drop_seconds * bytes_per_s / a.buffer_bytes)) * a.buffer_bytes
    t0 = time.monotonic()
    at = 0
    dropped = 0
    try:
        while at < len(data):
            end = min(at + a.buffer_bytes, len(data))
            due = t0 + end / (bytes_per_s * a.pace)  # a buffer leaves once the dongle has filled it
            if 0 <= a.stop_after < due - t0:
                break
            wait = due - time.monotonic()
            if wait > 0:
                time.sleep(wait)
            if drop_from <= at < drop_to:
                dropped += end - at
            else:
                conn.sendall(data[at:end])
            at = end
    except (BrokenPipeError, ConnectionResetError):
        print("rtltcp_server: client went away", file=sys.stderr)
    stop.set()
    try:
        conn.shutdown(socket.SHUT_RDWR)
    except OSError:
        pass
    conn.close()
    reader.join(timeout=1)
    print(f"rtltcp_server: sent {at - dropped} bytes, dropped {dropped // 2} samples at sample {max(drop_from, 0) // 2}",
          file=sys.stderr)


if __name__ == "__main__":
    main()
