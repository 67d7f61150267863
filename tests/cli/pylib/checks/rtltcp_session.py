"""cli.rtltcp_session: a run over rtltcp:// against the test server.

  python3 -m checks.rtltcp_session RUN_DIR COMMANDS_FILE DROPPED_SAMPLES SAMPLE_RATE_HZ

The tuning commands as the server received them, the dongle header read, fixes within a
few metres, and the samples the server left out reported as one gap within 20 ms.
"""
import sys

import products
from checklist import CheckList


def main():
    run, commands_file, dropped, rate_hz = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    s = products.summary(run)
    with open(commands_file) as f:
        commands = dict(line.split() for line in f if line.strip())
    st = s["stream"]
    want = {"sample_rate": str(rate_hz), "frequency": "1575420000", "freq_correction": str(2**32 - 3), "gain_mode": "1",
            "gain": "402", "agc_mode": "1", "bias_tee": "1"}
    h = s["horizontal_error_m"]["rms"] if s["fixes"] else float("nan")
    checks = CheckList()
    checks.check("tuning commands as sent", all(commands.get(k) == v for k, v in want.items()), commands)
    checks.check("dongle header read (R820T, 29 gain steps)",
                 st["dongle"]["tuner"] == "R820T" and st["dongle"]["gain_steps"] == 29, st["dongle"])
    checks.check("fixes >= 3", s["fixes"] >= 3, s["fixes"])
    checks.check("horizontal RMS <= 6 m", h <= 6.0, h)
    checks.check("the server dropped samples", dropped > 400000, dropped)
    checks.check("lost samples within 20 ms of those dropped", abs(st["lost_samples"] - dropped) <= 0.020 * rate_hz,
                 f'{st["lost_samples"]} lost in {len(st["gaps"])} gap(s) {st["gaps"]}')
    checks.check("one gap", len(st["gaps"]) == 1, st["gaps"])
    checks.check("the stream ended normally", not st["failed"], st["end"])
    checks.exit()


if __name__ == "__main__":
    main()
