// The streaming protocol: encode/decode round trips, every header/frame violation is a
// ProtocolError naming the field, and the incremental parser survives random input.
#include <gtest/gtest.h>

#include <chrono>
#include <random>

#include "receiver/stream/frame_sequencer.hpp"
#include "receiver/stream/stream_protocol.hpp"

namespace deepnav::stream {
namespace {

StreamHeader test_header() {
  StreamHeader h;
  h.format = SampleFormat::ishort;
  h.sample_rate_hz = 4.092e6;
  h.if_hz = 1.25e3;
  h.start_sample_index = 4096;
  h.start_time = GpsTime{2190, 525600.5};
  h.max_payload_bytes = 4096;
  return h;
}

std::vector<std::byte> valid_stream(std::mt19937_64& rng, int frames, std::vector<Frame>& sent) {
  const StreamHeader h = test_header();
  const auto hb = encode(h);
  std::vector<std::byte> out(hb.begin(), hb.end());
  std::int64_t index = h.start_sample_index;
  for (int i = 0; i < frames; ++i) {
    Frame f;
    const auto samples = std::uniform_int_distribution<std::uint32_t>(1, 1024)(rng);
    f.header = FrameHeader{static_cast<std::uint64_t>(i), index, samples * 4, false};
    f.payload.resize(f.header.payload_bytes);
    for (auto& b : f.payload) b = static_cast<std::byte>(rng());
    index += samples;
    const auto fb = encode(f.header);
    out.insert(out.end(), fb.begin(), fb.end());
    out.insert(out.end(), f.payload.begin(), f.payload.end());
    sent.push_back(f);
  }
  return out;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ProtocolError& e) {
    return e.what();
  }
  return "";
}

TEST(StreamProtocol, HeaderFrameAndRequestRoundTrip) {
  const StreamHeader h = test_header();
  const StreamHeader d = decode_header(encode(h));
  EXPECT_EQ(d.format, h.format);
  EXPECT_EQ(d.sample_rate_hz, h.sample_rate_hz);
  EXPECT_EQ(d.if_hz, h.if_hz);
  EXPECT_EQ(d.start_sample_index, h.start_sample_index);
  ASSERT_TRUE(d.start_time);
  EXPECT_EQ(d.start_time->week, 2190);
  EXPECT_EQ(d.start_time->sow, 525600.5);
  EXPECT_EQ(d.max_payload_bytes, 4096u);
  const FrameHeader f{77, 4096 + 77 * 1000, 4000, false};
  const FrameHeader g = decode_frame_header(encode(f), h);
  EXPECT_EQ(g.sequence, 77u);
  EXPECT_EQ(g.first_sample_index, 4096 + 77 * 1000);
  EXPECT_EQ(g.payload_bytes, 4000u);
  const ClientRequest r = decode_request(encode(ClientRequest{987654321, true}));
  EXPECT_EQ(r.resume_from_sample, 987654321);
  EXPECT_TRUE(r.stop);
}

TEST(StreamProtocol, Cu8IsFormatCodeFour) {
  StreamHeader h = test_header();
  h.format = SampleFormat::cu8;
  const auto bytes = encode(h);
  EXPECT_EQ(bytes[8], std::byte{4});
  EXPECT_EQ(decode_header(bytes).format, SampleFormat::cu8);
}

TEST(StreamProtocol, BadHeadersAreClearErrors) {
  auto bytes = encode(test_header());
  auto with = [&](std::size_t at, std::byte value) {
    auto b = bytes;
    b[at] = value;
    return error_of([&] { decode_header(b); });
  };
  EXPECT_NE(with(0, std::byte{'X'}).find("magic is \"XNIF\", expected \"DNIF\""), std::string::npos);
  EXPECT_NE(with(4, std::byte{9}).find("protocol version 9 is not supported"), std::string::npos);
  EXPECT_NE(with(8, std::byte{7}).find("sample format code 7"), std::string::npos);
  EXPECT_NE(with(9, std::byte{0x80}).find("flag"), std::string::npos);
  EXPECT_NE(with(15, std::byte{0x7f}).find("maximum payload"), std::string::npos);
  EXPECT_NE(with(23, std::byte{0xff}).find("sample rate"), std::string::npos);  // NaN
  const std::string ok = error_of([&] { decode_header(bytes); });
  EXPECT_EQ(ok, "");
}

TEST(StreamProtocol, BadFramesAreClearErrors) {
  const StreamHeader h = test_header();
  EXPECT_NE(error_of([&] {
              decode_frame_header(encode(FrameHeader{3, 5000, 1u << 30, false}), h);
            }).find("payload length 1073741824 bytes exceeds the stream's maximum of 4096"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              decode_frame_header(encode(FrameHeader{3, 5000, 6, false}), h);
            }).find("not whole"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              decode_frame_header(encode(FrameHeader{3, 10, 8, false}), h);
            }).find("before the stream's start"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              decode_frame_header(encode(FrameHeader{3, 5000, 0, false}), h);
            }).find("may be empty"),
            std::string::npos);
  StreamParser parser;
  std::vector<Frame> frames;
  const std::string garbage = "GET / HTTP/1.1\r\nHost: x\r\n\r\n";
  const std::string e =
      error_of([&] { parser.feed(std::as_bytes(std::span<const char>(garbage.data(), garbage.size())), frames); });
  EXPECT_NE(e.find("magic is \"GET \", expected \"DNIF\""), std::string::npos) << e;
}

TEST(StreamProtocol, SequenceNumberAndSampleIndexBoundEachOther) {
  // Frames of a session carry 1 to 1024 samples each (4096-byte payloads of ishort) from
  // sample 4096: frame n starts between 4096 + n and 4096 + 1024 n.
  const StreamHeader h = test_header();
  EXPECT_EQ(error_of([&] { decode_frame_header(encode(FrameHeader{10, 4096 + 10, 4, false}), h); }), "");
  EXPECT_EQ(error_of([&] { decode_frame_header(encode(FrameHeader{10, 4096 + 10240, 4, false}), h); }), "");
  EXPECT_EQ(error_of([&] { decode_frame_header(encode(FrameHeader{0, 4096, 4, false}), h); }), "");
  // A sequence number of 2^63 (the loss accounting would count 9e18 frames lost).
  const std::string seq = error_of([&] { decode_frame_header(encode(FrameHeader{1ULL << 63, 1000000, 4, false}), h); });
  EXPECT_NE(seq.find("sequence number 9223372036854775808 is beyond what its first sample index 1000000 allows"),
            std::string::npos)
      << seq;
  EXPECT_NE(error_of([&] {
              decode_frame_header(encode(FrameHeader{11, 4096 + 10, 4, false}), h);
            }).find("sequence number"),
            std::string::npos);
  // A sample index 1e15 ahead of what 500 frames can carry (the receiver would wait for it).
  const std::string idx = error_of([&] {
    decode_frame_header(encode(FrameHeader{500, 1000000000000000 + 500 * 1024, 4, false}), h);
  });
  EXPECT_NE(idx.find("first sample index 1000000000512000 is beyond what its sequence number allows"),
            std::string::npos)
      << idx;
  EXPECT_NE(error_of([&] {
              decode_frame_header(encode(FrameHeader{10, 4096 + 10241, 4, false}), h);
            }).find("beyond"),
            std::string::npos);
  // Start indices past 2^53 are no longer whole samples as doubles.
  StreamHeader late = h;
  late.start_sample_index = std::int64_t{1} << 62;
  EXPECT_NE(
      error_of([&] { decode_header(encode(late)); }).find("start sample index 4611686018427387904 is beyond 2^53"),
      std::string::npos);
}

TEST(StreamProtocol, ParserReassemblesAnySplit) {
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    std::mt19937_64 rng(seed);
    std::vector<Frame> sent, got;
    const auto bytes = valid_stream(rng, 20, sent);
    StreamParser parser;
    std::size_t at = 0;
    while (at < bytes.size()) {
      const std::size_t n =
          std::min<std::size_t>(bytes.size() - at, std::uniform_int_distribution<std::size_t>(1, 700)(rng));
      parser.feed(std::span<const std::byte>(bytes.data() + at, n), got);
      at += n;
    }
    ASSERT_EQ(got.size(), sent.size()) << "seed " << seed;
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].header.first_sample_index, sent[i].header.first_sample_index);
      EXPECT_EQ(got[i].payload, sent[i].payload);
    }
    EXPECT_TRUE(parser.at_boundary());
  }
}

TEST(StreamProtocol, ParserSurvivesRandomAndCorruptedInput) {
  // 2000 seeds: pure noise, and valid streams with random bytes flipped, inserted or cut.
  // Every outcome is frames or a ProtocolError; a corrupted length never allocates more
  // than the header's maximum payload.
  for (std::uint64_t seed = 1; seed <= 2000; ++seed) {
    std::mt19937_64 rng(seed);
    std::vector<Frame> sent, got;
    std::vector<std::byte> bytes = valid_stream(rng, 8, sent);
    const int mode = static_cast<int>(seed % 4);
    if (mode == 0) {
      for (auto& b : bytes) b = static_cast<std::byte>(rng());
    } else if (mode == 1) {
      for (int k = 0; k < 4; ++k) bytes[rng() % bytes.size()] = static_cast<std::byte>(rng());
    } else if (mode == 2) {
      bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(rng() % bytes.size()), static_cast<std::byte>(rng()));
    } else {
      bytes.resize(rng() % bytes.size());
    }
    StreamParser parser;
    try {
      std::size_t at = 0;
      while (at < bytes.size()) {
        const std::size_t n = std::min<std::size_t>(bytes.size() - at, 1 + rng() % 300);
        parser.feed(std::span<const std::byte>(bytes.data() + at, n), got);
        at += n;
      }
    } catch (const ProtocolError&) {
    }
    EXPECT_LE(parser.partial_bytes(), kHeaderBytes + 4096);
    for (const auto& f : got) EXPECT_LE(f.payload.size(), 4096u);
    // The same bytes as datagrams: each is a header, a frame or a ProtocolError.
    const std::optional<StreamHeader> h = test_header();
    const std::size_t cut = bytes.empty() ? 0 : rng() % bytes.size();
    try {
      decode_datagram(std::span<const std::byte>(bytes.data(), cut), h);
    } catch (const ProtocolError&) {
    }
  }
}

TEST(FrameSequencer, ClassifiesLostDuplicatedReorderedAndLateFrames) {
  std::vector<std::uint64_t> delivered;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> lost;
  FrameSequencer seq(
      4, [&](Frame&& f) { delivered.push_back(f.header.sequence); },
      [&](std::uint64_t a, std::uint64_t b) { lost.emplace_back(a, b); });
  auto add = [&](std::uint64_t s) {
    Frame f;
    f.header.sequence = s;
    seq.add(std::move(f));
  };
  for (std::uint64_t s : {0, 1, 3, 2, 2, 4, 6, 7, 8, 9, 10, 5, 11}) add(s);
  seq.flush();
  EXPECT_EQ(delivered, (std::vector<std::uint64_t>{0, 1, 2, 3, 4, 6, 7, 8, 9, 10, 11}));
  EXPECT_EQ(lost, (std::vector<std::pair<std::uint64_t, std::uint64_t>>{{5, 5}}));
  EXPECT_EQ(seq.reordered(), 1);   // 2 after 3 (in time)
  EXPECT_EQ(seq.duplicated(), 1);  // the second 2
  EXPECT_EQ(seq.late(), 1);        // 5 after being declared lost
  EXPECT_EQ(seq.lost(), 1);
}

TEST(FrameSequencer, FramesLostJustBeforeTheEndAreLost) {
  // No later frame shows the hole after 3: the end-of-stream frame, numbered 6, does.
  std::vector<std::uint64_t> delivered;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> lost;
  FrameSequencer seq(
      4, [&](Frame&& f) { delivered.push_back(f.header.sequence); },
      [&](std::uint64_t a, std::uint64_t b) { lost.emplace_back(a, b); });
  for (std::uint64_t s : {0, 1, 3}) {
    Frame f;
    f.header.sequence = s;
    seq.add(std::move(f));
  }
  seq.finish(6);
  EXPECT_EQ(delivered, (std::vector<std::uint64_t>{0, 1, 3}));
  EXPECT_EQ(lost, (std::vector<std::pair<std::uint64_t, std::uint64_t>>{{2, 2}, {4, 5}}));
  EXPECT_EQ(seq.lost(), 3);
}

TEST(FrameSequencer, AFrameHeldBackJustAfterALostOneIsStillInTime) {
  // 1 is lost; 2 comes after 3, 4 and 5 (three later frames, inside a window of 4): it is
  // used, and only 1 is lost. Then 7 and 8 are lost and reported as one run.
  std::vector<std::uint64_t> delivered;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> lost;
  FrameSequencer seq(
      4, [&](Frame&& f) { delivered.push_back(f.header.sequence); },
      [&](std::uint64_t a, std::uint64_t b) { lost.emplace_back(a, b); });
  for (std::uint64_t s : {0, 3, 4, 5, 2, 6, 9, 10, 11, 12}) {
    Frame f;
    f.header.sequence = s;
    seq.add(std::move(f));
  }
  seq.flush();
  EXPECT_EQ(delivered, (std::vector<std::uint64_t>{0, 2, 3, 4, 5, 6, 9, 10, 11, 12}));
  EXPECT_EQ(lost, (std::vector<std::pair<std::uint64_t, std::uint64_t>>{{1, 1}, {7, 8}}));
  EXPECT_EQ(seq.late(), 0);
  EXPECT_EQ(seq.reordered(), 1);
}

TEST(FrameSequencer, HugeJumpIsOneLostRangeInBoundedTime) {
  // 2^62 numbers declared lost at once: reported as one range, remembered only as far as a
  // late frame can be told apart (not one step per number, which would never end).
  std::vector<std::pair<std::uint64_t, std::uint64_t>> lost;
  FrameSequencer seq(
      4, [](Frame&&) {}, [&](std::uint64_t a, std::uint64_t b) { lost.emplace_back(a, b); });
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t s : {std::uint64_t{0}, std::uint64_t{1} << 62}) {
    Frame f;
    f.header.sequence = s;
    seq.add(std::move(f));
  }
  seq.flush();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
  EXPECT_EQ(lost, (std::vector<std::pair<std::uint64_t, std::uint64_t>>{{1, (std::uint64_t{1} << 62) - 1}}));
  EXPECT_EQ(seq.lost(), (std::int64_t{1} << 62) - 1);
}

}  // namespace
}  // namespace deepnav::stream
