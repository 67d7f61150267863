#!/usr/bin/env python3
"""A seeded, impairing UDP relay for the deepnav stream protocol (loopback tests).

  relay:   sits between a `deepnav run --input udp://...` client and `deepnav serve --udp`.
           It binds a local port (written to --port-file as "udp N"), forwards the client's
           requests to the server and the server's datagrams back to the client, and on the
           way back drops, duplicates or reorders frame datagrams. The stream header and the
           end-of-stream frame always pass untouched, so the client can tell what it lost.
           When the stream ends (or on SIGTERM, or after --idle-timeout s of silence) it
           writes --report, a JSON file of exactly what it did.
  compare: reads a relay report and the client's summary.json and checks that the
           receiver reported exactly what was injected (see expected_stream_report()).

With --rechunk N the stream is raw (`deepnav serve --raw --udp`: bare samples, no header or
frames): the server's datagrams are taken as one byte stream and sent on in datagrams of N
bytes, which end inside a sample when N is not a multiple of the sample size (the tail goes
once the server falls silent). The report then says how many bytes and datagrams went out.

Impairments act on frame sequence numbers: explicit lists (--drop 5,6,7 --duplicate 40
--reorder 90:3) and seeded fractions of the other frames (--drop-fraction 0.01 ...). Each
frame gets at most one impairment. A reordered frame is held back and sent after the next
K frames (its displacement); the frames it is held across pass untouched, so a reorder never
overlaps another impairment and the counts stay exact.

usage: udp_impair.py relay --server HOST:PORT --port-file F --report F [--seed N] [impairments | --rechunk N]
       udp_impair.py compare --report F --summary F [--json F]
Python standard library only.
"""
import argparse
import dataclasses
import json
import os
import random
import signal
import socket
import struct
import sys
import time

HEADER_MAGIC = b"DNIF"
FRAME_MAGIC = b"DNFR"
HEADER_BYTES = 56
FRAME_HEADER_BYTES = 28
FRAME_FLAG_END = 1
# Format code (stream header byte 8) -> bytes per sample: ibyte, ishort, gr_complex, byte, cu8
# (receiver/stream/stream_protocol.cpp, kFormats; signals/sample_format.cpp, bytes_per_sample).
BYTES_PER_SAMPLE = {0: 2, 1: 4, 2: 8, 3: 1, 4: 2}
# UdpSampleSource::kReorderWindow (receiver/stream/udp_sample_source.hpp): a frame still
# missing when a frame this many sequence numbers later arrives is declared lost, so a frame
# held back across at most 63 frames arrives in time.
RECEIVER_REORDER_WINDOW = 64
SOCKET_BUFFER_BYTES = 8 << 20  # best effort (capped by net.core.rmem_max / wmem_max)


def die(message):
    print(f"udp_impair.py: {message}", file=sys.stderr)
    sys.exit(2)


# ------------------------------------------------------------------ protocol


def parse_stream_header(datagram):
    """The fields of a 'DNIF' datagram the relay needs (byte layout: stream_protocol.cpp)."""
    fmt_code, = struct.unpack_from("<B", datagram, 8)
    max_payload, = struct.unpack_from("<I", datagram, 12)
    start, = struct.unpack_from("<q", datagram, 32)
    if fmt_code not in BYTES_PER_SAMPLE:
        raise ValueError(f"stream header: unknown sample format code {fmt_code}")
    return {"format_code": fmt_code, "bytes_per_sample": BYTES_PER_SAMPLE[fmt_code],
            "start_sample_index": start, "max_payload_bytes": max_payload}


def parse_frame_header(datagram):
    """(sequence, first sample index, payload bytes, end of stream) of a 'DNFR' datagram."""
    payload, sequence, first, flags = struct.unpack_from("<IQqI", datagram, 4)
    return sequence, first, payload, bool(flags & FRAME_FLAG_END)


def kind_of(datagram):
    if len(datagram) == HEADER_BYTES and datagram[:4] == HEADER_MAGIC:
        return "header"
    if len(datagram) >= FRAME_HEADER_BYTES and datagram[:4] == FRAME_MAGIC:
        return "frame"
    return "other"


def kernel_udp_receive_buffer_errors():
    """Datagrams the kernel dropped for a full receive buffer (all sockets), or None."""
    try:
        with open("/proc/net/snmp") as f:
            udp = [line.split() for line in f if line.startswith("Udp:")]
        return int(udp[1][udp[0].index("RcvbufErrors")])
    except (OSError, ValueError, IndexError):
        return None


# ------------------------------------------------------------------ impairment plan


def sequence_list(text):
    return {int(s) for s in text.split(",") if s.strip()} if text else set()


def reorder_list(text):
    """'90:3,400' -> {90: 3, 400: 1} (sequence: frames it is held across; default 1)."""
    out = {}
    for item in (text.split(",") if text else []):
        seq, _, depth = item.partition(":")
        out[int(seq)] = int(depth) if depth else 1
        if out[int(seq)] < 1:
            raise ValueError(f"--reorder {item}: the displacement must be at least 1 frame")
    return out


class ImpairmentPlan:
    """Decides, frame by frame in arrival order, what happens to each sequence number.

    Explicit lists win; the other frames draw from a seeded generator, one draw per frame
    that is free to be impaired, so a seed gives the same decisions on every run of the same
    stream. Random reorders skip a frame right after a dropped one: the receiver declares a
    whole run of missing frames lost at once, which would sweep the held frame in with the
    loss and make its fate depend on timing rather than on the plan; for the same reason no
    random drop falls right before an explicit reorder. Nor do random reorders hold a frame
    across an explicitly impaired one (explicit reorders are checked for that up front), and
    they stay within the receiver's tolerance (an explicit --reorder SEQ:K may go beyond it).
    """

    def __init__(self, args):
        self.drop = sequence_list(args.drop)
        self.duplicate = sequence_list(args.duplicate)
        self.reorder = reorder_list(args.reorder)
        overlap = (self.drop & self.duplicate) | (self.drop & self.reorder.keys()) | (self.duplicate & self.reorder.keys())
        if overlap:
            raise ValueError(f"frames {sorted(overlap)} are given more than one impairment")
        self.explicit = self.drop | self.duplicate | self.reorder.keys()
        for seq, depth in self.reorder.items():
            inside = sorted(s for s in self.explicit if seq < s <= seq + depth)
            if inside:  # those frames pass while `seq` is held back: impairments may not overlap
                raise ValueError(f"--reorder {seq}:{depth}: frames {inside} fall while it is held back")
        self.p_drop, self.p_duplicate, self.p_reorder = args.drop_fraction, args.duplicate_fraction, args.reorder_fraction
        if min(self.p_drop, self.p_duplicate, self.p_reorder) < 0 or self.p_drop + self.p_duplicate + self.p_reorder > 1:
            raise ValueError("the fractions must be non-negative and add up to at most 1")
        self.max_depth = args.reorder_depth
        self.rng = random.Random(args.seed)
        self.previous_dropped = False

    def decide(self, sequence, free):
        """('pass' | 'drop' | 'duplicate' | 'reorder', displacement). `free`: no frame is held."""
        action = ("pass", 0)
        if sequence in self.drop:
            action = ("drop", 0)
        elif sequence in self.duplicate:
            action = ("duplicate", 0)
        elif sequence in self.reorder:
            action = ("reorder", self.reorder[sequence])
        elif free and (self.p_drop or self.p_duplicate or self.p_reorder):
            r = self.rng.random()
            depth = self.rng.randint(1, self.max_depth)
            if r < self.p_drop and sequence + 1 not in self.reorder:
                action = ("drop", 0)
            elif r < self.p_drop + self.p_duplicate:
                action = ("duplicate", 0)
            elif (r < self.p_drop + self.p_duplicate + self.p_reorder and not self.previous_dropped
                  and not any(sequence < s <= sequence + depth for s in self.explicit)):
                action = ("reorder", depth)
        self.previous_dropped = action[0] == "drop"
        return action


# ------------------------------------------------------------------ relay


@dataclasses.dataclass
class HeldFrame:
    """A frame held back for reordering: sent once `wanted` later frames have gone out."""
    datagram: bytes
    record: dict
    wanted: int
    sent_after: int = 0


class Relay:
    def __init__(self, args):
        self.args = args
        host, _, port = args.server.rpartition(":")
        self.server = (socket.gethostbyname(host or "127.0.0.1"), int(port))
        self.plan = ImpairmentPlan(args)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        for option in (socket.SO_RCVBUF, socket.SO_SNDBUF):
            self.sock.setsockopt(socket.SOL_SOCKET, option, SOCKET_BUFFER_BYTES)
        self.sock.bind((args.bind, args.port))
        self.sock.settimeout(0.1)
        self.client = None
        self.stream = None
        self.held = None  # a HeldFrame
        self.frames_from_server = 0
        self.log = {"dropped": [], "duplicated": [], "reordered": []}
        self.ended_by = None
        self.raw_pending = b""  # --rechunk: bytes not yet sent on
        self.last_from_server = time.monotonic()
        self.raw_sent = {"bytes": 0, "datagrams": 0}
        self.rcvbuf_errors_at_start = kernel_udp_receive_buffer_errors()
        self.terminated = False

    def port(self):
        return self.sock.getsockname()[1]

    def to_client(self, datagram):
        if self.client is not None:
            self.sock.sendto(datagram, self.client)

    def frame_record(self, sequence, first, payload_bytes):
        samples = payload_bytes // self.stream["bytes_per_sample"] if self.stream else None
        return {"sequence": sequence, "first_sample": first, "samples": samples}

    def release_held(self):
        held, self.held = self.held, None
        self.to_client(held.datagram)
        if held.sent_after > 0:  # held across no frame (the stream ended): not reordered at all
            self.log["reordered"].append({**held.record, "displacement": held.sent_after})

    def handle_frame(self, datagram):
        sequence, first, payload_bytes, end = parse_frame_header(datagram)
        if end:
            if self.held:
                self.release_held()
            self.to_client(datagram)
            self.ended_by = self.ended_by or "end of stream"
            return
        self.frames_from_server += 1
        action, depth = self.plan.decide(sequence, free=self.held is None)
        record = self.frame_record(sequence, first, payload_bytes)
        if action == "drop":
            self.log["dropped"].append(record)
        elif action == "duplicate":
            self.to_client(datagram)
            self.to_client(datagram)
            self.log["duplicated"].append(record)
        elif action == "reorder":
            self.held = HeldFrame(datagram, record, depth)
        else:
            self.to_client(datagram)
            if self.held:
                self.held.sent_after += 1
                if self.held.sent_after >= self.held.wanted:
                    self.release_held()

    def handle(self, datagram, sender):
        if sender != self.server:
            self.client = sender  # the client's requests (subscribe, keep-alive, stop) go through untouched
            self.sock.sendto(datagram, self.server)
            return
        self.last_from_server = time.monotonic()
        if self.args.rechunk:
            self.rechunk(datagram)
            return
        kind = kind_of(datagram)
        if kind == "header":
            self.stream = parse_stream_header(datagram)
        if kind == "frame" and self.stream is not None:
            self.handle_frame(datagram)
        else:
            self.to_client(datagram)

    def rechunk(self, datagram, flush=False):
        """Raw samples on in datagrams of --rechunk bytes (the tail too when `flush`)."""
        self.raw_pending += datagram
        size = self.args.rechunk
        while len(self.raw_pending) >= size or (flush and self.raw_pending):
            piece, self.raw_pending = self.raw_pending[:size], self.raw_pending[size:]
            self.to_client(piece)
            self.raw_sent["bytes"] += len(piece)
            self.raw_sent["datagrams"] += 1

    def run(self):
        signal.signal(signal.SIGTERM, lambda *_: setattr(self, "terminated", True))
        last_datagram = time.monotonic()
        # After the end of the stream, linger briefly: the server repeats its end frame and
        # the client's stop request still has to reach the server.
        while not self.terminated:
            silence = time.monotonic() - last_datagram
            if self.ended_by and silence > self.args.linger:
                break
            if silence > self.args.idle_timeout:
                self.ended_by = f"no datagram for {self.args.idle_timeout} s"
                break
            try:
                datagram, sender = self.sock.recvfrom(65536)
            except socket.timeout:
                # The server paused or ended (the client's keep-alives go on): the tail goes on.
                if self.raw_pending and time.monotonic() - self.last_from_server > 0.2:
                    self.rechunk(b"", flush=True)
                continue
            except ConnectionRefusedError:  # ICMP port unreachable from an earlier send: the peer is gone
                continue
            last_datagram = time.monotonic()
            self.handle(datagram, sender)
        if self.terminated and not self.ended_by:
            self.ended_by = "SIGTERM"

    def report(self):
        errors_now = kernel_udp_receive_buffer_errors()
        return {
            "server": f"{self.server[0]}:{self.server[1]}",
            "seed": self.args.seed,
            "ended_by": self.ended_by,
            "stream": self.stream,
            "frames_from_server": self.frames_from_server,
            "dropped": self.log["dropped"],
            "duplicated": self.log["duplicated"],
            "reordered": self.log["reordered"],
            # Stopped (SIGTERM) while a frame was held back: the client never got it.
            "held_unsent": self.held.record if self.held else None,
            "rechunked": {"datagram_bytes": self.args.rechunk, **self.raw_sent} if self.args.rechunk else None,
            "kernel_udp_rcvbuf_errors": None if errors_now is None or self.rcvbuf_errors_at_start is None
            else errors_now - self.rcvbuf_errors_at_start,
        }


def write_json_atomically(path, data):
    """Readers polling for the file never see it half written."""
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w") as f:
        json.dump(data, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)


def relay_main(args):
    try:
        relay = Relay(args)
    except (ValueError, OSError) as e:
        die(f"cannot start the relay: {e}")
    with open(args.port_file + ".tmp", "w") as f:
        f.write(f"udp {relay.port()}\n")
    os.replace(args.port_file + ".tmp", args.port_file)
    relay.run()
    write_json_atomically(args.report, relay.report())
    return 0


# ------------------------------------------------------------------ compare


def runs(sequences):
    """Sorted sequence numbers -> [[first, last], ...] of consecutive runs."""
    out = []
    for s in sorted(sequences):
        if out and s == out[-1][1] + 1:
            out[-1][1] = s
        else:
            out.append([s, s])
    return out


def expected_stream_report(report, window=RECEIVER_REORDER_WINDOW):
    """What the receiver's summary.json "stream" object must say for what the relay did.

    Dropped frames are lost; a frame held back across fewer than `window` frames is
    reordered (used); one held longer was declared lost before it came and is late. Lost
    frames become gaps: one per run of consecutive lost sequence numbers, at the first
    sample of its first frame, as long as the frames' samples together.
    """
    lost = {d["sequence"]: d for d in report["dropped"]}
    late = [r for r in report["reordered"] if r["displacement"] >= window]
    lost.update({r["sequence"]: r for r in late})
    ranges = runs(lost)
    gaps = [{"first_missing_sample": lost[a]["first_sample"],
             "missing_samples": sum(lost[s]["samples"] for s in range(a, b + 1))} for a, b in ranges]
    return {
        "lost_frame_ranges": ranges,
        "frames_lost": len(lost),
        "gaps": gaps,
        "lost_samples": sum(g["missing_samples"] for g in gaps),
        "frames_duplicated": len(report["duplicated"]),
        "frames_reordered": len(report["reordered"]) - len(late),
        "frames_late": len(late),
        "frames_received": report["frames_from_server"] - len(lost),
        "frames_overrun": 0,
        "end": "end of stream",
        "failed": False,
    }


def compare(report, summary_stream):
    """Rows of (field, expected, reported, equal)."""
    expected = expected_stream_report(report)
    return [(key, want, summary_stream.get(key), summary_stream.get(key) == want) for key, want in expected.items()]


def short(value, width=48):
    text = json.dumps(value) if not isinstance(value, str) else value
    return text if len(text) <= width else text[: width - 3] + "..."


def compare_main(args):
    try:
        with open(args.report) as f:
            report = json.load(f)
        with open(args.summary) as f:
            stream = json.load(f)["stream"]
    except (OSError, ValueError, KeyError) as e:
        die(f"cannot read the relay report or the summary's stream object: {e}")
    rows = compare(report, stream)
    print(f"{'':4} {'field':<18} {'injected (expected)':<48} {'reported':<48}")
    for key, want, got, ok in rows:
        print(f"{'ok' if ok else 'FAIL':<4} {key:<18} {short(want):<48} {short(got):<48}")
        if not ok and isinstance(want, list) and isinstance(got, list):
            # Long lists are cut above: name the entries that differ.
            print(f"     {key}: injected but not reported {[w for w in want if w not in got]}, "
                  f"reported but not injected {[g for g in got if g not in want]}")
    match = all(ok for *_, ok in rows)
    if not match and report.get("kernel_udp_rcvbuf_errors"):
        print(f"note: the kernel dropped {report['kernel_udp_rcvbuf_errors']} UDP datagrams for full receive "
              f"buffers meanwhile (losses nobody injected)")
    if args.json:
        write_json_atomically(args.json, {"match": match, "rows": [
            {"field": k, "expected": w, "reported": g, "equal": ok} for k, w, g, ok in rows]})
    return 0 if match else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    r = sub.add_parser("relay", help="relay and impair a deepnav UDP stream")
    r.add_argument("--server", required=True, help="HOST:PORT of `deepnav serve --udp`")
    r.add_argument("--port-file", required=True, help="written as 'udp N' once the relay listens")
    r.add_argument("--report", required=True, help="JSON of what the relay did, written when it stops")
    r.add_argument("--bind", default="127.0.0.1")
    r.add_argument("--port", type=int, default=0, help="local port (0: any free one)")
    r.add_argument("--seed", type=int, default=1)
    r.add_argument("--drop", default="", help="sequence numbers to drop (comma separated)")
    r.add_argument("--duplicate", default="", help="sequence numbers to send twice")
    r.add_argument("--reorder", default="", help="SEQ[:K],... frames to send after the next K frames (default 1)")
    r.add_argument("--drop-fraction", type=float, default=0.0)
    r.add_argument("--duplicate-fraction", type=float, default=0.0)
    r.add_argument("--reorder-fraction", type=float, default=0.0)
    r.add_argument("--reorder-depth", type=int, default=8, help="random reorders hold a frame across 1..K frames")
    r.add_argument("--idle-timeout", type=float, default=30.0, help="stop after this long without any datagram (s)")
    r.add_argument("--linger", type=float, default=0.5, help="keep relaying this long after the end of stream (s)")
    r.add_argument("--rechunk", type=int, default=0,
                   help="raw stream: send the bytes on in datagrams of N bytes (no impairments)")
    c = sub.add_parser("compare", help="check a receiver's summary.json against a relay report")
    c.add_argument("--report", required=True)
    c.add_argument("--summary", required=True)
    c.add_argument("--json", default="", help="write the comparison here")
    args = ap.parse_args()
    if args.command == "relay" and not 1 <= args.reorder_depth < RECEIVER_REORDER_WINDOW:
        die(f"--reorder-depth {args.reorder_depth}: random reorders hold a frame across 1 to "
            f"{RECEIVER_REORDER_WINDOW - 1} frames (the receiver's tolerance); use --reorder SEQ:K for more")
    return relay_main(args) if args.command == "relay" else compare_main(args)


if __name__ == "__main__":
    sys.exit(main())
