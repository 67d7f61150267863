#include "receiver/stream/rtltcp_sample_source.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <boost/asio/connect.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "receiver/stream/asio_wait.hpp"

namespace deepnav {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;
using asio_wait::Clock;

constexpr std::size_t kReadBytes = 1 << 16;
constexpr double kIdleTimeout_s = 10.0;  // a dongle that sends nothing this long is gone

using asio_wait::after;

double seconds_now() { return std::chrono::duration<double>(Clock::now().time_since_epoch()).count(); }

StreamSourceSettings as_raw_cu8(StreamSourceSettings s, const RtlTcpSettings& rtl) {
  rtltcp::validate(rtl.tuning);
  s.raw = true;
  s.listen = false;
  s.raw_format = SampleFormat::cu8;
  s.raw_sample_rate_hz = rtl.tuning.sample_rate_hz;
  return s;
}

}  // namespace

RtlTcpSampleSource::RtlTcpSampleSource(StreamSourceSettings settings, RtlTcpSettings rtl)
    : StreamSampleSource(as_raw_cu8(settings, rtl), fmt::format("rtltcp://{}:{}", settings.host, settings.port)),
      rtl_(rtl),
      socket_(io_),
      detector_(rtl.tuning.sample_rate_hz, rtl.loss_threshold_s, rtl.loss_horizon_s),
      settle_bytes_(2 * std::llround(rtl.settle_s * rtl.tuning.sample_rate_hz)),
      settle_bytes_left_(settle_bytes_) {
  const auto deadline = after(settings_.connect_timeout_s);
  const std::atomic<bool> never{false};
  const std::atomic<bool>& cancel = settings_.stop != nullptr ? *settings_.stop : never;
  boost::system::error_code ec;
  tcp::resolver resolver(io_);
  const auto endpoints = resolver.resolve(settings_.host, std::to_string(settings_.port), ec);
  if (ec) throw std::runtime_error(fmt::format("{}: cannot resolve '{}': {}", url_, settings_.host, ec.message()));
  bool done = false;
  asio::async_connect(socket_, endpoints, [&](const boost::system::error_code& e, const tcp::endpoint&) {
    ec = e;
    done = true;
  });
  if (!asio_wait::run_until_done(io_, done, deadline, cancel, [&] { socket_.close(); }))
    throw std::runtime_error(fmt::format("{}: no connection within {} s", url_, settings_.connect_timeout_s));
  if (ec) throw std::runtime_error(fmt::format("{}: cannot connect: {}", url_, ec.message()));

  std::array<std::byte, rtltcp::kDongleInfoBytes> header{};
  std::size_t got = 0;
  done = false;
  asio::async_read(socket_, asio::buffer(header), [&](const boost::system::error_code& e, std::size_t n) {
    ec = e;
    got = n;
    done = true;
  });
  if (!asio_wait::run_until_done(io_, done, deadline, cancel, [&] { socket_.close(); }))
    throw std::runtime_error(
        fmt::format("{}: no rtl_tcp dongle header within {} s", url_, settings_.connect_timeout_s));
  if (ec)
    throw std::runtime_error(fmt::format("{}: the dongle header ended after {} of its {} bytes: {}", url_, got,
                                         header.size(), ec.message()));
  try {
    dongle_ = rtltcp::decode_dongle_info(header);
  } catch (const stream::ProtocolError& e) {
    throw std::runtime_error(fmt::format("{}: {}", url_, e.what()));
  }

  std::vector<std::byte> commands;
  for (const auto& c : rtltcp::tuning_commands(rtl_.tuning)) commands.insert(commands.end(), c.begin(), c.end());
  done = false;
  asio::async_write(socket_, asio::buffer(commands), [&](const boost::system::error_code& e, std::size_t) {
    ec = e;
    done = true;
  });
  if (!asio_wait::run_until_done(io_, done, deadline, cancel, [&] { socket_.close(); }) || ec)
    throw std::runtime_error(
        fmt::format("{}: cannot send the tuning commands: {}", url_, ec ? ec.message() : "timed out"));
  const auto& t = rtl_.tuning;
  spdlog::info(
      "{}: {} tuner ({} gain steps); tuned to {:.6f} MHz at {} samples/s, gain {}, RTL AGC {}, {} ppm, bias tee {}",
      url_, rtltcp::tuner_name(dongle_.tuner_type), dongle_.gain_count, t.center_frequency_hz / 1e6, t.sample_rate_hz,
      t.gain_db ? fmt::format("{:.1f} dB", *t.gain_db) : std::string("auto (tuner AGC)"), t.rtl_agc ? "on" : "off",
      t.ppm, t.bias_tee ? "on" : "off");
  start_io([this] { io_loop(); });
}

RtlTcpSampleSource::~RtlTcpSampleSource() { stop_io(); }

bool RtlTcpSampleSource::release(bool flush) {
  for (const ArrivalLossDetector::Verdict& v : detector_.release(seconds_now(), flush)) {
    StreamPiece piece;
    piece.raw = std::move(held_bytes_.front());
    held_bytes_.pop_front();
    // The tuner settles in the first samples: they go (a loss among them matters to no one).
    const bool settling = settle_bytes_left_ > 0;
    if (settling) {
      const auto drop = static_cast<std::size_t>(
          std::min<std::int64_t>(settle_bytes_left_, static_cast<std::int64_t>(piece.raw.size())));
      piece.raw.erase(piece.raw.begin(), piece.raw.begin() + static_cast<std::ptrdiff_t>(drop));
      settle_bytes_left_ -= static_cast<std::int64_t>(drop);
      if (piece.raw.empty()) continue;
    }
    if (v.missing_before > 0 && !settling) {
      spdlog::warn("{}: {} samples ({:.3f} s) went missing before sample {}: the server dropped data", url_,
                   v.missing_before, static_cast<double>(v.missing_before) / rtl_.tuning.sample_rate_hz,
                   next_index_ + v.missing_before);
      next_index_ += v.missing_before;
    }
    piece.first_sample_index = next_index_;
    next_index_ += static_cast<std::int64_t>(piece.raw.size() / 2);
    if (!queue_.try_push(std::move(piece))) {
      // The receiver falls behind: arrival times now say when we read, not when the dongle
      // sampled, so they cannot tell losses until a new baseline stands.
      detector_.backlogged(seconds_now());
      spdlog::warn("{}: the receiver falls behind the stream; samples the server drops meanwhile cannot be counted",
                   url_);
      if (!queue_.push(std::move(piece), cancel_)) return false;
    }
  }
  report_pace();
  return true;
}

void RtlTcpSampleSource::report_pace() {
  const bool slow = detector_.slow();
  const double fs = rtl_.tuning.sample_rate_hz;
  if (slow && !reported_slow_) {
    const double pace = detector_.pace().mean().value_or(0.0);
    spdlog::warn(
        "{}: the stream runs at {:.3g} of real time ({:.0f} of {:.0f} samples/s): the sender is slower than the "
        "sample rate, which a dongle is not; its samples are taken as they come, and lost ones cannot be told "
        "from arrival times while it is",
        url_, pace, pace * fs, fs);
  } else if (!slow && reported_slow_) {
    spdlog::info("{}: the stream keeps real time again", url_);
  }
  reported_slow_ = slow;
  update_stats([&](StreamStats& s) {
    s.pace_of_real_time = detector_.pace().overall();
    s.slower_than_real_time = s.slower_than_real_time || slow;
  });
}

std::string RtlTcpSampleSource::end_reason(const std::string& why) const {
  if (next_index_ > 0 || settle_bytes_left_ == settle_bytes_) return why;
  // Everything that came went while the tuner settled: say so, for the run that got nothing.
  return fmt::format("{}; every sample received came within the first {} s, discarded while the tuner settles", why,
                     rtl_.settle_s);
}

void RtlTcpSampleSource::io_loop() {
  std::vector<std::byte> buffer(kReadBytes);
  std::vector<std::byte> data;
  std::string why;
  while (!cancel_) {
    const std::size_t got = asio_wait::read_some(io_, socket_, buffer, kIdleTimeout_s, cancel_, why);
    if (got == 0) break;
    update_stats([&](StreamStats& s) { s.bytes_received += static_cast<std::int64_t>(got); });
    // cu8 samples are byte pairs: a read may end inside one (data keeps that byte).
    data.insert(data.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(got));
    const std::size_t whole = data.size() / 2 * 2;
    if (whole > 0) {
      detector_.arrived(seconds_now(), static_cast<std::int64_t>(whole / 2));
      held_bytes_.emplace_back(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(whole));
      data.erase(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(whole));
    }
    if (!release(false)) break;
  }
  if (!cancel_ && release(true)) queue_.finish({end_reason(why), false});
  if (cancel_) queue_.finish({"interrupted", false});
}

}  // namespace deepnav
