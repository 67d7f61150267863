# Sourced by the CLI tests: same_product A B compares two runs' copies of one product byte
# for byte, except summary.json, whose `resources` block (peak memory, CPU seconds) is what
# the machine did, not what the receiver computed.
same_product() {
  if [[ $(basename "$1") == summary.json ]]; then
    python3 - "$1" "$2" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
for s in (a, b):
    s.pop("resources", None)
sys.exit(0 if a == b else 1)
PY
  else
    cmp -s "$1" "$2"
  fi
}
