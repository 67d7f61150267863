#include "receiver/stream/stream_protocol.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace deepnav::stream {
namespace {

constexpr std::uint8_t kHeaderFlagGpsTime = 1;
constexpr std::uint8_t kHeaderFlagInverted = 2;
constexpr std::uint32_t kFrameFlagEnd = 1;
constexpr std::uint16_t kRequestFlagStop = 1;
const std::array<SampleFormat, 5> kFormats{SampleFormat::ibyte, SampleFormat::ishort, SampleFormat::gr_complex,
                                           SampleFormat::byte, SampleFormat::cu8};

template <typename T>
void put(std::byte* at, T value) {
  using U = std::make_unsigned_t<std::conditional_t<std::is_floating_point_v<T>,
                                                    std::conditional_t<sizeof(T) == 8, std::int64_t, std::int32_t>, T>>;
  const U bits = std::bit_cast<U>(value);
  for (std::size_t i = 0; i < sizeof(U); ++i) at[i] = static_cast<std::byte>((bits >> (8 * i)) & 0xFF);
}

template <typename T>
T get(const std::byte* at) {
  using U = std::make_unsigned_t<std::conditional_t<std::is_floating_point_v<T>,
                                                    std::conditional_t<sizeof(T) == 8, std::int64_t, std::int32_t>, T>>;
  U bits = 0;
  for (std::size_t i = 0; i < sizeof(U); ++i) bits |= static_cast<U>(std::to_integer<unsigned>(at[i])) << (8 * i);
  return std::bit_cast<T>(bits);
}

void put_magic(std::byte* at, const std::array<char, 4>& magic) { std::memcpy(at, magic.data(), 4); }

std::string printable(const std::byte* at, std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = std::to_integer<unsigned char>(at[i]);
    s += (c >= 0x20 && c < 0x7F) ? std::string(1, static_cast<char>(c)) : fmt::format("\\x{:02x}", c);
  }
  return s;
}

void check_magic(const std::byte* at, const std::array<char, 4>& magic, const char* what) {
  if (std::memcmp(at, magic.data(), 4) != 0)
    throw ProtocolError(fmt::format("{}: magic is \"{}\", expected \"{}\"", what, printable(at, 4),
                                    std::string(magic.begin(), magic.end())));
}

void check_version(std::uint16_t version, const char* what) {
  if (version != kProtocolVersion)
    throw ProtocolError(fmt::format("{}: protocol version {} is not supported (this program speaks version {})", what,
                                    version, kProtocolVersion));
}

}  // namespace

bool streamable(const SampleFormat& format) {
  return std::find(kFormats.begin(), kFormats.end(), format) != kFormats.end();
}

std::uint8_t format_code(const SampleFormat& format) {
  const auto at = std::find(kFormats.begin(), kFormats.end(), format);
  if (at == kFormats.end())
    throw std::invalid_argument(
        fmt::format("sample format {} cannot be streamed: the stream protocol carries "
                    "ibyte, ishort, gr_complex, byte and cu8 (packed formats are read from files)",
                    to_string(format)));
  return static_cast<std::uint8_t>(at - kFormats.begin());
}

std::array<std::byte, kHeaderBytes> encode(const StreamHeader& h) {
  std::array<std::byte, kHeaderBytes> b{};
  put_magic(b.data(), kHeaderMagic);
  put<std::uint16_t>(b.data() + 4, kProtocolVersion);
  put<std::uint16_t>(b.data() + 6, static_cast<std::uint16_t>(kHeaderBytes));
  put<std::uint8_t>(b.data() + 8, format_code(h.format));
  put<std::uint8_t>(b.data() + 9, static_cast<std::uint8_t>((h.start_time ? kHeaderFlagGpsTime : 0) |
                                                            (h.inverted_spectrum ? kHeaderFlagInverted : 0)));
  put<std::uint32_t>(b.data() + 12, h.max_payload_bytes);
  put<double>(b.data() + 16, h.sample_rate_hz);
  put<double>(b.data() + 24, h.if_hz);
  put<std::int64_t>(b.data() + 32, h.start_sample_index);
  put<std::int32_t>(b.data() + 40, h.start_time ? h.start_time->week : 0);
  put<double>(b.data() + 48, h.start_time ? h.start_time->sow : 0.0);
  return b;
}

std::array<std::byte, kFrameHeaderBytes> encode(const FrameHeader& f) {
  std::array<std::byte, kFrameHeaderBytes> b{};
  put_magic(b.data(), kFrameMagic);
  put<std::uint32_t>(b.data() + 4, f.payload_bytes);
  put<std::uint64_t>(b.data() + 8, f.sequence);
  put<std::int64_t>(b.data() + 16, f.first_sample_index);
  put<std::uint32_t>(b.data() + 24, f.end_of_stream ? kFrameFlagEnd : 0);
  return b;
}

std::array<std::byte, kRequestBytes> encode(const ClientRequest& r) {
  std::array<std::byte, kRequestBytes> b{};
  put_magic(b.data(), kRequestMagic);
  put<std::uint16_t>(b.data() + 4, kProtocolVersion);
  put<std::uint16_t>(b.data() + 6, r.stop ? kRequestFlagStop : 0);
  put<std::int64_t>(b.data() + 8, r.resume_from_sample);
  return b;
}

StreamHeader decode_header(std::span<const std::byte, kHeaderBytes> bytes) {
  const std::byte* b = bytes.data();
  check_magic(b, kHeaderMagic, "stream header");
  check_version(get<std::uint16_t>(b + 4), "stream header");
  if (const auto n = get<std::uint16_t>(b + 6); n != kHeaderBytes)
    throw ProtocolError(fmt::format("stream header: header length is {} bytes, expected {}", n, kHeaderBytes));
  const auto code = get<std::uint8_t>(b + 8);
  if (code >= kFormats.size())
    throw ProtocolError(
        fmt::format("stream header: sample format code {} is unknown (0 ibyte, 1 ishort, "
                    "2 gr_complex, 3 byte, 4 cu8)",
                    code));
  const auto flags = get<std::uint8_t>(b + 9);
  if ((flags & ~(kHeaderFlagGpsTime | kHeaderFlagInverted)) != 0)
    throw ProtocolError(fmt::format("stream header: unknown flag bits 0x{:02x}", flags));
  if (get<std::uint16_t>(b + 10) != 0 || get<std::uint32_t>(b + 44) != 0)
    throw ProtocolError("stream header: reserved fields must be zero");
  StreamHeader h;
  h.format = kFormats[code];
  h.inverted_spectrum = (flags & kHeaderFlagInverted) != 0;
  const std::size_t bps = bytes_per_sample(h.format);
  h.max_payload_bytes = get<std::uint32_t>(b + 12);
  if (h.max_payload_bytes < bps || h.max_payload_bytes > kMaxPayloadLimit || h.max_payload_bytes % bps != 0)
    throw ProtocolError(
        fmt::format("stream header: maximum payload of {} bytes must be whole {} samples of {} "
                    "bytes, at most {} bytes",
                    h.max_payload_bytes, to_string(h.format), bps, kMaxPayloadLimit));
  h.sample_rate_hz = get<double>(b + 16);
  if (!std::isfinite(h.sample_rate_hz) || h.sample_rate_hz < 1e3 || h.sample_rate_hz > 1e9)
    throw ProtocolError(fmt::format("stream header: sample rate {} Hz is not in [1 kHz, 1 GHz]", h.sample_rate_hz));
  h.if_hz = get<double>(b + 24);
  if (!std::isfinite(h.if_hz) || std::abs(h.if_hz) >= h.sample_rate_hz)
    throw ProtocolError(fmt::format("stream header: IF {} Hz must be finite and below the sample rate {} Hz", h.if_hz,
                                    h.sample_rate_hz));
  h.start_sample_index = get<std::int64_t>(b + 32);
  if (h.start_sample_index < 0)
    throw ProtocolError(fmt::format("stream header: start sample index {} is negative", h.start_sample_index));
  // Sample indices become times as doubles: past 2^53 they no longer hold whole samples
  // (and 2^53 samples are 71 years at 4 Msps).
  if (h.start_sample_index > kMaxSampleIndex)
    throw ProtocolError(
        fmt::format("stream header: start sample index {} is beyond 2^53 ({})", h.start_sample_index, kMaxSampleIndex));
  if ((flags & kHeaderFlagGpsTime) != 0) {
    const auto week = get<std::int32_t>(b + 40);
    const auto sow = get<double>(b + 48);
    if (week < 0 || week > 100000 || !(sow >= 0.0 && sow < kSecondsPerWeek))
      throw ProtocolError(fmt::format("stream header: GPS time week {} sow {} is out of range", week, sow));
    h.start_time = GpsTime{week, sow};
  }
  return h;
}

FrameHeader decode_frame_header(std::span<const std::byte, kFrameHeaderBytes> bytes, const StreamHeader& header) {
  const std::byte* b = bytes.data();
  check_magic(b, kFrameMagic, "frame");
  FrameHeader f;
  f.payload_bytes = get<std::uint32_t>(b + 4);
  f.sequence = get<std::uint64_t>(b + 8);
  f.first_sample_index = get<std::int64_t>(b + 16);
  const auto flags = get<std::uint32_t>(b + 24);
  if ((flags & ~kFrameFlagEnd) != 0)
    throw ProtocolError(fmt::format("frame {}: unknown flag bits 0x{:08x}", f.sequence, flags));
  f.end_of_stream = (flags & kFrameFlagEnd) != 0;
  const std::size_t bps = bytes_per_sample(header.format);
  if (f.payload_bytes > header.max_payload_bytes)
    throw ProtocolError(fmt::format("frame {}: payload length {} bytes exceeds the stream's maximum of {} bytes",
                                    f.sequence, f.payload_bytes, header.max_payload_bytes));
  if (f.payload_bytes % bps != 0)
    throw ProtocolError(fmt::format("frame {}: payload length {} bytes is not whole {} samples of {} bytes", f.sequence,
                                    f.payload_bytes, to_string(header.format), bps));
  if (f.end_of_stream != (f.payload_bytes == 0))
    throw ProtocolError(fmt::format("frame {}: {} bytes of payload{}", f.sequence, f.payload_bytes,
                                    f.end_of_stream ? " in the end-of-stream frame (expected none)"
                                                    : " (only the end-of-stream frame may be empty)"));
  if (f.first_sample_index < header.start_sample_index)
    throw ProtocolError(fmt::format("frame {}: first sample index {} is before the stream's start {}", f.sequence,
                                    f.first_sample_index, header.start_sample_index));
  // Frames 0 .. sequence - 1 came before this one, each with at least one sample and at
  // most the header's maximum payload: so the sequence number bounds where this frame can
  // start, and a sequence number or sample index beyond that is corrupt (it would make the
  // client declare 2^63 frames lost, or wait for 10^15 samples).
  const std::int64_t offset = f.first_sample_index - header.start_sample_index;
  const auto max_samples = static_cast<std::uint64_t>(header.max_payload_bytes / bps);
  if (f.sequence > static_cast<std::uint64_t>(offset))
    throw ProtocolError(
        fmt::format("frame {}: sequence number {} is beyond what its first sample index {} allows "
                    "(at most {}: every earlier frame carries at least one sample from the start {})",
                    f.sequence, f.sequence, f.first_sample_index, offset, header.start_sample_index));
  if ((static_cast<std::uint64_t>(offset) + max_samples - 1) / max_samples > f.sequence ||
      f.first_sample_index > kMaxSampleIndex)
    throw ProtocolError(
        fmt::format("frame {}: first sample index {} is beyond what its sequence number allows (at "
                    "most the start {} + {} earlier frames x {} samples of a maximum payload, and at "
                    "most 2^53)",
                    f.sequence, f.first_sample_index, header.start_sample_index, f.sequence, max_samples));
  return f;
}

ClientRequest decode_request(std::span<const std::byte, kRequestBytes> bytes) {
  const std::byte* b = bytes.data();
  check_magic(b, kRequestMagic, "client request");
  check_version(get<std::uint16_t>(b + 4), "client request");
  const auto flags = get<std::uint16_t>(b + 6);
  if ((flags & ~kRequestFlagStop) != 0)
    throw ProtocolError(fmt::format("client request: unknown flag bits 0x{:04x}", flags));
  ClientRequest r;
  r.stop = (flags & kRequestFlagStop) != 0;
  r.resume_from_sample = get<std::int64_t>(b + 8);
  if (r.resume_from_sample < 0)
    throw ProtocolError(fmt::format("client request: resume sample index {} is negative", r.resume_from_sample));
  return r;
}

void StreamParser::feed(std::span<const std::byte> bytes, std::vector<Frame>& frames) {
  while (!bytes.empty()) {
    if (frame_) {  // payload of the current frame
      const std::size_t n = std::min(bytes.size(), frame_->payload.size() - payload_filled_);
      std::copy_n(bytes.begin(), n, frame_->payload.begin() + static_cast<std::ptrdiff_t>(payload_filled_));
      payload_filled_ += n;
      bytes = bytes.subspan(n);
      if (payload_filled_ == frame_->payload.size()) {
        frames.push_back(std::move(*frame_));
        frame_.reset();
      }
      continue;
    }
    const std::size_t want = header_ ? kFrameHeaderBytes : kHeaderBytes;
    const std::size_t n = std::min(bytes.size(), want - pending_.size());
    pending_.insert(pending_.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
    bytes = bytes.subspan(n);
    // A wrong magic is reported as soon as its four bytes are in, not after a whole header.
    if (pending_.size() >= 4 && pending_.size() - n < 4)
      check_magic(pending_.data(), header_ ? kFrameMagic : kHeaderMagic, header_ ? "frame" : "stream header");
    if (pending_.size() < want) continue;
    if (!header_) {
      header_ = decode_header(std::span<const std::byte, kHeaderBytes>(pending_.data(), kHeaderBytes));
    } else {
      Frame f;
      f.header = decode_frame_header(std::span<const std::byte, kFrameHeaderBytes>(pending_.data(), kFrameHeaderBytes),
                                     *header_);
      f.payload.resize(f.header.payload_bytes);
      payload_filled_ = 0;
      if (f.payload.empty()) {
        frames.push_back(std::move(f));
      } else {
        frame_ = std::move(f);
      }
    }
    pending_.clear();
  }
}

Datagram decode_datagram(std::span<const std::byte> bytes, const std::optional<StreamHeader>& header) {
  if (bytes.size() < 4) throw ProtocolError(fmt::format("datagram of {} bytes is too short", bytes.size()));
  Datagram d;
  if (std::memcmp(bytes.data(), kHeaderMagic.data(), 4) == 0) {
    if (bytes.size() != kHeaderBytes)
      throw ProtocolError(fmt::format("header datagram is {} bytes, expected {}", bytes.size(), kHeaderBytes));
    d.header = decode_header(bytes.first<kHeaderBytes>());
    return d;
  }
  check_magic(bytes.data(), kFrameMagic, "datagram");
  if (!header) throw ProtocolError("frame datagram before any stream header");
  if (bytes.size() < kFrameHeaderBytes)
    throw ProtocolError(fmt::format("frame datagram of {} bytes is shorter than a frame header ({} bytes)",
                                    bytes.size(), kFrameHeaderBytes));
  Frame f;
  f.header = decode_frame_header(bytes.first<kFrameHeaderBytes>(), *header);
  if (bytes.size() != kFrameHeaderBytes + f.header.payload_bytes)
    throw ProtocolError(fmt::format("frame {}: datagram carries {} bytes of payload, its header says {}",
                                    f.header.sequence, bytes.size() - kFrameHeaderBytes, f.header.payload_bytes));
  f.payload.assign(bytes.begin() + kFrameHeaderBytes, bytes.end());
  d.frame = std::move(f);
  return d;
}

}  // namespace deepnav::stream
