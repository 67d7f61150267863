"""Edits of the walk's recordings (data/walk_0827) for the fuse tests, made at test time:

  python3 -m walk_edit obs-time-system WALK_OBS OUT SYSTEM SHIFT_S
      every epoch tag moved by SHIFT_S and TIME OF FIRST/LAST OBS in SYSTEM (a file whose
      tags are in BDT is the walk's moved by -14 s)
  python3 -m walk_edit obs-header-record WALK_OBS OUT 'CONTENT' 'LABEL'
      one more header record before END OF HEADER
  python3 -m walk_edit obs-new-types WALK_OBS OUT EPOCH
      after epoch EPOCH (0-based) an event (flag 4) with a new GPS type list, the first two
      types swapped, and every later GPS record written in that order
  python3 -m walk_edit obs-repeat-epoch WALK_OBS OUT EPOCH
      epoch EPOCH written twice
  python3 -m walk_edit obs-without WALK_OBS OUT SYSTEM
      every record of SYSTEM (a letter) dropped, the epochs' counts to match
  python3 -m walk_edit imu-drop-rows IMU OUT FIRST LAST
      the log without its lines FIRST to LAST (1-based; LAST 0: to the end)
  python3 -m walk_edit imu-swap-rows IMU OUT LINE
      lines LINE and LINE + 1 swapped
  python3 -m walk_edit imu-repeat-row IMU OUT LINE
      line LINE written twice
  python3 -m walk_edit pos-shift-days POS OUT DAYS
      an RTKLIB .pos file's dates moved by DAYS

Each edit fails, naming the file, where the file is not laid out as the walk's is (so that
a changed recording cannot turn a test into one of nothing).
"""
import datetime
import sys

EPOCH_PREFIX = "> "
HEADER_END = "END OF HEADER"
# RINEX 3 epoch line: "> yyyy mm dd hh mm" then the seconds as F11.7 (columns 19-29), then
# the flag (column 32) and the number of satellites (columns 33-35).
SECONDS_AT, SECONDS_WIDTH = 18, 11
TENTH_MICROSECONDS = 10_000_000


def read_lines(path):
    with open(path) as f:
        return f.readlines()


def write_lines(path, lines):
    with open(path, "w") as f:
        f.writelines(lines)


def fail(path, what):
    sys.exit(f"walk_edit: {path}: {what}")


def header_end(lines, path):
    for i, line in enumerate(lines):
        if line[60:].strip() == HEADER_END:
            return i
    fail(path, "no END OF HEADER")


def epochs(lines, path):
    """(start, end) line indices of each epoch block (the epoch line and its records)."""
    starts = [i for i, line in enumerate(lines) if line.startswith(EPOCH_PREFIX)]
    if not starts:
        fail(path, "no epoch lines")
    for i in starts:
        count = int(lines[i][32:35])
        if i + count + 1 != len(lines) and not lines[i + count + 1].startswith(EPOCH_PREFIX):
            fail(path, f"line {i + 1}: {count} records do not end at an epoch line")
    return [(i, i + int(lines[i][32:35]) + 1) for i in starts]


def header_record(content, label):
    return f"{content:<60}{label:<20}\n"


def moved_epoch_line(line, shift_s):
    fields = line[2:SECONDS_AT].split()
    seconds = line[SECONDS_AT:SECONDS_AT + SECONDS_WIDTH]
    whole, _, fraction = seconds.strip().partition(".")
    units = int(whole) * TENTH_MICROSECONDS + int(fraction.ljust(7, "0"))
    t = datetime.datetime(*(int(x) for x in fields)) + datetime.timedelta(
        microseconds=(units + round(shift_s * TENTH_MICROSECONDS)) / 10)
    sec_units = (t.second * 1_000_000 + t.microsecond) * 10
    return (f"> {t.year:04d} {t.month:02d} {t.day:02d} {t.hour:02d} {t.minute:02d}"
            f" {sec_units // TENTH_MICROSECONDS:2d}.{sec_units % TENTH_MICROSECONDS:07d}"
            + line[SECONDS_AT + SECONDS_WIDTH:])


def obs_time_system(path, out, system, shift_s):
    lines = read_lines(path)
    end = header_end(lines, path)
    found = 0
    for i in range(end):
        if lines[i][60:].strip() in ("TIME OF FIRST OBS", "TIME OF LAST OBS"):
            lines[i] = lines[i][:48] + f"{system:<3}" + lines[i][51:]
            found += 1
    if found != 2:
        fail(path, f"{found} TIME OF FIRST/LAST OBS records, expected 2")
    for start, _ in epochs(lines, path):
        lines[start] = moved_epoch_line(lines[start], float(shift_s))
    write_lines(out, lines)


def obs_header_record(path, out, content, label):
    lines = read_lines(path)
    end = header_end(lines, path)
    write_lines(out, lines[:end] + [header_record(content, label)] + lines[end:])


def obs_new_types(path, out, epoch):
    lines = read_lines(path)
    end = header_end(lines, path)
    gps = [i for i in range(end) if lines[i].startswith("G") and lines[i][60:].strip() == "SYS / # / OBS TYPES"]
    if len(gps) != 1:
        fail(path, f"{len(gps)} GPS SYS / # / OBS TYPES lines, expected 1")
    types = lines[gps[0]][7:60].split()
    if len(types) < 2 or types[0] != "C1C":
        fail(path, f"GPS types {types}: expected C1C first")
    types[0], types[1] = types[1], types[0]
    blocks = epochs(lines, path)
    after = blocks[int(epoch)][1]
    for i in range(after, len(lines)):
        if lines[i].startswith("G"):
            text = lines[i].rstrip("\n").ljust(3 + 16 * len(types))
            lines[i] = text[:3] + text[19:35] + text[3:19] + text[35:] + "\n"
    event = [f">{'4':>31}{1:3d}\n", header_record(f"G{len(types):5d} " + " ".join(types), "SYS / # / OBS TYPES")]
    write_lines(out, lines[:after] + event + lines[after:])


def obs_repeat_epoch(path, out, epoch):
    lines = read_lines(path)
    start, stop = epochs(lines, path)[int(epoch)]
    write_lines(out, lines[:stop] + lines[start:stop] + lines[stop:])


def obs_without(path, out, system):
    lines = read_lines(path)
    end = header_end(lines, path)
    kept = lines[:end + 1]
    for start, stop in epochs(lines, path):
        records = [r for r in lines[start + 1:stop] if not r.startswith(system)]
        kept.append(lines[start][:32] + f"{len(records):3d}" + lines[start][35:])
        kept.extend(records)
    write_lines(out, kept)


def imu_drop_rows(path, out, first, last):
    lines = read_lines(path)
    first, last = int(first), int(last) or len(lines)
    if not 1 < first <= last <= len(lines):
        fail(path, f"lines {first} to {last} are not inside its {len(lines)} lines")
    write_lines(out, lines[:first - 1] + lines[last:])


def imu_swap_rows(path, out, line):
    lines = read_lines(path)
    i = int(line) - 1
    if lines[i].rsplit(",", 1)[-1] == lines[i + 1].rsplit(",", 1)[-1]:
        fail(path, f"lines {line} and {i + 2} have one time: swapping them changes nothing")
    lines[i], lines[i + 1] = lines[i + 1], lines[i]
    write_lines(out, lines)


def imu_repeat_row(path, out, line):
    lines = read_lines(path)
    i = int(line) - 1
    write_lines(out, lines[:i + 1] + [lines[i]] + lines[i + 1:])


def pos_shift_days(path, out, days):
    lines = read_lines(path)
    moved = 0
    for i, line in enumerate(lines):
        if line.startswith("%") or not line.strip():
            continue
        date = datetime.date(*(int(x) for x in line[:10].split("/"))) + datetime.timedelta(days=int(days))
        lines[i] = date.strftime("%Y/%m/%d") + line[10:]
        moved += 1
    if moved == 0:
        fail(path, "no solution lines")
    write_lines(out, lines)


EDITS = {
    "obs-time-system": obs_time_system,
    "obs-header-record": obs_header_record,
    "obs-new-types": obs_new_types,
    "obs-repeat-epoch": obs_repeat_epoch,
    "obs-without": obs_without,
    "imu-drop-rows": imu_drop_rows,
    "imu-swap-rows": imu_swap_rows,
    "imu-repeat-row": imu_repeat_row,
    "pos-shift-days": pos_shift_days,
}


def main():
    if len(sys.argv) < 4 or sys.argv[1] not in EDITS:
        sys.exit(__doc__)
    EDITS[sys.argv[1]](*sys.argv[2:])


if __name__ == "__main__":
    main()
