// The framed UDP stream: datagrams (decode_datagram) put back in order by the frame
// sequencer (receiver/stream/frame_sequencer.hpp), as udp_sample_source does, and client
// requests (decode_request). The input is a list of datagrams, each preceded by its
// length (one byte, 0: a 16-byte request, 255: a 56-byte header slot, else the length).
// Frames must come out in sequence order, each exactly once.
#include <cstring>
#include <optional>
#include <vector>

#include "receiver/stream/frame_sequencer.hpp"
#include "receiver/stream/stream_protocol.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

namespace stream = deepnav::stream;

/// The next datagram's bytes, or an empty span at the end of the input.
std::span<const std::byte> next_datagram(std::span<const std::byte>& input) {
  if (input.empty()) return {};
  const auto code = static_cast<unsigned>(input[0]);
  const std::size_t length = code == 0 ? stream::kRequestBytes : code == 255 ? stream::kHeaderBytes : code;
  const std::size_t n = std::min(length, input.size() - 1);
  const auto out = input.subspan(1, n);
  input = input.subspan(1 + n);
  return out;
}

class Receiver {
 public:
  Receiver()
      : sequencer_(
            8, [this](stream::Frame&& f) { delivered(f); },
            [](std::uint64_t first, std::uint64_t last) {
              if (last < first) deepnav::fuzz::broken_promise("lost range with last before first");
            }) {}

  void datagram(std::span<const std::byte> bytes) {
    if (bytes.size() == stream::kRequestBytes && std::memcmp(bytes.data(), stream::kRequestMagic.data(), 4) == 0) {
      (void)stream::decode_request(bytes.first<stream::kRequestBytes>());
      return;
    }
    const stream::Datagram d = stream::decode_datagram(bytes, header_);
    if (d.header) {
      header_ = d.header;  // a new session: numbering restarts
      sequencer_.restart(0);
      next_ = 0;
    } else if (d.frame->header.end_of_stream) {
      sequencer_.flush();
    } else {
      sequencer_.add(std::move(*d.frame));
    }
  }
  void end() { sequencer_.flush(); }

 private:
  void delivered(const stream::Frame& f) {
    if (f.header.sequence < next_) deepnav::fuzz::broken_promise("frame delivered out of order or twice");
    next_ = f.header.sequence + 1;
  }

  std::optional<stream::StreamHeader> header_;
  deepnav::FrameSequencer sequencer_;
  std::uint64_t next_ = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::span<const std::byte> input(reinterpret_cast<const std::byte*>(data), size);
  Receiver receiver;
  deepnav::fuzz::guarded(
      [&] {
        while (!input.empty()) receiver.datagram(next_datagram(input));
        receiver.end();
      },
      deepnav::fuzz::is_a<stream::ProtocolError>);
  return 0;
}
