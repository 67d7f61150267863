#pragma once
// How a source's samples are read (format, rate, IF, spectrum sense) and where each of
// those came from: a flag (or its default), a metadata file, or a stream's header. A
// message about a setting that looks wrong names what to change: the flag, or the file,
// or the flag that overrode the file.
#include <map>
#include <optional>
#include <string>

#include "ins/gps_time.hpp"
#include "signals/sample_format.hpp"

namespace deepnav {

enum class SourceSetting { format, sample_rate, intermediate_frequency, spectrum_sense };

enum class SettingOrigin {
  flag,           ///< the command line (or a --config file), or the flag's default
  metadata,       ///< the --metadata file
  stream_header,  ///< a framed stream's header
};

struct SourceSettings {
  SampleFormat format = SampleFormat::ibyte;
  double sample_rate_hz = 0.0;
  double if_hz = 0.0;
  bool inverted_spectrum = false;
  std::string metadata;  ///< the metadata file read, empty without one
  /// Where each setting came from (absent: a flag).
  std::map<SourceSetting, SettingOrigin> origins;
  /// The metadata file's value of each setting a flag overrode, as the file gave it.
  std::map<SourceSetting, std::string> overridden;
  /// The metadata's date of the file's first sample (UTC), and where it was read
  /// ("x.xml's <metadata/session[capture]/toa>"); absent when the metadata dates nothing.
  std::optional<CalendarTime> start_time_utc;
  std::string start_time_origin;

  SettingOrigin origin(SourceSetting s) const;
  /// The flag that sets it: "--format", "--fs", "--if", "--inverted-spectrum".
  static std::string flag(SourceSetting s);
  /// Its value as a flag takes it: "ibyte", "4000000", "0", "true".
  std::string value(SourceSetting s) const;
  /// How a message names it: "--fs 2500000", "--fs 2500000 (over x.xml's 4000000)", "the
  /// sample rate 4000000 Hz of x.xml", "no --inverted-spectrum".
  std::string named(SourceSetting s) const;
};

}  // namespace deepnav
