"""Position differences in the local frame of a fix, for the tests' error bounds."""
import math


def ecef_m(row):
    """[x, y, z] in metres of a pvt.csv or truth.csv row (x_ecef_m, y_ecef_m, z_ecef_m)."""
    return [float(row[axis + "_ecef_m"]) for axis in "xyz"]


def ned_of_ecef_difference(lat_deg, lon_deg, d_ecef_m):
    """(north, east, up) in metres of an ECEF difference, at the given latitude and longitude."""
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    x, y, z = d_ecef_m
    north = -math.sin(lat) * math.cos(lon) * x - math.sin(lat) * math.sin(lon) * y + math.cos(lat) * z
    east = -math.sin(lon) * x + math.cos(lon) * y
    up = math.cos(lat) * math.cos(lon) * x + math.cos(lat) * math.sin(lon) * y + math.sin(lat) * z
    return north, east, up


def difference_neu(fix, other):
    """(north, east, up) of other - fix, in fix's local frame (pvt.csv rows, or a truth.csv row as other)."""
    d = [b - a for a, b in zip(ecef_m(fix), ecef_m(other))]
    return ned_of_ecef_difference(float(fix["lat_deg"]), float(fix["lon_deg"]), d)


def horizontal_m(fix, other):
    north, east, _ = difference_neu(fix, other)
    return math.hypot(north, east)


def rms(values):
    values = list(values)
    return math.sqrt(sum(v * v for v in values) / len(values)) if values else float("nan")
