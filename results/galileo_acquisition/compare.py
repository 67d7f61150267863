#!/usr/bin/env python3
"""Tables of `deepnav acquire --systems galileo` beside GNSS-SDR's positive acquisitions.

  usage: compare.py DEEPNAV_JSON GNSS_SDR_LOG FILTER_DELAY_SAMPLES FILE_SAMPLES GAP_SAMPLE

GNSS-SDR logs a code phase in samples after `sample_stamp`, the first sample of its search;
the code epoch after sample 0 of the capture is then
  (sample_stamp + code phase - filter delay + sample_stamp f_D / f_E1) mod the code period,
the filter delay being the group delay of GNSS-SDR's input filter ((taps - 1) / 2 for its
31-tap Freq_Xlating_Fir_Filter on the real-IF capture, 0 without one) and the last term the
code's drift since sample 0 at the Doppler f_D (1.6 samples for E02 after 73 ms). FILE_SAMPLES: the length of one copy of the capture (the 12 MHz one is
repeated); GAP_SAMPLE: where the capture drops samples (searches after it are not compared;
0 when there is none).
"""
import json
import re
import sys

LINE = re.compile(r"satellite E (\d+), sample_stamp (\d+), test statistics value ([\d.e+-]+), "
                  r"test statistics threshold ([\d.e+-]+), code phase ([\d.e+-]+), doppler (-?[\d.e+-]+)")


def main():
    deepnav_json, log, filter_delay, file_samples, gap = sys.argv[1], sys.argv[2], float(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
    doc = json.load(open(deepnav_json))
    fs = doc["sample_rate_hz"]
    period = round(fs * 4e-3)
    ours = {r["prn"]: r for r in doc["results"] if r["system"] == "galileo" and r["detected"]}
    theirs = {}
    for line in open(log):
        m = LINE.search(line)
        if not m:
            continue
        svid, stamp, stat, thr, cp, doppler = int(m[1]), int(m[2]), float(m[3]), float(m[4]), float(m[5]), float(m[6])
        position = stamp % file_samples
        if gap and position + period > gap:
            continue  # its block spans or follows the capture's gap
        delay = (position + cp - filter_delay + position * doppler / 1575.42e6) % period
        theirs.setdefault(svid, (delay, doppler, stat, thr, stamp))
    print("| SVID | deepnav Doppler (Hz) | deepnav delay (samples) | deepnav code phase (chips) | deepnav C/N0 (dB-Hz) "
          "| GNSS-SDR Doppler (Hz) | GNSS-SDR delay (samples) | GNSS-SDR statistic / threshold | delay difference (samples) "
          "| Doppler difference (Hz) |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for svid in sorted(set(ours) | set(theirs)):
        a, b = ours.get(svid), theirs.get(svid)
        cells = [f"E{svid:02d}"]
        cells += [f"{a['doppler_hz']:.1f}", f"{a['delay_samples']:.2f}", f"{a['code_phase_chips']:.3f}", f"{a['cn0_dbhz']:.1f}"] if a else ["not detected"] + [""] * 3
        cells += [f"{b[1]:.0f}", f"{b[0]:.0f}", f"{b[2]:.1f} / {b[3]:.1f}"] if b else ["not detected", "", ""]
        if a and b:
            d = (a["delay_samples"] - b[0]) % period
            d = d - period if d > period / 2 else d
            cells += [f"{d:+.2f}", f"{a['doppler_hz'] - b[1]:+.0f}"]
        else:
            cells += ["", ""]
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
