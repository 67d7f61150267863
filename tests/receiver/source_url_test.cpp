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

TEST(SourceUrl, ParsesEveryScheme) {
  const auto tcp = parse_source_url("tcp://localhost:5000");
  ASSERT_TRUE(tcp);
  EXPECT_EQ(tcp->scheme, StreamScheme::tcp);
  EXPECT_EQ(tcp->host, "localhost");
  EXPECT_EQ(tcp->port, 5000);
  EXPECT_FALSE(tcp->listen);

  const auto udp = parse_source_url("udp://192.168.1.20:1234");
  ASSERT_TRUE(udp);
  EXPECT_EQ(udp->scheme, StreamScheme::udp);
  EXPECT_EQ(udp->host, "192.168.1.20");
  EXPECT_EQ(udp->port, 1234);
  EXPECT_FALSE(udp->listen);

  const auto rtl = parse_source_url("rtltcp://sdr.local:1234");
  ASSERT_TRUE(rtl);
  EXPECT_EQ(rtl->scheme, StreamScheme::rtltcp);
  EXPECT_EQ(rtl->host, "sdr.local");
  EXPECT_EQ(rtl->port, 1234);
}

TEST(SourceUrl, SchemeNamesRoundTrip) {
  for (const StreamScheme s : {StreamScheme::tcp, StreamScheme::udp, StreamScheme::rtltcp}) {
    const auto url = parse_source_url(std::string(to_string(s)) + "://h:1");
    ASSERT_TRUE(url) << to_string(s);
    EXPECT_EQ(url->scheme, s);
  }
  EXPECT_EQ(to_string(StreamScheme::rtltcp), "rtltcp");
}

TEST(SourceUrl, ListenFormBindsAndMayOmitHostAndPort) {
  const auto on_host = parse_source_url("udp://@127.0.0.1:4000");
  ASSERT_TRUE(on_host);
  EXPECT_TRUE(on_host->listen);
  EXPECT_EQ(on_host->host, "127.0.0.1");
  EXPECT_EQ(on_host->port, 4000);

  // No host: every interface; port 0: any free one (a listener only).
  const auto anywhere = parse_source_url("udp://@:0");
  ASSERT_TRUE(anywhere);
  EXPECT_TRUE(anywhere->listen);
  EXPECT_EQ(anywhere->host, "0.0.0.0");
  EXPECT_EQ(anywhere->port, 0);
}

TEST(SourceUrl, FilePathsAreNotStreams) {
  EXPECT_FALSE(parse_source_url("data/L1_20211202_084700_4MHz_IQ.bin"));
  EXPECT_FALSE(parse_source_url("/tmp/capture:1.bin"));  // a ':' alone makes no URL
  EXPECT_FALSE(parse_source_url("http://example.com:80"));  // not a scheme a source reads
  EXPECT_FALSE(parse_source_url("TCP://host:1"));  // schemes are lower case
  EXPECT_FALSE(parse_source_url(""));
}

TEST(SourceUrl, Ipv6AddressesNeedNoBrackets) {
  // The port follows the last ':', so the address keeps its own colons.
  const auto url = parse_source_url("tcp://::1:5000");
  ASSERT_TRUE(url);
  EXPECT_EQ(url->host, "::1");
  EXPECT_EQ(url->port, 5000);
  const auto listen = parse_source_url("udp://@fe80::2:7000");
  ASSERT_TRUE(listen);
  EXPECT_EQ(listen->host, "fe80::2");
  EXPECT_EQ(listen->port, 7000);
}

TEST(SourceUrl, PortsOutsideOneTo65535AreRefused) {
  EXPECT_EQ(rejection("tcp://host:0"), "--input 'tcp://host:0': port '0' is not a number in 1..65535");
  EXPECT_EQ(rejection("tcp://host:65536"), "--input 'tcp://host:65536': port '65536' is not a number in 1..65535");
  EXPECT_EQ(rejection("udp://host:-1"), "--input 'udp://host:-1': port '-1' is not a number in 1..65535");
  EXPECT_EQ(rejection("tcp://host:50x"), "--input 'tcp://host:50x': port '50x' is not a number in 1..65535");
  EXPECT_EQ(rejection("tcp://host:"), "--input 'tcp://host:': port '' is not a number in 1..65535");
  EXPECT_EQ(rejection("rtltcp://host:99999999999999999999"),
            "--input 'rtltcp://host:99999999999999999999': port '99999999999999999999' is not a number in 1..65535");
  EXPECT_EQ(parse_source_url("tcp://host:65535")->port, 65535);
  EXPECT_EQ(parse_source_url("tcp://host:1")->port, 1);
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
