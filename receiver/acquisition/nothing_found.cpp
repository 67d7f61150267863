#include "receiver/acquisition/nothing_found.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace deepnav {
namespace {

/// A correlation this close to the threshold (statistic over threshold) is taken for a
/// signal too weak to pass rather than for noise: the strongest noise cell of a whole
/// search lands near three quarters of it.
constexpr double kNearThreshold = 0.9;
/// A spectrum band centred this far from the IF (or a quarter of its width, if more) is
/// another IF: front-end filters are centred on their IF to within a small part of their
/// width, and the band's centre is measured to within a few periodogram bins.
constexpr double kBandOffsetTolerance_hz = 100e3;
/// Unbalanced I and Q powers beyond this (dB) are not one front end's pair.
constexpr double kMaxIqImbalance_db = 3.0;
/// More values than this at full scale, in an 8- or 16-bit container, is not an ADC's
/// signal under a working gain control.
constexpr double kMaxFullScaleFraction = 0.05;
/// Satellites the search with the spectrum inverted must find to be taken for the sky.
constexpr std::size_t kMinInvertedDetections = 2;

struct Finding {
  std::vector<SourceSetting> suspects;
  std::string text;
};

std::string setting_id(SourceSetting s) {
  switch (s) {
    case SourceSetting::format:
      return "format";
    case SourceSetting::sample_rate:
      return "sample_rate";
    case SourceSetting::intermediate_frequency:
      return "intermediate_frequency";
    case SourceSetting::spectrum_sense:
      return "spectrum_sense";
  }
  return "";
}

/// Frequencies to the precision a band's edges give (about 10 kHz): MHz from 100 kHz up.
std::string frequency_text(double hz) {
  const double a = std::abs(hz);
  if (a >= 1e5) return fmt::format("{:.2f} MHz", hz / 1e6);
  if (a >= 1e3) return fmt::format("{:.1f} kHz", hz / 1e3);
  return fmt::format("{:.0f} Hz", hz);
}

std::string duration_text(double s) { return s < 1.0 ? fmt::format("{:.0f} ms", s * 1e3) : fmt::format("{:.1f} s", s); }

std::string prn_list(const std::vector<int>& prns) {
  std::string out;
  const std::size_t shown = std::min<std::size_t>(prns.size(), 4);
  for (std::size_t i = 0; i < shown; ++i)
    out += (i == 0 ? "PRN " : i + 1 == shown && shown == prns.size() ? " and " : ", ") + std::to_string(prns[i]);
  if (shown < prns.size()) out += fmt::format(" and {} more", prns.size() - shown);
  return out;
}

/// The PRNs detected in `samples` with the spectrum inverted (I and Q conjugated), none
/// when they are real (a real signal has no sense to invert) or too few for a search.
std::optional<std::vector<int>> search_inverted(const AcquisitionEvidence& e, bool real) {
  if (real) return std::nullopt;
  Acquisition acquisition(e.config);
  const std::int64_t block = acquisition.samples_needed() / std::max(1, e.config.noncoherent);
  if (static_cast<std::int64_t>(e.samples.size()) < block) return std::nullopt;
  std::vector<Sample> conjugated(e.samples.size());
  std::transform(e.samples.begin(), e.samples.end(), conjugated.begin(), [](const Sample& s) {
    return Sample(s.real(), static_cast<std::int16_t>(std::min(32767, -static_cast<int>(s.imag()))));
  });
  std::vector<AcquisitionResult> results = acquisition.search(conjugated);
  std::erase_if(results, [](const AcquisitionResult& r) { return !r.detected; });
  std::sort(results.begin(), results.end(), [](const auto& a, const auto& b) { return a.cn0_dbhz > b.cn0_dbhz; });
  std::vector<int> prns;
  for (const AcquisitionResult& r : results) prns.push_back(r.prn);
  return prns;
}

std::optional<Finding> inverted_finding(const std::optional<std::vector<int>>& found, const SourceSettings& s) {
  // One detection alone can be the false alarm a search makes now and then (a band-limited
  // floor makes them likelier); a sky turned the other way round shows several satellites.
  if (!found || found->size() < kMinInvertedDetections) return std::nullopt;
  const SourceSetting sense = SourceSetting::spectrum_sense;
  std::string fix;
  if (s.origin(sense) == SettingOrigin::flag)
    fix = s.inverted_spectrum ? "drop --inverted-spectrum" : "add --inverted-spectrum";
  else fix = fmt::format("{} is the wrong way round", s.named(sense));
  return Finding{{sense}, fmt::format("with the spectrum inverted, acquisition finds {}: {}", prn_list(*found), fix)};
}

std::optional<Finding> spectrum_finding(const SpectrumBand& band, const SourceSettings& s, bool real) {
  if (!band.found) return std::nullopt;
  const SourceSetting if_setting = SourceSetting::intermediate_frequency;
  const double expected = real ? std::abs(s.if_hz) : s.if_hz;
  const double offset = band.centre_hz - expected;
  const double tolerance = std::max(kBandOffsetTolerance_hz, band.width_hz / 4.0);
  if (std::abs(offset) <= tolerance) return std::nullopt;
  if (!real && s.if_hz != 0.0 && std::abs(band.centre_hz + s.if_hz) <= tolerance)
    return Finding{
        {SourceSetting::spectrum_sense, if_setting},
        fmt::format("the spectrum's centre, {}, is minus {}: is the spectrum inverted ({})?",
                    frequency_text(band.centre_hz), s.named(if_setting), s.named(SourceSetting::spectrum_sense))};
  const std::string guess = std::abs(band.centre_hz) <= tolerance && !real
                                ? std::string("0 Hz (complex baseband)")
                                : (band.centre_hz > 0.0 ? "+" : "") + frequency_text(band.centre_hz);
  return Finding{{if_setting},
                 fmt::format("the spectrum's centre is {} {} {}: is the IF {}?", frequency_text(std::abs(offset)),
                             offset > 0 ? "above" : "below", s.named(if_setting), guess)};
}

/// What in the samples' levels says they are not of the format they were read as.
std::vector<Finding> format_findings(const AcquisitionEvidence& e, const SampleLevels& l, const SourceSettings& s,
                                     bool real) {
  const SampleValueRange range = converted_value_range(s.format);
  const std::string format = s.named(SourceSetting::format);
  std::vector<Finding> out;
  const auto add = [&](std::string text) { out.push_back({{SourceSetting::format}, text + " (" + format + ")"}); };
  if (const std::string problem = if_sample_problem(e.samples, real); !problem.empty()) add(problem);
  if (range.max >= 32767 && l.low_byte_levels <= 16 && l.levels_used > 64)
    add(fmt::format("the 16-bit values take only {} distinct low bytes: pairs of 8-bit values read as one?",
                    l.low_byte_levels));
  if (!real && std::abs(l.iq_power_ratio_db) > kMaxIqImbalance_db)
    add(fmt::format("I and Q differ by {:.1f} dB in power: not the two halves of one front end's samples",
                    std::abs(l.iq_power_ratio_db)));
  if (range.max >= 127 && l.at_full_scale_fraction > kMaxFullScaleFraction)
    add(fmt::format("{:.0f} % of the values sit at full scale: another format's bytes, or a front end clipping",
                    100.0 * l.at_full_scale_fraction));
  return out;
}

std::optional<Finding> weak_signal_finding(const std::optional<AcquisitionResult>& best) {
  if (!best || threshold_ratio(*best) < kNearThreshold) return std::nullopt;
  return Finding{{},
                 fmt::format("the strongest correlation, PRN {} at {:+.0f} Hz, came to {:.2f} of the threshold: a "
                             "signal too weak to pass (antenna, gain, sky view) rather than a wrong setting?",
                             best->prn, best->doppler_hz, threshold_ratio(*best))};
}

/// No specific evidence: every setting that decides whether the code lines up, as it was set.
Finding usual_causes(const SourceSettings& s) {
  const std::vector<SourceSetting> all{SourceSetting::sample_rate, SourceSetting::format,
                                       SourceSetting::intermediate_frequency, SourceSetting::spectrum_sense};
  if (!s.overridden.empty()) {
    Finding f;
    std::string flags, values;
    for (const auto& [setting, value] : s.overridden) {
      f.suspects.push_back(setting);
      flags += (flags.empty() ? "" : ", ") + SourceSettings::flag(setting) + " " + s.value(setting);
      values += (values.empty() ? "" : ", ") + value;
    }
    f.text = fmt::format("{} overrode {}'s {}: is the metadata right after all?", flags, s.metadata, values);
    return f;
  }
  const bool all_from_metadata =
      std::all_of(all.begin(), all.end(), [&](SourceSetting x) { return s.origin(x) == SettingOrigin::metadata; });
  if (all_from_metadata)
    return {all, fmt::format("no correlation came near the threshold: check the metadata file {} (its sample rate, "
                             "IF, format and spectrum sense)",
                             s.metadata)};
  return {all, fmt::format("no correlation came near the threshold: {} (at a wrong rate the code lines up at no "
                           "delay), {}, {} or {} is wrong?",
                           s.named(SourceSetting::sample_rate), s.named(SourceSetting::format),
                           s.named(SourceSetting::intermediate_frequency), s.named(SourceSetting::spectrum_sense))};
}

std::string seen_text(const SampleLevels& l, const SpectrumBand& band, const std::optional<AcquisitionResult>& best,
                      const std::optional<std::vector<int>>& inverted) {
  std::string text = fmt::format("power {:.1f} dBFS, {} levels used, {:.1f} % at full scale; ", l.power_dbfs,
                                 l.levels_used, 100.0 * l.at_full_scale_fraction);
  text += band.found ? fmt::format("a band {} wide centred at {}", frequency_text(band.width_hz),
                                   frequency_text(band.centre_hz))
                     : std::string("a flat spectrum (no band to place the IF by)");
  if (best)
    text += fmt::format("; strongest correlation PRN {} at {:+.0f} Hz, {:.2f} of the threshold", best->prn,
                        best->doppler_hz, threshold_ratio(*best));
  if (inverted && inverted->empty()) text += "; nothing with the spectrum inverted either";
  return text;
}

nlohmann::json seen_json(const AcquisitionEvidence& e, const SampleLevels& l, const SpectrumBand& band,
                         const std::optional<std::vector<int>>& inverted, const SourceSettings& s, double signal_s) {
  nlohmann::json settings = {{"format", to_string(s.format)},
                             {"sample_rate_hz", s.sample_rate_hz},
                             {"if_hz", s.if_hz},
                             {"inverted_spectrum", s.inverted_spectrum},
                             {"metadata", s.metadata.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.metadata)}};
  nlohmann::json overridden = nlohmann::json::object();
  for (const auto& [setting, value] : s.overridden) overridden[SourceSettings::flag(setting)] = value;
  settings["overridden"] = overridden;
  nlohmann::json strongest = nullptr;
  if (e.strongest)
    strongest = {{"prn", e.strongest->prn},
                 {"doppler_hz", e.strongest->doppler_hz},
                 {"statistic", e.strongest->statistic},
                 {"threshold", e.strongest->threshold},
                 {"ratio", threshold_ratio(*e.strongest)}};
  const double expected_if = is_complex(s.format) ? s.if_hz : std::abs(s.if_hz);
  return {
      {"signal_s", signal_s},
      {"samples_examined", l.samples},
      {"power_dbfs", l.power_dbfs},
      {"rms", {l.rms_i, l.rms_q}},
      {"levels_used", l.levels_used},
      {"at_full_scale_fraction", l.at_full_scale_fraction},
      {"low_byte_levels", l.low_byte_levels},
      {"iq_power_ratio_db", l.iq_power_ratio_db},
      {"spectrum",
       {{"band_found", band.found},
        {"centre_hz", band.found ? nlohmann::json(band.centre_hz) : nlohmann::json(nullptr)},
        {"offset_from_if_hz", band.found ? nlohmann::json(band.centre_hz - expected_if) : nlohmann::json(nullptr)},
        {"width_hz", band.found ? nlohmann::json(band.width_hz) : nlohmann::json(nullptr)},
        {"contrast_db", band.contrast_db},
        {"resolution_hz", band.resolution_hz}}},
      {"strongest_correlation", strongest},
      {"inverted_spectrum_search", inverted ? nlohmann::json{{"detected_prns", *inverted}} : nlohmann::json(nullptr)},
      {"settings", settings}};
}

}  // namespace

nlohmann::json NothingFound::json() const {
  return {{"reason", reason}, {"message", message}, {"suspects", suspects}, {"seen", seen}};
}

NothingFound diagnose_no_satellite(const AcquisitionEvidence& evidence, const SourceSettings& settings,
                                   double signal_s) {
  const bool real = !is_complex(settings.format);
  const SampleLevels levels = measure_levels(evidence.samples, real, converted_value_range(settings.format));
  const SpectrumBand band = find_spectrum_band(evidence.samples, evidence.config.sample_rate_hz, real);
  const std::optional<std::vector<int>> inverted = search_inverted(evidence, real);
  std::vector<Finding> findings;
  if (auto f = inverted_finding(inverted, settings)) findings.push_back(*f);
  if (auto f = spectrum_finding(band, settings, real); f && findings.empty()) findings.push_back(*f);
  for (Finding& f : format_findings(evidence, levels, settings, real)) findings.push_back(std::move(f));
  if (findings.empty()) {
    if (auto f = weak_signal_finding(evidence.strongest)) findings.push_back(*f);
    else findings.push_back(usual_causes(settings));
  }
  NothingFound out;
  out.reason = "no_satellite_acquired";
  std::string hints;
  for (const Finding& f : findings) {
    hints += (hints.empty() ? "" : "; ") + f.text;
    for (SourceSetting s : f.suspects)
      if (std::find(out.suspects.begin(), out.suspects.end(), setting_id(s)) == out.suspects.end())
        out.suspects.push_back(setting_id(s));
  }
  out.message = fmt::format("no satellite found in {} of signal: {} (seen: {})", duration_text(signal_s), hints,
                            seen_text(levels, band, evidence.strongest, inverted));
  out.seen = seen_json(evidence, levels, band, inverted, settings, signal_s);
  return out;
}

NothingFound too_short(double signal_s, double needed_s, const std::string& purpose) {
  NothingFound out;
  out.reason = "too_short";
  out.message = fmt::format("only {:.1f} ms of signal: {} needs {:.1f} ms", signal_s * 1e3, purpose, needed_s * 1e3);
  out.seen = {{"signal_ms", signal_s * 1e3}, {"needed_ms", needed_s * 1e3}};
  return out;
}

}  // namespace deepnav
