#include "aiding/ultra_tight_tracker.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <variant>

#include "aiding/measurement_models.hpp"
#include "ins/gps_time.hpp"
#include "receiver/tracking/tracking_loops.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav::aiding {
namespace {

constexpr double kBroadcastRangeSigma_m = 3.0;  // broadcast orbit and clock error along a look (1 sigma)

}  // namespace

UltraTightTracker::UltraTightTracker(UltraTightConfig config, double sample_rate_hz,
                                     const RangeErrorModel& range_errors, const SatelliteFaultMonitor* faults,
                                     const AtmosphereModels& atmosphere)
    : cfg_(config), fs_(sample_rate_hz), range_errors_(range_errors), faults_(faults), atmosphere_(atmosphere) {}

SteeredChannelController* UltraTightTracker::controller_for(int prn) {
  auto it = controllers_.find(prn);
  if (it == controllers_.end())
    it = controllers_
             .emplace(std::piecewise_construct, std::forward_as_tuple(prn),
                      std::forward_as_tuple(cfg_, fs_, engagement_))
             .first;
  return &it->second;
}

SteeredE1Controller* UltraTightTracker::e1_controller_for(int svid) {
  auto it = e1_controllers_.find(svid);
  if (it == e1_controllers_.end())
    it = e1_controllers_
             .emplace(std::piecewise_construct, std::forward_as_tuple(svid),
                      std::forward_as_tuple(cfg_, fs_, engagement_, galileo_offset_known_))
             .first;
  return &it->second;
}

bool UltraTightTracker::e1_steered(int svid) const {
  const auto it = e1_controllers_.find(svid);
  return it != e1_controllers_.end() && it->second.steered();
}

void UltraTightTracker::set_galileo_offset(std::optional<double> offset_m, double sigma_m) {
  galileo_offset_m_ = offset_m;
  galileo_offset_sigma_m_ = sigma_m;
  galileo_offset_known_ = offset_m.has_value();
}

int UltraTightTracker::count_steerable(const BlockSnapshot& block) {
  int n = 0;
  for (const ChannelStatus& ch : block.channels)
    if (can_steer(ch.bit_synced, ch.state, ch.decoder_synchronised, ch.ephemeris.has_value())) ++n;
  return n;
}

int UltraTightTracker::steered_channels() const {
  int n = 0;
  for (const auto& [prn, c] : controllers_) n += c.steered() ? 1 : 0;
  for (const auto& [svid, c] : e1_controllers_) n += c.steered() ? 1 : 0;
  return n;
}

std::optional<UltraTightTracker::SamplePrediction> UltraTightTracker::predict_at(const BroadcastEphemeris& eph,
                                                                                 std::int64_t sample,
                                                                                 const AidedNavigator& nav,
                                                                                 const BlockSnapshot& block) const {
  if (!block.clock) return std::nullopt;
  const bool galileo = system_of(eph) == GnssSystem::galileo;
  if (galileo && !galileo_offset_m_) return std::nullopt;
  SamplePrediction p;
  p.t_rx = block.clock->at(sample);
  const double t_s = static_cast<double>(sample) / fs_;
  p.offset_s = t_s - nav.time_s();
  p.clock_bias_m = nav.clock_bias_m() + nav.clock_drift_mps() * p.offset_s + (galileo ? *galileo_offset_m_ : 0.0);
  p.antenna_velocity_ecef_mps = nav.antenna_velocity_ecef_at(t_s);
  const Eigen::Vector3d r_ecef_m = nav.antenna_ecef_at(t_s);
  p.range = std::visit(
      [&](const auto& e) {
        return predict_range(e, p.t_rx, p.clock_bias_m, r_ecef_m, p.antenna_velocity_ecef_mps, block.iono, atmosphere_);
      },
      eph);
  return p;
}

std::optional<RangeMeasurement> UltraTightTracker::to_measurement(const DiscriminatorSample& d,
                                                                  const AidedNavigator& nav,
                                                                  const BlockSnapshot& block) const {
  const std::optional<SamplePrediction> p = predict_at(d.ephemeris, d.mid_sample, nav, block);
  if (!p) return std::nullopt;
  RangeMeasurement m;
  m.satellite = d.satellite();
  m.time_offset_s = p->offset_s;
  m.geometry = p->range;
  // E1 and L1 C/A share the chip rate.
  const double t_tx = d.replica_transmit_sow + d.code_error_chips / gps::kCodeRate_cps;
  m.pseudorange_m = gps::kSpeedOfLight_mps * seconds_of_week_difference(p->t_rx.sow, t_tx);
  // Discriminator noise plus what the range models leave, by elevation (the PVT's weights).
  const bool galileo = m.satellite.system == GnssSystem::galileo;
  if (galileo) {
    // On the GPS clock: less the system offset, whose uncertainty is shared by every row of
    // a second (as the range models' terms are).
    *m.pseudorange_m -= *galileo_offset_m_;
    const double per_row = 1.0 / std::min(d.integration_s, 1.0);
    m.pseudorange_sigma_m =
        std::hypot(e1_discriminator_pseudorange_sigma_m(range_errors_, p->range.elevation_rad, d.cn0_dbhz,
                                                        d.integration_s, d.spacing_chips, d.code_sigma_floor_chips),
                   std::sqrt(per_row) * galileo_offset_sigma_m_);
  } else {
    m.pseudorange_sigma_m = discriminator_pseudorange_sigma_m(range_errors_, p->range.elevation_rad, d.cn0_dbhz,
                                                              d.integration_s, d.spacing_chips, d.piece_s);
  }
  if (d.doppler_hz) {
    // Predicted where the Doppler refers to (doppler_sample), not at mid_sample.
    const std::optional<SamplePrediction> at_rate = predict_at(d.ephemeris, d.doppler_sample, nav, block);
    if (!at_rate) return m;
    m.rate_at_own_time = true;
    m.rate_geometry = at_rate->range;
    m.rate_time_offset_s = at_rate->offset_s;
    m.rate_mps = -gps::kL1Wavelength_m * *d.doppler_hz;
    // A non-coherent integration's discriminator spans one of its pieces, averaged over its pairs.
    // E1: the phase is the pilot's.
    m.rate_sigma_mps =
        discriminator_rate_sigma_mps(galileo ? e1_pilot_cn0_dbhz(d.cn0_dbhz) : d.cn0_dbhz,
                                     d.piece_s > 0.0 ? d.piece_s : d.integration_s, d.rate_window_s, d.frequency_pairs);
  }
  return m;
}

std::vector<RangeResidual> UltraTightTracker::mean_pseudorange_residuals() const {
  std::vector<RangeResidual> out;
  for (const auto& [prn, sum] : residual_sums_) {
    RangeResidual r = sum.latest;
    r.residual_m = sum.sum_m / sum.count;
    out.push_back(r);
  }
  return out;
}

void UltraTightTracker::collect(std::vector<DiscriminatorSample> samples, const AidedNavigator& nav,
                                const BlockSnapshot& block, std::vector<RangeMeasurement>& ms,
                                std::vector<RangeMeasurement>& watched) {
  for (const DiscriminatorSample& d : samples) {
    if (!d.measurement) continue;
    const std::optional<RangeMeasurement> m = to_measurement(d, nav, block);
    if (!m) continue;
    const SatelliteId sat = d.satellite();
    last_measured_sample_[sat] = d.mid_sample;
    (faults_ && faults_->excluded(sat) ? watched : ms).push_back(*m);
    // The atmosphere watch fits GPS residuals: a Galileo one also carries the offset's error.
    if (m->pseudorange_m && sat.system == GnssSystem::gps) {
      const RangePrediction& g = m->geometry;
      const double predicted =
          g.pseudorange_m(nav.clock_bias_m() + nav.clock_drift_mps() * m->time_offset_s) + nav.residual_delay_m(g);
      ResidualSum& sum = residual_sums_[d.prn];
      sum.latest = {g.los_ecef, g.elevation_rad, d.cn0_dbhz, *m->pseudorange_m - predicted, g.ionosphere_m};
      sum.sum_m += sum.latest.residual_m;
      ++sum.count;
    }
  }
}

KalmanUpdate UltraTightTracker::update_and_steer(AidedNavigator& nav, const BlockSnapshot& block, bool measure,
                                                 std::vector<SatelliteInnovation>* innovations) {
  std::vector<RangeMeasurement> ms, watched;
  // Channel order, each channel's integrations in time order: the same rows whichever
  // thread tracked which channel. GPS channels first, then Galileo ones.
  for (const int prn : block.tracked_prns) {
    std::vector<DiscriminatorSample> samples = controller_for(prn)->take_samples();
    if (measure) collect(std::move(samples), nav, block, ms, watched);
  }
  for (const int svid : block.tracked_galileo_svids) {
    std::vector<DiscriminatorSample> samples = e1_controller_for(svid)->take_samples();
    if (measure) collect(std::move(samples), nav, block, ms, watched);
  }
  // Satellites measured within the longest integration (plus a block): with long
  // integrations a channel's measurement arrives every few blocks, not in each.
  const double longest_ms =
      std::max({cfg_.long_integration.coherent_ms, cfg_.long_integration.noncoherent_ms, cfg_.e1_weak_coherent_ms});
  const auto span = static_cast<std::int64_t>((1e-3 * longest_ms + 0.02) * fs_);
  measuring_ = 0;
  for (auto it = last_measured_sample_.begin(); it != last_measured_sample_.end();) {
    if (block.end_sample - it->second > span) {
      it = last_measured_sample_.erase(it);
    } else {
      ++measuring_;
      ++it;
    }
  }
  KalmanUpdate result;
  if (!ms.empty()) result = nav.update_ranges(ms, innovations, watched);
  for (const ChannelStatus& ch : block.channels) {
    SteeredChannelController& controller = *controller_for(ch.prn);
    if (controller.steered() && ch.ephemeris)
      steer({GnssSystem::gps, ch.prn}, ch.replica_transmit_sow, *ch.ephemeris, controller, nav, block);
  }
  for (const E1ChannelStatus& ch : block.galileo_channels) {
    SteeredE1Controller& controller = *e1_controller_for(ch.svid);
    if (controller.steered() && ch.ephemeris)
      steer({GnssSystem::galileo, ch.svid}, ch.replica_transmit_sow, *ch.ephemeris, controller, nav, block);
  }
  return result;
}

double UltraTightTracker::transmit_sow(const SamplePrediction& p, const AidedNavigator& nav) {
  const RangePrediction& g = p.range;
  return p.t_rx.sow - (g.pseudorange_m(p.clock_bias_m) + nav.residual_delay_m(g)) / gps::kSpeedOfLight_mps;
}

double UltraTightTracker::doppler_hz(const SamplePrediction& p, const AidedNavigator& nav) {
  const RangePrediction& g = p.range;
  return -(g.pseudorange_rate_mps(p.antenna_velocity_ecef_mps, nav.clock_drift_mps()) +
           nav.residual_delay_rate_mps(g)) /
         gps::kL1Wavelength_m;
}

std::optional<SignalPrediction> UltraTightTracker::predict_signal(int prn, const Ephemeris& eph,
                                                                  const AidedNavigator& nav, const BlockSnapshot& block,
                                                                  double elevation_mask_rad) const {
  const std::optional<SamplePrediction> now = predict_at(eph, block.end_sample, nav, block);
  if (!now || now->range.elevation_rad < elevation_mask_rad) return std::nullopt;
  // The Doppler's rate over the next second (the satellite's motion; the vehicle's
  // acceleration of the last IMU interval).
  const std::optional<SamplePrediction> later = predict_at(eph, block.end_sample + std::llround(fs_), nav, block);
  if (!later) return std::nullopt;
  SignalPrediction s;
  s.prn = prn;
  s.sample = block.end_sample;
  s.transmit_sow = transmit_sow(*now, nav);
  s.doppler_hz = doppler_hz(*now, nav);
  s.doppler_rate_hzps = doppler_hz(*later, nav) - s.doppler_hz;
  const AidedNavigator::PredictionSigma sigma = nav.prediction_sigma(now->range);
  // The broadcast orbit and clock add a few metres the filter does not hold.
  const double range_sigma_m = std::hypot(sigma.range_m, kBroadcastRangeSigma_m);
  s.code_sigma_chips = range_sigma_m / gps::kSpeedOfLight_mps * gps::kCodeRate_cps;
  s.doppler_sigma_hz = sigma.rate_mps / gps::kL1Wavelength_m;
  s.elevation_deg = now->range.elevation_rad * 180.0 / M_PI;
  return s;
}

std::optional<NcoCommand> UltraTightTracker::command_for(const SatelliteId& sat, const SamplePrediction& predicted,
                                                         double replica_sow, const AidedNavigator& nav) {
  const double tt_predicted = transmit_sow(predicted, nav);
  const double correction_chips = seconds_of_week_difference(tt_predicted, replica_sow) * gps::kCodeRate_cps;
  if (std::abs(correction_chips) > cfg_.max_code_correction_chips) {
    // The replica and the filter disagree by more than a plausible tracking error: the
    // channel or the filter is wrong. Once per episode: the controller takes the channel
    // again at its next integration.
    if (disagreeing_.insert(sat).second)
      spdlog::warn("{}: filter and replica differ by {:.1f} chips; channel back to scalar tracking",
                   sat.system == GnssSystem::gps ? fmt::format("PRN {:2d}", sat.prn) : sat.to_string(),
                   correction_chips);
    return std::nullopt;
  }
  disagreeing_.erase(sat);
  NcoCommand cmd;
  cmd.carrier_doppler_hz = doppler_hz(predicted, nav);
  cmd.code_rate_cps = gps::kCodeRate_cps * (1.0 + cmd.carrier_doppler_hz / gps::kL1_Hz);
  cmd.code_phase_correction_chips = correction_chips;
  return cmd;
}

template <class Controller>
void UltraTightTracker::steer(const SatelliteId& sat, const std::optional<double>& replica_sow,
                              const BroadcastEphemeris& eph, Controller& controller, const AidedNavigator& nav,
                              const BlockSnapshot& block) {
  if (!replica_sow) return;
  const std::optional<SamplePrediction> predicted = predict_at(eph, block.end_sample, nav, block);
  if (!predicted) return;
  if (const std::optional<NcoCommand> cmd = command_for(sat, *predicted, *replica_sow, nav)) controller.publish(*cmd);
  else controller.publish_release();
}

void UltraTightTracker::release_all() {
  for (auto& [prn, controller] : controllers_) controller.release();
  for (auto& [svid, controller] : e1_controllers_) controller.release();
}

}  // namespace deepnav::aiding
