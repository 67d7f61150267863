#pragma once
// The stream addresses --input takes: tcp://HOST:PORT and udp://HOST:PORT (a `deepnav serve`,
// or a plain IQ socket with --raw), udp://@HOST:PORT (bind there and take the datagrams sent
// to it; HOST may be left out for every interface) and rtltcp://HOST:PORT (an rtl_tcp
// server). Anything else is a file path. The port is what follows the last ':', so an IPv6
// address stands without brackets (tcp://::1:5000).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace deepnav {

enum class StreamScheme { tcp, udp, rtltcp };

/// "tcp", "udp" or "rtltcp": the scheme as an address writes it.
std::string_view to_string(StreamScheme scheme);

struct SourceUrl {
  StreamScheme scheme = StreamScheme::tcp;
  std::string host;
  std::uint16_t port = 0;  ///< 0 only when listening: any free port
  bool listen = false;     ///< udp://@: bind host:port instead of subscribing to a server there
};

/// The stream `input` names, or nullopt when it names none (a file path: no "://", or a
/// scheme other than the three). Throws InputError quoting `input` for a stream address
/// that is malformed: no ':' before the port, no host (outside udp://@), '@' outside
/// udp://, or a port that is not a number in 1..65535 (0..65535 when listening).
std::optional<SourceUrl> parse_source_url(const std::string& input);

}  // namespace deepnav
