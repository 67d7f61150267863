"""Values of the JSON products for the shell tests (tests/cli/lib/harness.sh).

  python3 -m query get FILE PATH [--integer]     prints the value (JSON for containers)
  python3 -m query check-each FILE NAME PATH OP VALUE [NAME PATH OP VALUE]...
                                                 prints "ok|FAIL NAME: PATH = value" for each
                                                 group of four; exits 1 unless `value OP
                                                 VALUE` held in all
  python3 -m query same A B [--ignore KEY...]    exits 1 unless the two JSON files are
                                                 equal without those top-level keys
  python3 -m query imu SCENARIO_YAML             prints "grade x y z" of a simulation's IMU
  python3 -m query source SIM_DIR                prints the receiver's options for a
                                                 simulation's IF file, one a line

PATH: keys and list indices joined by dots (stream.gaps.0.missing_samples), "." for the
whole document, or len(PATH) for the length of a list, map or string. OP: == != < <= > >=,
contains (VALUE is in the string, list or map's keys) or lacks (it is not). VALUE: JSON
(3, 2.5, true, null, "text", [[5, 7]]), else taken as a string.
"""
import argparse
import json
import operator
import sys

import products

COMPARISONS = {"==": operator.eq, "!=": operator.ne, "<": operator.lt, "<=": operator.le, ">": operator.gt,
               ">=": operator.ge, "contains": operator.contains, "lacks": lambda a, b: b not in a}


def lookup(doc, path, file):
    wants_length = path.startswith("len(") and path.endswith(")")
    keys = path[4:-1] if wants_length else path
    value = doc
    for key in [] if keys == "." else keys.split("."):
        if isinstance(value, list) and key.lstrip("-").isdigit():
            index = int(key)
            if not -len(value) <= index < len(value):
                raise LookupError(f"{file}: {keys}: index {index} beyond a list of {len(value)}")
            value = value[index]
        elif isinstance(value, dict) and key in value:
            value = value[key]
        else:
            raise LookupError(f"{file}: no '{key}' in {keys} (have: {list(value) if isinstance(value, dict) else value})")
    return len(value) if wants_length else value


def literal(text):
    try:
        return json.loads(text)
    except json.JSONDecodeError:
        return text


def shown(value):
    return value if isinstance(value, str) else json.dumps(value)


def get(args):
    value = lookup(products.read_json(args.file), args.path, args.file)
    if args.integer:
        if not isinstance(value, (int, float)) or value != int(value):
            raise ValueError(f"{args.file}: {args.path} = {value}, expected a whole number")
        value = int(value)
    print(shown(value))
    return 0


def judge(doc, file, path, op, value_text):
    """(holds, "PATH = value[, expected OP VALUE]") of one check on a read document."""
    value = lookup(doc, path, file)
    expected = literal(value_text)
    try:
        holds = COMPARISONS[op](value, expected)
    except TypeError:  # a null or a string where a number was expected fails the check
        holds = False
    if op == "lacks" and isinstance(value, dict):  # the keys, not a whole document
        value = sorted(value)
    return holds, f"{path} = {shown(value)}" + ("" if holds else f", expected {op} {shown(expected)}")


def check_each(args):
    """Several named checks on one file: an ok or FAIL line each; the exit status is 0
    only when all held."""
    if len(args.checks) % 4:
        raise ValueError(f"check-each: {len(args.checks)} arguments, expected NAME PATH OP VALUE groups of 4")
    try:
        doc, error = products.read_json(args.file), None
    except (OSError, ValueError) as e:
        doc, error = None, str(e)
    failed = 0
    for i in range(0, len(args.checks), 4):
        name, path, op, value_text = args.checks[i:i + 4]
        if op not in COMPARISONS:
            raise ValueError(f"check-each: '{op}' is not one of {sorted(COMPARISONS)}")
        try:
            holds, text = (False, error) if error else judge(doc, args.file, path, op, value_text)
        except LookupError as e:
            holds, text = False, str(e)
        print(("ok   " if holds else "FAIL ") + f"{name}: {text}")
        failed += not holds
    return 1 if failed else 0


def same(args):
    a, b = products.read_json(args.a), products.read_json(args.b)
    for doc in (a, b):
        for key in args.ignore:
            doc.pop(key, None)
    if a == b:
        return 0
    differing = sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k))
    print(f"{args.a} and {args.b} differ in {differing}")
    return 1


def imu(args):
    grade, lever_arm_m = products.scenario_imu(args.scenario)
    print(grade, *lever_arm_m)
    return 0


def source(args):
    s = products.synthesis(args.sim_dir)
    rate = s["sample_rate_hz"]
    if rate != int(rate):
        raise ValueError(f"{args.sim_dir}/synthesis.json: sample_rate_hz {rate}, expected a whole number")
    print("\n".join(["--input", f"{args.sim_dir}/{s['if_file']}", "--format", s["format"], "--fs", str(int(rate)),
                     "--week", str(s["start_gps_week"])]))
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("get")
    p.add_argument("file")
    p.add_argument("path")
    p.add_argument("--integer", action="store_true", help="print a whole number without a decimal point")
    p.set_defaults(run=get)
    p = sub.add_parser("check-each")
    p.add_argument("file")
    p.add_argument("checks", nargs="+", help="NAME PATH OP VALUE, repeated")
    p.set_defaults(run=check_each)
    p = sub.add_parser("same")
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("--ignore", nargs="*", default=[], help="top-level keys left out of the comparison")
    p.set_defaults(run=same)
    p = sub.add_parser("imu")
    p.add_argument("scenario")
    p.set_defaults(run=imu)
    p = sub.add_parser("source")
    p.add_argument("sim_dir")
    p.set_defaults(run=source)
    args = parser.parse_args()
    try:
        return args.run(args)
    except (OSError, LookupError, ValueError) as e:
        print(e)
        return 2


if __name__ == "__main__":
    sys.exit(main())
