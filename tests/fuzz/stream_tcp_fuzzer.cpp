// The framed TCP stream (receiver/stream/stream_protocol.hpp, StreamParser): the input's
// first byte sets the size of the pieces the rest arrives in, as a socket hands them out.
// Every frame handed out must agree with the header it was checked against.
#include <algorithm>
#include <string>
#include <vector>

#include "receiver/stream/stream_protocol.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

using deepnav::stream::Frame;
using deepnav::stream::StreamHeader;

void check(const Frame& f, const StreamHeader& h) {
  if (f.payload.size() != f.header.payload_bytes)
    deepnav::fuzz::broken_promise("frame payload size differs from its header's payload length");
  if (f.header.payload_bytes > h.max_payload_bytes)
    deepnav::fuzz::broken_promise("frame payload beyond the header's maximum");
  if (f.header.end_of_stream && !f.payload.empty()) deepnav::fuzz::broken_promise("end-of-stream frame with a payload");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t piece = data[0] == 0 ? size : data[0];
  const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data + 1), size - 1);
  deepnav::stream::StreamParser parser;
  std::vector<Frame> frames;
  deepnav::fuzz::guarded(
      [&] {
        for (std::size_t at = 0; at < bytes.size(); at += piece) {
          parser.feed(bytes.subspan(at, std::min(piece, bytes.size() - at)), frames);
          for (const Frame& f : frames) check(f, *parser.header());
          frames.clear();
        }
      },
      deepnav::fuzz::is_a<deepnav::stream::ProtocolError>);
  return 0;
}
