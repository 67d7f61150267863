#include "aiding/ultra_tight_tracker.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

#include "ins/gps_time.hpp"
#include "receiver/tracking_loops.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav::aiding {
namespace {

constexpr double kChip_m = gps::kSpeedOfLight_mps / gps::kCodeRate_cps;
constexpr double kRateWindow_s = 0.1;   // phase-locked rate: adjoining windows of the mean frequency
// Rate sigma floors (m/s). Phase windows: what the model leaves out inside a window (the
// Doppler's second derivative around the window's middle, the INS velocity error there).
// The receiver clock's white frequency noise is common to every channel (3 cm/s over
// 100 ms for a TCXO with h0 = 2e-21); the clock drift state takes it, its random walk
// moves it by that much within a window. Frequency discriminator: more dynamics left over
// across one integration.
constexpr double kPhaseRateFloor_mps = 0.005;
constexpr double kDiscriminatorRateFloor_mps = 0.02;
constexpr double kMaxWindowPhaseError_cycles = 0.1;  // a window's ends: Costas error within +-36 deg

/// 1-sigma of the normalised early-minus-late envelope discriminator (chips) for spacing d
/// and coherent time T (Kaplan & Hegarty, noncoherent E-L power with normalisation).
double code_sigma_chips(double cn0_dbhz, double t_s, double spacing_chips) {
  const double snr = std::pow(10.0, cn0_dbhz / 10.0) * t_s;
  return std::sqrt(spacing_chips / (4.0 * snr) * (1.0 + 2.0 / ((2.0 - spacing_chips) * snr)));
}

/// Variance (rad^2) of the Costas phase discriminator over one integration of T.
double phase_variance_rad2(double cn0_dbhz, double t_s) {
  const double snr = std::pow(10.0, cn0_dbhz / 10.0) * t_s;
  return 1.0 / (2.0 * snr) * (1.0 + 1.0 / (2.0 * snr));
}

/// 1-sigma (Hz) of a mean frequency from two phases `span_s` apart, each with variance
/// `phase_var_rad2`: the carrier phase at both ends of a window, or the cross/dot
/// discriminator between two adjoining integrations (span T).
double mean_frequency_sigma_hz(double phase_var_rad2, double span_s) {
  return std::sqrt(2.0 * phase_var_rad2) / (2.0 * M_PI * span_s);
}

}  // namespace

bool UltraTightTracker::can_steer(bool bit_synced, const TrackingChannel& ch, const NavDecoder& nav) const {
  return bit_synced && ch.state() != ChannelState::lost && nav.synchronised() && rx_.ephemeris(ch.prn()) != nullptr;
}

int UltraTightTracker::count_steerable() {
  int n = 0;
  rx_.for_each_channel([&](TrackingChannel& ch, const NavDecoder& nav) {
    if (can_steer(ch.bit_edge_period().has_value(), ch, nav)) ++n;
  });
  return n;
}

std::optional<UltraTightTracker::SamplePrediction> UltraTightTracker::predict_at(const Ephemeris& eph,
                                                                                 std::int64_t sample,
                                                                                 const AidedNavigator& nav) const {
  const std::optional<GpsTime> t_rx = rx_.receiver_time(sample);
  if (!t_rx) return std::nullopt;
  SamplePrediction p;
  p.t_rx = *t_rx;
  const double t_s = static_cast<double>(sample) / rx_.sample_rate_hz();
  p.offset_s = t_s - nav.time_s();
  p.clock_bias_m = nav.clock_bias_m() + nav.clock_drift_mps() * p.offset_s;
  p.antenna_velocity_ecef_mps = nav.antenna_velocity_ecef_at(t_s);
  p.range = predict_range(eph, *t_rx, p.clock_bias_m, nav.antenna_ecef_at(t_s), p.antenna_velocity_ecef_mps, rx_.iono(),
                          rx_.atmosphere());
  return p;
}

UltraTightTracker::UltraTightTracker(ScalarReceiver& receiver, UltraTightConfig config,
                                     const RangeErrorModel& range_errors, const SatelliteFaultMonitor* faults)
    : rx_(receiver), cfg_(config), range_errors_(range_errors), faults_(faults) {}

bool UltraTightTracker::on_epoch(const CorrelatorEpoch& e, TrackingChannel& ch, const NavDecoder& nav,
                                 Engagement engagement) {
  ChannelMemory& mem = memory_[e.prn];
  const std::int64_t end = e.first_sample + e.samples;
  std::optional<double> doppler;
  if (mem.end_sample == e.first_sample) {
    // Consecutive integrations: the phase advance between their prompts is the mean
    // residual frequency over the interval between their centres.
    // A phase correction applied between them turned the replica: add its share back.
    doppler = 0.5 * (mem.doppler_hz + e.carrier_doppler_hz) + fll_frequency_error_hz(mem.prompt, e.prompt, e.integration_s) +
              mem.applied_correction_cycles / e.integration_s;
  }
  mem.applied_correction_cycles = 0.0;
  mem.prompt = e.prompt;
  mem.end_sample = end;
  mem.doppler_hz = e.carrier_doppler_hz;
  mem.last_cn0_dbhz = e.cn0_dbhz;
  const bool was_steered = steered_.count(e.prn) > 0;
  bool engaged = engagement == Engagement::all;
  if (engagement == Engagement::faded_only) {
    // C/N0 reads 0 until the channel's estimator window is full: not a fade.
    const bool faded = e.cn0_dbhz > 0.0 && e.cn0_dbhz < cfg_.faded_below_dbhz;
    engaged = faded || (was_steered && e.cn0_dbhz < cfg_.recovered_above_dbhz);
  }
  if (!engaged || !can_steer(e.bit_synced, ch, nav) || !rx_.receiver_time(end)) {
    if (was_steered) {
      steered_.erase(e.prn);
      ch.set_loss_detection(true);
    }
    mem.rate_window_start.reset();  // a window must lie inside one steered stretch
    return false;
  }
  if (!was_steered) {
    steered_[e.prn] = true;
    ch.set_loss_detection(false);
    spdlog::debug("PRN {:2d}: steered by the navigation filter", e.prn);
  }
  if (cfg_.carrier_phase_tracking) mem.phase_correction_cycles = cfg_.carrier_phase_gain * costas_phase_error_cycles(e.prompt);
  const std::int64_t mid = e.first_sample + e.samples / 2;
  const std::optional<double> tt = transmit_time_sow(nav, ch, mid);
  if (!tt) return true;
  DiscriminatorSample d;
  d.prn = e.prn;
  d.mid_sample = mid;
  d.replica_transmit_sow = *tt;
  d.code_error_chips = dll_code_error_chips(e.early, e.late, cfg_.spacing_chips);
  // The phase is only as good as the Costas error is small: near its +-0.25 cycle range a
  // noise sample wraps it by half a cycle (5 Hz over a window). A large error means the
  // phase loop is stressed (the filter's Doppler still off after a start); then the
  // frequency discriminator serves.
  const double costas_cycles = costas_phase_error_cycles(e.prompt);
  if (cfg_.carrier_phase_tracking && e.pll_lock && std::abs(costas_cycles) < kMaxWindowPhaseError_cycles) {
    // Phase-locked: the mean frequency over adjoining windows of the carrier phase, a delta
    // range every window. The phase at an integration's end is the NCO's accumulated phase
    // (Costas corrections included) plus the Costas error still left: the loop's lag then
    // cancels, so the filter's own corrections to the NCO Doppler do not echo back into
    // the next window. The frequency discriminator across NCO updates is biased that way
    // (up to 0.6 m of position error on the aircraft circle). Without the phase loop the
    // accumulated phase would only repeat the filter's own commands.
    const double phase_cycles = e.carrier_phase_cycles + costas_cycles;
    const auto window = static_cast<std::int64_t>(std::llround(kRateWindow_s * rx_.sample_rate_hz()));
    if (mem.rate_window_start && end - *mem.rate_window_start >= window - e.samples / 2) {
      d.rate_window_s = static_cast<double>(end - *mem.rate_window_start) / rx_.sample_rate_hz();
      d.doppler_hz = (phase_cycles - mem.rate_window_start_cycles) / d.rate_window_s;
      d.doppler_sample = (*mem.rate_window_start + end) / 2;
    }
    if (!mem.rate_window_start || d.doppler_hz) {
      mem.rate_window_start = end;
      mem.rate_window_start_cycles = phase_cycles;
    }
  } else {
    // Frequency tracking only (weak signals): the cross/dot discriminator between the two
    // adjoining integrations, referred to their common edge.
    mem.rate_window_start.reset();
    d.doppler_hz = doppler;
    d.doppler_sample = e.first_sample;
  }
  d.cn0_dbhz = e.cn0_dbhz;
  d.integration_s = e.integration_s;
  d.ephemeris = *rx_.ephemeris(e.prn);
  queued_.push_back(d);
  return true;
}

std::optional<RangeMeasurement> UltraTightTracker::to_measurement(const DiscriminatorSample& d,
                                                                  const AidedNavigator& nav) const {
  const std::optional<SamplePrediction> p = predict_at(d.ephemeris, d.mid_sample, nav);
  if (!p) return std::nullopt;
  RangeMeasurement m;
  m.prn = d.prn;
  m.time_offset_s = p->offset_s;
  m.geometry = p->range;
  const double t_tx = d.replica_transmit_sow + d.code_error_chips / gps::kCodeRate_cps;
  m.pseudorange_m = gps::kSpeedOfLight_mps * seconds_of_week_difference(p->t_rx.sow, t_tx);
  // Discriminator noise plus what the range models leave, by elevation (the PVT's weights),
  // shared by every integration of the same second (range_weight.hpp).
  const double code_sigma = code_sigma_chips(d.cn0_dbhz, d.integration_s, cfg_.spacing_chips) * kChip_m;
  m.pseudorange_sigma_m = std::sqrt(code_sigma * code_sigma +
                                    range_errors_.model_variance_per_row_m2(p->range.elevation_rad, d.integration_s));
  if (d.doppler_hz) {
    // Predicted where the Doppler refers to (doppler_sample), not at mid_sample.
    const std::optional<SamplePrediction> at_rate = predict_at(d.ephemeris, d.doppler_sample, nav);
    if (!at_rate) return m;
    m.rate_at_own_time = true;
    m.rate_geometry = at_rate->range;
    m.rate_time_offset_s = at_rate->offset_s;
    m.rate_mps = -gps::kL1Wavelength_m * *d.doppler_hz;
    // One integration's phase noise at both ends of the window or of the discriminator's
    // span (adjoining windows share an end, so their errors are negatively correlated:
    // taking them as independent understates what a run of windows says).
    const bool phase_window = d.rate_window_s > 0.0;
    const double sigma_hz = mean_frequency_sigma_hz(phase_variance_rad2(d.cn0_dbhz, d.integration_s),
                                                    phase_window ? d.rate_window_s : d.integration_s);
    m.rate_sigma_mps =
        std::hypot(sigma_hz * gps::kL1Wavelength_m, phase_window ? kPhaseRateFloor_mps : kDiscriminatorRateFloor_mps);
  }
  return m;
}

std::vector<RangeResidual> UltraTightTracker::take_mean_pseudorange_residuals() {
  std::vector<RangeResidual> out;
  for (const auto& [prn, sum] : residual_sums_) {
    RangeResidual r = sum.latest;
    r.residual_m = sum.sum_m / sum.count;
    out.push_back(r);
  }
  residual_sums_.clear();
  return out;
}

UpdateResult UltraTightTracker::update_and_steer(AidedNavigator& nav, std::int64_t end_sample, bool measure,
                                                 std::vector<SatelliteInnovation>* innovations) {
  std::vector<RangeMeasurement> ms, watched;
  for (const DiscriminatorSample& d : queued_) {
    if (!measure || d.cn0_dbhz < cfg_.min_cn0_dbhz) continue;
    const std::optional<RangeMeasurement> m = to_measurement(d, nav);
    if (!m) continue;
    (faults_ && faults_->excluded(d.prn) ? watched : ms).push_back(*m);
    if (m->pseudorange_m) {
      const RangePrediction& g = m->geometry;
      const double predicted = g.pseudorange_m(nav.clock_bias_m() + nav.clock_drift_mps() * m->time_offset_s) +
                               nav.residual_delay_m(g);
      ResidualSum& sum = residual_sums_[d.prn];
      sum.latest = {g.los_ecef, g.elevation_rad, d.cn0_dbhz, *m->pseudorange_m - predicted};
      sum.sum_m += sum.latest.residual_m;
      ++sum.count;
    }
  }
  queued_.clear();
  measuring_ = static_cast<int>(ms.size());
  UpdateResult result;
  if (!ms.empty()) result = nav.update_ranges(ms, innovations, watched);
  rx_.for_each_channel([&](TrackingChannel& ch, const NavDecoder& decoder) {
    if (steered_.count(ch.prn())) steer(ch, decoder, nav, end_sample);
  });
  return result;
}

void UltraTightTracker::steer(TrackingChannel& ch, const NavDecoder& decoder, const AidedNavigator& nav,
                              std::int64_t sample) {
  const std::optional<double> tt_replica = transmit_time_sow(decoder, ch, sample);
  const Ephemeris* eph = rx_.ephemeris(ch.prn());
  if (!tt_replica || !eph) return;
  const std::optional<SamplePrediction> predicted = predict_at(*eph, sample, nav);
  if (!predicted) return;
  const RangePrediction& p = predicted->range;
  const double tt_predicted =
      predicted->t_rx.sow - (p.pseudorange_m(predicted->clock_bias_m) + nav.residual_delay_m(p)) / gps::kSpeedOfLight_mps;
  const double correction_chips = seconds_of_week_difference(tt_predicted, *tt_replica) * gps::kCodeRate_cps;
  if (std::abs(correction_chips) > cfg_.max_code_correction_chips) {
    // The replica and the filter disagree by more than a plausible tracking error: the
    // channel or the filter is wrong. Give the channel back to its own loops.
    spdlog::warn("PRN {:2d}: filter and replica differ by {:.1f} chips; channel back to scalar tracking", ch.prn(),
                 correction_chips);
    steered_.erase(ch.prn());
    ch.set_loss_detection(true);
    return;
  }
  ChannelMemory& mem = memory_[ch.prn()];
  NcoCommand cmd;
  cmd.carrier_doppler_hz = -(p.pseudorange_rate_mps(predicted->antenna_velocity_ecef_mps, nav.clock_drift_mps()) +
                             nav.residual_delay_rate_mps(p)) /
                           gps::kL1Wavelength_m;
  cmd.code_rate_cps = gps::kCodeRate_cps * (1.0 + cmd.carrier_doppler_hz / gps::kL1_Hz);
  cmd.code_phase_correction_chips = correction_chips;
  if (cfg_.carrier_phase_tracking && mem.phase_correction_cycles != 0.0) {
    cmd.carrier_phase_correction_cycles = mem.phase_correction_cycles;
    mem.applied_correction_cycles += mem.phase_correction_cycles;
    mem.phase_correction_cycles = 0.0;
  }
  ch.apply(cmd);
}

void UltraTightTracker::release_all() {
  rx_.for_each_channel([&](TrackingChannel& ch, const NavDecoder&) {
    if (steered_.count(ch.prn())) ch.set_loss_detection(true);
  });
  steered_.clear();
  queued_.clear();
}

}  // namespace deepnav::aiding
