"""cli.receiver_hot_start: a run's fixes against the synthesizer's truth after a hot start.

  python3 -m checks.receiver_hot_start RUN_DIR SIM_DIR --first-fix-by S [--steady-from S]
      [--method M] [--wrong-m M]
      the first fix at or before S seconds, made as M (summary.json's first_fix.method); the
      horizontal RMS of the coarse-time fixes (the first hot_start.fixes ones) within twice
      that of the fixes from --steady-from on (the steady state, after the broadcast time is
      decoded); no fix of the run farther than --wrong-m from the truth (a hot start never
      publishes a wrong fix). Single fixes scatter by a factor of 3-5 about their RMS
      (0.3-1.5 m in the steady state here), so the comparison is of RMS values.
"""
import argparse

import products
from checklist import CheckList
from geodesy import horizontal_m, rms


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("run")
    parser.add_argument("sim")
    parser.add_argument("--first-fix-by", type=float, required=True)
    parser.add_argument("--steady-from", type=float, default=10.0)
    parser.add_argument("--method", default="coarse-time")
    parser.add_argument("--wrong-m", type=float, default=50.0)
    args = parser.parse_args()
    checks = CheckList()
    summary = products.summary(args.run)
    truth = products.truth_by_epoch(args.sim)
    # A fix at the scenario's very end has no truth row: not scored.
    fixes = [r for r in products.pvt(args.run) if r["valid"] == "1" and products.epoch_key(r["t_s"]) in truth]
    checks.check("the run has fixes", bool(fixes), len(fixes))
    if not fixes:
        checks.exit()
    errors = [(float(r["t_s"]), horizontal_m(r, truth[products.epoch_key(r["t_s"])])) for r in fixes]
    first_t, first_error = errors[0]
    checks.check(f"first fix at or before {args.first_fix_by} s", first_t <= args.first_fix_by, first_t)
    checks.check(f"summary's time to first fix {first_t} s", summary["time_to_first_fix_s"] == first_t,
                 summary["time_to_first_fix_s"])
    checks.check(f"first fix made as {args.method}", (summary["first_fix"] or {}).get("method") == args.method,
                 summary["first_fix"])
    steady = [e for t, e in errors if t >= args.steady_from]
    checks.check(f"fixes from {args.steady_from} s on", bool(steady), len(steady))
    coarse = [e for _, e in errors[:(summary.get("hot_start") or {}).get("fixes", 0)]]
    if steady and coarse:
        checks.check(f"coarse-time fixes' horizontal RMS {rms(coarse):.2f} m (first {first_error:.2f} m) within twice "
                     f"the steady RMS {rms(steady):.2f} m", rms(coarse) <= 2.0 * rms(steady), round(rms(coarse), 2))
    worst = max(e for _, e in errors)
    checks.check(f"no fix farther than {args.wrong_m} m", worst <= args.wrong_m, round(worst, 1))
    checks.exit()


if __name__ == "__main__":
    main()
