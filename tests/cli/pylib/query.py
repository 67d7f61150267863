"""Values of the JSON products for the shell tests (tests/cli/lib/harness.sh).

  python3 -m query get FILE PATH [--integer]     prints the value (JSON for containers)
  python3 -m query check FILE PATH OP VALUE      prints "PATH = value" and exits 1 unless
                                                 `value OP VALUE` holds
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


def check(args):
    value = lookup(products.read_json(args.file), args.path, args.file)
    expected = literal(args.value)
    try:
        holds = COMPARISONS[args.op](value, expected)
    except TypeError:  # a null or a string where a number was expected fails the check
        holds = False
    if args.op == "lacks" and isinstance(value, dict):  # the keys, not a whole document
        value = sorted(value)
    print(f"{args.path} = {shown(value)}" + ("" if holds else f", expected {args.op} {shown(expected)}"))
    return 0 if holds else 1


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
    p = sub.add_parser("check")
    p.add_argument("file")
    p.add_argument("path")
    p.add_argument("op", choices=sorted(COMPARISONS))
    p.add_argument("value")
    p.set_defaults(run=check)
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
