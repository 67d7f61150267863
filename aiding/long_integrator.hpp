#pragma once
// Long integrations of a steered channel: its bit-aligned integrations (10 or 20 ms) summed
// into 20 ms data bits, and the bits summed
//  - coherently, with the data wiped off, where each bit's sign is predicted, up to
//    `coherent_ms` (a gain of 10 log10(coherent_ms / 20) dB in post-integration SNR over
//    bit-edge-limited integration);
//  - in power (non-coherently) where it is not, up to `noncoherent_ms`: the code
//    discriminator still works on summed early/late powers, at the squaring loss of 20 ms
//    pieces; the carrier phase is then held by the filter alone.
// A coherent run ends early where the next bit is not predicted, and a non-coherent one
// where the next bit is, so each integration is one kind or the other.
//
// Coherence across the bits needs the carrier replica to follow the signal's phase within
// a small fraction of a cycle over the whole integration: the INS-steered NCO does that
// (the filter's Doppler between blocks), and the phase loop on the wiped prompt removes
// what is left. The bits' NCO phase is continuous, so their prompts add as they are.
#include <complex>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "aiding/integration_cn0_estimator.hpp"
#include "receiver/tracking/tracking_types.hpp"

namespace deepnav::aiding {

struct LongIntegrationConfig {
  int coherent_ms = 200;      ///< data-wiped coherent length: a multiple of 20 ms; 20: no wipe-off
  int noncoherent_ms = 1000;  ///< power sum of 20 ms bits where the data are not predicted (multiple of 20)
  /// Predict subframes 1-3 from the receiver's ephemeris where they have not been decoded
  /// (an assisted ephemeris from a navigation file): assisted data bits.
  bool assist_data_bits = false;
  double enter_below_dbhz = 30.0;  ///< a steered channel integrates long below this C/N0 ...
  double leave_above_dbhz = 34.0;  ///< ... and goes back to its 10 ms integrations above this
};

/// Throws std::invalid_argument naming the field when a length is not a positive multiple of 20 ms.
void validate(const LongIntegrationConfig& config);

/// One long integration.
struct SteeredIntegration {
  /// Sums over the integration (data wiped when `data_wiped`); for a non-coherent one the
  /// complex sums are the last bit's. Timing, NCO state and flags are those at its end.
  CorrelatorEpoch sums;
  bool data_wiped = false;  ///< coherent across bits with the data removed
  int pieces = 1;           ///< coherent pieces combined in power (1: one coherent integration)
  double piece_s = 0.0;     ///< length of each coherent piece
  double early_power = 0.0, prompt_power = 0.0, late_power = 0.0;  ///< sum of |.|^2 over the pieces
  /// The noise correlator's |N|^2 summed over the channel's integrations (each an independent
  /// sample of the noise density; |sum N|^2 would be a single one) and the samples it covered.
  double noise_power = 0.0;
  int noise_samples = 0;
  /// Non-coherent: the sum over consecutive pieces of conj(P_k-1) P_k, each turned by the sign
  /// of its real part (a data-bit change between the two flips the pair): its angle over
  /// 2 pi piece_s is the mean residual frequency, as a cross/dot discriminator averaged.
  std::complex<double> frequency_product;
  int frequency_pairs = 0;
  double start_carrier_phase_cycles = 0.0;  ///< NCO carrier phase where the integration began
};

/// What the C/N0 estimator takes from one of the channel's own integrations, and from a long one.
IntegrationPower power_of(const CorrelatorEpoch& epoch, double sample_rate_hz);
IntegrationPower power_of(const SteeredIntegration& integration, double sample_rate_hz);

class LongIntegrator {
 public:
  /// The sign to multiply a completed bit by (+-1), or 0 when its data are not predicted;
  /// called once per bit, in order, with the code period the bit started at and its prompt.
  using BitSigner = std::function<int(std::int64_t bit_start_period, const std::complex<double>& bit_prompt)>;

  explicit LongIntegrator(const LongIntegrationConfig& config);

  /// Adds one of the channel's integrations (which never straddle a bit edge once the bits
  /// are synchronised). Completed long integrations are appended to `out`.
  void add(const CorrelatorEpoch& epoch, std::int64_t bit_edge_period, const BitSigner& signer,
           std::vector<SteeredIntegration>& out);
  /// Drops what is being summed (a gap, a change of owner, leaving long integration).
  void reset();

  /// For the bit being completed (inside a BitSigner call): the carrier phase its prompt
  /// should be judged against - the wiped prompt summed so far in this integration, or the
  /// previous data-wiped integration's when it ended where this run began. nullopt after a
  /// stretch of unpredicted bits (the phase is then the Costas loop's, half-cycle ambiguous).
  std::optional<std::complex<double>> phase_reference() const;

 private:
  void finish_bit(const BitSigner& signer, std::vector<SteeredIntegration>& out);
  void flush(std::vector<SteeredIntegration>& out);

  LongIntegrationConfig cfg_;
  std::optional<CorrelatorEpoch> bit_;  ///< the bit being summed
  int bit_ms_ = 0;
  double bit_noise_power_ = 0.0;  ///< sum of the bit's integrations' |N|^2
  std::int64_t bit_start_period_ = 0;
  double bit_start_phase_cycles_ = 0.0;
  std::optional<SteeredIntegration> run_;  ///< the integration being summed
  int run_ms_ = 0;
  std::int64_t end_sample_ = -1;
  std::optional<std::complex<double>> last_wiped_prompt_;  ///< of the wiped integration just before the run
};

}  // namespace deepnav::aiding
