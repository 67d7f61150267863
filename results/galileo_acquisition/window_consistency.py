#!/usr/bin/env python3
"""Second check of `deepnav acquire --systems galileo`: the same search on successive,
disjoint 20 ms windows of a capture (--skip). A satellite shows up in window after window at
its Doppler, and its code epoch moves by exactly what that Doppler implies for the code rate:
  delay(t) = delay(0) - t fs f_D / f_E1   (mod the 4 ms code period in samples),
t being a whole number of code periods. A false alarm or a cross-correlation does neither.

  usage: window_consistency.py DEEPNAV METADATA_XML WINDOWS OUT_JSON
(run from the source tree: the metadata files name their data files relative to it)
"""
import json
import subprocess
import sys
import tempfile

F_E1 = 1575.42e6
WINDOW_S = 0.020  # --galileo-noncoherent 5: five 4 ms periods


def main():
    deepnav, metadata, windows, out_path = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
    seen = {}
    fs = None
    with tempfile.TemporaryDirectory() as tmp:
        for w in range(windows):
            path = f"{tmp}/w{w}.json"
            subprocess.run([deepnav, "acquire", "--metadata", metadata, "--systems", "galileo", "--skip",
                            f"{w * WINDOW_S:.3f}", "--json", path], check=False, capture_output=True)
            doc = json.load(open(path))
            fs = doc["sample_rate_hz"]
            for r in doc["results"]:
                if r["detected"]:
                    seen.setdefault(r["satellite"], []).append((w, r["doppler_hz"], r["delay_samples"], r["cn0_dbhz"]))
    period = fs * 4e-3
    report = {"capture": metadata, "windows": windows, "window_s": WINDOW_S, "satellites": {}}
    print(f"{metadata}: {windows} windows of {WINDOW_S * 1e3:g} ms")
    print(f"{'sat':>4} {'windows':>8} {'doppler_hz':>11} {'cn0_dbhz':>9} {'max |delay - predicted| (samples)':>34}")
    for sat in sorted(seen):
        rows = seen[sat]
        w0, f0, d0, _ = rows[0]
        worst = 0.0
        for w, f, d, _ in rows:
            t = (w - w0) * WINDOW_S
            predicted = (d0 - t * fs * f0 / F_E1) % period
            err = abs(d - predicted) % period
            worst = max(worst, min(err, period - err))
        doppler = sum(r[1] for r in rows) / len(rows)
        cn0 = sum(r[3] for r in rows) / len(rows)
        report["satellites"][sat] = {"windows_detected": len(rows), "mean_doppler_hz": round(doppler, 1),
                                     "mean_cn0_dbhz": round(cn0, 1), "max_delay_error_samples": round(worst, 2),
                                     "detections": [{"window": w, "doppler_hz": round(f, 1), "delay_samples": round(d, 2),
                                                     "cn0_dbhz": round(c, 1)} for w, f, d, c in rows]}
        print(f"{sat:>4} {len(rows):>4}/{windows:<3} {doppler:>11.1f} {cn0:>9.1f} {worst:>34.2f}")
    json.dump(report, open(out_path, "w"), indent=1)


if __name__ == "__main__":
    main()
