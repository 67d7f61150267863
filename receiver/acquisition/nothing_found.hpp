#pragma once
// Why a search for satellites found nothing, told from what the samples show, so that an
// everyday mistake (a wrong sample rate, IF, format or spectrum sense, a file too short)
// gets a hint instead of a silent empty run. The evidence, most specific first: the
// satellites appear once the spectrum is turned the other way round; the spectrum's band
// (a front end's filter) sits away from the IF; the samples do not look like their format
// (I and Q unbalanced, values crowding full scale, 8-bit pairs read as 16-bit values); a
// correlation came near the threshold (a weak signal). Without any, the usual causes are
// named, each as it was set: the flag, the metadata file, or the flag given over the
// file's value.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "receiver/acquisition/signal_diagnostics.hpp"
#include "receiver/sources/source_settings.hpp"

namespace deepnav {

struct NothingFound {
  std::string reason;   ///< "no_satellite_acquired" or "too_short"
  std::string message;  ///< what was not found, the likely causes, what was seen
  /// The settings the evidence points at: "sample_rate", "intermediate_frequency",
  /// "format", "spectrum_sense" (empty when it points at the signal itself).
  std::vector<std::string> suspects;
  nlohmann::json seen;  ///< the figures behind the message
  /// {reason, message, suspects, seen}: summary.json's `nothing_found`.
  nlohmann::json json() const;
};

/// Nothing acquired in `signal_s` seconds of signal, from what the acquisition saw and how
/// the samples were read. Measures the samples kept (levels, spectrum) and searches them
/// once more with the spectrum inverted (complex samples): about one search's time.
NothingFound diagnose_no_satellite(const AcquisitionEvidence& evidence, const SourceSettings& settings,
                                   double signal_s);

/// `signal_s` seconds of signal where `purpose` (e.g. "one observation epoch at --rate 1")
/// needs `needed_s`.
NothingFound too_short(double signal_s, double needed_s, const std::string& purpose);

}  // namespace deepnav
