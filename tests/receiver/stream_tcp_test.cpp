// TCP streaming on loopback (ephemeral ports): a scripted server checks what the
// receiver's source does with a disconnect in the middle of a frame (reconnect, resume,
// no gap), a wrong magic, a wrong version and an oversized frame length (clear errors);
// and the real StreamServer survives a client sending garbage and serves the next one.
#include <gtest/gtest.h>

#include <boost/asio.hpp>
#include <thread>

#include "receiver/stream/stream_protocol.hpp"
#include "receiver/stream/stream_server.hpp"
#include "receiver/stream/tcp_sample_source.hpp"

namespace deepnav {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;

stream::StreamHeader header_at(std::int64_t start) {
  stream::StreamHeader h;
  h.format = SampleFormat::ishort;
  h.sample_rate_hz = 1.0e6;
  h.start_sample_index = start;
  h.max_payload_bytes = 4000;
  return h;
}

/// Sample value for index i (so the test sees exactly which samples arrived).
std::vector<std::byte> payload(std::int64_t first, int count) {
  std::vector<std::byte> out(static_cast<std::size_t>(count) * 4);
  for (int k = 0; k < count; ++k) {
    const auto i = static_cast<std::int16_t>((first + k) % 30000);
    const std::int16_t iq[2] = {i, static_cast<std::int16_t>(-i)};
    std::memcpy(out.data() + 4 * k, iq, 4);
  }
  return out;
}

void send(tcp::socket& s, std::span<const std::byte> bytes) {
  asio::write(s, asio::buffer(bytes.data(), bytes.size()));
}

void send_frame(tcp::socket& s, std::uint64_t seq, std::int64_t first, int count, std::size_t cut = 0) {
  const auto p = payload(first, count);
  const auto h = stream::encode(stream::FrameHeader{seq, first, static_cast<std::uint32_t>(p.size()), false});
  send(s, h);
  send(s, std::span<const std::byte>(p).first(cut ? cut : p.size()));
}

stream::ClientRequest read_request(tcp::socket& s) {
  std::array<std::byte, stream::kRequestBytes> b{};
  asio::read(s, asio::buffer(b));
  return stream::decode_request(b);
}

struct ScriptedServer {
  asio::io_context io;
  tcp::acceptor acceptor{io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)};
  std::thread thread;
  std::uint16_t port() const { return acceptor.local_endpoint().port(); }
  ~ScriptedServer() {
    if (thread.joinable()) thread.join();
  }
};

StreamSourceSettings settings_for(std::uint16_t port) {
  StreamSourceSettings s;
  s.port = port;
  s.connect_timeout_s = 5.0;
  s.reconnect_timeout_s = 5.0;
  return s;
}

TEST(StreamTcp, DisconnectMidFrameReconnectsAndResumesWithoutGap) {
  ScriptedServer server;
  std::int64_t resume_asked = -1;
  server.thread = std::thread([&] {
    {
      tcp::socket s = server.acceptor.accept();
      EXPECT_EQ(read_request(s).resume_from_sample, 0);
      send(s, stream::encode(header_at(0)));
      send_frame(s, 0, 0, 1000);
      send_frame(s, 1, 1000, 1000, 1234);  // cut in the middle of the payload
    }
    tcp::socket s = server.acceptor.accept();
    resume_asked = read_request(s).resume_from_sample;
    send(s, stream::encode(header_at(resume_asked)));
    send_frame(s, 0, resume_asked, 1000);
    send_frame(s, 1, resume_asked + 1000, 500);
    send(s, stream::encode(stream::FrameHeader{2, resume_asked + 1500, 0, true}));
  });
  TcpSampleSource source(settings_for(server.port()));
  std::vector<Sample> all;
  SampleBlock block;
  while (source.read_block(block, 700)) {
    EXPECT_EQ(block.first_sample_index, static_cast<std::int64_t>(all.size()));
    all.insert(all.end(), block.samples.begin(), block.samples.end());
  }
  EXPECT_EQ(resume_asked, 1000);
  ASSERT_EQ(all.size(), 2500u);
  for (std::size_t i = 0; i < all.size(); ++i) ASSERT_EQ(all[i].real(), static_cast<std::int16_t>(i)) << i;
  const StreamStats st = source.stats();
  EXPECT_EQ(st.reconnects, 1);
  EXPECT_EQ(st.partial_frame_bytes_discarded, stream::kFrameHeaderBytes + 1234);
  EXPECT_EQ(source.lost_sample_count(), 0);
  EXPECT_EQ(st.end_reason, "end of stream");
  EXPECT_FALSE(st.failed);
}

std::string open_error(const std::function<void(tcp::socket&)>& script) {
  ScriptedServer server;
  server.thread = std::thread([&] {
    tcp::socket s = server.acceptor.accept();
    read_request(s);
    script(s);
    boost::system::error_code ec;
    s.shutdown(tcp::socket::shutdown_send, ec);
    std::array<char, 64> sink{};
    while (!ec) s.read_some(asio::buffer(sink), ec);  // until the client hangs up
  });
  try {
    TcpSampleSource source(settings_for(server.port()));
    SampleBlock block;
    while (source.read_block(block, 1000)) {
    }
    return source.stats().failed ? source.stats().end_reason : "";
  } catch (const std::runtime_error& e) {
    return e.what();
  }
}

TEST(StreamTcp, MalformedStreamsAreClearErrors) {
  auto header = stream::encode(header_at(0));
  auto wrong_magic = header;
  wrong_magic[1] = std::byte{'X'};
  EXPECT_NE(open_error([&](tcp::socket& s) { send(s, wrong_magic); }).find("magic is \"DXIF\", expected \"DNIF\""),
            std::string::npos);
  auto wrong_version = header;
  wrong_version[4] = std::byte{2};
  EXPECT_NE(open_error([&](tcp::socket& s) { send(s, wrong_version); }).find("protocol version 2 is not supported"),
            std::string::npos);
  const std::string oversized = open_error([&](tcp::socket& s) {
    send(s, header);
    send(s, stream::encode(stream::FrameHeader{0, 0, 0x7fffffff, false}));
  });
  EXPECT_NE(oversized.find("payload length 2147483647 bytes exceeds the stream's maximum of 4000 bytes"),
            std::string::npos)
      << oversized;
  EXPECT_NE(open_error([&](tcp::socket& s) {
              send(s, header);
              send_frame(s, 0, 0, 10);
              send_frame(s, 2, 10, 10);
            }).find("frame sequence number 2 where 1 was expected"),
            std::string::npos);
}

TEST(StreamTcp, ServerSurvivesGarbageClientAndServesTheNext) {
  StreamServerOptions o;
  o.tcp_port = 0;
  o.pace = 0.0;
  o.tcp_payload_bytes = 4000;
  o.open_stream = [] {
    // A small in-memory stream of 10000 ishort samples.
    struct Memory final : IfByteStream {
      std::int64_t next = 0;
      SampleFormat format() const override { return SampleFormat::ishort; }
      double sample_rate_hz() const override { return 1.0e6; }
      double if_hz() const override { return 0.0; }
      std::optional<GpsTime> start_time() const override { return std::nullopt; }
      std::optional<std::int64_t> total_samples() const override { return 10000; }
      std::size_t read(std::vector<std::byte>& out, std::size_t max) override {
        const int n = static_cast<int>(std::min<std::int64_t>(static_cast<std::int64_t>(max), 10000 - next));
        out = payload(next, n);
        next += n;
        return static_cast<std::size_t>(n);
      }
      void seek(std::int64_t i) override { next = i; }
      std::int64_t next_sample_index() const override { return next; }
    };
    return std::unique_ptr<IfByteStream>(new Memory);
  };
  StreamServer server(o);
  std::atomic<bool> stop{false};
  std::thread runner([&] { server.run(stop, 2); });
  {
    asio::io_context io;
    tcp::socket s(io);
    s.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), server.tcp_port()));
    const std::string garbage = "\x01\x02 this is not a request";
    asio::write(s, asio::buffer(garbage));
    boost::system::error_code ec;
    std::array<char, 64> sink{};
    std::size_t got = 0;
    while (!ec) got += s.read_some(asio::buffer(sink), ec);
    EXPECT_EQ(ec, asio::error::eof);  // the server closed it, sending nothing
    EXPECT_EQ(got, 0u);
  }
  TcpSampleSource source(settings_for(server.tcp_port()));
  SampleBlock block;
  std::int64_t n = 0;
  while (source.read_block(block, 3000)) n += static_cast<std::int64_t>(block.samples.size());
  EXPECT_EQ(n, 10000);
  runner.join();
  const auto reports = server.reports();
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_NE(reports[0].end.find("bad request"), std::string::npos) << reports[0].end;
  EXPECT_NE(reports[0].end.find("magic"), std::string::npos) << reports[0].end;
  EXPECT_EQ(reports[1].samples_sent, 10000);
}

}  // namespace
}  // namespace deepnav
