#include "receiver/sources/source_settings.hpp"

#include <fmt/format.h>

namespace deepnav {
namespace {

/// The setting in words, for naming a value that came from a file or a header.
std::string noun(SourceSetting s) {
  switch (s) {
    case SourceSetting::format:
      return "format";
    case SourceSetting::sample_rate:
      return "sample rate";
    case SourceSetting::intermediate_frequency:
      return "IF";
    case SourceSetting::spectrum_sense:
      return "spectrum sense";
  }
  return "setting";
}

std::string unit(SourceSetting s) {
  return s == SourceSetting::sample_rate || s == SourceSetting::intermediate_frequency ? " Hz" : "";
}

}  // namespace

SettingOrigin SourceSettings::origin(SourceSetting s) const {
  const auto it = origins.find(s);
  return it == origins.end() ? SettingOrigin::flag : it->second;
}

std::string SourceSettings::flag(SourceSetting s) {
  switch (s) {
    case SourceSetting::format:
      return "--format";
    case SourceSetting::sample_rate:
      return "--fs";
    case SourceSetting::intermediate_frequency:
      return "--if";
    case SourceSetting::spectrum_sense:
      return "--inverted-spectrum";
  }
  return "";
}

std::string SourceSettings::value(SourceSetting s) const {
  switch (s) {
    case SourceSetting::format:
      return to_string(format);
    case SourceSetting::sample_rate:
      return fmt::format("{}", sample_rate_hz);
    case SourceSetting::intermediate_frequency:
      return fmt::format("{}", if_hz);
    case SourceSetting::spectrum_sense:
      return inverted_spectrum ? "true" : "false";
  }
  return "";
}

std::string SourceSettings::named(SourceSetting s) const {
  const bool sense = s == SourceSetting::spectrum_sense;
  switch (origin(s)) {
    case SettingOrigin::metadata:
      return sense ? fmt::format("the {} spectrum of {}", inverted_spectrum ? "inverted" : "upright", metadata)
                   : fmt::format("the {} {}{} of {}", noun(s), value(s), unit(s), metadata);
    case SettingOrigin::stream_header:
      return fmt::format("the {} {}{} of the stream's header", noun(s), value(s), unit(s));
    case SettingOrigin::flag:
      break;
  }
  std::string text = sense ? (inverted_spectrum ? flag(s) : "no " + flag(s)) : flag(s) + " " + value(s);
  if (const auto it = overridden.find(s); it != overridden.end())
    text += fmt::format(" (over {}'s {})", metadata, it->second);
  return text;
}

}  // namespace deepnav
