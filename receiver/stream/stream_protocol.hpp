#pragma once
// The deepnav IF streaming protocol (version 1), little endian throughout. docs/streaming.md,
// "Protocol", has the tables.
//
//  server -> client: one StreamHeader, then frames (TCP: back to back; UDP: the header
//  and each frame in a datagram of its own). A frame carries a sequence number (0, 1, 2,
//  ... per session), the absolute index of its first sample and a payload of whole
//  samples, so the client finds lost, duplicated and reordered frames exactly. A frame
//  with the end flag (empty payload) ends the stream.
//  client -> server: a ClientRequest (TCP: right after connecting; UDP: subscribes, and
//  repeated as a keep-alive) asking for the stream from a sample index (a reconnecting
//  client resumes where it stopped).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "signals/sample_format.hpp"

namespace deepnav::stream {

constexpr std::uint16_t kProtocolVersion = 1;
constexpr std::array<char, 4> kHeaderMagic{'D', 'N', 'I', 'F'};
constexpr std::array<char, 4> kFrameMagic{'D', 'N', 'F', 'R'};
constexpr std::array<char, 4> kRequestMagic{'D', 'N', 'R', 'Q'};
constexpr std::size_t kHeaderBytes = 56;
constexpr std::size_t kFrameHeaderBytes = 28;
constexpr std::size_t kRequestBytes = 16;
/// No frame payload may exceed this, whatever the header announces (bounds the memory a
/// corrupt length field can make a client allocate).
constexpr std::uint32_t kMaxPayloadLimit = 1u << 20;
/// No sample index may exceed this (2^53: the last a double holds exactly).
constexpr std::int64_t kMaxSampleIndex = std::int64_t{1} << 53;

/// A violation of the protocol: the message names the field and what was expected.
struct ProtocolError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct StreamHeader {
  SampleFormat format = SampleFormat::ibyte;
  double sample_rate_hz = 0.0;
  double if_hz = 0.0;
  std::int64_t start_sample_index = 0;  ///< index of the first sample this session sends
  std::optional<GpsTime> start_time;    ///< GPS time (receiver clock) of sample 0, when known
  std::uint32_t max_payload_bytes = 0;  ///< no frame of this stream carries more
  bool inverted_spectrum = false;       ///< the samples are I - jQ
};

struct FrameHeader {
  std::uint64_t sequence = 0;
  std::int64_t first_sample_index = 0;
  std::uint32_t payload_bytes = 0;
  bool end_of_stream = false;
};

struct ClientRequest {
  std::int64_t resume_from_sample = 0;  ///< first sample wanted (0: from the start)
  bool stop = false;                    ///< UDP: the client leaves; the session ends
};

std::array<std::byte, kHeaderBytes> encode(const StreamHeader& header);
std::array<std::byte, kFrameHeaderBytes> encode(const FrameHeader& frame);
std::array<std::byte, kRequestBytes> encode(const ClientRequest& request);

/// Each decoder validates every field (magic, version, lengths, enumerations, finite
/// positive rates, flags) and throws ProtocolError naming the first bad one.
StreamHeader decode_header(std::span<const std::byte, kHeaderBytes> bytes);
/// `header` bounds the payload length and requires whole samples; with the sequence number
/// it bounds the first sample index: start + sequence <= index <= start + sequence x the
/// samples of a maximum payload (a session's frames are numbered 0, 1, ... and each carries
/// 1 to that many samples, the lost ones of a datagram stream included).
FrameHeader decode_frame_header(std::span<const std::byte, kFrameHeaderBytes> bytes, const StreamHeader& header);
ClientRequest decode_request(std::span<const std::byte, kRequestBytes> bytes);

/// One frame with its payload (the raw sample bytes, in the header's format).
struct Frame {
  FrameHeader header;
  std::vector<std::byte> payload;
};

/// Incremental parser of a framed byte stream (TCP): feed it whatever arrived, in any
/// pieces; it hands out the header once and then every complete frame. Throws
/// ProtocolError on the first violation (the stream cannot be trusted past it).
class StreamParser {
 public:
  /// Consumes all of `bytes`; complete frames are appended to `frames`.
  void feed(std::span<const std::byte> bytes, std::vector<Frame>& frames);
  const std::optional<StreamHeader>& header() const { return header_; }
  /// True between frames (no partial header or frame buffered).
  bool at_boundary() const { return pending_.empty() && !frame_; }
  /// Bytes of a header or frame received only in part (a frame's header included).
  std::size_t partial_bytes() const { return pending_.size() + (frame_ ? kFrameHeaderBytes + payload_filled_ : 0); }

 private:
  std::optional<StreamHeader> header_;
  std::vector<std::byte> pending_;  ///< a header or frame header being assembled
  std::optional<Frame> frame_;      ///< a frame whose payload is being assembled
  std::size_t payload_filled_ = 0;
};

/// One UDP datagram: either a header or a frame (with its payload), validated entirely;
/// `header` is the stream's header once known (frames before it cannot be checked and
/// are rejected). Throws ProtocolError for anything else.
struct Datagram {
  std::optional<StreamHeader> header;
  std::optional<Frame> frame;
};
Datagram decode_datagram(std::span<const std::byte> bytes, const std::optional<StreamHeader>& header);

/// Whether the protocol carries the format (the whole-byte formats; not the packed ones).
bool streamable(const SampleFormat& format);
/// The format code carried in the header; throws std::invalid_argument naming the format
/// for one the protocol does not carry.
std::uint8_t format_code(const SampleFormat& format);

}  // namespace deepnav::stream
