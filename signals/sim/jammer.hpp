#pragma once
// Interference sources added to the synthesized IF: CW, swept (chirp), band-limited
// noise and pulsed jammers.
//
// Power convention (same as the satellites, thermal noise density N0 = 1): a jammer
// with J/S = js_db has power J = C_ref 10^(js_db/10), where C_ref = 10^(cn0_ref_dbhz/10)
// is the power of a satellite at the scenario's nominal C/N0. The jammer is generated as
// a complex analytic signal at IF + center_offset_hz with E|x|^2 = J, exactly as the
// satellites are (complex amplitude sqrt(C)); for real IF output the real part is taken
// of the sum, so J/S is preserved. For pulsed jammers J is the peak (on-time) power.
//
// Time: sample index 0 is scenario time 0. Every waveform is a function of the absolute
// sample index and the seed only, so the output does not depend on how the run is cut
// into blocks and no floating-point time is accumulated.
#include <complex>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace deepnav {

enum class JammerType { cw, chirp, wideband, pulsed };

struct JammerConfig {
  JammerType type = JammerType::cw;
  double js_db = 0.0;             ///< jammer-to-signal ratio (peak for pulsed), dB
  double center_offset_hz = 0.0;  ///< carrier / band centre relative to the receiver IF (i.e. to L1)
  double bandwidth_hz = 0.0;      ///< chirp: swept span; wideband: noise bandwidth (two-sided);
                                  ///< pulsed: 0 = carrier bursts, > 0 = noise bursts of this bandwidth
  double sweep_period_s = 0.0;    ///< chirp: duration of one sawtooth sweep
  double duty_cycle = 1.0;        ///< pulsed: on-time fraction of each period, (0, 1]
  double pulse_rate_hz = 0.0;     ///< pulsed: pulse repetition frequency
  double start_s = 0.0;           ///< on from this scenario time ...
  double end_s = 0.0;             ///< ... until this one; <= 0 means until the end
};

/// "cw", "chirp", "wideband", "pulsed"; throws std::invalid_argument listing them otherwise.
JammerType parse_jammer_type(const std::string& name);
std::string to_string(JammerType type);
/// Throws std::invalid_argument naming the offending field and the accepted range:
/// js_db in [-50, 120]; |center_offset_hz| <= fs/2; chirp: 0 < bandwidth <= fs,
/// sweep period > 0 and at least 2 samples; wideband: 0 < bandwidth <= fs; pulsed:
/// duty cycle in (0, 1], 0 < pulse rate <= fs/2, 0 <= bandwidth <= fs; start_s >= 0 and
/// end_s <= 0 or > start_s; sample rate > 0 and IF within +-fs/2.
void validate_jammer(const JammerConfig& config, double sample_rate_hz, double if_hz);

class ToneGenerator;
class ChirpGenerator;
class BandLimitedNoise;

class Jammer {
 public:
  /// Validates the configuration (see validate_jammer). `seed` drives the noise waveforms.
  Jammer(const JammerConfig& config, double sample_rate_hz, double if_hz, double cn0_ref_dbhz, std::uint64_t seed);
  ~Jammer();
  Jammer(Jammer&&) noexcept;
  Jammer& operator=(Jammer&&) noexcept;

  /// block[k] += jammer(first_sample + k) (zero outside [start_s, end_s) and pulse off-times).
  void add_to(std::span<std::complex<float>> block, std::int64_t first_sample);

  const JammerConfig& config() const { return config_; }
  double power() const { return power_; }  ///< J (peak power for pulsed)
  /// Whether the pulse gate is on at this sample (always true for non-pulsed types;
  /// ignores start_s/end_s).
  bool pulse_on(std::int64_t sample) const;

 private:
  void generate(std::span<std::complex<float>> out, std::int64_t first_sample);
  void gate_pulses(std::span<std::complex<float>> out, std::int64_t first_sample) const;
  std::int64_t pulse_start(std::int64_t pulse) const;
  std::int64_t pulse_end(std::int64_t pulse) const;

  JammerConfig config_;
  double sample_rate_hz_;
  double power_;
  std::int64_t first_on_sample_, end_sample_;
  std::unique_ptr<ToneGenerator> tone_;
  std::unique_ptr<ChirpGenerator> chirp_;
  std::unique_ptr<BandLimitedNoise> noise_;
  std::vector<std::complex<float>> scratch_;
};

}  // namespace deepnav
