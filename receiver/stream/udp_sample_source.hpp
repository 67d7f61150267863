#pragma once
// Samples from UDP datagrams. Framed (default): subscribes to a `deepnav serve` at
// host:port with a ClientRequest, repeated every second as a keep-alive; every datagram
// is a header or one frame, and the FrameSequencer restores order, drops duplicates and
// names each lost frame; the samples of lost frames become reported gaps. With
// `listen`, binds host:port and takes what arrives (a server pushing to it). Raw
// datagrams (bare samples) carry no index, so their losses cannot be detected; they are
// taken as one byte stream, a sample split across two datagrams put back together.
#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>

#include "receiver/stream/frame_sequencer.hpp"
#include "receiver/stream/stream_sample_source.hpp"

namespace deepnav {

class UdpSampleSource final : public StreamSampleSource {
 public:
  /// Opens the socket and, for a framed stream, waits for the header; throws
  /// std::runtime_error naming udp://host:port when that fails within connect_timeout_s.
  explicit UdpSampleSource(StreamSourceSettings settings);
  ~UdpSampleSource() override;
  UdpSampleSource(const UdpSampleSource&) = delete;
  UdpSampleSource& operator=(const UdpSampleSource&) = delete;

  /// The local port (useful with listen on port 0).
  std::uint16_t local_port() const { return local_port_; }
  /// Frames per reorder window: a frame missing while this many later ones arrived is lost.
  static constexpr std::size_t kReorderWindow = 64;

 private:
  void io_loop();
  void send_request(bool stop);
  void handle_datagram(std::span<const std::byte> bytes);
  void handle_raw_datagram(std::span<const std::byte> bytes);
  void deliver(stream::Frame&& frame);

  boost::asio::io_context io_;
  boost::asio::ip::udp::socket socket_;
  boost::asio::ip::udp::endpoint server_;
  std::atomic<std::uint16_t> local_port_{0};
  std::optional<stream::StreamHeader> header_seen_;
  FrameSequencer sequencer_;
  std::int64_t resume_from_ = 0;
  std::int64_t raw_index_ = 0;
  std::vector<std::byte> raw_carry_;  ///< raw: the start of a sample a datagram ended inside
  bool warned_split_sample_ = false;
  bool finished_ = false;
};

}  // namespace deepnav
