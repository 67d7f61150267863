"""cli.aided_troposphere_mismatch and cli.aided_ionosphere_mismatch: IF without one
atmosphere delay, the receiver keeping its default models.

  python3 -m checks.atmosphere_mismatch WORK troposphere|ionosphere

WORK holds the runs loose, tight, ultra and ultra_off (--no-MODEL-mismatch). Tight and
ultra find the mismatch (its fit within the bounds below) and take the state, end no worse
than loose horizontally and well under it vertically; loose finds it but takes no state
(it has no ranges); ultra_off takes none.
"""
import sys
from pathlib import Path

import products
from checklist import CheckList

# The fitted error when the whole of the model's delay is missing: the troposphere model's
# 2.3 m zenith delay, or the ionosphere model scaled by -1.
FIT_BOUNDS = {"troposphere": ("zenith_error_m", -3.0, -1.5), "ionosphere": ("scale_error", -1.3, -0.75)}


def main():
    work, model = Path(sys.argv[1]), sys.argv[2]
    fit_key, fit_low, fit_high = FIT_BOUNDS[model]
    key = f"{model}_mismatch"
    s = {run: products.summary(work / run) for run in ("loose", "tight", "ultra", "ultra_off")}
    h = {run: s[run]["horizontal_error_m"]["rms"] for run in s}
    v = {run: s[run]["vertical_error_m"]["rms"] for run in s}
    print(" ".join(f"{run}: h {h[run]:.2f} v {v[run]:.2f}" for run in s))
    checks = CheckList()
    for mode in ("tight", "ultra"):
        found = s[mode].get(key)
        checks.check(f"{mode}: {key} with {fit_key} in ({fit_low}, {fit_high}) and the state taken",
                     bool(found) and fit_low < found[fit_key] < fit_high and found["state_from_s"] is not None, found)
        checks.check(f"{mode}: horizontal RMS no more than loose's {h['loose']:.2f} m", h[mode] <= h["loose"],
                     f"{h[mode]:.2f} m")
        checks.check(f"{mode}: vertical RMS within 0.6 of loose's {v['loose']:.2f} m", v[mode] <= 0.6 * v["loose"],
                     f"{v[mode]:.2f} m")
    found = s["loose"].get(key)
    checks.check(f"loose: {key} found, no state (loose has no ranges)", bool(found) and found["state_from_s"] is None,
                 found)
    checks.check(f"--no-{model}-mismatch: no state taken", key not in s["ultra_off"])
    checks.exit()


if __name__ == "__main__":
    main()
