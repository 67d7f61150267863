#include "receiver/sources/source_url.hpp"

#include <fmt/format.h>

#include <array>
#include <charconv>

#include "ins/input_error.hpp"

namespace deepnav {
namespace {

/// The schemes' names, in the order of StreamScheme's enumerators.
constexpr std::array<std::string_view, 3> kSchemeNames{"tcp", "udp", "rtltcp"};

std::optional<StreamScheme> scheme_named(std::string_view name) {
  for (std::size_t i = 0; i < kSchemeNames.size(); ++i)
    if (kSchemeNames[i] == name) return static_cast<StreamScheme>(i);
  return std::nullopt;
}

/// The port after the last ':'; port 0 (any free one) only makes sense for a listener.
std::uint16_t parse_port(const std::string& input, std::string_view text, bool listen) {
  unsigned long port = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), port);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || port > 65535 ||
      (port == 0 && !listen))
    throw InputError(fmt::format("--input '{}': port '{}' is not a number in 1..65535", input, text));
  return static_cast<std::uint16_t>(port);
}

}  // namespace

std::string_view to_string(StreamScheme scheme) { return kSchemeNames.at(static_cast<std::size_t>(scheme)); }

std::optional<SourceUrl> parse_source_url(const std::string& input) {
  const auto separator = input.find("://");
  if (separator == std::string::npos) return std::nullopt;
  const std::optional<StreamScheme> scheme = scheme_named(std::string_view(input).substr(0, separator));
  if (!scheme) return std::nullopt;
  SourceUrl url;
  url.scheme = *scheme;
  std::string_view rest = std::string_view(input).substr(separator + 3);
  if (!rest.empty() && rest.front() == '@') {
    if (url.scheme != StreamScheme::udp)
      throw InputError(fmt::format("--input '{}': '@' (listen) is for udp:// only", input));
    url.listen = true;
    rest.remove_prefix(1);
  }
  const auto colon = rest.rfind(':');
  if (colon == std::string_view::npos)
    throw InputError(fmt::format("--input '{}': expected {}://HOST:PORT", input, to_string(url.scheme)));
  url.host = rest.substr(0, colon);
  if (url.host.empty()) {
    if (!url.listen) throw InputError(fmt::format("--input '{}': the host is missing", input));
    url.host = "0.0.0.0";  // a listener without a host takes datagrams on every interface
  }
  url.port = parse_port(input, rest.substr(colon + 1), url.listen);
  return url;
}

}  // namespace deepnav
