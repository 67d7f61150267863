#include "receiver/pvt/snapshot_measurement.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

std::string error_of(const std::vector<SnapshotMeasurement>& measurements) {
  try {
    check_snapshot_measurements(measurements);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SnapshotMeasurement, SubmillisecondPseudorangeIsTheRangeModuloOneCodePeriod) {
  // A satellite transmitted at t_sv = 525599.9321234567 s; received at 525600.0004 s: the
  // pseudorange is 68.2765433 ms, of which 0.2765433 ms is left modulo 1 ms.
  const double t_sv = 525599.9321234567;
  const double code_phase_chips = std::fmod(t_sv, 1e-3) * gps::kCodeRate_cps;
  const GpsTime t_hint{2190, 525600.0004};
  const double z = submillisecond_pseudorange_m(code_phase_chips, t_hint);
  // Seconds of week in a double carry about 0.1 ns: a few centimetres of range.
  constexpr double kTolerance_m = 0.05;
  EXPECT_NEAR(z, gps::kSpeedOfLight_mps * 0.2765433e-3, kTolerance_m);
  // Whole seconds of hint error leave it unchanged; a millisecond fraction shifts it.
  EXPECT_NEAR(submillisecond_pseudorange_m(code_phase_chips, t_hint.plus_seconds(60.0)), z, kTolerance_m);
  EXPECT_NEAR(submillisecond_pseudorange_m(code_phase_chips, t_hint.plus_seconds(0.25e-3)),
              z + 0.25e-3 * gps::kSpeedOfLight_mps, kTolerance_m);
  // Always within one code period.
  for (double chips : {0.0, 511.5, 1022.999}) {
    const double zz = submillisecond_pseudorange_m(chips, t_hint);
    EXPECT_GE(zz, 0.0);
    EXPECT_LT(zz, kCodePeriodRange_m);
  }
}

TEST(SnapshotMeasurement, MalformedMeasurementsAreNamed) {
  EXPECT_EQ(error_of({{5, 100.0, 1200.0, 45.0}, {7, 1022.5, std::nullopt, 40.0}}), "");
  EXPECT_NE(error_of({{0, 100.0, {}, 45.0}}).find("prn 0 is outside 1..32"), std::string::npos);
  EXPECT_NE(error_of({{5, 1.0, {}, 45.0}, {5, 2.0, {}, 45.0}}).find("prn 5 appears twice"), std::string::npos);
  EXPECT_NE(error_of({{5, 1023.0, {}, 45.0}}).find("code_phase_chips 1023 is outside [0, 1023)"), std::string::npos);
  EXPECT_NE(error_of({{5, -0.5, {}, 45.0}}).find("measurement 0 (PRN 5): code_phase_chips"), std::string::npos);
  EXPECT_NE(error_of({{5, 1.0, NAN, 45.0}}).find("doppler_hz is not finite"), std::string::npos);
  EXPECT_NE(error_of({{5, 1.0, {}, INFINITY}}).find("cn0_dbhz is not finite"), std::string::npos);
}

}  // namespace
}  // namespace deepnav
