#pragma once
// The propagation channel between each satellite and the antenna beyond the direct
// line of sight: blockage of the direct path and delayed echoes. For each satellite at
// each 1 ms boundary it gives a PathSet, which the synthesizer turns into one signal
// replica per path (the direct one scaled, each echo delayed, scaled and phase-rotated).
//
// Models (MultipathSpec::Model):
// - ground: one specular reflection off flat ground below an antenna at height h. The
//   reflected ray travels 2 h sin(el) further, so its code is that much later and its
//   carrier lags by 2 pi (2 h sin(el)) / lambda plus the reflection's pi; as the
//   satellite's elevation changes the relative phase turns, which gives the classic slowly
//   oscillating code and carrier multipath error of a static antenna. The echo amplitude
//   is |Gamma| times the antenna's rejection of arrivals from below the horizon.
// - land_mobile: in the spirit of the Lutz two-state land-mobile satellite channel and
//   the DLR tapped-delay-line channel: per satellite a two-state Markov process (LOS /
//   blocked; exponential sojourns, blocked share depending on elevation) attenuates the
//   direct path while blocked, and N echo taps with exponentially distributed excess
//   delays carry Rician/Rayleigh fading whose Doppler spread follows the antenna's speed.
//   A tap's fading is a sum of sinusoids over the distance the antenna has travelled
//   (a fixed spatial interference pattern driven through at the vehicle's speed), so it
//   slows down and freezes with the vehicle; a floor speed stands for moving scatterers.
//   The synthesizer interpolates an echo's phase across each millisecond, which needs the
//   Doppler spread v / lambda below 500 Hz: land speeds (below 95 m/s).
//
// Determinism: everything derives from the scenario seed, in streams keyed by PRN (not
// by the satellite's index in the run). The blockage switch times and the distance
// travelled are computed once, in the constructor, over the whole run; a tap's delay and
// fading parameters are a hash of (seed, PRN, tap, reflector generation). paths() is
// therefore a pure function of (satellite, time): boundaries may be evaluated in any
// order on any number of threads and give the same samples.
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "signals/sim/multipath_spec.hpp"

namespace deepnav {

struct EchoPath {
  double excess_delay_m = 0.0;     ///< path length beyond the direct path's (>= 0): the code arrives this much later
  double amplitude = 0.0;          ///< relative to the direct signal's nominal (unblocked) amplitude
  double carrier_phase_rad = 0.0;  ///< echo carrier phase minus the direct path's, in the samples, in [-pi, pi)
  /// Identity of the reflector: the same id at consecutive boundaries means the same echo,
  /// whose delay and phase the synthesizer interpolates; a new id starts a new echo.
  std::uint32_t id = 0;
};

/// The paths of one satellite's signal at one instant.
struct PathSet {
  double direct_gain = 1.0;  ///< direct-path amplitude factor: 1 unblocked, < 1 shadowed or blocked
  int echo_count = 0;
  std::array<EchoPath, MultipathSpec::kMaxEchoes> echoes{};
};

/// The ground-reflection model's paths at an elevation (no echo at or below the horizon).
PathSet ground_reflection_paths(const MultipathSpec& spec, double elevation_rad);

/// Code tracking error (chips; positive: the measured pseudorange is too long) of an ideal
/// early-minus-late envelope DLL with the given spacing locked on this path set: infinite
/// bandwidth (triangular C/A correlation), no noise, and any normalisation of E - L (the
/// lock point is where |E| = |L|). With the direct path blocked it is where the DLL sits on
/// the echoes. 0 for the direct path alone.
double ideal_dll_multipath_error_chips(const PathSet& paths, double spacing_chips);

class MultipathChannel {
 public:
  /// Elevation of satellite `sat` at t_s seconds after the start (land-mobile only: it sets
  /// the blocked share); called only from the constructor.
  using ElevationFn = std::function<double(std::size_t sat, double t_s)>;
  /// Antenna speed over ground at t_s (land-mobile only: it sets the fading rate);
  /// called only from the constructor.
  using SpeedFn = std::function<double(double t_s)>;

  /// `prns[sat]` is the PRN of satellite index `sat`; paths() is defined for t_s in
  /// [0, duration_s + 1] (later times keep the last blockage state and speed).
  MultipathChannel(const MultipathSpec& spec, std::uint64_t seed, std::vector<int> prns, double duration_s,
                   const ElevationFn& elevation_rad, const SpeedFn& speed_mps);

  /// The paths of satellite `sat` at t_s; `elevation_rad` is its elevation then (ground model).
  PathSet paths(std::size_t sat, double t_s, double elevation_rad) const;
  /// Whether the land-mobile process has the satellite's direct path blocked at t_s.
  bool blocked(std::size_t sat, double t_s) const;
  /// The land-mobile long-run blocked share at an elevation (see MultipathSpec::blocked_probability).
  static double blocked_share(const MultipathSpec& spec, double elevation_rad);
  const MultipathSpec& spec() const { return spec_; }

 private:
  struct Blockage {
    bool blocked_at_start = false;
    std::vector<double> switch_times_s;  ///< increasing; the state flips at each
  };
  /// Distance (m) the fading pattern has been driven through by t_s.
  double fading_distance_m(double t_s) const;
  EchoPath land_mobile_tap(int prn, int tap, double t_s) const;

  MultipathSpec spec_;
  std::uint64_t seed_;
  std::vector<int> prns_;
  std::vector<Blockage> blockage_;
  std::vector<double> distance_m_;  ///< at t = i * kDistanceStep_s
};

}  // namespace deepnav
