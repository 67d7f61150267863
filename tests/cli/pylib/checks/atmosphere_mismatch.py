"""cli.aided_troposphere_mismatch and cli.aided_ionosphere_mismatch: IF without one
atmosphere delay, the receiver keeping its default models.

  python3 -m checks.atmosphere_mismatch WORK troposphere|ionosphere

WORK holds the simulation (sim) and the runs loose, tight, ultra and ultra_off
(--no-MODEL-mismatch). Tight and ultra find the mismatch (its fit within the bounds below)
and take the state from the fit (summary: the room given to the height, the state's
estimate at the end), end no worse than loose horizontally and well under it vertically,
and from 10 s after the detection their height is within 1 m RMS; loose finds it but takes
no state (it has no ranges); ultra_off takes none.
"""
import math
import sys
from pathlib import Path

import products
from checklist import CheckList

# The fitted error when the whole of the model's delay is missing: the troposphere model's
# 2.3 m zenith delay, or the ionosphere model scaled by -1.
FIT_BOUNDS = {"troposphere": ("zenith_error_m", -3.0, -1.5), "ionosphere": ("scale_error", -1.3, -0.75)}


def settled_vertical_rms_m(sim, run, from_s):
    """The vertical RMS of a run's fixes from `from_s` on, against the simulation's truth."""
    truth = products.truth_by_epoch(sim)
    dh = [float(r["height_m"]) - float(truth[products.epoch_key(r["t_s"])]["height_m"]) for r in products.pvt(run)
          if float(r["t_s"]) >= from_s and products.epoch_key(r["t_s"]) in truth]
    return math.sqrt(sum(d * d for d in dh) / len(dh)) if dh else float("nan")


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
        if found:
            checks.check(f"{mode}: the state started from the fit, with room for the height and an estimate at the end",
                         found["height_room_m"] is not None and found["height_room_m"] > 1.0
                         and found["state_at_end"] is not None, found)
            settled = settled_vertical_rms_m(work / "sim", work / mode, found["found_at_s"] + 10.0)
            checks.check(f"{mode}: vertical RMS from 10 s after the detection within 1 m", settled <= 1.0,
                         f"{settled:.2f} m")
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
