#pragma once
// Samples from an rtl_tcp server (an RTL-SDR dongle on this or another machine): connects,
// reads the 12-byte dongle header (magic "RTL0", tuner type, gain steps), tunes the dongle
// with rtl_tcp's 5-byte commands (sample rate, centre frequency, crystal correction, gain or
// the tuner's AGC, the RTL2832's AGC, bias tee for an active antenna) and streams its cu8
// samples into the receiver through the stream source's queue and loss accounting. rtl_tcp
// carries no sample indices: samples the server drops (it does when the link cannot carry
// the rate) are found from arrival times (receiver/stream/arrival_loss_detector.hpp), which
// holds the samples back for its horizon (1 s) before the receiver sees them, and reported as
// gaps the channels coast across. A sender slower than real time is slow, not lossy: it is
// warned of, with its pace, and its samples are taken as they come (no losses are counted
// while it is). The first samples after tuning are discarded while the tuner settles. A
// closed connection ends the stream (a dongle's stream cannot be resumed).
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <optional>
#include <string>

#include "receiver/stream/arrival_loss_detector.hpp"
#include "receiver/stream/rtltcp_protocol.hpp"
#include "receiver/stream/stream_sample_source.hpp"

namespace deepnav {

struct RtlTcpSettings {
  rtltcp::Tuning tuning;
  double settle_s = 0.25;  ///< samples discarded after tuning
  double loss_threshold_s = 0.025;
  double loss_horizon_s = 1.0;
};

class RtlTcpSampleSource final : public StreamSampleSource {
 public:
  /// Connects, reads the dongle header and sends the tuning, all within the connect timeout;
  /// throws std::runtime_error naming rtltcp://host:port (refused, timed out, not an
  /// rtl_tcp server) and std::invalid_argument for a tuning the dongle cannot do. The
  /// settings' format and rate are set here (cu8 at the tuning's rate).
  RtlTcpSampleSource(StreamSourceSettings settings, RtlTcpSettings rtl);
  ~RtlTcpSampleSource() override;
  RtlTcpSampleSource(const RtlTcpSampleSource&) = delete;
  RtlTcpSampleSource& operator=(const RtlTcpSampleSource&) = delete;

  bool gap_sizes_exact() const override { return false; }
  const rtltcp::DongleInfo& dongle() const { return dongle_; }
  const RtlTcpSettings& rtl_settings() const { return rtl_; }

 private:
  void io_loop();
  /// Releases the pieces whose verdict is in into the queue (those of the settling time
  /// dropped); false once cancelled.
  bool release(bool flush);
  /// Warns when the stream turns slower than real time (and says when it keeps it again);
  /// keeps the stats' pace up to date.
  void report_pace();
  /// Why the stream ended, with what became of its samples when none got past settling.
  std::string end_reason(const std::string& why) const;

  RtlTcpSettings rtl_;
  boost::asio::io_context io_;
  boost::asio::ip::tcp::socket socket_;
  rtltcp::DongleInfo dongle_;
  ArrivalLossDetector detector_;
  std::deque<std::vector<std::byte>> held_bytes_;  ///< the bytes of the pieces the detector holds
  std::int64_t next_index_ = 0;
  const std::int64_t settle_bytes_;  ///< discarded after tuning
  std::int64_t settle_bytes_left_;
  bool reported_slow_ = false;
};

}  // namespace deepnav
