"""GPS ephemerides from the CNAV messages (L2C, L5) of a u-blox UBX log, added to a RINEX 3
navigation file in the LNAV record layout.

A short log often holds the complete L1 C/A LNAV ephemeris (subframes 1-3 of one issue) of
only some satellites, while the same satellites' CNAV on L2C and L5 (messages 10 and 11:
ephemeris, 30-37: clock, 30: group delays and Klobuchar parameters) came in full. RTKLIB 2.4.3's
convbin decodes LNAV only. This script decodes the CNAV messages of RXM-SFRBX (CRC-24Q
checked) and writes, for every satellite that NAV_IN has no ephemeris of, one record in
LNAV form whose reference time toe' is the middle of the observation span, so that the
RINEX readers of deepnav and RTKLIB use it as they use any broadcast record:

  CNAV (IS-GPS-200 Table 30-II) differs from LNAV by a semi-major axis rate (A_k = A0 +
  Adot t_k) and a mean-motion rate (Delta n_A = Delta n0 + Delta n0dot t_k / 2). At toe' =
  toe + D the LNAV parameters are: A' = A0 + Adot D; mean motion n0 + Delta n0 + Delta
  n0dot D (Delta n' is that minus sqrt(mu / A'^3)); M0' = M0 + (n0 + Delta n0) D + Delta
  n0dot D^2 / 2; Omega0' = Omega0 + Omegadot D; i0' = i0 + idot D (exact). What remains,
  Adot (t - toe') in the radius and Delta n0dot (t - toe')^2 / 2 in the mean anomaly, is
  printed per satellite as the largest position difference over the span against the CNAV
  model itself, and the satellites that have both LNAV and CNAV are compared too.
  The clock (toc, af0-af2) is the same model; the L1 C/A group delay is TGD - ISC_L1C/A
  (IS-GPS-200 30.3.3.3.1.1.1), written as TGD. CNAV has no IODE: IODE and IODC are
  written as toe' / 16 modulo 256 (a label, unique per record here).
  The Klobuchar parameters of message 30 go into the header when NAV_IN has none.

Usage: ubx_cnav_nav.py UBX NAV_IN OBS NAV_OUT
  OBS (RINEX observation file) gives the span; NAV_OUT gets NAV_IN's header and records
  plus the CNAV ones (comment lines say which).
"""
import collections
import datetime
import math
import struct
import sys

MU = 3.986005e14
C = 299792458.0
OMEGA_E = 7.2921151467e-5
A_REF = 26559710.0
OMEGA_DOT_REF = -2.6e-9 * math.pi
SC = math.pi  # semicircles to radians
SECONDS_PER_WEEK = 604800.0
GPS_EPOCH_DAYS = 722820  # date(1980, 1, 6).toordinal()
STEP = 16.0  # s between the reference times of the records written for one satellite
# URA index 0-15 in metres (IS-GPS-200 20.3.3.3.1.3), negative CNAV indices below 2.4 m.
URA_M = [2.4, 3.4, 4.85, 6.85, 9.65, 13.65, 24.0, 48.0, 96.0, 192.0, 384.0, 768.0, 1536.0, 3072.0, 6144.0, 6144.0]


def ubx_messages(data):
    i = 0
    while i + 8 <= len(data):
        if data[i] == 0xB5 and data[i + 1] == 0x62:
            cls, mid, length = data[i + 2], data[i + 3], struct.unpack_from("<H", data, i + 4)[0]
            end = i + 6 + length
            if end + 2 <= len(data):
                a = b = 0
                for x in data[i + 2:end]:
                    a = (a + x) & 0xFF
                    b = (b + a) & 0xFF
                if a == data[end] and b == data[end + 1]:
                    yield cls, mid, data[i + 6:end]
                    i = end + 2
                    continue
        i += 1


def crc24q(bits):
    crc = 0
    for bit in bits:
        crc ^= bit << 23
        crc <<= 1
        if crc & 0x1000000:
            crc ^= 0x1864CFB
        crc &= 0xFFFFFF
    return crc


class Bits:
    """A CNAV message; positions are IS-GPS-200's (1-based)."""

    def __init__(self, bits):
        self.bits = bits

    def u(self, first, n):
        v = 0
        for b in self.bits[first - 1:first - 1 + n]:
            v = (v << 1) | b
        return v

    def s(self, first, n):
        v = self.u(first, n)
        return v - (1 << n) if v >> (n - 1) else v


def cnav_messages(data):
    """(prn, signal, message type, tow, Bits) of every CRC-valid GPS CNAV message."""
    out = []
    for cls, mid, p in ubx_messages(data):
        if (cls, mid) != (0x02, 0x13) or p[0] != 0 or p[2] not in (3, 4, 6, 7):
            continue
        words = struct.unpack_from("<%dI" % p[4], p, 8)
        bits = [int(c) for c in "".join(format(w, "032b") for w in words)][:300]
        if len(bits) < 300 or bits[:8] != [1, 0, 0, 0, 1, 0, 1, 1]:
            continue
        if crc24q(bits[:276]) != Bits(bits).u(277, 24):
            continue
        m = Bits(bits)
        out.append((m.u(9, 6), p[2], m.u(15, 6), m.u(21, 17) * 6, m))
    return out


def lnav_orbits(data):
    """Orbit parameters of every GPS satellite whose L1 C/A subframes 2 and 3 (one IODE)
    are in RXM-SFRBX, by PRN: a check of the CNAV orbits, also for satellites whose
    subframe 1 (the clock) never came. u-blox gives each 30-bit word with its data bits
    already in true polarity; the 24 data bits are kept."""
    frames = collections.defaultdict(dict)
    for cls, mid, p in ubx_messages(data):
        if (cls, mid) != (0x02, 0x13) or p[0] != 0 or p[2] != 0 or p[4] != 10:
            continue
        words = struct.unpack_from("<10I", p, 8)
        m = Bits([int(c) for c in "".join(format((w >> 6) & 0xFFFFFF, "024b") for w in words)])
        if m.u(1, 8) == 0x8B:
            frames[p[1]][m.u(44, 3)] = m

    def field(m, word, bit, n, signed):
        return m.s(24 * (word - 1) + bit, n) if signed else m.u(24 * (word - 1) + bit, n)

    def split(m, word, n_msb, signed):  # n_msb bits at the end of `word`, 24 in the next
        v = (field(m, word, 25 - n_msb, n_msb, False) << 24) | field(m, word + 1, 1, 24, False)
        n = n_msb + 24
        return v - (1 << n) if signed and v >> (n - 1) else v

    out = {}
    for prn, f in frames.items():
        if 2 not in f or 3 not in f or field(f[2], 3, 1, 8, False) != field(f[3], 10, 1, 8, False):
            continue
        s2, s3 = f[2], f[3]
        out[prn] = dict(Crs=field(s2, 3, 9, 16, True) * 2.0**-5, dn=field(s2, 4, 1, 16, True) * 2.0**-43 * SC,
                        M0=split(s2, 4, 8, True) * 2.0**-31 * SC, Cuc=field(s2, 6, 1, 16, True) * 2.0**-29,
                        e=split(s2, 6, 8, False) * 2.0**-33, Cus=field(s2, 8, 1, 16, True) * 2.0**-29,
                        sqrtA=split(s2, 8, 8, False) * 2.0**-19, toe=field(s2, 10, 1, 16, False) * 16.0,
                        Cic=field(s3, 3, 1, 16, True) * 2.0**-29, Omega0=split(s3, 3, 8, True) * 2.0**-31 * SC,
                        Cis=field(s3, 5, 1, 16, True) * 2.0**-29, i0=split(s3, 5, 8, True) * 2.0**-31 * SC,
                        Crc=field(s3, 7, 1, 16, True) * 2.0**-5, omega=split(s3, 7, 8, True) * 2.0**-31 * SC,
                        Omegadot=field(s3, 9, 1, 24, True) * 2.0**-43 * SC,
                        idot=field(s3, 10, 9, 14, True) * 2.0**-43 * SC)
    return out


def decode(messages):
    """Per PRN: the last ephemeris (types 10 + 11 of one toe) with a clock (30-37) and
    group delays (30)."""
    eph10, eph11, clocks, delays, ionos = {}, {}, {}, {}, []
    for prn, sig, mtype, tow, m in messages:
        if mtype == 10:
            eph10[(prn, m.u(71, 11) * 300)] = dict(
                week=m.u(39, 13), l1_health=m.u(52, 1), ura=m.s(66, 5), toe=m.u(71, 11) * 300.0,
                dA=m.s(82, 26) * 2.0**-9, Adot=m.s(108, 25) * 2.0**-21, dn0=m.s(133, 17) * 2.0**-44 * SC,
                dn0dot=m.s(150, 23) * 2.0**-57 * SC, M0=m.s(173, 33) * 2.0**-32 * SC, e=m.u(206, 33) * 2.0**-34,
                omega=m.s(239, 33) * 2.0**-32 * SC, tx=tow - (12 if sig in (3, 4) else 6))
        elif mtype == 11:
            eph11[(prn, m.u(39, 11) * 300)] = dict(
                Omega0=m.s(50, 33) * 2.0**-32 * SC, i0=m.s(83, 33) * 2.0**-32 * SC,
                dOmegadot=m.s(116, 17) * 2.0**-44 * SC, idot=m.s(133, 15) * 2.0**-44 * SC,
                Cis=m.s(148, 16) * 2.0**-30, Cic=m.s(164, 16) * 2.0**-30, Crs=m.s(180, 24) * 2.0**-8,
                Crc=m.s(204, 24) * 2.0**-8, Cus=m.s(228, 21) * 2.0**-30, Cuc=m.s(249, 21) * 2.0**-30)
        if 30 <= mtype <= 37:
            clocks[prn] = dict(toc=m.u(61, 11) * 300.0, af0=m.s(72, 26) * 2.0**-35, af1=m.s(98, 20) * 2.0**-48,
                               af2=m.s(118, 10) * 2.0**-60)
        if mtype == 30:
            delays[prn] = dict(tgd=m.s(128, 13) * 2.0**-35, isc_l1ca=m.s(141, 13) * 2.0**-35)
            ionos.append((m.s(193, 8) * 2.0**-30, m.s(201, 8) * 2.0**-27, m.s(209, 8) * 2.0**-24,
                          m.s(217, 8) * 2.0**-24, m.s(225, 8) * 2.0**11, m.s(233, 8) * 2.0**14,
                          m.s(241, 8) * 2.0**16, m.s(249, 8) * 2.0**16))
    out = {}
    for (prn, toe), e10 in sorted(eph10.items()):
        e11 = eph11.get((prn, toe))
        if e11 is None or prn not in clocks or prn not in delays:
            continue
        out[prn] = dict(prn=prn, **e10, **e11, **clocks[prn], **delays[prn])
    iono = collections.Counter(ionos).most_common(1)[0][0] if ionos else None
    return out, iono


def kepler(M, e):
    E = M
    for _ in range(30):
        E = M + e * math.sin(E)
    return E


def position(p, t, cnav):
    """ECEF position at GPS seconds of week t: IS-GPS-200 Table 30-II (cnav) or 20-IV."""
    tk = t - p["toe"]
    if cnav:
        A0 = A_REF + p["dA"]
        A = A0 + p["Adot"] * tk
        n = math.sqrt(MU / A0**3) + p["dn0"] + 0.5 * p["dn0dot"] * tk
        Omegadot = OMEGA_DOT_REF + p["dOmegadot"]
    else:
        A = p["sqrtA"] ** 2
        n = math.sqrt(MU / A**3) + p["dn"]
        Omegadot = p["Omegadot"]
    E = kepler(p["M0"] + n * tk, p["e"])
    nu = math.atan2(math.sqrt(1 - p["e"] ** 2) * math.sin(E), math.cos(E) - p["e"])
    phi = nu + p["omega"]
    u = phi + p["Cus"] * math.sin(2 * phi) + p["Cuc"] * math.cos(2 * phi)
    r = A * (1 - p["e"] * math.cos(E)) + p["Crs"] * math.sin(2 * phi) + p["Crc"] * math.cos(2 * phi)
    i = p["i0"] + p["idot"] * tk + p["Cis"] * math.sin(2 * phi) + p["Cic"] * math.cos(2 * phi)
    Om = p["Omega0"] + (Omegadot - OMEGA_E) * tk - OMEGA_E * p["toe"]
    x, y = r * math.cos(u), r * math.sin(u)
    return (x * math.cos(Om) - y * math.cos(i) * math.sin(Om), x * math.sin(Om) + y * math.cos(i) * math.cos(Om),
            y * math.sin(i))


def clock(p, toc, t):
    return p["af0"] + p["af1"] * (t - toc) + p["af2"] * (t - toc) ** 2


def to_lnav(c, toe_new):
    D = toe_new - c["toe"]
    A0 = A_REF + c["dA"]
    A = A0 + c["Adot"] * D
    n = math.sqrt(MU / A0**3) + c["dn0"] + c["dn0dot"] * D
    Omegadot = OMEGA_DOT_REF + c["dOmegadot"]
    return dict(prn=c["prn"], week=c["week"], toe=toe_new, sqrtA=math.sqrt(A), dn=n - math.sqrt(MU / A**3),
                M0=c["M0"] + (math.sqrt(MU / A0**3) + c["dn0"]) * D + 0.5 * c["dn0dot"] * D * D, e=c["e"],
                omega=c["omega"], Omega0=c["Omega0"] + Omegadot * D, Omegadot=Omegadot, i0=c["i0"] + c["idot"] * D,
                idot=c["idot"], Cis=c["Cis"], Cic=c["Cic"], Crs=c["Crs"], Crc=c["Crc"], Cus=c["Cus"], Cuc=c["Cuc"],
                toc=c["toc"], af0=c["af0"], af1=c["af1"], af2=c["af2"], tgd=c["tgd"] - c["isc_l1ca"],
                health=c["l1_health"], ura=URA_M[max(0, min(15, c["ura"]))], tx=c["tx"],
                iode=int(round(toe_new / 16.0)) % 256)


def read_lnav(path):
    """GPS records of a RINEX 3 navigation file: header lines, records as line lists and
    their parameters."""
    lines = open(path).read().splitlines()
    end = next(i for i, l in enumerate(lines) if l[60:].strip() == "END OF HEADER")
    header, body = lines[:end], lines[end + 1:]
    records, params = [], {}
    i = 0
    while i < len(body):
        if not body[i].strip():
            i += 1
            continue
        system = body[i][0]
        n = {"G": 8, "E": 8, "J": 8, "C": 8, "I": 8, "R": 4, "S": 4}.get(system, 8)
        rec = body[i:i + n]
        records.append(rec)
        if system == "G":
            v = [float(rec[0][23 + 19 * k:42 + 19 * k].replace("D", "E")) for k in range(3)]
            for line in rec[1:]:
                v += [float(line[4 + 19 * k:23 + 19 * k].replace("D", "E")) if line[4 + 19 * k:23 + 19 * k].strip()
                      else 0.0 for k in range(4)]
            keys = ["af0", "af1", "af2", "iode", "Crs", "dn", "M0", "Cuc", "e", "Cus", "sqrtA", "toe", "Cic", "Omega0",
                    "Cis", "i0", "Crc", "omega", "Omegadot", "idot", "codes", "week"]
            params[int(rec[0][1:3])] = dict(zip(keys, v))
            f = rec[0][4:23].split()
            days = datetime.date(int(f[0]), int(f[1]), int(f[2])).toordinal() - GPS_EPOCH_DAYS
            params[int(rec[0][1:3])]["toc"] = (days % 7) * 86400.0 + int(f[3]) * 3600.0 + int(f[4]) * 60.0 + int(f[5])
        i += n
    return header, records, params


def obs_span(path):
    """First and last epoch of a RINEX 3 observation file as (week, seconds of week)."""
    times = []
    for line in open(path):
        if line.startswith(">"):
            f = line[1:].split()
            y, mo, d, h, mi = (int(x) for x in f[:5])
            days = datetime.date(y, mo, d).toordinal() - GPS_EPOCH_DAYS
            times.append((days // 7, (days % 7) * 86400.0 + h * 3600.0 + mi * 60.0 + float(f[5])))
    if not times:
        sys.exit("%s: no RINEX 3 epoch lines" % path)
    return times[0], times[-1]


def fmt(v):
    """RINEX D19.12 (the layout convbin writes: a leading '.', exponent D+nn)."""
    if v == 0.0:
        return "  .000000000000D+00"
    e = int(math.floor(math.log10(abs(v)))) + 1
    m = v / 10.0**e
    if round(abs(m), 12) >= 1.0:
        m /= 10.0
        e += 1
    s = "%.12f" % abs(m)
    return (("-" if v < 0 else "") + s[1:] + "D%+03d" % e).rjust(19)


def lnav_record(p, week):
    days = int(p["toc"] // 86400)
    date = datetime.date.fromordinal(GPS_EPOCH_DAYS + week * 7 + days)
    rest = p["toc"] - days * 86400
    head = "G%02d %04d %02d %02d %02d %02d %02d" % (p["prn"], date.year, date.month, date.day, rest // 3600,
                                                      (rest % 3600) // 60, rest % 60)
    rows = [[p["iode"], p["Crs"], p["dn"], p["M0"]], [p["Cuc"], p["e"], p["Cus"], p["sqrtA"]],
            [p["toe"], p["Cic"], p["Omega0"], p["Cis"]], [p["i0"], p["Crc"], p["omega"], p["Omegadot"]],
            [p["idot"], 0.0, float(week), 0.0], [p["ura"], float(p["health"]), p["tgd"], float(p["iode"])],
            [p["tx"], 4.0]]
    out = [head + "".join(fmt(v) for v in (p["af0"], p["af1"], p["af2"]))]
    out += ["    " + "".join(fmt(v) for v in row) for row in rows]
    return out


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    ubx_path, nav_in, obs_path, nav_out = sys.argv[1:]
    raw = open(ubx_path, "rb").read()
    cnav, iono = decode(cnav_messages(raw))
    subframes = lnav_orbits(raw)
    header, records, lnav = read_lnav(nav_in)
    lnav_toc = {prn: p["toc"] for prn, p in lnav.items()}
    (w0, t0), (w1, t1) = obs_span(obs_path)
    t_end = t1 + (w1 - w0) * SECONDS_PER_WEEK
    # Reference times every STEP seconds (LNAV's toe resolution) from before the first
    # epoch to after the last: no epoch is more than STEP / 2 from one.
    refs = [STEP * k for k in range(int(math.floor(t0 / STEP)), int(math.ceil(t_end / STEP)) + 1)]
    span = [t0 + k * (t_end - t0) / 200.0 for k in range(201)]
    print("CNAV ephemerides with clock and group delays: PRN %s" % ", ".join(str(p) for p in sorted(cnav)))
    print("records every %.0f s, toe' %.0f to %.0f (span %.2f to %.2f s of week %d)" % (STEP, refs[0], refs[-1], t0,
                                                                                       t_end, w0))
    added = []
    for prn, c in sorted(cnav.items()):
        fits = [to_lnav(c, r) for r in refs]
        worst = max(math.dist(position(c, t, True), position(min(fits, key=lambda f: abs(f["toe"] - t)), t, False))
                    for t in span)
        note = "LNAV form against the CNAV model over the span: largest difference %.4f m" % worst
        if prn in subframes:
            d = max(math.dist(position(c, t, True), position(subframes[prn], t, False)) for t in span)
            note += "; orbit of its L1 C/A subframes 2-3 against it: %.2f m" % d
        if prn in lnav:
            d = max(math.dist(position(c, t, True), position(lnav[prn], t, False)) for t in span)
            dc = max(abs(clock(c, c["toc"], t) - clock(lnav[prn], lnav_toc[prn], t)) for t in span) * C
            note += "; this satellite has an LNAV record, CNAV against it: position %.2f m, clock %.2f m (LNAV kept)" % (
                d, dc)
        else:
            added += fits
        print("PRN %02d: toe %.0f, Adot %.2e m/s, dn0dot %.2e rad/s^2, L1 health %d; %s" %
              (prn, c["toe"], c["Adot"], c["dn0dot"], c["l1_health"], note))
    body = []
    for rec in records:
        body += rec
    for p in added:
        body += lnav_record(p, p["week"])
    has_iono = any(l[60:].strip() == "IONOSPHERIC CORR" and l[:4] == "GPSA" for l in header)
    extra = ["%-60s%-20s" % ("GPS CNAV (L2C/L5) records added by ubx_cnav_nav.py:", "COMMENT"),
             "%-60s%-20s" % ("  PRN " + " ".join(sorted({"%02d" % p["prn"] for p in added})) +
                             ", LNAV form, toe' every %.0f s" % STEP, "COMMENT")]
    if iono and not has_iono:
        extra.append("GPSA " + "".join("%12.4E" % v for v in iono[:4]).replace("E", "D") + "       IONOSPHERIC CORR    ")
        extra.append("GPSB " + "".join("%12.4E" % v for v in iono[4:]).replace("E", "D") + "       IONOSPHERIC CORR    ")
        extra.append("%-60s%-20s" % ("  Klobuchar parameters: CNAV message 30", "COMMENT"))
    with open(nav_out, "w") as f:
        f.write("\n".join(header + extra + ["%-60s%-20s" % ("", "END OF HEADER")] + body) + "\n")
    print("%s: %d records from %s, %d added from CNAV%s" % (nav_out, len(records), nav_in, len(added),
                                                           ", Klobuchar parameters added" if iono and not has_iono else ""))


if __name__ == "__main__":
    main()
