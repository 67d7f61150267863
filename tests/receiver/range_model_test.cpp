#include "receiver/pvt/range_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ins/wgs84.hpp"
#include "signals/gps_constants.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/satellite_signal_model.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Receiver {
  Eigen::Vector3d r0, v;
  double bias0_s, drift_sps;
  GpsTime t0_rcv;  ///< receiver clock reading at t_rcv_rel = 0

  /// The receiver at clock reading t0_rcv + t_rel (straight line, linear clock).
  ReceiverInstant at(double t_rel) const {
    ReceiverInstant rx;
    rx.t_rcv_rel_s = t_rel;
    // t_rcv = t_true + b(t_true), b = b0 + d (t_true - t0_true)  =>  t_true - t0_true = t_rel / (1 + d)
    const double dt_true = t_rel / (1.0 + drift_sps);
    rx.clock_bias_s = bias0_s + drift_sps * dt_true;
    rx.clock_drift_sps = drift_sps;
    rx.t_true = t0_rcv.plus_seconds(t_rel - rx.clock_bias_s);
    rx.r_ecef_m = r0 + v * dt_true;
    rx.v_ecef_mps = v;
    rx.llh = wgs84::ecef_to_llh(rx.r_ecef_m);
    return rx;
  }
};

/// The pseudorange rate the receiver measures: -lambda times the rate of the synthesized
/// carrier phase (IF removed) against the receiver clock, by central difference.
double measured_rate_mps(const Ephemeris& e, const IonoParameters& iono, const Receiver& r, double if_hz) {
  constexpr double h = 0.05;
  const SatelliteInstant a = evaluate_satellite(e, iono, {true, true}, r.at(-h), if_hz);
  const SatelliteInstant b = evaluate_satellite(e, iono, {true, true}, r.at(h), if_hz);
  const double doppler_hz = (b.carrier_cycles - a.carrier_cycles) / (2.0 * h) - if_hz;
  return -gps::kL1Wavelength_m * doppler_hz;
}

// The predicted pseudorange rate the tight filter compares with the Doppler must be the
// rate of the carrier the synthesizer puts in the samples, at the true state: any
// per-satellite difference is a bias the filter turns into a velocity (and, through the
// pseudoranges, a position) error.
TEST(RangeModel, PredictedRateMatchesTheSynthesizedCarrierRate) {
  const NavData nav = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
  const wgs84::Llh llh{37.5 * kDeg, 127.0 * kDeg, 50.0};
  const Eigen::Vector3d r0 = wgs84::llh_to_ecef(llh);
  for (const Eigen::Vector3d& v : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(150.0, -200.0, 80.0)}) {
    for (const double t_sow : {525600.0, 532800.0}) {
      Receiver rx{r0, v, 2e-4, 3e-7, GpsTime{2190, t_sow}};
      int checked = 0;
      for (int prn = 1; prn <= 32; ++prn) {
        const Ephemeris* e = nav.select(prn, rx.t0_rcv);
        if (!e || !e->healthy()) continue;
        const ReceiverInstant now = rx.at(0.0);
        const RangePrediction p = predict_range(*e, rx.t0_rcv, gps::kSpeedOfLight_mps * now.clock_bias_s, now.r_ecef_m,
                                                now.v_ecef_mps, nav.iono);
        if (p.elevation_rad < 5.0 * kDeg) continue;
        const double predicted = p.pseudorange_rate_mps(now.v_ecef_mps, gps::kSpeedOfLight_mps * now.clock_drift_sps);
        const double measured = measured_rate_mps(*e, nav.iono, rx, 1.25e6);
        EXPECT_NEAR(predicted, measured, 5e-5) << "PRN " << prn << " at elevation " << p.elevation_rad / kDeg
                                               << " deg, receiver velocity " << v.transpose();
        ++checked;
      }
      EXPECT_GE(checked, 6);
    }
  }
}

}  // namespace
}  // namespace deepnav
