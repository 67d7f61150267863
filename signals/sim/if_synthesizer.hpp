#pragma once
// The GPS L1 C/A and Galileo E1 OS IF synthesizer: turns a Scenario into an IF sample file
// plus the truth a receiver is scored against.
//
// Time is the receiver's sample clock: sample n is taken when the receiver clock
// reads start_time + n / fs. The run is cut into 1 ms epochs; at every epoch
// boundary each satellite's code and carrier phase come from exact geometry
// (SatelliteInstant), and inside an epoch they advance linearly (the quadratic term
// of the range over 1 ms is below a micrometre). Chunks of epochs are generated in
// parallel; noise, jammers, AGC and quantization follow sequentially, so the output
// is bit-identical whatever the thread count.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ins/trajectory.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/satellite_id.hpp"
#include "signals/sim/scenario.hpp"

namespace deepnav {

/// A satellite chosen for the run and what it looked like at the start.
struct SynthesizedSatellite {
  int prn = 0;
  double elevation_start_deg = 0.0;
  double azimuth_start_deg = 0.0;
  double doppler_start_hz = 0.0;
  double cn0_start_dbhz = 0.0;
  double code_phase_start_chips = 0.0;  ///< within the code period: 1023 chips (C/A) or 4092 (E1)
  SatelliteId id{};                     ///< system and number (prn is the number)
};

struct SynthesisSummary {
  std::string if_path, truth_path, sat_truth_path, scenario_path;
  std::string metadata_path;  ///< the ION GNSS SDR metadata file describing if_path (beside it, .xml)
  std::string imu_path;       ///< empty when the scenario asks for no IMU
  std::int64_t samples = 0;
  std::int64_t bytes = 0;
  double duration_s = 0.0;
  std::vector<SynthesizedSatellite> satellites;
  double wall_s = 0.0;
};

struct SynthesisOptions {
  unsigned threads = 1;  ///< worker threads for the satellite signals (0: all cores)
  /// Called now and then with the fraction done (0..1); for progress display.
  std::function<void(double)> progress;
  /// Write only the IF file (no truth files): used by the speed benchmark.
  bool if_only = false;
};

class IfChunkGenerator;

class IfSynthesizer {
 public:
  IfSynthesizer(Scenario scenario, NavData nav);
  ~IfSynthesizer();
  IfSynthesizer(const IfSynthesizer&) = delete;
  IfSynthesizer& operator=(const IfSynthesizer&) = delete;

  /// The satellites the scenario selects (healthy, above the mask, strongest first).
  const std::vector<SynthesizedSatellite>& satellites() const;
  /// Writes if.<ext>, truth.csv, sat_truth.csv and scenario.yaml into out_dir
  /// (created if missing). Every file appears under its final name only when complete.
  SynthesisSummary run(const std::string& out_dir, const SynthesisOptions& options);
  /// The same IF samples as run() writes, chunk by chunk and without any file (streaming).
  /// The generator reads this synthesizer, which must outlive it; several generators may
  /// run at once, each from the first sample.
  std::unique_ptr<IfChunkGenerator> chunk_generator(unsigned threads) const;

  const Scenario& scenario() const;
  /// Samples in the whole run (whole milliseconds of the scenario's duration).
  std::int64_t total_samples() const;

 private:
  friend class IfChunkGenerator;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Block-wise synthesis: each call to next() gives the next chunk of up to 100 ms of IF
/// samples in the scenario's format (noise, jammers, AGC and ADC applied in sample order,
/// so the concatenated chunks are byte-identical to the file run() writes).
class IfChunkGenerator {
 public:
  ~IfChunkGenerator();
  IfChunkGenerator(const IfChunkGenerator&) = delete;
  IfChunkGenerator& operator=(const IfChunkGenerator&) = delete;

  /// Replaces `bytes` with the next chunk; false (and `bytes` empty) after the last one.
  bool next(std::vector<std::byte>& bytes);
  /// Absolute index of the first sample the next chunk starts with.
  std::int64_t next_sample_index() const;

 private:
  friend class IfSynthesizer;
  struct State;
  explicit IfChunkGenerator(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

/// The IF file name for a format (if.cs8 / if.cs16 / if.cf32 / if.s8 ...).
std::string if_file_name(SampleFormat format);

}  // namespace deepnav
