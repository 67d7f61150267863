"""Writes an edited copy of a real IF capture for a test:

  python3 -m capture_edit down-quarter-rate IN OUT --ms N

down-quarter-rate: the first N ms of an ibyte capture (interleaved int8 I/Q) moved down in
frequency by a quarter of its sample rate: sample n times (-j)^n, which only swaps and
negates I and Q, so the values stay exact (but -128, which
has no int8 negative). An inverted-spectrum capture at IF 0 (I - jQ of
the sky) becomes what an inverted front end with its IF at +fs/4 would have recorded: the
satellites sit at -fs/4 until the receiver turns the spectrum back over.
"""
import argparse
import sys


def down_quarter_rate(data):
    """(-j)^n on each I/Q pair of int8 bytes: (I, Q), (Q, -I), (-I, -Q), (-Q, I)."""
    i = data[0::2]
    q = data[1::2]
    neg_i = bytes((256 - b) & 0xFF for b in i)
    neg_q = bytes((256 - b) & 0xFF for b in q)
    out = bytearray(len(data))
    phases = ((i, q), (q, neg_i), (neg_i, neg_q), (neg_q, i))
    for phase, (new_i, new_q) in enumerate(phases):
        out[2 * phase::8] = new_i[phase::4]
        out[2 * phase + 1::8] = new_q[phase::4]
    return bytes(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("edit", choices=["down-quarter-rate"])
    parser.add_argument("source")
    parser.add_argument("out")
    parser.add_argument("--fs", type=float, required=True, help="the capture's sample rate (Hz)")
    parser.add_argument("--ms", type=float, required=True, help="milliseconds of the capture to keep")
    args = parser.parse_args()
    samples = int(args.fs * args.ms / 1000) // 4 * 4  # whole turns of (-j)^n
    with open(args.source, "rb") as f:
        data = f.read(2 * samples)
    if len(data) < 2 * samples:
        sys.exit(f"{args.source}: holds {len(data) // 2} samples, fewer than the {samples} of {args.ms} ms")
    with open(args.out, "wb") as f:
        f.write(down_quarter_rate(data))


if __name__ == "__main__":
    main()
