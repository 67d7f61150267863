// The --input address grammar: which inputs are streams, what each part parses to, and the
// messages a malformed address gets (the command-line tests and users read them).
#include "receiver/sources/source_url.hpp"

#include <gtest/gtest.h>

#include "ins/input_error.hpp"

namespace deepnav {
namespace {

/// The InputError message parse_source_url throws for `input` (empty when it throws none).
std::string rejection(const std::string& input) {
  try {
    parse_source_url(input);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

/// Checks that `input` parses to exactly `expected`.
void expect_parsed(const std::string& input, const SourceUrl& expected) {
  SCOPED_TRACE(input);
  const std::optional<SourceUrl> url = parse_source_url(input);
  ASSERT_TRUE(url);
  EXPECT_EQ(url->scheme, expected.scheme);
  EXPECT_EQ(url->host, expected.host);
  EXPECT_EQ(url->port, expected.port);
  EXPECT_EQ(url->listen, expected.listen);
}

TEST(SourceUrl, ParsesEveryScheme) {
  expect_parsed("tcp://localhost:5000", {StreamScheme::tcp, "localhost", 5000, false});
  expect_parsed("udp://192.168.1.20:1234", {StreamScheme::udp, "192.168.1.20", 1234, false});
  expect_parsed("rtltcp://sdr.local:1234", {StreamScheme::rtltcp, "sdr.local", 1234, false});
}

TEST(SourceUrl, SchemeNamesRoundTrip) {
  for (const StreamScheme s : {StreamScheme::tcp, StreamScheme::udp, StreamScheme::rtltcp})
    expect_parsed(std::string(to_string(s)) + "://h:1", {s, "h", 1, false});
  EXPECT_EQ(to_string(StreamScheme::rtltcp), "rtltcp");
}

TEST(SourceUrl, ListenFormBindsAndMayOmitHostAndPort) {
  expect_parsed("udp://@127.0.0.1:4000", {StreamScheme::udp, "127.0.0.1", 4000, true});
  // No host: every interface; port 0: any free one (a listener only).
  expect_parsed("udp://@:0", {StreamScheme::udp, "0.0.0.0", 0, true});
}

TEST(SourceUrl, FilePathsAreNotStreams) {
  EXPECT_FALSE(parse_source_url("data/L1_20211202_084700_4MHz_IQ.bin"));
  EXPECT_FALSE(parse_source_url("/tmp/capture:1.bin"));     // a ':' alone makes no URL
  EXPECT_FALSE(parse_source_url("http://example.com:80"));  // not a scheme a source reads
  EXPECT_FALSE(parse_source_url("TCP://host:1"));           // schemes are lower case
  EXPECT_FALSE(parse_source_url(""));
}

TEST(SourceUrl, Ipv6AddressesNeedNoBrackets) {
  // The port follows the last ':', so the address keeps its own colons.
  expect_parsed("tcp://::1:5000", {StreamScheme::tcp, "::1", 5000, false});
  expect_parsed("udp://@fe80::2:7000", {StreamScheme::udp, "fe80::2", 7000, true});
}

TEST(SourceUrl, PortsOutsideOneTo65535AreRefused) {
  for (const std::string port : {"0", "65536", "-1", "+80", " 80", "50x", "", "99999999999999999999"}) {
    const std::string input = "tcp://host:" + port;
    EXPECT_EQ(rejection(input), "--input '" + input + "': port '" + port + "' is not a number in 1..65535");
  }
  expect_parsed("tcp://host:65535", {StreamScheme::tcp, "host", 65535, false});
  expect_parsed("tcp://host:1", {StreamScheme::tcp, "host", 1, false});
}

TEST(SourceUrl, MissingPartsAreNamed) {
  EXPECT_EQ(rejection("tcp://:5000"), "--input 'tcp://:5000': the host is missing");
  EXPECT_EQ(rejection("rtltcp://:1234"), "--input 'rtltcp://:1234': the host is missing");
  EXPECT_EQ(rejection("udp://host"), "--input 'udp://host': expected udp://HOST:PORT");
  EXPECT_EQ(rejection("rtltcp://"), "--input 'rtltcp://': expected rtltcp://HOST:PORT");
}

TEST(SourceUrl, ListenIsForUdpOnly) {
  EXPECT_EQ(rejection("tcp://@host:5000"), "--input 'tcp://@host:5000': '@' (listen) is for udp:// only");
  EXPECT_EQ(rejection("rtltcp://@host:1234"), "--input 'rtltcp://@host:1234': '@' (listen) is for udp:// only");
}

}  // namespace
}  // namespace deepnav
