#include "receiver/sources/sample_source_factory.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <filesystem>

#include "ins/input_error.hpp"
#include "receiver/sources/file_sample_source.hpp"
#include "receiver/sources/source_url.hpp"
#include "receiver/stream/rtltcp_sample_source.hpp"
#include "receiver/stream/tcp_sample_source.hpp"
#include "receiver/stream/thread_safe_logging.hpp"
#include "receiver/stream/udp_sample_source.hpp"
#include "signals/data_path.hpp"
#include "signals/gps_constants.hpp"
#include "signals/if_metadata.hpp"

namespace deepnav {
namespace {

/// A file source that ends early once the stop flag is set.
class StoppableFileSource final : public SampleSource {
 public:
  StoppableFileSource(std::unique_ptr<FileSampleSource> file, const std::atomic<bool>* stop)
      : file_(std::move(file)), stop_(stop) {}
  double sample_rate_hz() const override { return file_->sample_rate_hz(); }
  double intermediate_frequency_hz() const override { return file_->intermediate_frequency_hz(); }
  bool is_real() const override { return file_->is_real(); }
  std::size_t read(std::span<Sample> out) override {
    if (stop_ != nullptr && stop_->load()) {
      interrupted_ = true;
      return 0;
    }
    return file_->read(out);
  }
  std::int64_t next_sample_index() const override { return file_->next_sample_index(); }
  bool at_end() const override { return interrupted_ || file_->at_end(); }
  bool interrupted() const { return interrupted_; }

 private:
  std::unique_ptr<FileSampleSource> file_;
  const std::atomic<bool>* stop_;
  bool interrupted_ = false;
};

/// The --format flag's sample format; the message names the flag and the accepted names.
SampleFormat format_flag(const std::string& text) {
  try {
    return parse_sample_format(text);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--format: ") + e.what());
  }
}

nlohmann::json stats_json(const StreamSampleSource& s) {
  const StreamStats st = s.stats();
  nlohmann::json lost = nlohmann::json::array(), gaps = nlohmann::json::array();
  for (const auto& [a, b] : st.lost_frame_ranges) lost.push_back({a, b});
  for (const auto& g : st.gaps)
    gaps.push_back({{"first_missing_sample", g.first_missing_index}, {"missing_samples", g.missing_count}});
  nlohmann::json out = {{"url", s.url()},
                        {"format", std::string(to_string(s.header().format))},
                        {"start_sample", s.header().start_sample_index},
                        {"bytes_received", st.bytes_received},
                        {"frames_received", st.frames_received},
                        {"frames_lost", st.frames_lost},
                        {"lost_frame_ranges", lost},
                        {"frames_duplicated", st.frames_duplicated},
                        {"frames_reordered", st.frames_reordered},
                        {"frames_late", st.frames_late},
                        {"frames_overrun", st.frames_overrun},
                        {"reconnects", st.reconnects},
                        {"partial_frame_bytes_discarded", st.partial_frame_bytes_discarded},
                        {"samples_duplicated", st.samples_duplicated},
                        {"lost_samples", s.lost_sample_count()},
                        {"gaps", gaps},
                        {"end", st.end_reason},
                        {"failed", st.failed}};
  if (dynamic_cast<const UdpSampleSource*>(&s) != nullptr && s.raw())
    out["datagrams_split_samples"] = st.datagrams_split_samples;
  if (const auto* rtl = dynamic_cast<const RtlTcpSampleSource*>(&s)) {
    out["pace_of_real_time"] = st.pace_of_real_time ? nlohmann::json(*st.pace_of_real_time) : nlohmann::json(nullptr);
    out["slower_than_real_time"] = st.slower_than_real_time;
    const rtltcp::Tuning& t = rtl->rtl_settings().tuning;
    out["dongle"] = {{"tuner", rtltcp::tuner_name(rtl->dongle().tuner_type)},
                     {"tuner_type", rtl->dongle().tuner_type},
                     {"gain_steps", rtl->dongle().gain_count},
                     {"center_frequency_hz", t.center_frequency_hz},
                     {"sample_rate_hz", t.sample_rate_hz},
                     {"gain_db", t.gain_db ? nlohmann::json(*t.gain_db) : nlohmann::json("auto")},
                     {"rtl_agc", t.rtl_agc},
                     {"ppm", t.ppm},
                     {"bias_tee", t.bias_tee}};
  }
  return out;
}

/// An rtl_tcp dongle: cu8 at --fs (default 2.048 Msps), tuned so that L1 lands at --if.
std::unique_ptr<StreamSampleSource> open_rtltcp(const SourceRequest& r, const SourceUrl& url) {
  if (r.raw) throw InputError("--raw does not apply to rtltcp:// (the stream is always bare cu8)");
  if (r.format_given && r.format != "cu8")
    throw InputError(fmt::format("--format {}: an rtl_tcp server sends cu8 (leave --format out)", r.format));
  if (r.inverted)
    throw InputError("--inverted-spectrum does not apply to rtltcp:// (an RTL-SDR's spectrum is upright)");
  StreamSourceSettings st;
  st.host = url.host;
  st.port = url.port;
  st.stop = r.stop;
  st.raw_if_hz = r.if_hz;
  RtlTcpSettings rtl;
  const double fs = r.fs_given || r.fs_hz > 0.0 ? r.fs_hz : 2048000.0;
  if (!(fs > 0.0) || fs != std::floor(fs) || fs > 4.0e9)
    throw InputError(fmt::format("--fs {}: not a sample rate in Hz", fs));
  rtl.tuning.sample_rate_hz = static_cast<std::uint32_t>(fs);
  rtl.tuning.center_frequency_hz = gps::kL1_Hz - r.if_hz;
  if (r.rtl_gain != "auto") {
    char* end = nullptr;
    const double g = std::strtod(r.rtl_gain.c_str(), &end);
    if (r.rtl_gain.empty() || *end != '\0')
      throw InputError(fmt::format("--rtl-gain '{}': expected a gain in dB or 'auto' (the tuner's AGC)", r.rtl_gain));
    rtl.tuning.gain_db = g;
  }
  rtl.tuning.rtl_agc = r.rtl_agc;
  rtl.tuning.ppm = r.rtl_ppm;
  rtl.tuning.bias_tee = r.rtl_bias_tee;
  try {
    return std::make_unique<RtlTcpSampleSource>(st, rtl);
  } catch (const std::exception& e) {
    throw InputError(e.what());
  }
}

OpenedSource open_stream(const SourceRequest& r, const SourceUrl& url) {
  use_thread_safe_logger();
  StreamSourceSettings st;
  st.host = url.host;
  st.port = url.port;
  st.listen = url.listen;
  st.raw = r.raw;
  st.inverted_spectrum = r.inverted;
  st.reconnect_timeout_s = r.reconnect_timeout_s;
  st.stop = r.stop;
  if (r.skip_s != 0.0) throw InputError("--skip applies to files only, not to streams");
  std::unique_ptr<StreamSampleSource> source;
  if (url.scheme == StreamScheme::rtltcp) {
    source = open_rtltcp(r, url);
  } else if (r.raw) {
    st.raw_format = format_flag(r.format);
    if (!stream::streamable(st.raw_format))
      throw InputError(
          fmt::format("--format {}: streams carry ibyte, ishort, gr_complex, byte or cu8 (packed formats "
                      "are read from files)",
                      to_string(st.raw_format)));
    if (!(r.fs_hz > 0.0)) throw InputError(fmt::format("--input '{}': a raw stream needs --fs", r.input));
    st.raw_sample_rate_hz = r.fs_hz;
    st.raw_if_hz = r.if_hz;
  }
  try {
    if (source) {
      // rtltcp:// opened above
    } else if (url.scheme == StreamScheme::tcp) {
      source = std::make_unique<TcpSampleSource>(st);
    } else {
      auto udp = std::make_unique<UdpSampleSource>(st);
      if (url.listen) spdlog::info("listening on udp://{}:{}", url.host, udp->local_port());
      source = std::move(udp);
    }
  } catch (const std::exception& e) {
    throw InputError(e.what());
  }
  if (!r.raw && url.scheme != StreamScheme::rtltcp && r.fs_hz > 0.0 && r.fs_hz != source->sample_rate_hz())
    throw InputError(fmt::format("--fs {} Hz disagrees with the sample rate {} Hz of the stream {}", r.fs_hz,
                                 source->sample_rate_hz(), source->url()));
  const std::string url_text = source->url();
  source->set_gap_handler([url_text, fs = source->sample_rate_hz(),
                           exact = source->gap_sizes_exact()](const SampleGap& g) {
    spdlog::warn("{}: {} samples {}lost at sample {} (t = {:.6f} s): {}", url_text, g.missing_count,
                 exact ? "" : "(estimated) ", g.first_missing_index, static_cast<double>(g.first_missing_index) / fs,
                 exact ? "channels coast across the gap" : "every satellite is acquired again after it");
  });
  spdlog::info("{}: {} at {} Hz, IF {} Hz, from sample {}", url_text, to_string(source->header().format),
               source->sample_rate_hz(), source->intermediate_frequency_hz(), source->header().start_sample_index);
  OpenedSource o;
  o.input = r.input;
  o.is_stream = true;
  o.settings.format = source->header().format;
  o.settings.sample_rate_hz = source->sample_rate_hz();
  o.settings.if_hz = source->intermediate_frequency_hz();
  o.settings.inverted_spectrum = r.inverted;
  if (!r.raw && url.scheme != StreamScheme::rtltcp) {
    for (const SourceSetting s :
         {SourceSetting::format, SourceSetting::sample_rate, SourceSetting::intermediate_frequency})
      o.settings.origins[s] = SettingOrigin::stream_header;
  }
  StreamSampleSource* s = source.get();
  o.report = [s] { return stats_json(*s); };
  o.failure = [s]() -> std::optional<std::string> {
    const StreamStats st = s->stats();
    if (!st.failed) return std::nullopt;
    return fmt::format("{}: {}", s->url(), st.end_reason);
  };
  o.interrupted = [s] { return s->interrupted(); };
  o.source = std::move(source);
  return o;
}

}  // namespace

FileSampleSourceOptions file_source_options(const SourceRequest& r) { return file_source_options(r, nullptr); }

FileSampleSourceOptions file_source_options(const SourceRequest& r, SourceSettings* settings) {
  SourceSettings where;
  FileSampleSourceOptions so;
  so.skip_s = r.skip_s;
  std::optional<IfMetadata> meta;
  if (!r.metadata.empty()) {
    try {
      meta = read_if_metadata(r.metadata);
    } catch (const std::exception& e) {
      throw InputError(e.what());
    }
    so.path = r.input.empty() ? meta->data_path : std::filesystem::path(r.input);
    if (so.path.empty())
      throw InputError(fmt::format("--metadata '{}' names no <file>: give the samples with --input", r.metadata));
    if (!r.fs_given && !(meta->sample_rate_hz >= r.min_fs_hz && meta->sample_rate_hz <= r.max_fs_hz))
      throw InputError(
          fmt::format("metadata file '{}': <{}>: sample rate {} Hz is outside the {} to {} Hz this "
                      "command takes",
                      r.metadata, meta->sample_rate_element, meta->sample_rate_hz, r.min_fs_hz, r.max_fs_hz));
    so.format = meta->format;
    so.sample_rate_hz = meta->sample_rate_hz;
    so.intermediate_frequency_hz = meta->if_hz;
    so.inverted_spectrum = meta->inverted_spectrum;
    so.header_bytes = meta->header_bytes;
    so.footer_bytes = meta->footer_bytes;
    so.length_bytes = meta->length_bytes;
    where.metadata = r.metadata;
    if (meta->start_time) {
      where.start_time_utc = meta->start_time->utc;
      where.start_time_origin = fmt::format("{}'s <{}>", r.metadata, meta->start_time->element);
    }
    spdlog::info("{}: {} at {} Hz, IF {} Hz{}, from '{}'", r.metadata, to_string(so.format), so.sample_rate_hz,
                 so.intermediate_frequency_hz, so.inverted_spectrum ? ", inverted spectrum" : "", so.path.string());
  } else {
    if (r.input.empty()) throw InputError("give the samples: --input FILE (or --metadata FILE.xml)");
    so.path = r.input;
  }
  // Whether the flag sets the value (given, or no metadata to take it from); a flag given
  // over a different metadata value is warned about and remembered for later messages.
  auto overrides = [&](SourceSetting setting, bool given, const std::string& value, const std::string& from_meta) {
    if (given && meta && value != from_meta) {
      spdlog::warn("{} {} overrides the metadata's {} ({})", SourceSettings::flag(setting), value, from_meta,
                   r.metadata);
      where.overridden[setting] = from_meta;
    }
    if (meta && !given) where.origins[setting] = SettingOrigin::metadata;
    return given || !meta;
  };
  if (overrides(SourceSetting::format, r.format_given, r.format, meta ? to_string(meta->format) : "")) {
    so.format = format_flag(r.format);
  }
  if (overrides(SourceSetting::sample_rate, r.fs_given, fmt::format("{}", r.fs_hz),
                meta ? fmt::format("{}", meta->sample_rate_hz) : ""))
    so.sample_rate_hz = r.fs_hz;
  if (overrides(SourceSetting::intermediate_frequency, r.if_given, fmt::format("{}", r.if_hz),
                meta ? fmt::format("{}", meta->if_hz) : ""))
    so.intermediate_frequency_hz = r.if_hz;
  if (overrides(SourceSetting::spectrum_sense, r.inverted_given, r.inverted ? "true" : "false",
                meta ? (meta->inverted_spectrum ? "true" : "false") : ""))
    so.inverted_spectrum = r.inverted;
  if (const auto missing = missing_file_reason(so.path.string()))
    throw InputError(meta && r.input.empty() ? fmt::format("--metadata '{}': its sample file '{}' {}", r.metadata,
                                                           so.path.string(), *missing)
                                             : fmt::format("--input: file '{}' {}", so.path.string(), *missing));
  if (!(so.sample_rate_hz > 0.0))
    throw InputError(fmt::format("--input '{}': a file needs its sample rate (--fs, or --metadata)", so.path.string()));
  if (settings) {
    where.format = so.format;
    where.sample_rate_hz = so.sample_rate_hz;
    where.if_hz = so.intermediate_frequency_hz;
    where.inverted_spectrum = so.inverted_spectrum;
    *settings = std::move(where);
  }
  return so;
}

OpenedSource open_sample_source(const SourceRequest& r) {
  if (const auto url = parse_source_url(r.input)) {
    if (!r.metadata.empty()) throw InputError("--metadata describes files; a stream says its own format");
    return open_stream(r, *url);
  }
  if (r.raw) throw InputError("--raw applies to tcp:// and udp:// inputs only");
  OpenedSource o;
  const FileSampleSourceOptions so = file_source_options(r, &o.settings);
  std::unique_ptr<FileSampleSource> file;
  try {
    file = std::make_unique<FileSampleSource>(so);
  } catch (const std::exception& e) {
    throw InputError(e.what());
  }
  for (const auto& w : file->warnings()) spdlog::warn("{}", w);
  o.input = so.path.string();
  o.duration_s = static_cast<double>(file->total_samples()) / so.sample_rate_hz;
  auto stoppable = std::make_unique<StoppableFileSource>(std::move(file), r.stop);
  StoppableFileSource* s = stoppable.get();
  o.interrupted = [s] { return s->interrupted(); };
  o.failure = [] { return std::optional<std::string>(); };
  o.report = [] { return nlohmann::json(nullptr); };
  o.source = std::move(stoppable);
  return o;
}

}  // namespace deepnav
