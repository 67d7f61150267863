#include "receiver/stream/stream_server.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>
#include <list>
#include <map>
#include <random>
#include <thread>

#include "receiver/stream/asio_wait.hpp"
#include "receiver/stream/stream_protocol.hpp"

namespace deepnav {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;
using asio::ip::udp;
using asio_wait::Clock;

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

/// The sample clock of a session: when the samples up to `end_index` are due.
struct Pacer {
  Clock::time_point start = Clock::now();
  std::int64_t first_index = 0;
  double samples_per_s = 0.0;  ///< 0: no pacing
  bool wait_for(std::int64_t end_index, const std::atomic<bool>& cancel) const {
    if (samples_per_s <= 0.0) return !cancel.load();
    return asio_wait::sleep_until(start + seconds(static_cast<double>(end_index - first_index) / samples_per_s),
                                  cancel);
  }
};

std::string ranges_text(const std::vector<std::uint64_t>& v) {
  std::string out;
  for (std::size_t i = 0; i < v.size();) {
    std::size_t j = i;
    while (j + 1 < v.size() && v[j + 1] == v[j] + 1) ++j;
    if (!out.empty()) out.push_back(',');
    out.append(i == j ? fmt::format("{}", v[i]) : fmt::format("{}-{}", v[i], v[j]));
    i = j + 1;
  }
  return out;
}

}  // namespace

void check_frame_payload(const std::string& option, std::uint32_t payload_bytes, SampleFormat format, bool framed) {
  const std::size_t bps = bytes_per_sample(format);
  if (payload_bytes % bps == 0 && payload_bytes >= kMinFramePayloadBytes) return;
  const std::size_t whole = payload_bytes / bps * bps;
  const std::string cost =
      framed ? fmt::format("{} sample{} in a {}-byte frame, {:.0f} % of it the {}-byte header", whole / bps,
                           whole / bps == 1 ? "" : "s", whole + stream::kFrameHeaderBytes,
                           100.0 * static_cast<double>(stream::kFrameHeaderBytes) /
                               static_cast<double>(whole + stream::kFrameHeaderBytes),
                           stream::kFrameHeaderBytes)
             : fmt::format("{} sample{} a send", whole / bps, whole / bps == 1 ? "" : "s");
  throw std::invalid_argument(fmt::format(
      "{} {}: a frame carries whole {} samples ({} bytes each) and at least {} bytes ({} would send {}); give a "
      "multiple of {} from {}",
      option, payload_bytes, to_string(format), bps, kMinFramePayloadBytes, payload_bytes, cost, bps,
      (kMinFramePayloadBytes + bps - 1) / bps * bps));
}

struct StreamServer::Impl {
  StreamServerOptions opt;
  asio::io_context io;  // acceptor and UDP requests, on the run() thread
  std::optional<tcp::acceptor> acceptor;
  std::optional<udp::socket> udp_socket;
  std::mutex udp_send_mutex;
  std::atomic<bool> stopping{false};

  struct Session {
    asio::io_context io;
    std::optional<tcp::socket> socket;
    std::atomic<Clock::rep> last_request{Clock::now().time_since_epoch().count()};
    std::atomic<bool> done{false};
    std::atomic<bool> stop_requested{false};
    std::thread thread;
  };
  std::list<std::unique_ptr<Session>> sessions;
  std::map<udp::endpoint, Session*> udp_sessions;
  mutable std::mutex reports_mutex;
  std::vector<ServerSessionReport> reports;
  int sessions_started = 0;

  void add_report(ServerSessionReport r) {
    spdlog::info("{}: session ended ({}): {} samples from {} in {} frames{}", r.client, r.end, r.samples_sent,
                 r.first_sample, r.frames_sent,
                 r.dropped_frames.empty() ? "" : fmt::format("; frames not sent: {}", ranges_text(r.dropped_frames)));
    std::lock_guard lock(reports_mutex);
    reports.push_back(std::move(r));
  }

  stream::StreamHeader header_for(const IfByteStream& s, std::int64_t start, std::uint32_t payload) const {
    stream::StreamHeader h;
    h.format = s.format();
    h.sample_rate_hz = s.sample_rate_hz();
    h.if_hz = s.if_hz();
    h.start_sample_index = start;
    h.start_time = s.start_time();
    h.max_payload_bytes = payload;
    return h;
  }

  /// Whole samples per frame for a payload budget.
  static std::size_t frame_samples(const IfByteStream& s, std::uint32_t payload) {
    return std::max<std::size_t>(1, payload / bytes_per_sample(s.format()));
  }

  // ---------------------------------------------------------------- TCP
  bool write_all(Session& s, const std::vector<asio::const_buffer>& buffers) {
    // No deadline: a slow client holds back its own session only (backpressure).
    return write_until(s, buffers, Clock::time_point::max(), stopping);
  }

  bool write_until(Session& s, const std::vector<asio::const_buffer>& buffers, Clock::time_point deadline,
                   const std::atomic<bool>& cancel) {
    bool done = false;
    boost::system::error_code ec;
    asio::async_write(*s.socket, buffers, [&](const boost::system::error_code& e, std::size_t) {
      ec = e;
      done = true;
    });
    const bool completed = asio_wait::run_until_done(s.io, done, deadline, cancel, [&] { s.socket->close(); });
    return completed && !ec;
  }

  /// The end-of-stream frame: at the end of the stream, as slowly as the client reads, like
  /// every frame; when the server stops (Ctrl-C) too, so that the client sees the stream end
  /// instead of a dropped connection it would keep reconnecting to, but then a client that
  /// does not read gets a second, not forever.
  void write_end(Session& s, std::uint64_t sequence, std::int64_t next_index) {
    static const std::atomic<bool> never{false};
    const auto end = stream::encode(stream::FrameHeader{sequence, next_index, 0, true});
    if (!stopping) {
      write_all(s, {asio::buffer(end)});
    } else {
      write_until(s, {asio::buffer(end)}, asio_wait::after(1.0), never);
    }
  }

  /// The client's request, or nullopt when it sent none in time (then: from the start).
  std::optional<stream::ClientRequest> read_request(Session& s, const std::string& client) {
    std::array<std::byte, stream::kRequestBytes> bytes{};
    bool done = false;
    boost::system::error_code ec;
    std::size_t got = 0;
    asio::async_read(*s.socket, asio::buffer(bytes), [&](const boost::system::error_code& e, std::size_t n) {
      ec = e;
      got = n;
      done = true;
    });
    const bool completed = asio_wait::run_until_done(s.io, done, Clock::now() + seconds(opt.request_timeout_s),
                                                     stopping, [&] { s.socket->cancel(); });
    if (!completed && got == 0) return std::nullopt;
    if (got < bytes.size())
      throw stream::ProtocolError(fmt::format("client request: {} bytes, expected {}", got, bytes.size()));
    (void)client;
    return stream::decode_request(bytes);
  }

  void tcp_session(Session& s, const std::string& client) {
    ServerSessionReport r;
    r.client = client;
    try {
      std::int64_t start = 0;
      if (!opt.raw) {
        if (const auto request = read_request(s, client)) start = request->resume_from_sample;
      }
      auto src = opt.open_stream();
      if (start > 0) src->seek(start);
      r.first_sample = start;
      const std::uint32_t payload =
          static_cast<std::uint32_t>(frame_samples(*src, opt.tcp_payload_bytes) * bytes_per_sample(src->format()));
      spdlog::info("{}: session from sample {} ({})", client, start, opt.raw ? "raw" : "framed");
      const auto header = stream::encode(header_for(*src, start, payload));
      if (!opt.raw && !write_all(s, {asio::buffer(header)})) throw std::runtime_error("connection closed");
      Pacer pacer{Clock::now(), start, opt.pace * src->sample_rate_hz()};
      std::vector<std::byte> bytes;
      std::uint64_t sequence = 0;
      std::int64_t next_index = src->next_sample_index();
      r.end = "end of stream";
      while (true) {
        const std::int64_t first = next_index;
        const std::size_t n = src->read(bytes, frame_samples(*src, payload));
        if (n == 0) break;
        if (!pacer.wait_for(first + static_cast<std::int64_t>(n), stopping)) {
          r.end = "server stopping";
          break;
        }
        const auto frame =
            stream::encode(stream::FrameHeader{sequence++, first, static_cast<std::uint32_t>(bytes.size()), false});
        const bool ok =
            opt.raw ? write_all(s, {asio::buffer(bytes)}) : write_all(s, {asio::buffer(frame), asio::buffer(bytes)});
        if (!ok) throw std::runtime_error(stopping ? "server stopping" : "the client closed the connection");
        r.samples_sent += static_cast<std::int64_t>(n);
        ++r.frames_sent;
        next_index = src->next_sample_index();
      }
      if (!opt.raw) write_end(s, sequence, next_index);
    } catch (const stream::ProtocolError& e) {
      r.end = fmt::format("bad request, connection closed: {}", e.what());
      spdlog::warn("{}: {}", client, r.end);
    } catch (const std::exception& e) {
      r.end = e.what();
    }
    boost::system::error_code ignored;
    s.socket->shutdown(tcp::socket::shutdown_both, ignored);
    s.socket->close(ignored);
    add_report(std::move(r));
  }

  void start_accept() {
    auto session = std::make_unique<Session>();
    Session* s = session.get();
    acceptor->async_accept(
        s->io, [this, session = std::move(session)](const boost::system::error_code& ec, tcp::socket socket) mutable {
          if (ec) return;  // the acceptor closed
          Session* sp = session.get();
          sp->socket.emplace(std::move(socket));
          boost::system::error_code e2;
          const auto peer = sp->socket->remote_endpoint(e2);
          const std::string client = fmt::format("tcp://{}:{}", peer.address().to_string(), peer.port());
          ++sessions_started;
          sp->thread = std::thread([this, sp, client] {
            tcp_session(*sp, client);
            sp->done = true;
          });
          sessions.push_back(std::move(session));
          start_accept();
        });
  }

  // ---------------------------------------------------------------- UDP
  void udp_send(const std::vector<asio::const_buffer>& buffers, const udp::endpoint& to) {
    std::lock_guard lock(udp_send_mutex);
    boost::system::error_code ec;
    udp_socket->send_to(buffers, to, 0, ec);  // UDP: a failed send is a lost datagram, which the client detects
  }

  void udp_send_end(std::uint64_t sequence, std::int64_t next_index, const udp::endpoint& to) {
    const auto end = stream::encode(stream::FrameHeader{sequence, next_index, 0, true});
    for (int i = 0; i < 3; ++i) udp_send({asio::buffer(end)}, to);  // three times: it may be lost too
  }

  void udp_session(Session& s, udp::endpoint client_ep, std::int64_t start) {
    ServerSessionReport r;
    r.client = fmt::format("udp://{}:{}", client_ep.address().to_string(), client_ep.port());
    r.first_sample = start;
    std::mt19937_64 rng(opt.drop_seed);
    std::bernoulli_distribution drop(std::clamp(opt.drop_probability, 0.0, 1.0));
    try {
      auto src = opt.open_stream();
      if (start > 0) src->seek(start);
      const std::uint32_t payload =
          static_cast<std::uint32_t>(frame_samples(*src, opt.udp_payload_bytes) * bytes_per_sample(src->format()));
      spdlog::info("{}: session from sample {} ({})", r.client, start, opt.raw ? "raw" : "framed");
      const auto header = stream::encode(header_for(*src, start, payload));
      if (!opt.raw) udp_send({asio::buffer(header)}, client_ep);
      Pacer pacer{Clock::now(), start, opt.pace * src->sample_rate_hz()};
      std::vector<std::byte> bytes;
      std::uint64_t sequence = 0;
      r.end = "end of stream";
      while (true) {
        if (s.stop_requested) {
          r.end = "the client left";
          break;
        }
        if (Clock::now() - Clock::time_point(Clock::duration(s.last_request.load())) >
            seconds(opt.udp_keepalive_timeout_s)) {
          r.end = fmt::format("no request from the client for {} s", opt.udp_keepalive_timeout_s);
          break;
        }
        const std::int64_t first = src->next_sample_index();
        const std::size_t n = src->read(bytes, frame_samples(*src, payload));
        if (n == 0) {
          if (!opt.raw) udp_send_end(sequence, first, client_ep);
          break;
        }
        if (!pacer.wait_for(first + static_cast<std::int64_t>(n), stopping)) {
          r.end = "server stopping";
          if (!opt.raw) udp_send_end(sequence, first, client_ep);  // the client ends, not waits for more
          break;
        }
        const std::uint64_t seq = sequence++;
        r.samples_sent += static_cast<std::int64_t>(n);
        if (opt.drop_frames.count(seq) > 0 || drop(rng)) {
          r.dropped_frames.push_back(seq);
          continue;
        }
        const auto frame =
            stream::encode(stream::FrameHeader{seq, first, static_cast<std::uint32_t>(bytes.size()), false});
        if (opt.raw) {
          udp_send({asio::buffer(bytes)}, client_ep);
        } else {
          udp_send({asio::buffer(frame), asio::buffer(bytes)}, client_ep);
        }
        ++r.frames_sent;
      }
    } catch (const std::exception& e) {
      r.end = e.what();
    }
    add_report(std::move(r));
  }

  void handle_udp_request(std::span<const std::byte> bytes, const udp::endpoint& from) {
    stream::ClientRequest request;
    try {
      if (bytes.size() != stream::kRequestBytes)
        throw stream::ProtocolError(
            fmt::format("client request: {} bytes, expected {}", bytes.size(), stream::kRequestBytes));
      request = stream::decode_request(bytes.first<stream::kRequestBytes>());
    } catch (const stream::ProtocolError& e) {
      spdlog::warn("udp://{}:{}: datagram ignored: {}", from.address().to_string(), from.port(), e.what());
      return;
    }
    const auto it = udp_sessions.find(from);
    if (it != udp_sessions.end() && !it->second->done) {
      it->second->last_request = Clock::now().time_since_epoch().count();
      if (request.stop) it->second->stop_requested = true;
      return;
    }
    if (request.stop) return;
    auto session = std::make_unique<Session>();
    Session* sp = session.get();
    ++sessions_started;
    sp->thread = std::thread([this, sp, from, start = request.resume_from_sample] {
      udp_session(*sp, from, start);
      sp->done = true;
    });
    udp_sessions[from] = sp;
    sessions.push_back(std::move(session));
  }

  void start_udp_receive(std::vector<std::byte>& buffer, udp::endpoint& from) {
    udp_socket->async_receive_from(asio::buffer(buffer), from,
                                   [this, &buffer, &from](const boost::system::error_code& ec, std::size_t n) {
                                     if (ec == asio::error::operation_aborted) return;
                                     if (!ec) handle_udp_request(std::span<const std::byte>(buffer.data(), n), from);
                                     start_udp_receive(buffer, from);
                                   });
  }

  /// Joins the sessions that ended (all of them when `all`: they are ending); returns how many.
  int reap(bool all = false) {
    int ended = 0;
    for (auto it = sessions.begin(); it != sessions.end();) {
      if (all || (*it)->done) {
        (*it)->thread.join();
        for (auto u = udp_sessions.begin(); u != udp_sessions.end();) {
          u = u->second == it->get() ? udp_sessions.erase(u) : std::next(u);
        }
        it = sessions.erase(it);
        ++ended;
      } else {
        ++it;
      }
    }
    return ended;
  }
};

StreamServer::StreamServer(StreamServerOptions options) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.opt = std::move(options);
  if (!m.opt.open_stream) throw std::invalid_argument("stream server: no stream to serve");
  if (!(m.opt.pace >= 0.0)) throw std::invalid_argument(fmt::format("stream server: pace {} must be >= 0", m.opt.pace));
  if (m.opt.tcp_payload_bytes == 0 || m.opt.tcp_payload_bytes > stream::kMaxPayloadLimit ||
      m.opt.udp_payload_bytes == 0 || m.opt.udp_payload_bytes > 65000)
    throw std::invalid_argument("stream server: frame payload must be 1 byte to 1 MiB (TCP), 65000 bytes (UDP)");
  boost::system::error_code ec;
  const auto address = asio::ip::make_address(m.opt.bind_address, ec);
  if (ec)
    throw std::runtime_error(fmt::format("stream server: bad bind address '{}': {}", m.opt.bind_address, ec.message()));
  if (m.opt.tcp_port) {
    m.acceptor.emplace(m.io);
    const tcp::endpoint ep(address, *m.opt.tcp_port);
    m.acceptor->open(ep.protocol(), ec);
    if (!ec) m.acceptor->set_option(tcp::acceptor::reuse_address(true), ec);
    if (!ec) m.acceptor->bind(ep, ec);
    if (!ec) m.acceptor->listen(asio::socket_base::max_listen_connections, ec);
    if (ec)
      throw std::runtime_error(
          fmt::format("cannot listen on tcp://{}:{}: {}", m.opt.bind_address, *m.opt.tcp_port, ec.message()));
  }
  if (m.opt.udp_port) {
    m.udp_socket.emplace(m.io);
    const udp::endpoint ep(address, *m.opt.udp_port);
    m.udp_socket->open(ep.protocol(), ec);
    if (!ec) m.udp_socket->bind(ep, ec);
    if (ec)
      throw std::runtime_error(
          fmt::format("cannot bind udp://{}:{}: {}", m.opt.bind_address, *m.opt.udp_port, ec.message()));
    m.udp_socket->set_option(asio::socket_base::send_buffer_size(4 << 20), ec);  // best effort
  }
  if (!m.acceptor && !m.udp_socket)
    throw std::invalid_argument("stream server: neither a TCP nor a UDP port to serve on");
}

StreamServer::~StreamServer() {
  Impl& m = *impl_;
  m.stopping = true;
  for (auto& s : m.sessions)
    if (s->thread.joinable()) s->thread.join();
}

std::uint16_t StreamServer::tcp_port() const { return impl_->acceptor ? impl_->acceptor->local_endpoint().port() : 0; }
std::uint16_t StreamServer::udp_port() const {
  return impl_->udp_socket ? impl_->udp_socket->local_endpoint().port() : 0;
}

void StreamServer::run(const std::atomic<bool>& stop, int max_sessions) {
  Impl& m = *impl_;
  std::vector<std::byte> udp_buffer(2048);
  udp::endpoint udp_from;
  if (m.acceptor) m.start_accept();
  if (m.udp_socket) m.start_udp_receive(udp_buffer, udp_from);
  int ended = 0;
  while (!stop.load() && !(max_sessions > 0 && ended >= max_sessions)) {
    m.io.run_for(std::chrono::milliseconds(50));
    ended += m.reap();
  }
  m.stopping = true;
  boost::system::error_code ignored;
  if (m.acceptor) m.acceptor->close(ignored);
  if (m.udp_socket) m.udp_socket->cancel(ignored);
  m.io.restart();
  m.io.poll();  // run the aborted handlers while the buffers above still exist
  // Each session sees `stopping` and ends; reap joins each thread exactly once (a second
  // join throws std::system_error "Invalid argument").
  m.reap(true);
}

std::vector<ServerSessionReport> StreamServer::reports() const {
  std::lock_guard lock(impl_->reports_mutex);
  return impl_->reports;
}

}  // namespace deepnav
