#include "receiver/stream/udp_sample_source.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstring>

#include "receiver/stream/asio_wait.hpp"

namespace deepnav {
namespace {

namespace asio = boost::asio;
using asio::ip::udp;
using asio_wait::Clock;

constexpr std::size_t kMaxDatagram = 65536;
constexpr int kSocketReceiveBuffer = 8 << 20;  // best effort: the kernel may cap it
constexpr auto kRequestInterval = std::chrono::seconds(1);
constexpr std::size_t kMaxLostRanges = 10000;

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace

UdpSampleSource::UdpSampleSource(StreamSourceSettings settings)
    : StreamSampleSource(settings,
                         fmt::format("udp://{}{}:{}", settings.listen ? "@" : "", settings.host, settings.port)),
      socket_(io_),
      sequencer_(
          kReorderWindow, [this](stream::Frame&& f) { deliver(std::move(f)); },
          [this](std::uint64_t first, std::uint64_t last) {
            update_stats([&](StreamStats& s) {
              s.frames_lost += static_cast<std::int64_t>(last - first + 1);
              if (s.lost_frame_ranges.size() < kMaxLostRanges) s.lost_frame_ranges.emplace_back(first, last);
            });
          }) {
  boost::system::error_code ec;
  udp::resolver resolver(io_);
  const auto endpoints = resolver.resolve(udp::v4(), settings_.host, std::to_string(settings_.port), ec);
  if (ec || endpoints.empty())
    throw std::runtime_error(fmt::format("{}: cannot resolve '{}': {}", url_, settings_.host, ec.message()));
  const udp::endpoint endpoint = *endpoints.begin();
  socket_.open(udp::v4(), ec);
  if (!ec && settings_.listen) socket_.bind(endpoint, ec);
  if (!ec && !settings_.listen) {
    server_ = endpoint;
    socket_.bind(udp::endpoint(udp::v4(), 0), ec);
  }
  if (ec) throw std::runtime_error(fmt::format("{}: cannot open the socket: {}", url_, ec.message()));
  socket_.set_option(asio::socket_base::receive_buffer_size(kSocketReceiveBuffer), ec);  // best effort
  local_port_ = socket_.local_endpoint().port();
  start_io([this] { io_loop(); });
}

UdpSampleSource::~UdpSampleSource() { stop_io(); }

void UdpSampleSource::send_request(bool stop) {
  if (settings_.listen) return;
  const auto request = stream::encode(stream::ClientRequest{resume_from_, stop});
  boost::system::error_code ec;
  socket_.send_to(asio::buffer(request), server_, 0, ec);  // a lost request is sent again a second later
}

void UdpSampleSource::deliver(stream::Frame&& frame) {
  const auto count = static_cast<std::int64_t>(frame.payload.size() / bytes_per_sample(header_seen_->format));
  resume_from_ = std::max(resume_from_, frame.header.first_sample_index + count);
  const bool queued = queue_.try_push(StreamPiece{frame.header.first_sample_index, std::move(frame.payload)});
  update_stats([&](StreamStats& s) {
    ++s.frames_received;
    if (!queued) ++s.frames_overrun;
  });
}

void UdpSampleSource::handle_raw_datagram(std::span<const std::byte> bytes) {
  const std::size_t bps = bytes_per_sample(settings_.raw_format);
  // A sender may cut its byte stream anywhere: the sample a datagram ends inside is
  // completed by the next one, so that every later sample keeps its I and Q in place.
  raw_carry_.insert(raw_carry_.end(), bytes.begin(), bytes.end());
  const std::size_t whole = raw_carry_.size() / bps * bps;
  const bool split = raw_carry_.size() != whole;
  if (split && !warned_split_sample_) {
    warned_split_sample_ = true;
    spdlog::warn(
        "{}: a datagram of {} bytes ends inside a {} sample ({} bytes each): the rest of the sample is taken from "
        "the next datagram (a datagram lost after such a one would shift every later sample)",
        url_, bytes.size(), to_string(settings_.raw_format), bps);
  }
  update_stats([&](StreamStats& s) {
    s.bytes_received += static_cast<std::int64_t>(bytes.size());
    if (split) ++s.datagrams_split_samples;
  });
  if (whole == 0) return;
  StreamPiece piece{
      raw_index_, std::vector<std::byte>(raw_carry_.begin(), raw_carry_.begin() + static_cast<std::ptrdiff_t>(whole))};
  raw_carry_.erase(raw_carry_.begin(), raw_carry_.begin() + static_cast<std::ptrdiff_t>(whole));
  raw_index_ += static_cast<std::int64_t>(whole / bps);
  if (!queue_.try_push(std::move(piece))) update_stats([](StreamStats& s) { ++s.frames_overrun; });
}

void UdpSampleSource::handle_datagram(std::span<const std::byte> bytes) {
  if (settings_.raw) {
    handle_raw_datagram(bytes);
    return;
  }
  if (!header_seen_ && bytes.size() >= 4 && std::memcmp(bytes.data(), stream::kFrameMagic.data(), 4) == 0) {
    send_request(false);  // the header datagram was lost: the server sends it again on a request
    return;
  }
  const stream::Datagram d = stream::decode_datagram(bytes, header_seen_);
  if (d.header) {
    if (!header_seen_) {
      header_seen_ = d.header;
      publish_header(*d.header);
      sequencer_.restart(0);
    } else if (d.header->start_sample_index != header_seen_->start_sample_index) {
      if (d.header->format != header_seen_->format || d.header->sample_rate_hz != header_seen_->sample_rate_hz ||
          d.header->if_hz != header_seen_->if_hz)
        throw stream::ProtocolError("the server started a different stream (format, rate or IF)");
      header_seen_ = d.header;  // a new session (the server lost ours): numbering restarts
      sequencer_.restart(0);
      update_stats([](StreamStats& s) { ++s.reconnects; });
    }
    return;
  }
  if (d.frame->header.end_of_stream) {
    // The end frame's number and index say how many frames and samples the stream had:
    // frames lost after the last one that came are lost all the same.
    sequencer_.finish(d.frame->header.sequence);
    send_request(true);
    queue_.finish({"end of stream", false, d.frame->header.first_sample_index});
    finished_ = true;
    return;
  }
  sequencer_.add(std::move(*d.frame));
  // The sequencer classifies the frames; the summary reads StreamStats (its counts run on
  // across restart()).
  update_stats([&](StreamStats& s) {
    s.bytes_received += static_cast<std::int64_t>(bytes.size());
    s.frames_duplicated = sequencer_.duplicated();
    s.frames_reordered = sequencer_.reordered();
    s.frames_late = sequencer_.late();
  });
}

void UdpSampleSource::io_loop() {
  std::vector<std::byte> buffer(kMaxDatagram);
  auto last_request = Clock::time_point{};
  auto last_datagram = Clock::now();
  while (!cancel_ && !finished_) {
    if (!header_seen_ || Clock::now() - last_request >= kRequestInterval) {
      if (Clock::now() - last_request >= std::chrono::milliseconds(200)) {
        send_request(false);
        last_request = Clock::now();
      }
    }
    bool done = false;
    boost::system::error_code ec;
    std::size_t got = 0;
    udp::endpoint sender;
    socket_.async_receive_from(asio::buffer(buffer), sender, [&](const boost::system::error_code& e, std::size_t n) {
      ec = e;
      got = n;
      done = true;
    });
    const bool completed = asio_wait::run_until_done(io_, done, Clock::now() + std::chrono::milliseconds(200), cancel_,
                                                     [&] { socket_.cancel(); });
    const double silence_limit_s =
        header_seen_ || settings_.raw ? settings_.reconnect_timeout_s : settings_.connect_timeout_s;
    if (!completed || ec) {
      if (cancel_) break;
      if (Clock::now() - last_datagram > seconds(silence_limit_s)) {
        sequencer_.flush();
        queue_.finish({fmt::format("no datagram for {} s", silence_limit_s), !settings_.raw});
        return;
      }
      continue;
    }
    if (!settings_.listen && sender != server_) continue;  // not from the server we subscribed to
    last_datagram = Clock::now();
    try {
      handle_datagram(std::span<const std::byte>(buffer.data(), got));
    } catch (const stream::ProtocolError& e) {
      send_request(true);
      queue_.finish({fmt::format("protocol error: {}", e.what()), true});
      return;
    }
  }
  if (!finished_) {
    send_request(true);
    sequencer_.flush();
    queue_.finish({"interrupted", false});
  }
}

}  // namespace deepnav
