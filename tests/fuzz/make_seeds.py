#!/usr/bin/env python3
"""Writes the generated seeds of the harnesses into corpus/<harness>/ (tests/fuzz/seeds.txt
lists those taken from data/):
- the stream and sample-converter harnesses (stream_tcp, stream_udp, sample_converter): valid
  streams in the layouts of docs/streaming.md, "Protocol", tables, so that fuzzing starts from
  inputs that reach the frame checks;
- IMU logs that fall short (imu_csv, imu_log): gaps, a log cut mid-line, time going back (a
  reset or rows out of order), rows and times repeated;
- RINEX observation files with event records (rinex_obs): flag 4 with header records (new type
  lists, scale factors), flags 2, 3 and 5 with theirs, cycle slip records, an epoch written
  twice, time systems other than GPS;
- the text readers (run_config, scenario, imu_grades, if_metadata): the shapes that once
  crashed, hung or fooled them, built on the project's own files: nesting far deeper than any
  real file's, YAML aliases that multiply or contain themselves, integers past 32 and 64 bits,
  UTF-16 text and NUL bytes.
Run from anywhere: python3 tests/fuzz/make_seeds.py"""
import os
import random
import re
import struct

here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
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


# IMU logs. The walk's layout (ax, ay, az in g; gx, gy, gz in deg/s; a millisecond tick) and
# KF-GINS increments (time, angle and velocity increments) for imu_log; our CSV for imu_csv.
def write_text(harness, name, text):
    write(harness, name, text.encode())


def walk_rows(ticks):
    return "".join(f"{0.01 * (k % 7):.3f},-0.007,1.011,{0.5 * k:.3f},-0.160,0.160,{t}\n"
                   for k, t in enumerate(ticks))


ticks = list(range(3326339, 3326339 + 6 * 40, 6))
cut_first_line = "0.007,1.011,0.038,-0.160\n"
write_text("imu_log", "walk_gap.csv", cut_first_line + walk_rows(ticks[:20] + [t + 400 for t in ticks[20:]]))
write_text("imu_log", "walk_end_cut.csv", walk_rows(ticks) + "-0.017,-0.007,1.0")
write_text("imu_log", "walk_reset.csv", walk_rows(ticks[:20] + [t - 100000 for t in ticks[20:]]))
write_text("imu_log", "walk_swapped.csv", walk_rows(ticks[:10] + [ticks[11], ticks[10]] + ticks[12:]))
repeated = walk_rows(ticks[:10])
write_text("imu_log", "walk_repeats.csv", repeated + repeated.splitlines(True)[-1] +
           walk_rows([ticks[9]]) + walk_rows(ticks[10:]))
write_text("imu_log", "kfgins_gap.txt", "".join(
    f"{456300.0 + 0.005 * k + (1.0 if k >= 30 else 0.0):.3f} 1e-4 2e-4 3e-4 0.01 0.02 -0.049\n" for k in range(60)))
deepnav_header = "# sample_rate_hz=100\nt_s,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,dv_z_mps\n"
increments = [f"{0.01 * k:.2f},1e-5,0,0,0,0,-0.0980665\n" for k in range(1, 60)]
write_text("imu_csv", "gap.csv", deepnav_header + "".join(increments[:20] + increments[40:]))
write_text("imu_csv", "reset.csv", deepnav_header + "".join(increments[:30] + increments[5:20]))
write_text("imu_csv", "end_cut.csv", deepnav_header + "".join(increments) + "0.60,1e-5,0,")


# RINEX observation files with events.
def rinex_record(content, label):
    return f"{content:<60}{label:<20}\n"


def field(value, lli=" "):
    return f"{value:14.3f}{lli} "


def epoch3(sec, count, flag=0):
    return f"> 2025 08 28 17 30 {sec:10.7f}  {flag}{count:3d}\n"


def gps3(prn, pr, phase, doppler, cn0, lli=" "):
    return f"G{prn:02d}" + field(pr) + field(phase, lli) + field(doppler) + field(cn0) + "\n"


v3 = rinex_record(f"{'3.04':>9}{'':11}{'OBSERVATION DATA':<20}{'M: Mixed':<20}", "RINEX VERSION / TYPE")
v3 += rinex_record(" -1276965.2487 -4717231.7278  4087230.1460", "APPROX POSITION XYZ")
v3 += rinex_record("G    4 C1C L1C D1C S1C", "SYS / # / OBS TYPES")
v3 += rinex_record("E    4 C1C L1C D1C S1C", "SYS / # / OBS TYPES")
v3 += rinex_record("  2025    08    28    17    30   10.0000000     BDT", "TIME OF FIRST OBS")
v3 += rinex_record("     0.100", "INTERVAL")
v3 += rinex_record("", "END OF HEADER")
body = epoch3(10.0, 2) + gps3(1, 2.1e7, 1.1e8, 1000.0, 45.0) + gps3(2, 2.2e7, 1.2e8, -500.0, 40.0)
body += epoch3(10.0, 2) + gps3(1, 2.1e7, 1.1e8, 1000.0, 45.0) + gps3(2, 2.2e7, 1.2e8, -500.0, 40.0)
body += epoch3(10.25, 4, 4) + rinex_record("G    4 L1C C1C S1C D1C", "SYS / # / OBS TYPES")
body += rinex_record("G   10   1 D1C", "SYS / SCALE FACTOR") + rinex_record("G  100", "SYS / SCALE FACTOR")
body += rinex_record("new GPS types from here", "COMMENT")
body += "G01" + field(1.1e8 + 1300.0) + field(2.1e7 - 250.0) + field(45.0) + field(10000.0) + "\n"
body += epoch3(10.5, 1, 2) + rinex_record("the antenna moves", "COMMENT")
body += epoch3(10.5, 2, 3) + rinex_record("SITE 2", "MARKER NAME") + rinex_record(
    " -1276960.0000 -4717230.0000  4087231.0000", "APPROX POSITION XYZ")
body += epoch3(10.6, 0, 5)
body += epoch3(10.75, 1, 6) + "G01" + field(0.0) + field(1.1e8 + 2600.0, "1") + "\n"
body += epoch3(11.0, 1, 1) + "G01" + field(1.1e8 + 3900.0) + field(2.1e7 - 750.0) + field(45.0) + field(10000.0) + "\n"
write_text("rinex_obs", "events_v3.obs", v3 + body)

v2 = rinex_record("     2.11           OBSERVATION DATA    M (MIXED)", "RINEX VERSION / TYPE")
v2 += rinex_record("     3    C1    L1    D1", "# / TYPES OF OBSERV")
v2 += rinex_record("  2025     8    28    17    30   40.0000000     GLO", "TIME OF FIRST OBS")
v2 += rinex_record("    18", "LEAP SECONDS")
v2 += rinex_record("", "END OF HEADER")
v2 += " 25  8 28 17 30 40.0000000  0  2G01R03\n" + field(2.1e7) + field(1.1e8) + field(1000.0) + "\n"
v2 += field(2.3e7) + field(1.2e8) + field(-10.0) + "\n"
v2 += "                            4  2\n" + rinex_record("     4    D1    C1    S1    L1", "# / TYPES OF OBSERV")
v2 += rinex_record("D1 first from here", "COMMENT")
v2 += " 25  8 28 17 30 41.0000000  0  1G01\n" + field(1001.0) + field(2.1e7 - 190.0) + field(44.0) + field(1.1e8) + "\n"
v2 += " 25  8 28 17 30 41.0000000  0  1G01\n" + field(1001.0) + field(2.1e7 - 190.0) + field(44.0) + field(1.1e8) + "\n"
write_text("rinex_obs", "events_v2.obs", v2)


# Text readers. YAML: aliases ten times over, six levels (a million nodes, refused at the first
# level past the limit); an alias inside its own node; lists nested deeper than yaml-cpp's
# limit of 2000; a NUL byte.
def alias_bomb(levels, first_key="a0"):
    lines = [f"{first_key}: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    for level in range(1, levels + 1):
        lines.append(f"a{level}: &a{level} [" + ", ".join([f"*a{level - 1}"] * 10) + "]")
    return "\n".join(lines) + "\n"


def deep_list(depth):
    return "[" * depth + "]" * depth


def text_seed(harness, name, text):
    write(harness, name, text.encode("utf-8") if isinstance(text, str) else text)


def utf16(text):
    return b"\xff\xfe" + text.encode("utf-16-le")


for harness in ("run_config", "scenario", "imu_grades"):
    text_seed(harness, "alias_bomb.yaml", alias_bomb(6))
    text_seed(harness, "alias_loop.yaml", "a: &a [1, {b: *a}]\n")
    text_seed(harness, "deep_list.yaml", "a: " + deep_list(2100) + "\n")
    text_seed(harness, "nul.yaml", "a: 1\nb: x\0y\nc: 3\n")
text_seed("run_config", "huge_integers.yaml",
          "channels: 4294967297\nthreads: 18446744073709551616\nfs: 1e400\nskip: -0\n")
text_seed("run_config", "key_twice_normalised.yaml",
          "imu_lever_arm: [1, 2, 3]\nimu-lever-arm: [1, 2, 3]\nfault-exclusion: true\nno-fault-exclusion: true\n")
text_seed("run_config", "aliases.yaml", "input: &f a.bin\nmode: &m scalar\n*f : 1\nimu-lever-arm: &v [1, 2, 3]\n")
with open(os.path.join(root, "data", "scenarios", "static_120s.yaml")) as f:
    scenario = f.read()
text_seed("scenario", "huge_integers.yaml",
          re.sub(r"(?m)^seed:.*$", "seed: 18446744073709551617", scenario) + "max_satellites: 4294967297\n")
text_seed("scenario", "anchored_blocks.yaml", "adc: &adc {bits: 4, agc: true}\n" + scenario.replace("adc:", "x_adc:"))
with open(os.path.join(root, "data", "imu_grades.yaml")) as f:
    grades = f.read()
text_seed("imu_grades", "huge_numbers.yaml", grades.replace("sample_rate_hz: 100", "sample_rate_hz: 18446744073709551617", 1))
text_seed("imu_grades", "anchored_grades.yaml",
          grades.replace("  consumer-mems:", "  consumer-mems: &consumer", 1) + "  copy: *consumer\n")

# Metadata XML, from the project's description of a real capture: nested 100 deep (the reader
# takes 64), numbers past 32 and 64 bits, a cycle count whose bytes overflow, UTF-16, a NUL.
with open(os.path.join(root, "data", "L1_20211202_084700_4MHz_IQ.xml")) as f:
    metadata = f.read()


def metadata_with(old, new):
    assert old in metadata, old
    return metadata.replace(old, new, 1)


text_seed("if_metadata", "deep_100.xml", metadata_with("</metadata>", "<x>" * 100 + "</x>" * 100 + "</metadata>"))
text_seed("if_metadata", "deep_60.xml", metadata_with("</metadata>", "<x>" * 60 + "</x>" * 60 + "</metadata>"))
text_seed("if_metadata", "quantization_2e32.xml",
          metadata_with("<quantization>8</quantization>", "<quantization>4294967304</quantization>"))
text_seed("if_metadata", "countwords_2e61.xml",
          metadata_with("<countwords>2</countwords>", "<countwords>2305843009213693952</countwords>"))
text_seed("if_metadata", "cycles_2e63.xml", metadata_with("<cycles>0</cycles>", "<cycles>9223372036854775808</cycles>"))
text_seed("if_metadata", "header_2e64.xml",
          metadata_with("<sizeheader>0</sizeheader>", "<sizeheader>18446744073709551616</sizeheader>"))
text_seed("if_metadata", "ratefactor_2e32.xml",
          metadata_with("<ratefactor>1</ratefactor>", "<ratefactor>4294967297</ratefactor>"))
text_seed("if_metadata", "freqbase_1hz.xml", metadata_with('<freqbase format="MHz">4.0</freqbase>', "<freqbase>1</freqbase>"))
text_seed("if_metadata", "utf16.xml", utf16(metadata))
text_seed("if_metadata", "nul.xml", metadata_with("<lane", "\0<lane"))
text_seed("if_metadata", "doctype_cdata.xml",
          metadata_with("<metadata ", '<!DOCTYPE metadata [<!ENTITY e "<x>">]>\n<metadata ')
          .replace("<equipment>", "<equipment><![CDATA[<a><b>]]>"))
