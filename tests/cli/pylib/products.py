"""Readers of the simulator's and the receiver's products for the command-line tests.

A simulation folder (`deepnav sim --out`) holds synthesis.json, scenario.yaml, truth.csv,
sat_truth.csv, imu.csv and the IF file; a run folder (`deepnav run --out`) holds
summary.json, pvt.csv, tracking.csv and the rest. Each reader names the file it read when
the file is not what it expects.
"""
import csv
import json
import re
from pathlib import Path

# tracking.csv writes a channel's state as the number of receiver/tracking/
# tracking_channel.hpp's `enum class ChannelState { pull_in, bit_sync, tracking, lost }`
# (receiver/products/file_products.cpp, TrackingCsvSink). The names, in that order:
CHANNEL_STATES = ("pull_in", "bit_sync", "tracking", "lost")


def channel_state_name(number):
    """The ChannelState name of tracking.csv's `state` value."""
    index = int(number)
    if not 0 <= index < len(CHANNEL_STATES):
        raise ValueError(f"tracking.csv state {number}: expected 0..{len(CHANNEL_STATES) - 1} ({CHANNEL_STATES})")
    return CHANNEL_STATES[index]


def read_json(path):
    with open(path) as f:
        return json.load(f)


def read_csv(path):
    """The rows of a CSV product as dicts of strings (the header's names)."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def summary(run_dir):
    return read_json(Path(run_dir) / "summary.json")


def synthesis(sim_dir):
    return read_json(Path(sim_dir) / "synthesis.json")


def sample_rate_hz(sim_dir):
    return float(synthesis(sim_dir)["sample_rate_hz"])


def synthesized_prns(sim_dir):
    return sorted(s["prn"] for s in synthesis(sim_dir)["satellites"])


def epoch_key(t_s):
    """Epoch times to the millisecond, so pvt.csv's and truth.csv's times match as keys."""
    return round(float(t_s), 3)


def pvt(run_dir):
    return read_csv(Path(run_dir) / "pvt.csv")


def truth_by_epoch(sim_dir):
    """truth.csv's rows keyed by epoch_key(t_s)."""
    return {epoch_key(r["t_s"]): r for r in read_csv(Path(sim_dir) / "truth.csv")}


def tracking(run_dir, sample_rate):
    """tracking.csv's rows with `prn` an int, `state` its ChannelState name, `cn0_dbhz` a
    float and `t_s` the integration's first sample in seconds (at sample_rate Hz)."""
    rows = read_csv(Path(run_dir) / "tracking.csv")
    for r in rows:
        r["prn"] = int(r["prn"])
        r["state"] = channel_state_name(r["state"])
        r["cn0_dbhz"] = float(r["cn0_dbhz"])
        r["t_s"] = int(r["first_sample"]) / sample_rate
    return rows


_IMU_LINE = re.compile(r"^imu: \{grade: (?P<grade>[^,]+), .*lever_arm_m: \[(?P<lever>[^\]]+)\]")


def scenario_imu(scenario_yaml):
    """(grade, [x, y, z] lever arm in metres) of the `imu:` line `deepnav sim` writes to a
    simulation's scenario.yaml (one flow mapping)."""
    with open(scenario_yaml) as f:
        for line in f:
            m = _IMU_LINE.match(line)
            if m:
                return m["grade"], [float(v) for v in m["lever"].split(",")]
    raise ValueError(f"{scenario_yaml}: no 'imu: {{grade: ..., lever_arm_m: [x, y, z]}}' line (a scenario without an IMU?)")
