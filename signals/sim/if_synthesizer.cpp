#include "signals/sim/if_synthesizer.hpp"

#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <exception>
#include <filesystem>
#include <fstream>
#include <future>
#include <stdexcept>
#include <system_error>

#include "ins/frames.hpp"
#include "ins/imu_model.hpp"
#include "ins/rotations.hpp"
#include "ins/sim/simulated_imu_file.hpp"
#include "ins/sim/trajectory_csv.hpp"
#include "ins/sim/trajectory_presets.hpp"
#include "signals/ca_code.hpp"
#include "signals/galileo/e1_codes.hpp"
#include "signals/galileo/galileo_constants.hpp"
#include "signals/galileo/gst.hpp"
#include "signals/gps_constants.hpp"
#include "signals/if_metadata.hpp"
#include "signals/lnav_message.hpp"
#include "signals/sim/e1_waveform.hpp"
#include "signals/sim/error_world.hpp"
#include "signals/sim/floor_div.hpp"
#include "signals/sim/front_end.hpp"
#include "signals/sim/if_file_writer.hpp"
#include "signals/sim/inav_broadcast.hpp"
#include "signals/sim/line_of_sight.hpp"
#include "signals/sim/lnav_broadcast.hpp"
#include "signals/sim/multipath_channel.hpp"
#include "signals/sim/parallel_ranges.hpp"
#include "signals/sim/receiver_clock_model.hpp"
#include "signals/sim/satellite_selection.hpp"
#include "signals/sim/satellite_signal_kernel.hpp"
#include "signals/sim/satellite_signal_model.hpp"
#include "signals/text_output_file.hpp"

namespace deepnav {
namespace {

constexpr int kEpochsPerChunk = 100;  // 100 ms of samples per parallel chunk
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
constexpr std::int64_t kMsPerWeek = 604800000;
constexpr double kChip_m = gps::kSpeedOfLight_mps / gps::kCodeRate_cps;
/// sat_truth.csv's multipath_m is the error of an ideal E-L DLL with this (the receiver's default) spacing.
constexpr double kTruthDllSpacing_chips = 0.5;

/// GST's start epoch in milliseconds of GPS time: the start of GPS week 1024 (GST and GPS time
/// share seconds and week boundaries; their labels differ by 1024 weeks).
constexpr std::int64_t kGstOriginMs = static_cast<std::int64_t>(galileo::kGstWeekOffsetFromGps) * kMsPerWeek;
/// Milliseconds per E1 code period (and I/NAV symbol): 4.
constexpr std::int64_t kE1PeriodMs = 4;
constexpr double kE1Chips = galileo::kE1CodeLength_chips;

struct SatelliteRun {
  SatelliteId id;
  Ephemeris eph;  ///< GPS satellites
  std::optional<galileo::GalileoEphemeris> galileo;
  const CaCodeChips* code = nullptr;
  std::unique_ptr<LnavSignTable> bits;
  std::unique_ptr<InavSymbolTable> symbols;  ///< Galileo: E1-B I/NAV symbols by GST code period
  std::unique_ptr<E1WaveformTables> e1;      ///< Galileo: the composite E1 waveform of its codes
  /// A key of its own for the seeded per-satellite models (multipath): the GPS PRN, 100 + the
  /// Galileo SVID.
  int model_key() const { return id.system == GnssSystem::gps ? id.prn : 100 + id.prn; }
};

/// Receiver-side state at an epoch boundary plus every satellite's signal there.
struct BoundaryState {
  ReceiverInstant rx;
  TrajectoryState traj;
  std::vector<SatelliteInstant> sats;
  std::vector<PathSet> paths;  ///< per satellite; empty without a multipath model
};

/// How messages name a satellite: "PRN 5" for GPS (as they always have), "E11" for Galileo.
std::string satellite_label(const SatelliteId& id) {
  return id.system == GnssSystem::gps ? fmt::format("PRN {}", id.prn) : id.to_string();
}

double ramp_offset_db(const Cn0Spec& spec, double t_s) {
  if (spec.ramp_delta_db == 0.0 || t_s <= spec.ramp_start_s) return 0.0;
  if (t_s >= spec.ramp_end_s) return spec.ramp_delta_db;
  return spec.ramp_delta_db * (t_s - spec.ramp_start_s) / (spec.ramp_end_s - spec.ramp_start_s);
}

/// The front end for a scenario. Without AGC the gain is fixed where the AGC would settle
/// on thermal noise alone, so a jammer then drives the converter into saturation.
FrontEndConfig make_front_end_config(const Scenario& sc) {
  FrontEndConfig fe;
  fe.sample_rate_hz = sc.sample_rate_hz;
  fe.if_hz = sc.if_hz;
  fe.format = sc.format;
  int bits = sc.adc.bits;
  if (bits == 0) bits = sc.format == SampleFormat::gr_complex ? 0 : value_bits(sc.format);
  fe.adc.bits = bits;
  fe.adc.agc_enabled = sc.adc.agc;
  fe.adc.agc_time_constant_s = sc.adc.agc_time_constant_s;
  const double noise_rms = std::sqrt(sc.sample_rate_hz / 2.0);  // per component, N0 = 1
  fe.adc.fixed_gain = optimum_quantizer_rms(bits) / noise_rms;
  fe.cn0_ref_dbhz = sc.cn0.reference_dbhz();
  fe.jammers = sc.jammers;
  return fe;
}

}  // namespace

struct IfSynthesizer::Impl {
  Scenario sc;
  NavData nav;
  std::unique_ptr<Trajectory> trajectory;
  std::vector<SatelliteRun> runs;
  std::vector<SynthesizedSatellite> info;
  std::int64_t samples_per_epoch = 0;
  std::int64_t epochs = 0;
  std::int64_t ref_ms_abs = 0;                  ///< whole ms of the start time, counted from the GPS time origin
  double ref_frac_s = 0.0;                      ///< start time minus ref_ms_abs (below 1 ms)
  GpsTime ref_time{};                           ///< the reference epoch as a GpsTime
  std::unique_ptr<ErrorWorld> world;            ///< the truth models the signal follows
  std::unique_ptr<MultipathChannel> multipath;  ///< null for model none: no extra work at all
  double gst_minus_gpst_s = 0.0;                ///< GGTO at the start, from the file's GAGP (0 without)

  Impl(Scenario s, NavData n) : sc(std::move(s)), nav(std::move(n)) {
    samples_per_epoch = std::llround(sc.sample_rate_hz / 1000.0);
    epochs = std::llround(sc.duration_s * 1000.0);
    const double sow_ms = std::floor(sc.start_time.sow * 1000.0);
    ref_ms_abs = static_cast<std::int64_t>(sc.start_time.week) * kMsPerWeek + static_cast<std::int64_t>(sow_ms);
    ref_frac_s = sc.start_time.sow - sow_ms / 1000.0;
    ref_time = GpsTime{sc.start_time.week, sow_ms / 1000.0};
    if (nav.ggto.valid)
      gst_minus_gpst_s = galileo::gst_minus_gpst_s(nav.ggto, galileo::gst_from_gps_time(sc.start_time));
    trajectory = make_trajectory();
    world =
        std::make_unique<ErrorWorld>(sc.errors, AtmosphereSwitches{sc.ionosphere, sc.troposphere}, sc.seed,
                                     sc.start_time, sc.duration_s, wgs84::ecef_to_llh(trajectory->at(0.0).r_ecef_m));
    choose_satellites();
    if (sc.errors.multipath.model != MultipathSpec::Model::none) make_multipath();
  }

  /// The channel over the whole run; the land-mobile model reads each satellite's
  /// elevation and the antenna's speed along the trajectory (receiver time since the start).
  void make_multipath() {
    std::vector<int> prns;
    for (const auto& run : runs) prns.push_back(run.model_key());
    auto state_at = [this](double t_s) { return trajectory->at(std::clamp(t_s, 0.0, trajectory->duration_s())); };
    auto elevation = [&](std::size_t sat, double t_s) {
      const TrajectoryState st = state_at(t_s);
      const LineOfSight los = line_of_sight_of(runs[sat], sc.start_time.plus_seconds(t_s), st.r_ecef_m, st.v_ecef_mps);
      return look_angles(st.r_ecef_m, los.r_sat_ecef_m).elevation_rad;
    };
    auto speed = [&](double t_s) { return state_at(t_s).v_ned_mps.norm(); };
    multipath = std::make_unique<MultipathChannel>(sc.errors.multipath, sc.seed, prns, sc.duration_s, elevation, speed);
  }

  LineOfSight line_of_sight_of(const SatelliteRun& run, const GpsTime& t, const Eigen::Vector3d& r,
                               const Eigen::Vector3d& v) const {
    if (run.galileo) return line_of_sight(*run.galileo, gst_minus_gpst_s, t, r, v);
    return line_of_sight(run.eph, t, r, v);
  }

  std::unique_ptr<Trajectory> make_trajectory() const {
    if (!sc.trajectory.csv_path.empty()) {
      auto traj = load_csv_trajectory(sc.trajectory.csv_path);
      try {
        traj->at(0.0);
        traj->at(sc.duration_s);
      } catch (const std::out_of_range&) {
        throw std::runtime_error(fmt::format("{}: trajectory file '{}' must cover the run: times 0 to {} s",
                                             sc.source_path, sc.trajectory.csv_path, sc.duration_s));
      }
      return traj;
    }
    return make_preset_trajectory(sc.trajectory.preset, sc.trajectory.start, sc.trajectory.heading_rad,
                                  sc.duration_s + 1.0);
  }

  void choose_satellites() {
    SelectionRequest request;
    request.start = sc.start_time;
    request.duration_s = sc.duration_s;
    request.elevation_mask_rad = sc.elevation_mask_rad;
    request.prns = sc.prns;
    request.galileo_prns = sc.galileo_prns;
    request.max_satellites = sc.max_satellites;
    request.systems = sc.systems;
    request.gst_minus_gpst_s = gst_minus_gpst_s;
    if (includes_system(sc.systems, GnssSystem::galileo)) require_galileo_records();
    const auto chosen = select_satellites(nav, *trajectory, request);
    if (chosen.empty()) {
      throw std::runtime_error(fmt::format("{}: no healthy satellite of '{}' is above the elevation mask at the start",
                                           sc.source_path, sc.nav_file));
    }
    // The satellite transmitted what arrives during the run between ~90 ms (plus the
    // receiver clock bias) before the start and the end; a second of margin each side.
    const double clock_span_s = std::abs(sc.clock.bias_s) + std::abs(sc.clock.drift_sps) * sc.duration_s + 1.0;
    const auto first_ms = ref_ms_abs - static_cast<std::int64_t>(std::ceil(clock_span_s * 1000.0)) - 1000;
    const auto last_ms = ref_ms_abs + epochs + static_cast<std::int64_t>(std::ceil(clock_span_s * 1000.0)) + 1000;
    for (const auto& c : chosen) {
      SatelliteRun run;
      run.id = c.id;
      if (c.id.system == GnssSystem::galileo) {
        run.galileo = *c.galileo_ephemeris;
        // GST code periods of 4 ms, counted from GST's start epoch.
        run.symbols =
            std::make_unique<InavSymbolTable>(nav, *run.galileo, floor_div(first_ms - kGstOriginMs, kE1PeriodMs),
                                              floor_div(last_ms - kGstOriginMs, kE1PeriodMs));
        run.e1 = std::make_unique<E1WaveformTables>(c.prn);
      } else {
        run.eph = *c.ephemeris;
        run.code = &ca_code_chips(c.prn);
        run.bits = std::make_unique<LnavSignTable>(synthesized_lnav_content(nav, run.eph), first_ms, last_ms);
      }
      runs.push_back(std::move(run));
      SynthesizedSatellite sat{c.prn, c.elevation_rad * kRadToDeg, c.azimuth_rad * kRadToDeg, 0, 0, 0};
      sat.id = c.id;
      info.push_back(sat);
    }
  }

  /// A Galileo scenario needs the file's Galileo records for its start: without them the
  /// error names the file rather than saying that no satellite is in view.
  void require_galileo_records() const {
    const galileo::GstTime start = galileo::gst_from_gps_time(sc.start_time, gst_minus_gpst_s);
    for (int svid = 1; svid <= galileo::kMaxPrn; ++svid) {
      if (select_galileo_ephemeris(nav, svid, start) != nullptr) return;
    }
    throw std::runtime_error(fmt::format(
        "{}: systems lists galileo, but the navigation file '{}' has no healthy E1-B I/NAV Galileo record valid at "
        "the start (GPS week {}, second {:.3f}; {} Galileo records in the file)",
        sc.source_path, sc.nav_file, sc.start_time.week, sc.start_time.sow, nav.galileo_ephemerides.size()));
  }

  /// The code phase within the satellite's code period of an unwrapped code phase counted
  /// (as SatelliteInstant::code_chips is) from the reference epoch: 1023 chips of C/A, 4092 of
  /// E1, whose periods start at GST multiples of 4 ms.
  double code_phase_in_period(const SatelliteRun& run, double code_chips) const {
    if (!run.galileo) return code_chips - std::floor(code_chips / 1023.0) * 1023.0;
    const double ms = std::floor(code_chips / 1023.0);
    const std::int64_t abs_ms = ref_ms_abs + static_cast<std::int64_t>(ms);
    const std::int64_t ms_in_period = abs_ms - floor_div(abs_ms, kE1PeriodMs) * kE1PeriodMs;
    return static_cast<double>(ms_in_period) * 1023.0 + (code_chips - ms * 1023.0);
  }

  ReceiverInstant receiver_at(std::int64_t k, const ClockState& clock, double bias0_s, TrajectoryState& traj) const {
    const double t_rcv_since_start = static_cast<double>(k) * 1e-3;
    double tau = t_rcv_since_start - (clock.bias_s - bias0_s);
    tau = std::clamp(tau, 0.0, trajectory->duration_s());
    traj = trajectory->at(tau);
    ReceiverInstant rx;
    rx.t_rcv_rel_s = ref_frac_s + t_rcv_since_start;
    rx.t_true = sc.start_time.plus_seconds(t_rcv_since_start - clock.bias_s);
    rx.r_ecef_m = traj.r_ecef_m;
    rx.v_ecef_mps = traj.v_ecef_mps;
    rx.llh = wgs84::ecef_to_llh(traj.r_ecef_m);
    rx.clock_bias_s = clock.bias_s;
    rx.clock_drift_sps = clock.drift_sps;
    return rx;
  }

  double cn0_dbhz(std::size_t sat, const SatelliteInstant& s, double t_s) const {
    const Cn0Spec& spec = sc.cn0;
    double cn0 = spec.fixed_dbhz;
    if (spec.model == Cn0Spec::Model::elevation) {
      cn0 = spec.horizon_dbhz + (spec.zenith_dbhz - spec.horizon_dbhz) * std::sin(std::max(0.0, s.elevation_rad));
    }
    const auto& overrides = runs[sat].id.system == GnssSystem::gps ? spec.per_prn_dbhz : spec.galileo_per_svid_dbhz;
    if (const auto it = overrides.find(runs[sat].id.prn); it != overrides.end()) cn0 = it->second;
    // The scenario's C/N0 is an isotropic antenna's; the antenna pattern comes on top.
    return cn0 + s.antenna_gain_db + ramp_offset_db(spec, t_s);
  }

  /// An outage without a satellite list blocks every satellite of every system.
  bool in_outage(const SatelliteId& id, double t_s) const {
    for (const auto& o : sc.outages) {
      const std::vector<int>& listed = id.system == GnssSystem::gps ? o.prns : o.galileo_prns;
      if (t_s >= o.start_s && t_s < o.end_s &&
          (o.all_satellites() || std::find(listed.begin(), listed.end(), id.prn) != listed.end())) {
        return true;
      }
    }
    return false;
  }

  /// Signal amplitude for a satellite over the epoch that starts at t_s (0 when blocked).
  float amplitude(std::size_t sat, const SatelliteInstant& s, double t_s) const {
    if (s.elevation_rad <= 0.0 || in_outage(runs[sat].id, t_s)) return 0.0f;
    return static_cast<float>(std::pow(10.0, cn0_dbhz(sat, s, t_s) / 20.0));
  }

  BoundaryState boundary(std::int64_t k, const ClockState& clock, double bias0_s) const {
    BoundaryState b;
    b.rx = receiver_at(k, clock, bias0_s, b.traj);
    b.sats.reserve(runs.size());
    for (const auto& run : runs) {
      b.sats.push_back(run.galileo
                           ? evaluate_satellite(*run.galileo, gst_minus_gpst_s, nav.iono, *world, b.rx, sc.if_hz)
                           : evaluate_satellite(run.eph, nav.iono, *world, b.rx, sc.if_hz));
    }
    if (multipath) {
      b.paths.reserve(runs.size());
      const double t_s = static_cast<double>(k) * 1e-3;
      for (std::size_t s = 0; s < runs.size(); ++s)
        b.paths.push_back(multipath->paths(s, t_s, b.sats[s].elevation_rad));
    }
    return b;
  }

  /// Every satellite's code must advance at the chipping rate give or take the Doppler of
  /// a physical range rate over the epoch k (1 ms) from boundary a to b. Anything else
  /// (an orbit from absurd broadcast values, a trajectory that jumps) is an error naming
  /// the satellite and time, before the signal kernels see it.
  void check_signal_rates(std::int64_t k, const BoundaryState& a, const BoundaryState& b) const {
    // Faster than anything that carries a GPS receiver, LEO satellites included, plus the
    // satellite's own motion: 20 km/s on the line of sight.
    // The receiver clock's drift scales the code rate as a range rate would.
    constexpr double kMaxRangeRate_mps = 2.0e4;
    const double limit_mps = kMaxRangeRate_mps + gps::kSpeedOfLight_mps * std::abs(a.rx.clock_drift_sps);
    for (std::size_t s = 0; s < runs.size(); ++s) {
      const double chips_per_ms = b.sats[s].code_chips - a.sats[s].code_chips;
      const double range_rate_mps = (1.0 - chips_per_ms / 1023.0) * gps::kSpeedOfLight_mps;
      if (std::isfinite(range_rate_mps) && std::abs(range_rate_mps) <= limit_mps) continue;
      throw std::runtime_error(fmt::format(
          "synthesizer: {} at t = {:.3f} s: the signal implies a range rate of {:.4g} m/s (the code advanced "
          "{:.6g} "
          "chips in 1 ms), beyond {:g} m/s: check the scenario's navigation file ({}, {}) and trajectory ({})",
          satellite_label(runs[s].id), static_cast<double>(k) * 1e-3, range_rate_mps, chips_per_ms, limit_mps,
          sc.nav_file, satellite_label(runs[s].id), trajectory->description()));
    }
  }

  /// Adds one path of satellite s over an epoch of n samples whose code and carrier phases
  /// go linearly from (code_a, carrier_a) to (code_b, carrier_b): segments split where the
  /// code period (and possibly the data bit) changes, each with that period's bit.
  void add_path(std::size_t s, int n, double code_a, double code_b, double carrier_a, double carrier_b, float amp,
                float* i_out, float* q_out, float* scratch) const {
    if (runs[s].galileo) {
      add_e1_path(runs[s], n, code_a, code_b, carrier_a, carrier_b, amp, i_out, q_out, scratch);
      return;
    }
    const double code_step = (code_b - code_a) / n;
    const double carrier_step = (carrier_b - carrier_a) / n;
    int first = 0;
    while (first < n) {
      const double chips = code_a + first * code_step;
      const double period = std::floor(chips / gps::kCodeLength_chips);
      const double next_edge = (period + 1.0) * gps::kCodeLength_chips;
      const int last = std::min(n, static_cast<int>(std::ceil((next_edge - code_a) / code_step)));
      const int count = std::max(1, last - first);
      const auto ms = ref_ms_abs + static_cast<std::int64_t>(period);
      SignalSegment seg;
      seg.carrier_phase_cycles = carrier_a + first * carrier_step;
      seg.carrier_step_cycles = carrier_step;
      seg.code_phase_chips = std::clamp(chips - period * gps::kCodeLength_chips, 0.0, 1022.999999);
      seg.code_step_chips = code_step;
      seg.amplitude = amp * static_cast<float>(runs[s].bits->sign_at_ms(ms));
      add_satellite_segment(i_out + first, q_out + first, count, seg, *runs[s].code, scratch);
      first += count;
    }
  }

  /// add_path for a Galileo satellite: segments split at its 4 ms code periods (GST
  /// multiples of 4 ms), each with that period's E1-B symbol and E1-C secondary code chip.
  void add_e1_path(const SatelliteRun& run, int n, double code_a, double code_b, double carrier_a, double carrier_b,
                   float amp, float* i_out, float* q_out, float* scratch) const {
    const double code_step = (code_b - code_a) / n;
    const double carrier_step = (carrier_b - carrier_a) / n;
    const galileo::E1SecondaryChips& secondary = galileo::e1c_secondary_chips();
    int first = 0;
    while (first < n) {
      const double chips = code_a + first * code_step;
      // Whole milliseconds from the reference epoch, then the absolute (GPS-labelled) ms:
      // code periods start at multiples of 4 ms of GST, whose labels are GPS time's.
      const double ms = std::floor(chips / gps::kCodeLength_chips);
      const std::int64_t abs_ms = ref_ms_abs + static_cast<std::int64_t>(ms);
      const std::int64_t period_start_ms = floor_div(abs_ms, kE1PeriodMs) * kE1PeriodMs;
      const double period_start_chips = static_cast<double>(period_start_ms - ref_ms_abs) * gps::kCodeLength_chips;
      const double next_edge = period_start_chips + kE1Chips;
      const int last = std::min(n, static_cast<int>(std::ceil((next_edge - code_a) / code_step)));
      const int count = std::max(1, last - first);
      const std::int64_t period = (period_start_ms - kGstOriginMs) / kE1PeriodMs;
      const int data = run.symbols->sign_at_period(period);
      const int pilot = secondary[static_cast<std::size_t>(
          period - floor_div(period, galileo::kE1cSecondaryLength_chips) * galileo::kE1cSecondaryLength_chips)];
      SignalSegment seg;
      seg.carrier_phase_cycles = carrier_a + first * carrier_step;
      seg.carrier_step_cycles = carrier_step;
      seg.code_phase_chips = std::clamp(chips - period_start_chips, 0.0, kE1Chips - 1e-6);
      seg.code_step_chips = code_step;
      seg.amplitude = amp * static_cast<float>(data);
      add_e1_segment(i_out + first, q_out + first, count, seg, run.e1->levels(data, pilot), scratch);
      first += count;
    }
  }

  /// Adds every satellite's signal for epoch k (between boundaries a and b) into i/q: the
  /// direct path, then (with a multipath model) each echo as a delayed, scaled and
  /// phase-rotated replica with the data bits of its own, delayed, timing.
  void synthesize_epoch(std::int64_t k, const BoundaryState& a, const BoundaryState& b, float* i_out, float* q_out,
                        float* scratch) const {
    constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
    const int n = static_cast<int>(samples_per_epoch);
    const double t_s = static_cast<double>(k) * 1e-3;
    for (std::size_t s = 0; s < runs.size(); ++s) {
      const SatelliteInstant& sa = a.sats[s];
      const SatelliteInstant& sb = b.sats[s];
      const float amp = amplitude(s, sa, t_s);
      if (amp == 0.0f) continue;
      if (!multipath) {
        add_path(s, n, sa.code_chips, sb.code_chips, sa.carrier_cycles, sb.carrier_cycles, amp, i_out, q_out, scratch);
        continue;
      }
      // The path set at the epoch's start holds for the epoch; an echo that is still the
      // same reflector at its end has its delay and phase interpolated across it (its
      // excess code and carrier rates), a new one keeps the start's values.
      const PathSet& pa = a.paths[s];
      const PathSet& pb = b.paths[s];
      const float direct = amp * static_cast<float>(pa.direct_gain);
      if (direct != 0.0f)
        add_path(s, n, sa.code_chips, sb.code_chips, sa.carrier_cycles, sb.carrier_cycles, direct, i_out, q_out,
                 scratch);
      for (int e = 0; e < pa.echo_count; ++e) {
        const EchoPath& ea = pa.echoes[static_cast<std::size_t>(e)];
        const float echo_amp = amp * static_cast<float>(ea.amplitude);
        if (echo_amp == 0.0f) continue;
        EchoPath eb = ea;
        if (e < pb.echo_count && pb.echoes[static_cast<std::size_t>(e)].id == ea.id)
          eb = pb.echoes[static_cast<std::size_t>(e)];
        // Unwrapped phase change over the epoch: well below half a cycle per millisecond.
        double dphi = eb.carrier_phase_rad - ea.carrier_phase_rad;
        dphi -= kTwoPi * std::round(dphi / kTwoPi);
        add_path(s, n, sa.code_chips - ea.excess_delay_m / kChip_m, sb.code_chips - eb.excess_delay_m / kChip_m,
                 sa.carrier_cycles + ea.carrier_phase_rad / kTwoPi,
                 sb.carrier_cycles + (ea.carrier_phase_rad + dphi) / kTwoPi, echo_amp, i_out, q_out, scratch);
      }
    }
  }
};

std::string if_file_name(SampleFormat format) { return fmt::format("if_{}.bin", to_string(format)); }

IfSynthesizer::IfSynthesizer(Scenario scenario, NavData nav)
    : impl_(std::make_unique<Impl>(std::move(scenario), std::move(nav))) {}
IfSynthesizer::~IfSynthesizer() = default;

const std::vector<SynthesizedSatellite>& IfSynthesizer::satellites() const { return impl_->info; }

namespace {

void write_truth_header(TextOutputFile& f) {
  f.write(
      "t_s,gps_week,gps_sow,x_ecef_m,y_ecef_m,z_ecef_m,vx_ecef_mps,vy_ecef_mps,vz_ecef_mps,lat_deg,lon_deg,height_m,"
      "vn_mps,ve_mps,vd_mps,roll_deg,pitch_deg,yaw_deg,clock_bias_s,clock_drift_sps\n");
}

void write_truth_row(TextOutputFile& f, const GpsTime& start, std::int64_t k, const BoundaryState& b) {
  const double t_s = static_cast<double>(k) * 1e-3;
  const GpsTime t = start.plus_seconds(t_s);
  const EulerAngles e = euler_from_quaternion(b.traj.q_b_n);
  const Eigen::Vector3d rpy = Eigen::Vector3d(e.roll_rad, e.pitch_rad, e.yaw_rad) * kRadToDeg;
  f.write(
      fmt::format("{:.3f},{},{:.9f},{:.4f},{:.4f},{:.4f},{:.5f},{:.5f},{:.5f},{:.10f},{:.10f},{:.4f},{:.5f},{:.5f},{:."
                  "5f},{:.6f},{:.6f},"
                  "{:.6f},{:.12e},{:.6e}\n",
                  t_s, t.week, t.sow, b.rx.r_ecef_m.x(), b.rx.r_ecef_m.y(), b.rx.r_ecef_m.z(), b.rx.v_ecef_mps.x(),
                  b.rx.v_ecef_mps.y(), b.rx.v_ecef_mps.z(), b.rx.llh.lat_rad * kRadToDeg, b.rx.llh.lon_rad * kRadToDeg,
                  b.rx.llh.height_m, b.traj.v_ned_mps.x(), b.traj.v_ned_mps.y(), b.traj.v_ned_mps.z(), rpy.x(), rpy.y(),
                  rpy.z(), b.rx.clock_bias_s, b.rx.clock_drift_sps));
}

void write_sat_truth_header(TextOutputFile& f) {
  f.write(
      "t_s,prn,code_phase_chips,doppler_hz,carrier_phase_cycles,cn0_dbhz,elevation_deg,azimuth_deg,pseudorange_m,"
      "range_m,range_rate_mps,iono_m,tropo_m,sat_clock_m,transmitting,iono_broadcast_m,tropo_model_m,orbit_m,"
      "sat_clock_error_m,antenna_gain_db,multipath_m,los_gain_db,echoes\n");
}

}  // namespace

/// The chunk loop shared by run() and the streaming generator: clock steps, epoch
/// boundaries and satellite signals (in parallel), then the front end in sample order.
struct IfChunkGenerator::State {
  const IfSynthesizer::Impl& m;
  FrontEnd front_end;
  ReceiverClockModel clock;
  double bias0;
  unsigned threads;
  std::int64_t n;  ///< samples per epoch
  std::vector<float> i_buf, q_buf;
  std::vector<std::complex<float>> iq;
  std::vector<ClockState> clocks;
  std::vector<BoundaryState> boundaries;  ///< of the last chunk: [0] is its first epoch
  ClockState current;
  std::int64_t k0 = 0;  ///< first epoch of the next chunk

  State(const IfSynthesizer::Impl& impl, unsigned thread_count)
      : m(impl),
        front_end(make_front_end_config(impl.sc), impl.sc.seed, resolved_threads(thread_count)),
        clock(impl.sc.clock.bias_s, impl.sc.clock.drift_sps, impl.sc.clock.h0, impl.sc.clock.h_minus2,
              impl.sc.seed ^ 0x9E3779B97F4A7C15ULL),
        bias0(impl.sc.clock.bias_s),
        threads(resolved_threads(thread_count)),
        n(impl.samples_per_epoch),
        i_buf(static_cast<std::size_t>(kEpochsPerChunk * n)),
        q_buf(i_buf.size()),
        iq(i_buf.size()),
        clocks(kEpochsPerChunk + 1),
        boundaries(kEpochsPerChunk + 1),
        current(clock.state()) {}

  /// Generates the next chunk into `bytes`; returns its epoch count (0 at the end).
  int generate(std::vector<std::byte>& bytes) {
    if (k0 >= m.epochs) {
      bytes.clear();
      return 0;
    }
    const int count = static_cast<int>(std::min<std::int64_t>(kEpochsPerChunk, m.epochs - k0));
    clocks[0] = current;
    for (int j = 1; j <= count; ++j) clocks[j] = clock.step(1e-3);
    current = clocks[count];

    // Boundaries then epochs, each split into contiguous ranges across the workers.
    run_in_ranges(threads, count + 1, [&](int, int a, int b) {
      for (int j = a; j < b; ++j) boundaries[j] = m.boundary(k0 + j, clocks[j], bias0);
    });
    for (int j = 0; j < count; ++j) m.check_signal_rates(k0 + j, boundaries[j], boundaries[j + 1]);
    run_in_ranges(threads, count, [&](int, int a, int b) {
      std::vector<float> scratch(static_cast<std::size_t>(n));
      const auto epoch = static_cast<std::size_t>(n);
      for (int j = a; j < b; ++j) {
        float* i = i_buf.data() + j * n;
        float* q = q_buf.data() + j * n;
        std::fill(i, i + n, 0.0f);
        std::fill(q, q + n, 0.0f);
        m.synthesize_epoch(k0 + j, boundaries[j], boundaries[j + 1], i, q, scratch.data());
        std::complex<float>* out = iq.data() + static_cast<std::size_t>(j) * epoch;
        for (std::size_t s = 0; s < epoch; ++s) out[s] = {i[s], q[s]};
      }
    });
    front_end.process(std::span<std::complex<float>>(iq.data(), static_cast<std::size_t>(count * n)), k0 * n, bytes);
    k0 += count;
    return count;
  }
};

IfChunkGenerator::IfChunkGenerator(std::unique_ptr<State> state) : state_(std::move(state)) {}
IfChunkGenerator::~IfChunkGenerator() = default;

bool IfChunkGenerator::next(std::vector<std::byte>& bytes) { return state_->generate(bytes) > 0; }

std::int64_t IfChunkGenerator::next_sample_index() const { return state_->k0 * state_->n; }

std::unique_ptr<IfChunkGenerator> IfSynthesizer::chunk_generator(unsigned threads) const {
  return std::unique_ptr<IfChunkGenerator>(
      new IfChunkGenerator(std::make_unique<IfChunkGenerator::State>(*impl_, threads)));
}

const Scenario& IfSynthesizer::scenario() const { return impl_->sc; }

std::int64_t IfSynthesizer::total_samples() const { return impl_->epochs * impl_->samples_per_epoch; }

SynthesisSummary IfSynthesizer::run(const std::string& out_dir, const SynthesisOptions& options) {
  Impl& m = *impl_;
  const auto wall_start = std::chrono::steady_clock::now();
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot create output folder '{}': {}", out_dir, ec.message()));

  SynthesisSummary summary;
  summary.if_path = (std::filesystem::path(out_dir) / if_file_name(m.sc.format)).string();
  summary.truth_path = (std::filesystem::path(out_dir) / "truth.csv").string();
  summary.sat_truth_path = (std::filesystem::path(out_dir) / "sat_truth.csv").string();
  summary.scenario_path = (std::filesystem::path(out_dir) / "scenario.yaml").string();

  IfFileWriter if_writer(summary.if_path);
  std::unique_ptr<TextOutputFile> truth, sat_truth;
  if (!options.if_only) {
    truth = std::make_unique<TextOutputFile>(summary.truth_path);
    sat_truth = std::make_unique<TextOutputFile>(summary.sat_truth_path);
    write_truth_header(*truth);
    write_sat_truth_header(*sat_truth);
  }

  // sat_truth.csv's prn column: the GPS PRN as a number in a GPS-only run (as it always was),
  // "G05" / "E11" in every row once Galileo is in the scenario.
  const bool mixed = includes_system(m.sc.systems, GnssSystem::galileo);
  const auto truth_name = [mixed](const SatelliteId& id) { return mixed ? id.to_string() : std::to_string(id.prn); };
  const std::int64_t truth_stride = std::llround(1000.0 / m.sc.truth_rate_hz);
  const std::int64_t sat_stride = std::llround(1000.0 / m.sc.sat_truth_rate_hz);
  const auto n = m.samples_per_epoch;
  IfChunkGenerator::State gen(m, options.threads);
  std::vector<std::byte> bytes, writing;
  // With more than one thread the IF file is written while the next chunk is made (the
  // write, a copy into the page cache, was a fifth of the run and held every worker up).
  const bool write_behind = gen.threads > 1;
  std::future<void> written;

  for (std::int64_t k0 = 0;; k0 += kEpochsPerChunk) {
    const int count = gen.generate(bytes);
    if (count == 0) break;
    const std::vector<BoundaryState>& boundaries = gen.boundaries;
    if (written.valid()) written.get();  // the previous chunk's write, and its error
    if (write_behind) {
      std::swap(writing, bytes);
      written = std::async(std::launch::async, [&if_writer, &writing] { if_writer.write(writing); });
    } else {
      if_writer.write(bytes);
    }
    summary.bytes += static_cast<std::int64_t>((write_behind ? writing : bytes).size());
    if (!options.if_only) {
      for (int j = 0; j < count; ++j) {
        const std::int64_t k = k0 + j;
        const BoundaryState& b = boundaries[j];
        if (k % truth_stride == 0) write_truth_row(*truth, m.sc.start_time, k, b);
        if (k % sat_stride == 0) {
          for (std::size_t s = 0; s < m.runs.size(); ++s) {
            const SatelliteInstant& si = b.sats[s];
            const double t_s = static_cast<double>(k) * 1e-3;
            const bool on = m.amplitude(s, si, t_s) > 0.0f;
            // Multipath truth: the pseudorange error an ideal wide (0.5 chip) E-L DLL would
            // have on the path set, the direct path's gain, and the number of echoes.
            double multipath_m = 0.0, los_gain_db = 0.0;
            int echoes = 0;
            if (m.multipath) {
              const PathSet& p = b.paths[s];
              multipath_m = ideal_dll_multipath_error_chips(p, kTruthDllSpacing_chips) * kChip_m;
              los_gain_db = p.direct_gain > 0.0 ? 20.0 * std::log10(p.direct_gain) : -300.0;
              echoes = p.echo_count;
            }
            sat_truth->write(fmt::format(
                "{:.3f},{},{:.6f},{:.4f},{:.4f},{:.2f},{:.4f},{:.4f},{:.4f},{:.4f},{:.5f},{:.4f},{:.4f},{:.4f},{},"
                "{:.4f},{:.4f},{:.4f},{:.4f},{:.3f},{:.4f},{:.2f},{}\n",
                t_s, truth_name(m.runs[s].id), m.code_phase_in_period(m.runs[s], si.code_chips), si.doppler_hz,
                m.sc.if_hz * b.rx.t_rcv_rel_s - si.carrier_cycles, m.cn0_dbhz(s, si, t_s), si.elevation_rad * kRadToDeg,
                si.azimuth_rad * kRadToDeg, si.pseudorange_m, si.range_m, si.range_rate_mps, si.iono_m, si.tropo_m,
                si.sat_clock_m, on ? 1 : 0, si.iono_broadcast_m, si.tropo_model_m, si.orbit_m, si.sat_clock_error_m,
                si.antenna_gain_db, multipath_m, los_gain_db, echoes));
          }
        }
      }
    }
    if (k0 == 0) {
      for (std::size_t s = 0; s < m.runs.size(); ++s) {
        const SatelliteInstant& si = boundaries[0].sats[s];
        m.info[s].doppler_start_hz = si.doppler_hz;
        m.info[s].cn0_start_dbhz = m.cn0_dbhz(s, si, 0.0);
        m.info[s].code_phase_start_chips = m.code_phase_in_period(m.runs[s], si.code_chips);
      }
    }
    if (options.progress) options.progress(static_cast<double>(k0 + count) / static_cast<double>(m.epochs));
  }

  if (written.valid()) written.get();
  // Everything written: only now do the files take their final names.
  if_writer.finish();
  {
    summary.metadata_path = metadata_path_for(summary.if_path).string();
    IfMetadataDescription d;
    d.data_file_name = std::filesystem::path(summary.if_path).filename().string();
    d.format = m.sc.format;
    d.sample_rate_hz = m.sc.sample_rate_hz;
    d.if_hz = m.sc.if_hz;
    d.comment = fmt::format("scenario {}, {} s from GPS week {} second {:.3f}, ADC {} bits", m.sc.name,
                            static_cast<double>(total_samples()) / m.sc.sample_rate_hz, m.sc.start_time.week,
                            m.sc.start_time.sow, make_front_end_config(m.sc).adc.bits);
    TextOutputFile metadata(summary.metadata_path);
    metadata.write(if_metadata_xml(d));
    metadata.commit();
  }
  if (!options.if_only) {
    truth->commit();
    sat_truth->commit();
    TextOutputFile scenario_file(summary.scenario_path);
    scenario_file.write(scenario_to_yaml(m.sc));
    scenario_file.commit();
    if (m.sc.imu.enabled) {
      // Same trajectory, trajectory time (true GPS time since the start, i.e. start_time - receiver clock bias at the start).
      ImuSimConfig imu;
      imu.imu = load_imu_grade(m.sc.imu.grades_file, m.sc.imu.grade).model;
      imu.imu.sample_rate_hz = m.sc.imu.rate_hz;
      imu.lever_arm_b_m = Eigen::Vector3d(m.sc.imu.lever_arm_m[0], m.sc.imu.lever_arm_m[1], m.sc.imu.lever_arm_m[2]);
      summary.imu_path = (std::filesystem::path(out_dir) / "imu.csv").string();
      write_simulated_imu_csv(summary.imu_path, *m.trajectory, imu, m.sc.seed ^ 0x5DEECE66DULL);
    }
  }
  summary.samples = m.epochs * n;
  summary.duration_s = static_cast<double>(m.epochs) * 1e-3;
  summary.satellites = m.info;
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return summary;
}

}  // namespace deepnav
