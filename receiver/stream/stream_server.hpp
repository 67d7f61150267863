#pragma once
// Serves IF over TCP and UDP (Boost.Asio): every client gets a session of its own with
// its own byte stream (a file or the synthesizer, opened for it) and its own pace, run
// in its own thread, so a slow TCP client only slows itself (backpressure) and never the
// others. Pacing follows the sample clock: a frame leaves when the wall clock passes
// session start + (its last sample - first sample) / (fs * pace), so it never drifts;
// pace 0 sends as fast as the client reads. Framed sessions (the protocol of
// stream_protocol.hpp) start at the sample the client's request asks for; raw sessions
// send bare samples from the first.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "signals/if_byte_stream.hpp"
#include "signals/sample_format.hpp"

namespace deepnav {

struct StreamServerOptions {
  std::string bind_address = "127.0.0.1";
  std::optional<std::uint16_t> tcp_port;  ///< 0: any free port (see tcp_port())
  std::optional<std::uint16_t> udp_port;
  bool raw = false;
  double pace = 1.0;  ///< multiple of real time; 0: as fast as the client reads
  std::uint32_t tcp_payload_bytes = 1 << 16;
  std::uint32_t udp_payload_bytes = 8192;
  /// UDP loss injection (tests, benchmarks): these sequence numbers are never sent, and
  /// each other frame is dropped with `drop_probability` (seeded by `drop_seed`).
  std::set<std::uint64_t> drop_frames;
  double drop_probability = 0.0;
  std::uint64_t drop_seed = 1;
  double request_timeout_s = 1.0;  ///< TCP: how long a framed session waits for the client's request
  double udp_keepalive_timeout_s = 5.0;
  /// Opens a fresh stream for each session (called from the session's thread).
  std::function<std::unique_ptr<IfByteStream>()> open_stream;
};

/// The smallest frame payload a server sends: a frame's header (28 bytes) then costs under
/// 3 % of the link, and a raw session's send a syscall per kilobyte at most.
inline constexpr std::uint32_t kMinFramePayloadBytes = 1024;

/// A frame payload of `payload_bytes` for samples of `format`: std::invalid_argument naming
/// `option` unless it holds whole samples and at least kMinFramePayloadBytes (the message
/// names the sample size and what the frame header would cost). `framed`: the frames carry
/// the protocol's header (raw sessions send bare samples).
void check_frame_payload(const std::string& option, std::uint32_t payload_bytes, SampleFormat format, bool framed);

/// What one session did, for logs and tests.
struct ServerSessionReport {
  std::string client;  ///< tcp://addr:port or udp://addr:port
  std::int64_t first_sample = 0;
  std::int64_t samples_sent = 0;
  std::int64_t frames_sent = 0;
  std::vector<std::uint64_t> dropped_frames;  ///< sequence numbers not sent (loss injection)
  std::string end;                            ///< why the session ended
};

class StreamServer {
 public:
  /// Binds the ports; throws std::runtime_error naming the address and port when it cannot.
  explicit StreamServer(StreamServerOptions options);
  ~StreamServer();
  StreamServer(const StreamServer&) = delete;
  StreamServer& operator=(const StreamServer&) = delete;

  std::uint16_t tcp_port() const;
  std::uint16_t udp_port() const;
  /// Accepts clients until `stop` is set, or until `max_sessions` (> 0) sessions have
  /// ended; then ends the sessions still running and returns.
  void run(const std::atomic<bool>& stop, int max_sessions = 0);
  std::vector<ServerSessionReport> reports() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deepnav
