#include "signals/sim/ionosphere_truth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "signals/atmosphere.hpp"
#include "signals/gps_constants.hpp"
#include "signals/sim/error_presets.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const GpsTime kMidnight{2190, 518400.0};  // 2022-01-01 00:00 GPS, the bundled navigation file's day
const wgs84::Llh kSeoul{37.5665 * kDeg, 126.978 * kDeg, 40.0};

/// Broadcast values of data/brdc0010.22n.
IonoParameters brdc_iono() {
  IonoParameters p;
  p.alpha = {0.1211e-07, -0.7451e-08, -0.5960e-07, 0.1192e-06};
  p.beta = {0.1167e+06, -0.2458e+06, -0.6554e+05, 0.1114e+07};
  p.valid = true;
  return p;
}

struct Residual {
  double truth_rms_m, residual_rms_m;
  double ratio() const { return residual_rms_m / truth_rms_m; }
};

/// Truth against Klobuchar over a day (every 30 min) and the sky above 10 deg.
Residual day_residual(const IonosphereTruth& truth, const wgs84::Llh& rx) {
  double t2 = 0.0, r2 = 0.0;
  int n = 0;
  for (int half_hour = 0; half_hour < 48; ++half_hour) {
    const GpsTime t = kMidnight.plus_seconds(half_hour * 1800.0);
    for (int el = 10; el <= 90; el += 10) {
      for (int az = 0; az < 360; az += 30) {
        const double k = klobuchar_delay_m(brdc_iono(), rx.lat_rad, rx.lon_rad, az * kDeg, el * kDeg, t.sow);
        const double d = truth.delay_m(k, rx, az * kDeg, el * kDeg, t);
        t2 += d * d;
        r2 += (d - k) * (d - k);
        ++n;
      }
    }
  }
  return {std::sqrt(t2 / n), std::sqrt(r2 / n)};
}

IonosphereTruth open_sky_truth(std::uint64_t seed, const wgs84::Llh& rx) {
  return IonosphereTruth(error_preset("open-sky").ionosphere, seed, rx, kMidnight);
}

TEST(IonosphereTruth, SingleLayerMappingAndDelayScale) {
  EXPECT_DOUBLE_EQ(single_layer_mapping(90 * kDeg, 450e3), 1.0);
  // R cos E / (R + H) at 10 deg and 450 km: 6371/6821 cos(10 deg) = 0.9198 -> M = 2.551.
  EXPECT_NEAR(single_layer_mapping(10 * kDeg, 450e3), 2.551, 0.002);
  EXPECT_NEAR(single_layer_mapping(0.0, 350e3), 1.0 / std::sqrt(1.0 - std::pow(6371.0 / 6721.0, 2)), 1e-12);
  // 1 TECU delays L1 by 0.1624 m.
  EXPECT_NEAR(l1_delay_m_from_tecu(1.0), 0.16237, 1e-5);
}

TEST(IonosphereTruth, OpenSkyResidualAfterKlobucharIsAboutHalf) {
  for (const auto& [name, rx] : {std::pair<const char*, wgs84::Llh>{"Seoul", kSeoul},
                                 {"Munich", {48.15 * kDeg, 11.58 * kDeg, 500.0}},
                                 {"Boulder", {40.0 * kDeg, -105.27 * kDeg, 1600.0}},
                                 {"Sydney", {-33.87 * kDeg, 151.21 * kDeg, 50.0}}}) {
    const Residual r = day_residual(open_sky_truth(1, rx), rx);
    std::printf("%s: truth RMS %.3f m, residual after Klobuchar %.3f m (%.0f %%)\n", name, r.truth_rms_m,
                r.residual_rms_m, 100.0 * r.ratio());
    EXPECT_GT(r.ratio(), 0.3) << name;
    EXPECT_LT(r.ratio(), 0.7) << name;
  }
}

TEST(IonosphereTruth, OpenSkyZenithResidualIsUpToAFewMetres) {
  const IonosphereTruth truth = open_sky_truth(1, kSeoul);
  double r2 = 0.0, lo = 1e9, hi = -1e9;
  int n = 0;
  for (int minute = 0; minute < 24 * 60; minute += 10) {
    const GpsTime t = kMidnight.plus_seconds(minute * 60.0);
    const double k = klobuchar_delay_m(brdc_iono(), kSeoul.lat_rad, kSeoul.lon_rad, 0.0, 90 * kDeg, t.sow);
    const double r = truth.delay_m(k, kSeoul, 0.0, 90 * kDeg, t) - k;
    r2 += r * r;
    lo = std::min(lo, r);
    hi = std::max(hi, r);
    ++n;
  }
  std::printf("Seoul zenith residual after Klobuchar over a day: RMS %.2f m, %.2f to %.2f m\n", std::sqrt(r2 / n), lo,
              hi);
  EXPECT_GT(std::sqrt(r2 / n), 0.3);
  EXPECT_LT(std::sqrt(r2 / n), 3.0);
  EXPECT_LT(hi, 5.0);
  EXPECT_GT(lo, -2.0);
}

TEST(IonosphereTruth, DiurnalPeakAfterNoonAndRealisticTec) {
  const IonosphereTruth truth = open_sky_truth(1, kSeoul);
  double max_vtec = 0.0, min_vtec = 1e9, peak_local_h = 0.0;
  for (int minute = 0; minute < 24 * 60; minute += 10) {
    const GpsTime t = kMidnight.plus_seconds(minute * 60.0);
    const IonosphereSample s = truth.thin_shell(kSeoul, 0.0, 90 * kDeg, t);
    const double local_h = std::fmod(minute / 60.0 + kSeoul.lon_rad / kDeg / 15.0, 24.0);
    if (s.vtec_tecu > max_vtec) {
      max_vtec = s.vtec_tecu;
      peak_local_h = local_h;
    }
    min_vtec = std::min(min_vtec, s.vtec_tecu);
  }
  EXPECT_NEAR(peak_local_h, 14.0, 1.0);
  EXPECT_GT(max_vtec, 35.0);
  EXPECT_LT(max_vtec, 50.0);
  EXPECT_GT(min_vtec, 2.0);
  EXPECT_LT(min_vtec, 5.0);
}

TEST(IonosphereTruth, LatitudeProfileHasCrestsAndFallsPoleward) {
  IonosphereTruthSpec spec = error_preset("open-sky").ionosphere;
  spec.disturbance_rms = 0.0;
  const IonosphereTruth truth(spec, 1, kSeoul, kMidnight);
  // Same local time (14 h) at the pierce point, zenith: only the latitude changes. At
  // 72.68 deg W geomagnetic and geographic latitudes coincide (the pole's meridian).
  auto vtec_at = [&](double lat_deg) {
    const wgs84::Llh rx{lat_deg * kDeg, -72.68 * kDeg, 0.0};
    const double sow = kMidnight.sow + std::fmod(14.0 + 72.68 / 15.0, 24.0) * 3600.0;
    return truth.thin_shell(rx, 0.0, 90 * kDeg, GpsTime{kMidnight.week, sow}).vtec_tecu;
  };
  // On that meridian geomagnetic latitude = 90 deg - |latitude - 80.65 deg|.
  EXPECT_NEAR(vtec_at(5.65), 50.0, 1e-9);           // geomagnetic 15 deg: the crest
  EXPECT_NEAR(vtec_at(-24.35), 50.0, 1e-9);         // the southern crest
  EXPECT_LT(vtec_at(-9.35), 0.95 * vtec_at(5.65));  // magnetic equator: the trough between the crests
  EXPECT_LT(vtec_at(60.0), 0.6 * vtec_at(5.65));
}

TEST(IonosphereTruth, KlobucharModelIsTheBroadcastDelayScaled) {
  IonosphereTruthSpec spec;
  spec.model = IonosphereTruthSpec::Model::klobuchar;
  EXPECT_EQ(IonosphereTruth(spec, 1, kSeoul, kMidnight).delay_m(3.25, kSeoul, 0.3, 0.5, kMidnight), 3.25);
  spec.vtec_scale = 1.5;
  EXPECT_DOUBLE_EQ(IonosphereTruth(spec, 1, kSeoul, kMidnight).delay_m(3.0, kSeoul, 0.3, 0.5, kMidnight), 4.5);
}

TEST(IonosphereTruth, DisturbancesAreSeededAndAFewPercent) {
  IonosphereTruthSpec quiet = error_preset("open-sky").ionosphere;
  quiet.disturbance_rms = 0.0;
  const IonosphereTruth smooth(quiet, 1, kSeoul, kMidnight);
  const IonosphereTruth a = open_sky_truth(7, kSeoul), b = open_sky_truth(7, kSeoul), c = open_sky_truth(8, kSeoul);
  double sum2 = 0.0, diff_ac = 0.0;
  int n = 0;
  for (int minute = 0; minute < 24 * 60; minute += 5) {
    const GpsTime t = kMidnight.plus_seconds(minute * 60.0);
    for (int az = 0; az < 360; az += 45) {
      const double s = smooth.thin_shell(kSeoul, az * kDeg, 30 * kDeg, t).delay_m;
      const double da = a.thin_shell(kSeoul, az * kDeg, 30 * kDeg, t).delay_m;
      EXPECT_EQ(da, b.thin_shell(kSeoul, az * kDeg, 30 * kDeg, t).delay_m);
      diff_ac += std::abs(da - c.thin_shell(kSeoul, az * kDeg, 30 * kDeg, t).delay_m);
      sum2 += std::pow(da / s - 1.0, 2);
      ++n;
    }
  }
  const double rms = std::sqrt(sum2 / n);
  EXPECT_GT(rms, 0.015);
  EXPECT_LT(rms, 0.05);
  EXPECT_GT(diff_ac / n, 0.01);  // another seed: other waves
}

}  // namespace
}  // namespace deepnav
