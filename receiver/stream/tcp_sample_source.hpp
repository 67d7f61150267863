#pragma once
// Samples from a TCP stream (`deepnav serve`, or any server sending bare samples in raw
// mode). A dropped connection is retried with exponential backoff (0.1 s doubling to
// 5 s) for up to reconnect_timeout_s; a framed stream then resumes at the first sample
// not received (the partial frame cut by the drop is discarded), so nothing is lost; a
// server that cannot resume there shows up as a reported gap. A raw stream ends when
// its connection closes (without sample indices it cannot be resumed).
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "receiver/stream/stream_sample_source.hpp"

namespace deepnav {

class TcpSampleSource final : public StreamSampleSource {
 public:
  /// Connects and, for a framed stream, waits for the header; throws std::runtime_error
  /// naming tcp://host:port when that fails within connect_timeout_s.
  explicit TcpSampleSource(StreamSourceSettings settings);
  ~TcpSampleSource() override;
  TcpSampleSource(const TcpSampleSource&) = delete;
  TcpSampleSource& operator=(const TcpSampleSource&) = delete;

 private:
  enum class SessionEnd { dropped, finished, cancelled };
  void io_loop();
  bool connect(boost::asio::ip::tcp::socket& socket, std::string& why);
  /// Reads some bytes with the idle deadline; 0 with `why` set when the connection ended.
  std::size_t read_some(boost::asio::ip::tcp::socket& socket, std::vector<std::byte>& buffer, std::string& why);
  SessionEnd receive_framed(boost::asio::ip::tcp::socket& socket, std::string& why);
  SessionEnd receive_raw(boost::asio::ip::tcp::socket& socket, std::string& why);

  boost::asio::io_context io_;
  std::int64_t resume_from_ = 0;  ///< first sample not received yet (framed)
  std::int64_t raw_index_ = 0;
  std::optional<stream::StreamHeader> first_header_;
};

}  // namespace deepnav
