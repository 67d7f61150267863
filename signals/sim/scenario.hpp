#pragma once
// A synthesis scenario: everything `deepnav sim` needs to produce an IF file and
// its truth. Loaded from YAML (JSON is valid YAML too); every field is validated
// and an error names the file and the field. The schema is documented in docs/scenarios.md.
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "ins/wgs84.hpp"
#include "signals/sample_format.hpp"
#include "signals/satellite_id.hpp"
#include "signals/sim/error_presets.hpp"
#include "signals/sim/jammer.hpp"

namespace deepnav {

struct TrajectorySpec {
  std::string preset = "static";  ///< a preset name, or empty when `csv_path` is set
  std::string csv_path;           ///< user trajectory (absolute, or resolved against the scenario file)
  wgs84::Llh start{};             ///< start position for presets
  double heading_rad = 0.0;
};

/// Carrier-to-noise density of each satellite over the run.
struct Cn0Spec {
  enum class Model { fixed, elevation } model = Model::fixed;
  double fixed_dbhz = 45.0;
  double zenith_dbhz = 50.0;                    ///< elevation model: C/N0 at 90 degrees
  double horizon_dbhz = 38.0;                   ///< elevation model: C/N0 at 0 degrees (linear in sin(elevation))
  std::map<int, double> per_prn_dbhz;           ///< overrides for single GPS PRNs (keys 7 or G07)
  std::map<int, double> galileo_per_svid_dbhz;  ///< overrides for single Galileo satellites (keys E11)
  /// Optional linear ramp applied to every satellite: offset goes from 0 dB at
  /// ramp_start_s to ramp_delta_db at ramp_end_s and stays there (tracking-threshold runs).
  double ramp_start_s = 0.0, ramp_end_s = 0.0, ramp_delta_db = 0.0;
  /// Nominal C/N0 that jammer J/S is relative to.
  double reference_dbhz() const { return model == Model::fixed ? fixed_dbhz : zenith_dbhz; }
};

/// Receiver oscillator: clock bias/drift at the start, plus two-state random walk noise
/// described by Allan-variance coefficients h0 and h-2 (Brown & Hwang's clock model).
struct ReceiverClockSpec {
  double bias_s = 0.0;
  double drift_sps = 0.0;
  std::string oscillator = "ideal";  ///< ideal | tcxo | ocxo | custom
  double h0 = 0.0;
  double h_minus2 = 0.0;
};

/// Sets the Allan coefficients of a named oscillator (ideal, tcxo, ocxo) and the name;
/// false (spec unchanged) for any other name.
bool set_oscillator_preset(ReceiverClockSpec& spec, const std::string& name);

/// A time window in which the listed satellites (all of every system when both lists are
/// empty) transmit nothing.
struct OutageSpec {
  double start_s = 0.0;
  double end_s = 0.0;
  std::vector<int> prns;          ///< GPS PRNs (7 or G07 in the file)
  std::vector<int> galileo_prns;  ///< Galileo SVIDs (E11 in the file)
  bool all_satellites() const { return prns.empty() && galileo_prns.empty(); }
};

struct AdcSpec {
  int bits = 0;     ///< 0: no quantization (the format's full resolution, or float)
  bool agc = true;  ///< automatic gain control before the quantizer
  double agc_time_constant_s = 0.01;
};

/// Optional IMU output for the same trajectory (written as imu.csv next to the IF file).
struct ImuSpec {
  bool enabled = false;
  std::string grade = "tactical";  ///< a grade name in grades_file
  std::string grades_file;         ///< resolved path (default data/imu_grades.yaml)
  double rate_hz = 100.0;
  std::array<double, 3> lever_arm_m{0.0, 0.0,
                                    0.0};  ///< IMU position from the antenna, body axes (x fwd, y right, z down)
};

struct Scenario {
  std::string name;
  std::string source_path;  ///< the file it was loaded from, for messages
  GpsTime start_time{};     ///< GPS time of the first sample (receiver clock time)
  double duration_s = 0.0;
  double sample_rate_hz = 4.092e6;
  double if_hz = 0.0;
  SampleFormat format = SampleFormat::ibyte;
  AdcSpec adc{};
  std::string nav_file;  ///< RINEX navigation file (resolved path)
  /// Systems whose satellites are synthesized (GPS L1 C/A, Galileo E1 OS); each once.
  std::vector<GnssSystem> systems{GnssSystem::gps};
  TrajectorySpec trajectory{};
  double elevation_mask_rad = 5.0 * 3.14159265358979323846 / 180.0;
  /// Only these GPS PRNs (7 or G07 in the file) / Galileo SVIDs (E11), each list for its own
  /// system (empty: every healthy satellite of that system above the mask).
  std::vector<int> prns;
  std::vector<int> galileo_prns;
  int max_satellites = 12;  ///< of each system
  Cn0Spec cn0{};
  ReceiverClockSpec clock{};
  bool ionosphere = true;   ///< false: no ionospheric delay in the signal at all
  bool troposphere = true;  ///< false: no tropospheric delay in the signal at all
  ErrorSpec errors{};       ///< how the truth differs from the receiver's models (preset none: it does not)
  std::uint64_t seed = 1;
  std::vector<JammerConfig> jammers;
  std::vector<OutageSpec> outages;
  ImuSpec imu{};
  double truth_rate_hz = 100.0;     ///< receiver truth rows per second
  double sat_truth_rate_hz = 10.0;  ///< per-satellite truth rows per second
};

/// Reads and validates a scenario file. Relative paths inside it (nav_file, trajectory
/// file) are resolved against the scenario file's folder, then against `search_root`
/// (the project source tree, so bundled scenarios can name `data/...`).
Scenario load_scenario(const std::string& path, const std::string& search_root = "");
/// Parses scenario text; `origin` names it in error messages.
Scenario parse_scenario(const std::string& yaml_text, const std::string& origin, const std::string& base_dir,
                        const std::string& search_root = "");
/// Checks cross-field consistency (throws std::invalid_argument naming the field).
void validate_scenario(const Scenario& scenario);
/// Throws InputError when the scenario (named `name` in the message) does not carry every
/// system of `systems`, what a benchmark's --systems asks the receiver to track.
void require_scenario_systems(const Scenario& scenario, const std::vector<GnssSystem>& systems,
                              const std::string& name);
/// Writes the scenario back as YAML with every default filled in (stored next to the outputs).
std::string scenario_to_yaml(const Scenario& scenario);

}  // namespace deepnav
