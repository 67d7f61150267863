#include "tools/bench/stream_bench.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>
#include <tuple>

#include "aiding/navigation_session.hpp"
#include "ins/input_error.hpp"
#include "receiver/sources/sample_source_factory.hpp"
#include "receiver/stream/stream_server.hpp"
#include "receiver/stream/tcp_sample_source.hpp"
#include "receiver/stream/thread_safe_logging.hpp"
#include "signals/if_file_stream.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/sim/scenario.hpp"
#include "tools/bench/bench_report.hpp"
#include "tools/bench/process_usage.hpp"

namespace deepnav::bench {
namespace {

struct StreamRun {
  double signal_s = 0.0, wall_s = 0.0, receiver_cpu_s = 0.0, process_cpu_s = 0.0;
  std::int64_t bytes = 0, lost_samples = 0;
  int max_tracking = 0;
};

/// The server's thread, stopped and joined however the run ends: a thread left joinable
/// would end the process without a word about what failed.
struct ServingThread {
  std::atomic<bool> stop{false};
  std::thread thread;
  void finish() {
    stop = true;
    if (thread.joinable()) thread.join();
  }
  ~ServingThread() { finish(); }
};

/// Serves `if_path` over TCP loopback at `pace` (0: as fast as read) for `seconds` of
/// signal and runs the receiver on it in this thread.
StreamRun run_over_tcp(const Scenario& sc, const std::string& if_path, double pace, double seconds) {
  IfFileStreamOptions fo;
  fo.path = if_path;
  fo.format = sc.format;
  fo.sample_rate_hz = sc.sample_rate_hz;
  fo.if_hz = sc.if_hz;
  fo.start_time = sc.start_time;
  StreamServerOptions so;
  so.tcp_port = 0;
  so.pace = pace;
  const auto limit = static_cast<std::int64_t>(std::llround(seconds * sc.sample_rate_hz));
  so.open_stream = [fo, limit] {
    // The file cut to `limit` samples: a stream that ends there.
    struct Cut final : IfByteStream {
      IfFileStream file;
      std::int64_t limit;
      Cut(const IfFileStreamOptions& o, std::int64_t l) : file(o), limit(l) {}
      SampleFormat format() const override { return file.format(); }
      double sample_rate_hz() const override { return file.sample_rate_hz(); }
      double if_hz() const override { return file.if_hz(); }
      std::optional<GpsTime> start_time() const override { return file.start_time(); }
      std::optional<std::int64_t> total_samples() const override { return limit; }
      std::size_t read(std::vector<std::byte>& out, std::size_t max) override {
        const auto left = static_cast<std::size_t>(std::max<std::int64_t>(0, limit - file.next_sample_index()));
        return file.read(out, std::min(max, left));
      }
      void seek(std::int64_t i) override { file.seek(i); }
      std::int64_t next_sample_index() const override { return file.next_sample_index(); }
    };
    return std::unique_ptr<IfByteStream>(new Cut(fo, limit));
  };
  StreamServer server(so);
  ServingThread serving;
  serving.thread = std::thread([&] { server.run(serving.stop, 1); });
  StreamRun r;
  const double cpu0 = thread_cpu_s(), process0 = process_cpu_s();
  const auto t0 = std::chrono::steady_clock::now();
  {
    StreamSourceSettings st;
    st.port = server.tcp_port();
    TcpSampleSource source(st);
    aiding::NavigationSessionConfig cfg;
    cfg.navigator.mode = aiding::NavMode::scalar;  // the receiver alone (the config's default is ultra)
    cfg.navigator.receiver.reference_week = sc.start_time.week;
    CallbackSink counter(
        [&](const NavigationEpoch& e) { r.max_tracking = std::max(r.max_tracking, e.receiver.channels_tracking); });
    aiding::NavigationSession(std::move(cfg), source, std::nullopt, std::nullopt).run({&counter});
    r.signal_s = static_cast<double>(source.next_sample_index()) / sc.sample_rate_hz;
    r.bytes = source.stats().bytes_received;
    r.lost_samples = source.lost_sample_count();
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.receiver_cpu_s = thread_cpu_s() - cpu0;
  serving.finish();
  r.process_cpu_s = process_cpu_s() - process0;
  return r;
}

}  // namespace

void run_stream_bench(const StreamBenchSettings& o) {
  use_thread_safe_logger();
  if (!(o.duration_s > 0.0) || !(o.paced_s > 0.0) || o.paced_s > o.duration_s)
    throw InputError("--duration and --paced must be positive, --paced at most --duration");
  Scenario sc;
  NavData nav;
  try {
    // A relative path is looked up in the source tree too, so the default works from anywhere.
    std::filesystem::path path = o.scenario_path;
    if (!std::filesystem::exists(path) && path.is_relative()) path = std::filesystem::path(DEEPNAV_SOURCE_DIR) / path;
    sc = load_scenario(path.string(), DEEPNAV_SOURCE_DIR);
    // Every satellite above the horizon, up to 12 (the default scenario, on the equator at
    // 12:00 GPS time on 2022-01-01, has 12 with the bundled navigation file).
    sc.duration_s = o.duration_s;
    sc.elevation_mask_rad = 0.0;
    sc.max_satellites = 12;
    validate_scenario(sc);
    nav = read_rinex_nav(sc.nav_file);
  } catch (const std::exception& e) {
    throw InputError(e.what());
  }
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("deepnav-bench-stream-{}", ::getpid());
  IfSynthesizer synth(sc, std::move(nav));
  SynthesisOptions so;
  so.threads = 0;
  so.if_only = true;
  spdlog::info("synthesizing {} s with {} satellites ...", sc.duration_s, synth.satellites().size());
  const SynthesisSummary s = synth.run(dir.string(), so);
  BenchReport report("Streaming over TCP loopback: server -> receiver",
                     {"pace", "signal_s", "wall_s", "MB_per_s", "x_real_time", "channels_tracking", "receiver_cpu_pct",
                      "process_cpu_pct", "lost_samples"});
  report.set_precision("receiver_cpu_pct", 1);
  report.set_precision("process_cpu_pct", 1);
  report.set_precision("MB_per_s", 1);
  report.set_precision("x_real_time", 2);
  for (const auto& [label, pace, seconds] :
       {std::tuple<std::string, double, double>{"as fast as read", 0.0, o.duration_s}, {"real time", 1.0, o.paced_s}}) {
    const StreamRun r = run_over_tcp(sc, s.if_path, pace, seconds);
    report.add_row({label, r.signal_s, r.wall_s, static_cast<double>(r.bytes) / 1e6 / r.wall_s, r.signal_s / r.wall_s,
                    static_cast<long long>(r.max_tracking), 100.0 * r.receiver_cpu_s / r.wall_s,
                    100.0 * r.process_cpu_s / r.wall_s, static_cast<long long>(r.lost_samples)});
  }
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  report.add_note("satellites", synth.satellites().size());
  report.add_note("format", std::string(to_string(sc.format)));
  report.add_note("sample_rate_hz", sc.sample_rate_hz);
  report.add_note("cpu_note",
                  "receiver_cpu_pct: the receiver thread (acquisition, tracking, PVT, sample conversion), "
                  "percent of one core; process_cpu_pct adds the server and the socket I/O thread");
  report.add_note("hardware_threads", std::thread::hardware_concurrency());
  report.emit(o.json_path);
}

}  // namespace deepnav::bench
