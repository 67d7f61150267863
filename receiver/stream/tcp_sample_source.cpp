#include "receiver/stream/tcp_sample_source.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <boost/asio/connect.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>

#include "receiver/stream/asio_wait.hpp"

namespace deepnav {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;
using asio_wait::Clock;

constexpr std::size_t kReadBytes = 1 << 16;
constexpr double kIdleTimeout_s = 10.0;  // a connection silent this long is taken as dropped
constexpr double kFirstBackoff_s = 0.1, kMaxBackoff_s = 5.0;

using asio_wait::after;

bool same_stream(const stream::StreamHeader& a, const stream::StreamHeader& b) {
  return a.format == b.format && a.sample_rate_hz == b.sample_rate_hz && a.if_hz == b.if_hz &&
         a.inverted_spectrum == b.inverted_spectrum;
}

}  // namespace

TcpSampleSource::TcpSampleSource(StreamSourceSettings settings)
    : StreamSampleSource(settings, fmt::format("tcp://{}:{}", settings.host, settings.port)) {
  start_io([this] { io_loop(); });
}

TcpSampleSource::~TcpSampleSource() { stop_io(); }

bool TcpSampleSource::connect(tcp::socket& socket, std::string& why) {
  boost::system::error_code ec;
  tcp::resolver resolver(io_);
  const auto endpoints = resolver.resolve(settings_.host, std::to_string(settings_.port), ec);
  if (ec) {
    why = fmt::format("cannot resolve '{}': {}", settings_.host, ec.message());
    return false;
  }
  bool done = false;
  asio::async_connect(socket, endpoints, [&](const boost::system::error_code& e, const tcp::endpoint&) {
    ec = e;
    done = true;
  });
  if (!asio_wait::run_until_done(io_, done, after(settings_.connect_timeout_s), cancel_, [&] { socket.close(); })) {
    why = cancel_ ? "interrupted" : "connection attempt timed out";
    return false;
  }
  if (ec) why = ec.message();
  return !ec;
}

std::size_t TcpSampleSource::read_some(tcp::socket& socket, std::vector<std::byte>& buffer, std::string& why) {
  return asio_wait::read_some(io_, socket, buffer, kIdleTimeout_s, cancel_, why);
}

TcpSampleSource::SessionEnd TcpSampleSource::receive_framed(tcp::socket& socket, std::string& why) {
  const auto request = stream::encode(stream::ClientRequest{resume_from_, false});
  bool done = false;
  boost::system::error_code ec;
  asio::async_write(socket, asio::buffer(request), [&](const boost::system::error_code& e, std::size_t) {
    ec = e;
    done = true;
  });
  if (!asio_wait::run_until_done(io_, done, after(kIdleTimeout_s), cancel_, [&] { socket.close(); }) || ec) {
    why = cancel_ ? "interrupted" : fmt::format("cannot send the request: {}", ec ? ec.message() : "timed out");
    return cancel_ ? SessionEnd::cancelled : SessionEnd::dropped;
  }
  stream::StreamParser parser;
  std::vector<stream::Frame> frames;
  std::vector<std::byte> buffer(kReadBytes);
  std::uint64_t expected_sequence = 0;
  bool header_checked = false;
  while (true) {
    const std::size_t got = read_some(socket, buffer, why);
    if (got == 0) {
      if (cancel_) return SessionEnd::cancelled;
      if (!parser.at_boundary()) {
        const auto partial = static_cast<std::int64_t>(parser.partial_bytes());
        update_stats([&](StreamStats& s) { s.partial_frame_bytes_discarded += partial; });
        why += fmt::format(" (in the middle of a frame: {} bytes discarded)", partial);
      }
      return SessionEnd::dropped;
    }
    update_stats([&](StreamStats& s) { s.bytes_received += static_cast<std::int64_t>(got); });
    frames.clear();
    try {
      parser.feed(std::span<const std::byte>(buffer.data(), got), frames);
      if (parser.header() && !header_checked) {
        header_checked = true;
        if (first_header_ && !same_stream(*first_header_, *parser.header()))
          throw stream::ProtocolError("after reconnecting, the server sends a different stream (format, rate or IF)");
        if (!first_header_) first_header_ = parser.header();
        publish_header(*parser.header());
      }
      for (auto& f : frames) {
        if (f.header.sequence != expected_sequence)
          throw stream::ProtocolError(fmt::format("frame sequence number {} where {} was expected (TCP keeps order)",
                                                  f.header.sequence, expected_sequence));
        ++expected_sequence;
        if (f.header.end_of_stream) {
          queue_.finish({"end of stream", false});
          return SessionEnd::finished;
        }
        update_stats([](StreamStats& s) { ++s.frames_received; });
        const auto count = static_cast<std::int64_t>(f.payload.size() / bytes_per_sample(parser.header()->format));
        const std::int64_t next = f.header.first_sample_index + count;
        if (!queue_.push(StreamPiece{f.header.first_sample_index, std::move(f.payload)}, cancel_))
          return SessionEnd::cancelled;
        resume_from_ = std::max(resume_from_, next);
      }
    } catch (const stream::ProtocolError& e) {
      queue_.finish({fmt::format("protocol error: {}", e.what()), true});
      return SessionEnd::finished;
    }
  }
}

TcpSampleSource::SessionEnd TcpSampleSource::receive_raw(tcp::socket& socket, std::string& why) {
  const std::size_t bps = bytes_per_sample(settings_.raw_format);
  std::vector<std::byte> buffer(kReadBytes);
  std::vector<std::byte> carry;  // a sample split across reads
  while (true) {
    const std::size_t got = read_some(socket, buffer, why);
    if (got == 0) return cancel_ ? SessionEnd::cancelled : SessionEnd::dropped;
    update_stats([&](StreamStats& s) { s.bytes_received += static_cast<std::int64_t>(got); });
    carry.insert(carry.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(got));
    const std::size_t whole = carry.size() / bps * bps;
    if (whole == 0) continue;
    StreamPiece piece{raw_index_,
                      std::vector<std::byte>(carry.begin(), carry.begin() + static_cast<std::ptrdiff_t>(whole))};
    carry.erase(carry.begin(), carry.begin() + static_cast<std::ptrdiff_t>(whole));
    raw_index_ += static_cast<std::int64_t>(whole / bps);
    if (!queue_.push(std::move(piece), cancel_)) return SessionEnd::cancelled;
  }
}

void TcpSampleSource::io_loop() {
  auto retry_deadline = after(settings_.connect_timeout_s);
  double backoff_s = kFirstBackoff_s;
  bool connected_before = false;
  while (!cancel_) {
    tcp::socket socket(io_);
    std::string why;
    if (connect(socket, why)) {
      if (connected_before) {
        update_stats([](StreamStats& s) { ++s.reconnects; });
        spdlog::info("{}: reconnected, resuming at sample {}", url_, resume_from_);
      }
      connected_before = true;
      backoff_s = kFirstBackoff_s;
      const SessionEnd end = settings_.raw ? receive_raw(socket, why) : receive_framed(socket, why);
      if (end == SessionEnd::finished) return;
      if (end == SessionEnd::cancelled) break;
      if (settings_.raw) {
        queue_.finish({why, false});
        return;
      }
      spdlog::warn("{}: connection lost ({}); retrying for up to {} s", url_, why, settings_.reconnect_timeout_s);
      retry_deadline = after(settings_.reconnect_timeout_s);
    }
    if (cancel_) break;
    if (Clock::now() + std::chrono::duration<double>(backoff_s) > retry_deadline) {
      queue_.finish({fmt::format("cannot connect: {} (gave up after {} s of retries)", why,
                                 connected_before ? settings_.reconnect_timeout_s : settings_.connect_timeout_s),
                     true});
      return;
    }
    asio_wait::sleep_until(after(backoff_s), cancel_);
    backoff_s = std::min(2.0 * backoff_s, kMaxBackoff_s);
  }
  queue_.finish({"interrupted", false});
}

}  // namespace deepnav
