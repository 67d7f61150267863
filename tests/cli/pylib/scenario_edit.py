"""Writes a variant of a scenario file for a test:

  python3 -m scenario_edit BASE OUT 'key: value'... [--append 'key: value'...]

Each 'key: value' replaces the line of that top-level key in BASE, which must be there and
hold its value on that one line (a misspelt key or a changed base file fails here rather
than leaving the scenario unchanged); --append adds lines for keys BASE does not have.
Comments and every other line are kept as they are.
"""
import argparse
import re
import sys


def edit(lines, replacements, appended, base):
    out = list(lines)
    for setting in replacements:
        key = setting.split(":", 1)[0]
        at = [i for i, line in enumerate(out) if re.match(re.escape(key) + r"\s*:", line)]
        if len(at) != 1:
            raise ValueError(f"{base}: {len(at)} top-level '{key}:' lines, expected one to replace with '{setting}'")
        following = out[at[0] + 1] if at[0] + 1 < len(out) else ""
        if following.startswith((" ", "-")) or out[at[0]].rstrip().endswith(":"):
            raise ValueError(f"{base}: '{key}' spans several lines; only one-line values are replaced")
        out[at[0]] = setting + "\n"
    for setting in appended:
        key = setting.split(":", 1)[0]
        if any(re.match(re.escape(key) + r"\s*:", line) for line in out):
            raise ValueError(f"{base}: '{key}' is there already; replace it instead of appending '{setting}'")
        out.append(setting + "\n")
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("base")
    parser.add_argument("out")
    parser.add_argument("settings", nargs="*", help="'key: value' replacing that top-level key's line")
    parser.add_argument("--append", nargs="+", default=[], help="'key: value' lines to add")
    args = parser.parse_args()
    with open(args.base) as f:
        lines = f.readlines()
    if lines and not lines[-1].endswith("\n"):
        lines[-1] += "\n"
    try:
        out = edit(lines, args.settings, args.append, args.base)
    except ValueError as e:
        print(e, file=sys.stderr)
        return 1
    with open(args.out, "w") as f:
        f.writelines(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
