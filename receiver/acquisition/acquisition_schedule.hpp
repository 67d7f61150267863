#pragma once
// When, and over which samples, the FFT acquisition searches for the satellites the receiver
// does not track: first over the first window of samples of the run (a cold start; those
// samples are then tracked too), then every reacquire interval over the latest window, as
// long as a channel is free. The window holds contiguous samples only: it starts over after
// a gap.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "receiver/acquisition/acquisition.hpp"
#include "receiver/sources/sample_history.hpp"
#include "receiver/sources/sample_source.hpp"

namespace deepnav {

class AcquisitionSchedule {
 public:
  /// `config` with the source's sample rate and IF set.
  AcquisitionSchedule(AcquisitionConfig config, double reacquire_interval_s);

  /// Samples one search takes (coherent_ms x noncoherent milliseconds): the run's first
  /// read, and the window kept for re-acquisition.
  std::size_t window_samples() const { return window_samples_; }
  /// Whether the configuration lets `prn` be searched (AcquisitionConfig::prns).
  bool searchable(int prn) const;

  /// The block just tracked joins the window while a channel is free; otherwise there is
  /// nothing to search for and the window empties.
  void keep(const SampleBlock& block, bool channel_free);
  /// Samples were lost: the window starts over after the gap.
  void restart_window() { window_.clear(); }
  /// Every channel was released: search as soon as the window is full again.
  void search_when_full() { last_search_s_ = -std::numeric_limits<double>::infinity(); }
  /// Whether a re-acquisition over the window is due at `t_s` (the interval has passed since
  /// the last one, a channel is free and the window full); when it is, notes it as made.
  bool reacquisition_due(double t_s, bool channel_free);
  const SampleHistory& window() const { return window_; }

  /// Searches `samples` for `prns`: the signals detected, strongest first; none when the
  /// samples are too few for a search.
  std::vector<AcquisitionResult> search(const std::vector<Sample>& samples, const std::vector<int>& prns);
  /// Of every search so far, the result that came nearest its threshold (detected or not):
  /// what a run that acquired nothing reports as the best it saw.
  const std::optional<AcquisitionResult>& strongest() const { return strongest_; }
  /// The searches' configuration (the source's rate and IF in it).
  const AcquisitionConfig& config() const { return cfg_; }

 private:
  AcquisitionConfig cfg_;
  double interval_s_;
  std::size_t window_samples_;
  SampleHistory window_;
  double last_search_s_ = 0.0;
  /// One search engine for the run, made at the first search: its plans, code spectra and
  /// buffers are made once.
  std::unique_ptr<Acquisition> engine_;
  std::optional<AcquisitionResult> strongest_;
};

}  // namespace deepnav
