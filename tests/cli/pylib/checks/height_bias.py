"""The mean signed height error of a run's fixes against the simulation's truth (the
summary holds magnitudes only):

  python3 -m checks.height_bias SIM_DIR RUN_DIR LIMIT_M

prints it and exits 1 unless its magnitude is within LIMIT_M (or there are no fixes).
"""
import sys

import products


def main():
    sim, run, limit_m = sys.argv[1], sys.argv[2], float(sys.argv[3])
    truth = products.truth_by_epoch(sim)
    dh = [float(r["height_m"]) - float(truth[products.epoch_key(r["t_s"])]["height_m"]) for r in products.pvt(run)
          if products.epoch_key(r["t_s"]) in truth]
    mean_m = sum(dh) / len(dh) if dh else float("nan")
    print(f"mean height error {mean_m:+.3f} m over {len(dh)} fixes")
    sys.exit(0 if abs(mean_m) <= limit_m else 1)


if __name__ == "__main__":
    main()
