#pragma once
// What the TCP and UDP sample sources share: the consumer side. An I/O thread (in the
// subclass) receives frames and queues their raw bytes; read() converts them to samples
// in order, reports every hole in the sample indices as a gap (never papering over it),
// trims samples delivered twice, and returns 0 at the end of the stream or once a stop
// is requested (Ctrl-C), so the receiver finishes and writes its products.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "receiver/sources/sample_converter.hpp"
#include "receiver/sources/sample_source.hpp"
#include "receiver/stream/stream_protocol.hpp"
#include "receiver/stream/stream_sample_queue.hpp"

namespace deepnav {

struct StreamSourceSettings {
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;
  /// Bare samples without header or frames (a plain IQ socket); the format, rate and IF
  /// then come from the fields below. Losses cannot be detected in this mode.
  bool raw = false;
  SampleFormat raw_format = SampleFormat::ibyte;
  double raw_sample_rate_hz = 0.0;
  double raw_if_hz = 0.0;
  bool inverted_spectrum = false;  ///< deliver I - jQ (on top of the header's own flag)
  /// UDP only: bind host:port and take the datagrams sent there (as from a plain IQ
  /// UDP sender), instead of subscribing to a `deepnav serve` at host:port.
  bool listen = false;
  double connect_timeout_s = 10.0;    ///< for the first connection and header
  double reconnect_timeout_s = 30.0;  ///< a dropped stream is retried with backoff this long
  std::size_t queue_bytes = std::size_t{64} << 20;
  /// Set from a signal handler: read() then ends the stream (interrupted()).
  const std::atomic<bool>* stop = nullptr;
};

/// What happened on the wire, for the run summary.
struct StreamStats {
  std::int64_t bytes_received = 0;
  std::int64_t frames_received = 0;
  std::int64_t frames_lost = 0;        ///< sequence numbers that never arrived
  std::int64_t frames_duplicated = 0;  ///< arrived twice (the copy is dropped)
  std::int64_t frames_reordered = 0;   ///< arrived after a later one, in time to be used
  std::int64_t frames_late = 0;        ///< arrived after being declared lost (dropped)
  std::int64_t frames_overrun = 0;     ///< dropped because the receiver fell behind (UDP)
  std::int64_t reconnects = 0;
  std::int64_t partial_frame_bytes_discarded = 0;                          ///< of frames cut by a dropped connection
  std::int64_t samples_duplicated = 0;                                     ///< delivered twice after a resume (trimmed)
  std::vector<std::pair<std::uint64_t, std::uint64_t>> lost_frame_ranges;  ///< [first, last] sequence numbers
  std::vector<SampleGap> gaps;
  std::string end_reason;
  bool failed = false;
  bool interrupted = false;
  /// rtl_tcp: the samples received per second of the stream's arrival time, as a fraction
  /// of the sample rate (1: real time); and whether it fell below kSlowPace at some point.
  std::optional<double> pace_of_real_time;
  bool slower_than_real_time = false;
  /// Raw UDP: datagrams that ended inside a sample (the rest carried into the next one).
  std::int64_t datagrams_split_samples = 0;
};

class StreamSampleSource : public SampleSource {
 public:
  ~StreamSampleSource() override = default;

  double sample_rate_hz() const override { return header_.sample_rate_hz; }
  double intermediate_frequency_hz() const override { return header_.if_hz; }
  bool is_real() const override { return !is_complex(header_.format); }
  /// Returns 0 at the end of the stream, also when it failed (protocol violation,
  /// connection lost for good, or it ended before delivering a single sample;
  /// stats().failed and end_reason say so) or was stopped.
  std::size_t read(std::span<Sample> out) override;
  std::int64_t next_sample_index() const override { return next_index_; }
  bool at_end() const override { return at_end_; }

  const stream::StreamHeader& header() const { return header_; }
  const std::string& url() const { return url_; }
  /// Bare samples without header or frames (StreamSourceSettings::raw).
  bool raw() const { return settings_.raw; }
  StreamStats stats() const;
  bool interrupted() const { return interrupted_; }

 protected:
  StreamSampleSource(StreamSourceSettings settings, std::string url);
  /// Blocks until the I/O thread published the header (framed) — throws
  /// std::runtime_error naming the stream when it ended or failed first, or after
  /// connect_timeout_s. Raw streams have theirs from the settings at once.
  void wait_for_header();
  /// Starts the I/O thread running `loop`, then (framed streams) waits for the header; on
  /// failure the thread is stopped before the error propagates. Called from a derived
  /// constructor, once its own members exist.
  void start_io(std::function<void()> loop);
  /// Tells the I/O thread to quit and joins it. Derived destructors call it first, while
  /// the members the thread uses still exist.
  void stop_io();
  /// Producer side.
  void publish_header(const stream::StreamHeader& header);
  template <typename F>
  void update_stats(F&& f) {
    std::lock_guard lock(stats_mutex_);
    f(stats_);
  }
  bool stop_requested() const { return settings_.stop != nullptr && settings_.stop->load(); }

  StreamSourceSettings settings_;
  std::string url_;
  StreamSampleQueue queue_;
  std::atomic<bool> cancel_{false};  ///< tells the I/O thread to quit
  std::thread io_thread_;

 private:
  bool next_piece();  ///< ensures held_ has a piece; false at the end / on stop
  void calibrate_if_needed();
  std::size_t deliver(std::span<Sample> out);

  stream::StreamHeader header_;
  std::mutex header_mutex_;
  std::condition_variable header_changed_;
  bool header_known_ = false;
  std::optional<SampleConverter> converter_;
  std::deque<StreamPiece> held_;  ///< pieces taken from the queue, the front partly consumed
  std::size_t held_offset_ = 0;   ///< bytes of held_.front() already delivered
  std::int64_t next_index_ = 0;
  std::int64_t delivered_ = 0;             ///< samples read() returned
  std::optional<std::int64_t> end_index_;  ///< one past the last sample, once the end says so
  bool at_end_ = false, ended_ = false, interrupted_ = false;
  mutable std::mutex stats_mutex_;
  StreamStats stats_;
};

}  // namespace deepnav
