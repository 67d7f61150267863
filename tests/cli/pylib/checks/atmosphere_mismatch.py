"""cli.aided_troposphere_mismatch, cli.aided_ionosphere_mismatch and
cli.aided_atmosphere_mismatch: IF without one atmosphere delay or without both, the
receiver keeping its default models.

  python3 -m checks.atmosphere_mismatch WORK troposphere|ionosphere|atmosphere

WORK holds the simulation (sim) and the runs loose, tight, ultra and ultra_off (the
watches off). Tight and ultra find each missing delay (the fit within the bounds below) and
take its state from the fit (summary: the room given to the height, the state's estimate
at the end), end no worse than loose horizontally and well under it vertically, and from
10 s after the last detection their height is within 1 m RMS; loose finds it but takes no
state (it has no ranges); ultra_off takes none.
"""
import math
import sys
from pathlib import Path

import products
from checklist import CheckList

# The fitted error when the whole of the model's delay is missing: the troposphere model's
# 2.3 m zenith delay, or the ionosphere model scaled by -1. With both missing the zenith fit
# also takes the part of the ionosphere's delay that looks like troposphere.
FIT_BOUNDS = {"troposphere": ("zenith_error_m", -3.0, -1.5), "ionosphere": ("scale_error", -1.3, -0.75)}
BOTH_FIT_BOUNDS = {"troposphere": ("zenith_error_m", -3.6, -2.3), "ionosphere": ("scale_error", -1.6, -0.75)}
SETTLED_BOUND_M = {"troposphere": 1.0, "ionosphere": 1.0, "atmosphere": 3.0}


def settled_vertical_rms_m(sim, run, from_s):
    """The vertical RMS of a run's fixes from `from_s` on, against the simulation's truth."""
    truth = products.truth_by_epoch(sim)
    dh = [float(r["height_m"]) - float(truth[products.epoch_key(r["t_s"])]["height_m"]) for r in products.pvt(run)
          if float(r["t_s"]) >= from_s and products.epoch_key(r["t_s"]) in truth]
    return math.sqrt(sum(d * d for d in dh) / len(dh)) if dh else float("nan")


def check_found(checks, s, mode, model, bounds):
    """The mismatch of `model` found in run `mode` with its fit within `bounds`, the state taken
    from it (the room given to the height, the estimate at the end); returns the finding."""
    fit_key, fit_low, fit_high = bounds[model]
    key = f"{model}_mismatch"
    found = s[mode].get(key)
    checks.check(f"{mode}: {key} with {fit_key} in ({fit_low}, {fit_high}) and the state taken",
                 bool(found) and fit_low < found[fit_key] < fit_high and found["state_from_s"] is not None, found)
    if found:
        checks.check(f"{mode}: {model} state started from the fit, with room for the height and an estimate at the end",
                     found["height_room_m"] is not None and found["height_room_m"] > 1.0
                     and found["state_at_end"] is not None, found)
    return found


def main():
    work, case = Path(sys.argv[1]), sys.argv[2]
    models = ("troposphere", "ionosphere") if case == "atmosphere" else (case,)
    bounds = BOTH_FIT_BOUNDS if case == "atmosphere" else FIT_BOUNDS
    s = {run: products.summary(work / run) for run in ("loose", "tight", "ultra", "ultra_off")}
    h = {run: s[run]["horizontal_error_m"]["rms"] for run in s}
    v = {run: s[run]["vertical_error_m"]["rms"] for run in s}
    print(" ".join(f"{run}: h {h[run]:.2f} v {v[run]:.2f}" for run in s))
    checks = CheckList()
    for mode in ("tight", "ultra"):
        found = [check_found(checks, s, mode, model, bounds) for model in models]
        if all(found):
            # From 10 s after the last state was taken the height is back: within 1 m with one
            # delay missing; with both, the ionosphere fitted beside the troposphere is the less
            # sure (results/mismatch: 1.8-4.0 m RMS over 10 runs), still far under loose's.
            settled_from = max(f["found_at_s"] for f in found) + 10.0
            settled = settled_vertical_rms_m(work / "sim", work / mode, settled_from)
            bound_m = SETTLED_BOUND_M[case]
            checks.check(f"{mode}: vertical RMS from 10 s after the detection within {bound_m} m", settled <= bound_m,
                         f"{settled:.2f} m")
        checks.check(f"{mode}: horizontal RMS no more than loose's {h['loose']:.2f} m", h[mode] <= h["loose"],
                     f"{h[mode]:.2f} m")
        checks.check(f"{mode}: vertical RMS within 0.6 of loose's {v['loose']:.2f} m", v[mode] <= 0.6 * v["loose"],
                     f"{v[mode]:.2f} m")
    for model in models:
        key = f"{model}_mismatch"
        found = s["loose"].get(key)
        checks.check(f"loose: {key} found, no state (loose has no ranges)",
                     bool(found) and found["state_from_s"] is None, found)
        checks.check(f"watch off: no {model} state taken", key not in s["ultra_off"])
    checks.exit()


if __name__ == "__main__":
    main()
