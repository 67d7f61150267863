// rtl_tcp: the dongle header and the tuning commands byte for byte, the tuning limits, the
// arrival-time loss detector (jitter, a stall then a burst, a slow sample clock and a
// consumer falling behind are no loss; a dropped buffer is, of the right size and place),
// and the source against a scripted rtl_tcp server on loopback.
#include <gtest/gtest.h>

#include <boost/asio.hpp>
#include <random>
#include <thread>

#include "receiver/stream/arrival_loss_detector.hpp"
#include "receiver/stream/rtltcp_protocol.hpp"
#include "receiver/stream/rtltcp_sample_source.hpp"
#include "receiver/stream/stream_protocol.hpp"

namespace deepnav {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;

std::vector<int> bytes_of(std::span<const std::byte> b) {
  std::vector<int> out;
  for (const std::byte x : b) out.push_back(std::to_integer<int>(x));
  return out;
}

TEST(RtlTcpProtocol, DongleHeaderAndCommands) {
  const auto header = rtltcp::encode(rtltcp::DongleInfo{5, 29});
  EXPECT_EQ(bytes_of(header), (std::vector<int>{'R', 'T', 'L', '0', 0, 0, 0, 5, 0, 0, 0, 29}));
  const rtltcp::DongleInfo info = rtltcp::decode_dongle_info(header);
  EXPECT_EQ(info.tuner_type, 5u);
  EXPECT_EQ(info.gain_count, 29u);
  EXPECT_EQ(rtltcp::tuner_name(5), "R820T");
  EXPECT_EQ(rtltcp::tuner_name(1), "E4000");
  EXPECT_EQ(rtltcp::tuner_name(77), "unknown tuner 77");
  auto bad = header;
  bad[3] = std::byte{'1'};
  try {
    rtltcp::decode_dongle_info(bad);
    FAIL() << "accepted RTL1";
  } catch (const stream::ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("magic is \"RTL1\", expected \"RTL0\""), std::string::npos) << e.what();
  }
  // Command byte, then the parameter big-endian.
  EXPECT_EQ(bytes_of(rtltcp::encode_command(rtltcp::Command::set_frequency, 1575420000)),
            (std::vector<int>{0x01, 0x5D, 0xE7, 0x00, 0x60}));
}

TEST(RtlTcpProtocol, TuningCommandsInOrder) {
  rtltcp::Tuning t;  // 1575.42 MHz, 2.048 Msps, tuner AGC
  auto commands = rtltcp::tuning_commands(t);
  std::vector<int> codes;
  for (const auto& c : commands) codes.push_back(std::to_integer<int>(c[0]));
  EXPECT_EQ(codes, (std::vector<int>{0x02, 0x01, 0x05, 0x03, 0x08, 0x0e}));
  EXPECT_EQ(bytes_of(commands[0]), (std::vector<int>{0x02, 0x00, 0x1F, 0x40, 0x00}));  // 2048000
  EXPECT_EQ(bytes_of(commands[3]), (std::vector<int>{0x03, 0, 0, 0, 0}));              // automatic gain
  t.gain_db = 40.2;
  t.ppm = -3;
  t.rtl_agc = true;
  t.bias_tee = true;
  commands = rtltcp::tuning_commands(t);
  ASSERT_EQ(commands.size(), 7u);
  EXPECT_EQ(bytes_of(commands[2]), (std::vector<int>{0x05, 0xFF, 0xFF, 0xFF, 0xFD}));  // -3 ppm
  EXPECT_EQ(bytes_of(commands[3]), (std::vector<int>{0x03, 0, 0, 0, 1}));              // manual gain
  EXPECT_EQ(bytes_of(commands[4]), (std::vector<int>{0x04, 0, 0, 0x01, 0x92}));        // 402 tenths of a dB
  EXPECT_EQ(bytes_of(commands[5]), (std::vector<int>{0x08, 0, 0, 0, 1}));
  EXPECT_EQ(bytes_of(commands[6]), (std::vector<int>{0x0e, 0, 0, 0, 1}));
  EXPECT_NO_THROW(rtltcp::validate(t));
  rtltcp::Tuning bad = t;
  bad.sample_rate_hz = 2600000;
  EXPECT_NO_THROW(rtltcp::validate(bad));
  bad.sample_rate_hz = 500000;
  EXPECT_THROW(rtltcp::validate(bad), std::invalid_argument);
  bad = t;
  bad.center_frequency_hz = 2.4e9;
  EXPECT_THROW(rtltcp::validate(bad), std::invalid_argument);
  bad = t;
  bad.gain_db = 75.0;
  EXPECT_THROW(rtltcp::validate(bad), std::invalid_argument);
}

/// Pieces of `piece` samples made at fs, arriving with a random latency of up to
/// `jitter_s`, except as `latency` says; returns the detector's verdicts.
struct Feed {
  double fs = 2.048e6;
  std::int64_t piece = 16384;
  ArrivalLossDetector detector{2.048e6};
  std::vector<ArrivalLossDetector::Verdict> verdicts;
  std::int64_t made = 0;  ///< samples the dongle has made
  void run(double seconds, const std::function<double(double)>& extra_latency, double jitter_s = 0.003,
           double rate_factor = 1.0, std::int64_t drop_at = -1, std::int64_t drop = 0,
           const std::function<void(double, std::size_t)>& on_release = {}) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> jitter(0.0, jitter_s);
    const auto end = static_cast<std::int64_t>(seconds * fs);
    while (made < end) {
      made += piece;
      const double t_made = static_cast<double>(made) / (fs * rate_factor);
      if (drop_at >= 0 && made > drop_at && made <= drop_at + drop) continue;  // never sent
      const double t = t_made + 0.002 + jitter(rng) + extra_latency(t_made);
      detector.arrived(t, piece);
      const auto released = detector.release(t);
      if (on_release) on_release(t, released.size());
      verdicts.insert(verdicts.end(), released.begin(), released.end());
    }
    for (const auto& v : detector.release(1e9, true)) verdicts.push_back(v);
  }
  std::int64_t lost() const {
    std::int64_t n = 0;
    for (const auto& v : verdicts) n += v.missing_before;
    return n;
  }
};

TEST(ArrivalLossDetector, JitterDelaysSlowClocksAreNoLoss) {
  Feed steady;
  steady.run(30.0, [](double) { return 0.0; });
  EXPECT_EQ(steady.lost(), 0);
  EXPECT_EQ(steady.verdicts.size(), static_cast<std::size_t>(steady.made / steady.piece));
  // Nothing arrives for 0.6 s at 10 s, then everything at once (a stalled link): late, not lost.
  Feed stall;
  stall.run(20.0, [](double t) { return t > 10.0 && t < 10.6 ? 10.6 - t : 0.0; });
  EXPECT_EQ(stall.lost(), 0);
  // A dongle clock 100 ppm slow for 100 s: the lag grows by 10 ms, slowly.
  Feed slow;
  slow.run(
      100.0, [](double) { return 0.0; }, 0.003, 1.0 - 100e-6);
  EXPECT_EQ(slow.lost(), 0);
}

TEST(ArrivalLossDetector, ADroppedStretchIsLostBeforeTheRightPiece) {
  Feed f;
  const std::int64_t drop_at = 10 * 16384 * 125, drop = 16384 * 12;  // ~96 ms after ~10 s
  f.run(
      20.0, [](double) { return 0.0; }, 0.003, 1.0, drop_at, drop);
  EXPECT_NEAR(static_cast<double>(f.lost()), static_cast<double>(drop), 0.004 * f.fs);
  // The loss is reported before the first piece after the hole, and only there.
  std::int64_t delivered = 0;
  int with_loss = 0;
  for (const auto& v : f.verdicts) {
    if (v.missing_before > 0) {
      ++with_loss;
      EXPECT_EQ(delivered, drop_at);
    }
    delivered += v.count;
  }
  EXPECT_EQ(with_loss, 1);
  EXPECT_EQ(f.detector.declared_lost(), f.lost());
}

TEST(ArrivalLossDetector, NoVerdictAgainstABaselineThatWasReset) {
  // Real time for 3 s, then everything 0.3 s later from then on: a loss of 300 samples; but
  // not when the consumer fell behind in between (a shift then may be its own backlog, not
  // the server's doing).
  for (const bool reset : {false, true}) {
    ArrivalLossDetector d(1000.0, 0.025, 0.1, 10.0);
    std::int64_t lost = 0;
    double t = 0.0;
    for (int i = 0; i < 300; ++i) d.arrived(t += 0.01, 10);
    for (const auto& v : d.release(t)) lost += v.missing_before;
    if (reset) d.backlogged(t);
    for (int i = 0; i < 300; ++i) d.arrived((t += 0.01) + 0.3, 10);
    for (const auto& v : d.release(t + 1.0, true)) lost += v.missing_before;
    EXPECT_EQ(lost, reset ? 0 : 300) << (reset ? "after a reset" : "without one");
    EXPECT_FALSE(d.slow());
  }
}

TEST(ArrivalLossDetector, PiecesWaitUntilThePaceIsKnown) {
  // A loss in the first second is judged where it happened, once 2 s of arrivals tell the
  // pace: no piece is released before.
  Feed f;
  const std::int64_t drop_at = 16384 * 40, drop = 16384 * 12;  // ~96 ms after ~0.3 s
  std::size_t released_early = 0;
  f.run(
      20.0, [](double) { return 0.0; }, 0.003, 1.0, drop_at, drop,
      [&](double t, std::size_t released) {
        if (t < 2.0) released_early += released;
      });
  EXPECT_EQ(released_early, 0u);
  EXPECT_NEAR(static_cast<double>(f.lost()), static_cast<double>(drop), 0.004 * f.fs);
  std::int64_t delivered = 0;
  for (const auto& v : f.verdicts) {
    if (v.missing_before > 0) {
      EXPECT_EQ(delivered, drop_at);
    }
    delivered += v.count;
  }
}

TEST(ArrivalLossDetector, ASlowSenderIsSlowNotLossy) {
  // Half real time (a file replayed slowly): every piece later than the one before, which
  // once made 19.9 M samples "lost" in 304 gaps. No loss, and the stream is slow.
  Feed half;
  half.run(
      20.0, [](double) { return 0.0; }, 0.003, 0.5);
  EXPECT_EQ(half.lost(), 0);
  EXPECT_TRUE(half.detector.slow());
  EXPECT_NEAR(*half.detector.pace().overall(), 0.5, 0.01);
  // 0.9 of real time (a link a little narrower than the rate): slow too.
  Feed narrow;
  narrow.run(
      20.0, [](double) { return 0.0; }, 0.003, 0.9);
  EXPECT_EQ(narrow.lost(), 0);
  EXPECT_TRUE(narrow.detector.slow());
  // A loss while the sender keeps real time is still one.
  Feed lossy;
  lossy.run(
      20.0, [](double) { return 0.0; }, 0.003, 1.0, 16384 * 1250, 16384 * 12);
  EXPECT_FALSE(lossy.detector.slow());
  EXPECT_GT(lossy.lost(), 0);
}

TEST(RtlTcpSource, TunesTheDongleAndStreamsItsSamples) {
  asio::io_context io;
  tcp::acceptor acceptor(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  std::vector<std::byte> commands(7 * rtltcp::kCommandBytes);
  std::thread server([&] {
    tcp::socket s = acceptor.accept();
    const auto header = rtltcp::encode(rtltcp::DongleInfo{5, 29});
    asio::write(s, asio::buffer(header));
    asio::read(s, asio::buffer(commands));
    // 3000 samples: I = i % 256, Q = 255 - I; sent in odd-sized pieces (split samples).
    std::vector<std::byte> data(6000);
    for (std::size_t i = 0; i < 3000; ++i) {
      data[2 * i] = static_cast<std::byte>(i % 256);
      data[2 * i + 1] = static_cast<std::byte>(255 - i % 256);
    }
    for (std::size_t at = 0; at < data.size(); at += 1001) {
      asio::write(s, asio::buffer(data.data() + at, std::min<std::size_t>(1001, data.size() - at)));
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  });
  StreamSourceSettings st;
  st.port = acceptor.local_endpoint().port();
  st.connect_timeout_s = 5.0;
  RtlTcpSettings rtl;
  rtl.tuning.gain_db = 40.2;
  rtl.tuning.ppm = -3;
  rtl.tuning.bias_tee = true;
  rtl.settle_s = 1000.0 / rtl.tuning.sample_rate_hz;  // the first 1000 samples
  rtl.loss_horizon_s = 0.05;
  RtlTcpSampleSource source(st, rtl);
  EXPECT_EQ(source.dongle().tuner_type, 5u);
  EXPECT_FALSE(source.gap_sizes_exact());
  EXPECT_FALSE(source.is_real());
  EXPECT_EQ(source.sample_rate_hz(), 2048000.0);
  std::vector<Sample> all;
  SampleBlock block;
  while (source.read_block(block, 700)) {
    EXPECT_EQ(block.first_sample_index, static_cast<std::int64_t>(all.size()));
    all.insert(all.end(), block.samples.begin(), block.samples.end());
  }
  server.join();
  std::vector<std::byte> expected;
  for (const auto& c : rtltcp::tuning_commands(rtl.tuning)) expected.insert(expected.end(), c.begin(), c.end());
  EXPECT_EQ(commands, expected);
  ASSERT_EQ(all.size(), 2000u);
  for (std::size_t k = 0; k < all.size(); ++k) {
    const int u = static_cast<int>((k + 1000) % 256);
    ASSERT_EQ(all[k], Sample(static_cast<std::int16_t>(2 * u - 255), static_cast<std::int16_t>(2 * (255 - u) - 255)))
        << k;
  }
  EXPECT_EQ(source.lost_sample_count(), 0);
  EXPECT_EQ(source.stats().end_reason, "the server closed the connection");
  EXPECT_EQ(source.stats().bytes_received, 6000);
}

TEST(RtlTcpSource, NotAnRtlTcpServerIsNamed) {
  asio::io_context io;
  tcp::acceptor acceptor(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  std::thread server([&] {
    tcp::socket s = acceptor.accept();
    asio::write(s, asio::buffer(std::string("SSH-2.0-OpenSSH\r\n")));
    std::array<char, 64> sink{};
    boost::system::error_code ec;
    while (!ec) s.read_some(asio::buffer(sink), ec);
  });
  StreamSourceSettings st;
  st.port = acceptor.local_endpoint().port();
  st.connect_timeout_s = 5.0;
  try {
    RtlTcpSampleSource source(st, RtlTcpSettings{});
    ADD_FAILURE() << "accepted an SSH server";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("rtltcp://127.0.0.1:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("magic is \"SSH-\""), std::string::npos) << msg;
  }
  server.join();
}

}  // namespace
}  // namespace deepnav
