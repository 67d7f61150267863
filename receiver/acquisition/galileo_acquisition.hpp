#pragma once
// FFT parallel code-phase search for Galileo E1 OS (E1-B data and E1-C pilot), beside the GPS
// L1 C/A one (acquisition.hpp), whose design it follows: FFTW plans made once, the input's
// spectrum per Doppler bin shared by every PRN, a detection statistic normalised by the
// grid's mean cell away from the peak and a threshold from the false-alarm probability.
//
// Coherent block: one primary code period, 4 ms (4092 chips), correlated with a sampled
// BOC(1,1) replica of each code. Each code period of E1-B carries one data symbol and each
// of E1-C one secondary-code chip, so the two are combined non-coherently: a cell holds
// sum over blocks of |B|^2 + |C|^2, 2K terms for K blocks, and under noise alone is
// Gamma(2K, 1) distributed after normalisation; the threshold follows as for GPS with 2K.
// A block is not aligned with the code epochs: where a symbol or secondary chip changes sign
// inside it, that component's correlation loses twice the part after the change (all of it
// for an epoch mid-block). E1-B's symbol changes half the time and CS25 12 times in 25, so
// the expected power is about 0.5 of the aligned one for an epoch mid-block (-3 dB) and 2/3
// (-1.7 dB) averaged over where the epoch falls; the refinement below sums epoch to epoch and
// loses nothing. (Two-period blocks against a zero-padded replica would avoid the loss at
// twice the transform length.)
//
// Doppler bins: 125 Hz (1 / (2 T) for T = 4 ms: at most 0.9 dB lost half a bin off) over the
// same range as GPS. Per bin the forward FFT of each block serves all PRNs; each PRN then
// costs two inverse FFTs per block (E1-B and E1-C). Only a per-PRN summary of the grid is
// kept (the row holding the peak and each lag's sum over Doppler), not the grid itself: 36
// PRNs x 81 bins x 48000 lags at 12 Msps would be 560 MB.
//
// Detected satellites are refined in the time domain (e1_code_phase_refinement.hpp): Doppler
// to a tenth of a bin and code phase on the main peak of the BOC(1,1) correlation, never on a
// side lobe; C/N0 (of the whole E1 OS signal, both components) follows from the refined
// power over whole code periods and the grid's noise floor.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "receiver/sources/sample_source.hpp"
#include "signals/satellite_id.hpp"

namespace deepnav {

/// Galileo SVIDs searched when none are given (the constellation's numbering, SatelliteId).
inline constexpr int kGalileoMaxSvid = 36;
/// The lowest sample rate searched: BOC(1,1)'s two main lobes lie at +-1.023 MHz, each 2.046
/// MHz wide between nulls; 4 MHz complex keeps most of their power, and the grid's lags are
/// then at most a quarter chip apart (the main peak is 2/3 chip wide).
inline constexpr double kGalileoMinSampleRate_hz = 4.0e6;

struct GalileoAcquisitionConfig {
  double sample_rate_hz = 4.0e6;
  double if_hz = 0.0;
  int noncoherent = 5;  ///< 4 ms blocks summed (1..kMaxNoncoherent; limited by the samples given)
  double doppler_max_hz = 5000.0;
  double doppler_step_hz = 125.0;
  double pfa = 1e-5;  ///< false-alarm probability per PRN search under white noise (as for GPS)
  /// A detection this far (dB) below the strongest Galileo one in the same search is taken as
  /// a correlation with that satellite (or another strong signal) and rejected: the GPS
  /// value. Random 4092-chip codes would cross-correlate some 25 dB down at worst over the
  /// grid, but the 4 MHz real capture shows a detection 18.2 dB below its strongest
  /// satellite in one 20 ms window of 25 and in no GNSS-SDR search
  /// (results/galileo_acquisition): not a satellite.
  double cross_correlation_margin_db = 18.0;
  std::vector<int> prns;  ///< SVIDs; empty: 1..36
};

struct GalileoAcquisitionResult {
  SatelliteId satellite{GnssSystem::galileo, 0};
  bool detected = false;
  double doppler_hz = 0.0;        ///< refined (coarse bin when not detected)
  double delay_samples = 0.0;     ///< where the code epoch starts after the first sample, in [0, samples per 4 ms)
  double code_phase_chips = 0.0;  ///< code phase at the first sample, in [0, 4092)
  double cn0_dbhz = 0.0;          ///< of the E1 OS signal (E1-B and E1-C together)
  double statistic = 0.0;         ///< normalised peak (Gamma(2K, 1) under noise)
  double threshold = 0.0;
  bool cross_correlation_suspect = false;  ///< over the threshold but rejected (see the config)
  bool moved_off_side_lobe = false;        ///< the grid's peak was a BOC side lobe; the main peak is reported
};

class GalileoAcquisition {
 public:
  /// Makes the FFTW plans and the code spectra (E1-B and E1-C of every configured PRN).
  /// Throws std::invalid_argument naming the setting that is out of range.
  explicit GalileoAcquisition(GalileoAcquisitionConfig config);
  ~GalileoAcquisition();
  GalileoAcquisition(const GalileoAcquisition&) = delete;
  GalileoAcquisition& operator=(const GalileoAcquisition&) = delete;

  /// Samples needed for the full search (4 ms x noncoherent).
  std::int64_t samples_needed() const;
  /// Searches every configured PRN in `samples` (the first of them defines delay 0). Fewer
  /// samples than samples_needed() shorten the non-coherent sum; fewer than one code period
  /// throw std::invalid_argument.
  std::vector<GalileoAcquisitionResult> search(std::span<const Sample> samples);
  /// The same for `prns` only (a subset of those configured, else std::invalid_argument):
  /// the searches after the first, for the satellites predicted in view.
  std::vector<GalileoAcquisitionResult> search(std::span<const Sample> samples, const std::vector<int>& prns);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deepnav
