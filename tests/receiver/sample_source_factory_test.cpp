// The sample-source factory: a file's options from flags, from a real metadata file (data/)
// and from both (the flags given win), the combinations it refuses before opening anything,
// and sources opened end to end: a real capture read as a file, and the same capture served
// as a framed tcp:// stream.
#include "receiver/sources/sample_source_factory.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>
#include <vector>

#include "ins/input_error.hpp"
#include "receiver/stream/stream_server.hpp"
#include "signals/if_file_stream.hpp"

namespace deepnav {
namespace {

const std::filesystem::path kData = std::filesystem::path(DEEPNAV_SOURCE_DIR) / "data";
/// PocketSDR capture: ibyte, 4 Msps, IF 0, inverted spectrum, 500 ms (data/README.md).
const std::filesystem::path kIqCapture = kData / "L1_20211202_084700_4MHz_IQ.bin";
const std::filesystem::path kIqMetadata = kData / "L1_20211202_084700_4MHz_IQ.xml";
/// PocketSDR capture: real int8 (byte), 12 Msps, L1 at +3 MHz.
const std::filesystem::path kRealMetadata = kData / "L1_20211125_004000_12MHz_I.xml";

/// The message of the InputError `f` throws (empty when it throws none).
template <typename F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

std::string open_error(const SourceRequest& r) {
  return input_error([&] { open_sample_source(r); });
}

std::string options_error(const SourceRequest& r) {
  return input_error([&] { file_source_options(r); });
}

SourceRequest metadata_request(const std::filesystem::path& xml) {
  SourceRequest r;
  r.metadata = xml.string();
  return r;
}

/// A copy of the 4 MHz capture's metadata in a fresh folder, with its <file> element's
/// lines replaced by `file_element` (the samples it names are not copied).
std::filesystem::path edited_metadata(const std::string& name, const std::string& file_element) {
  std::ifstream in(kIqMetadata);
  std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto from = xml.find("  <file>");
  const auto to = xml.find("</file>") + std::string("</file>\n").size();
  EXPECT_NE(from, std::string::npos);
  xml.replace(from, to - from, file_element);
  const auto dir = std::filesystem::temp_directory_path() / "deepnav_sample_source_factory";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << xml;
  return path;
}

TEST(FileSourceOptions, FlagsAloneDescribeTheFile) {
  SourceRequest r;
  r.input = (kData / "GPS_L1_CA_ID_1_Fs_4Msps_2ms.dat").string();
  r.format = "gr_complex";
  r.fs_hz = 4.0e6;
  r.if_hz = 1250.0;
  r.skip_s = 0.001;
  r.inverted = true;
  const FileSampleSourceOptions o = file_source_options(r);
  EXPECT_EQ(o.path, r.input);
  EXPECT_EQ(o.format, SampleFormat::gr_complex);
  EXPECT_EQ(o.sample_rate_hz, 4.0e6);
  EXPECT_EQ(o.intermediate_frequency_hz, 1250.0);
  EXPECT_EQ(o.skip_s, 0.001);
  EXPECT_TRUE(o.inverted_spectrum);
  EXPECT_EQ(o.header_bytes, 0u);
  EXPECT_FALSE(o.length_bytes);
}

TEST(FileSourceOptions, MetadataAloneDescribesAndNamesTheFile) {
  const FileSampleSourceOptions iq = file_source_options(metadata_request(kIqMetadata));
  EXPECT_EQ(iq.path, kIqCapture);
  EXPECT_EQ(iq.format, SampleFormat::ibyte);
  EXPECT_EQ(iq.sample_rate_hz, 4.0e6);
  EXPECT_EQ(iq.intermediate_frequency_hz, 0.0);
  EXPECT_TRUE(iq.inverted_spectrum);  // the stream format IQn: Q negated

  const FileSampleSourceOptions real = file_source_options(metadata_request(kRealMetadata));
  EXPECT_EQ(real.path, kData / "L1_20211125_004000_12MHz_I.bin");
  EXPECT_EQ(real.format, SampleFormat::byte);
  EXPECT_EQ(real.sample_rate_hz, 12.0e6);
  EXPECT_EQ(real.intermediate_frequency_hz, 3.0e6);
  EXPECT_FALSE(real.inverted_spectrum);
}

TEST(FileSourceOptions, FlagsGivenOverrideTheMetadataAndOnlyThose) {
  SourceRequest r = metadata_request(kIqMetadata);
  // Values that were not given (their defaults) leave the metadata's in place.
  r.fs_hz = 0.0;
  r.format = "cu8";
  EXPECT_EQ(file_source_options(r).sample_rate_hz, 4.0e6);
  EXPECT_EQ(file_source_options(r).format, SampleFormat::ibyte);

  r.format_given = r.fs_given = r.if_given = r.inverted_given = true;
  r.fs_hz = 4.092e6;
  r.if_hz = -500.0;
  r.inverted = false;
  const FileSampleSourceOptions o = file_source_options(r);
  EXPECT_EQ(o.format, SampleFormat::cu8);
  EXPECT_EQ(o.sample_rate_hz, 4.092e6);
  EXPECT_EQ(o.intermediate_frequency_hz, -500.0);
  EXPECT_FALSE(o.inverted_spectrum);
  EXPECT_EQ(o.path, kIqCapture);  // still the metadata's file
}

TEST(FileSourceOptions, InputNamesTheSamplesOverTheMetadatasFile) {
  SourceRequest r = metadata_request(kIqMetadata);
  r.input = (kData / "GPS_L1_CA_ID_1_Fs_4Msps_2ms.dat").string();
  const FileSampleSourceOptions o = file_source_options(r);
  EXPECT_EQ(o.path, r.input);
  EXPECT_EQ(o.format, SampleFormat::ibyte);  // the layout still the metadata's
}

TEST(FileSourceOptions, MissingPiecesAreNamed) {
  EXPECT_EQ(options_error(SourceRequest{}), "give the samples: --input FILE (or --metadata FILE.xml)");

  SourceRequest no_rate;
  no_rate.input = kIqCapture.string();
  EXPECT_EQ(options_error(no_rate),
            "--input '" + kIqCapture.string() + "': a file needs its sample rate (--fs, or --metadata)");

  SourceRequest missing;
  missing.input = (kData / "no_such_capture.bin").string();
  missing.fs_hz = 4.0e6;
  EXPECT_EQ(options_error(missing), "--input: file '" + missing.input + "' does not exist");

  // A name past the system's limit cannot even be looked up: said so, not a filesystem_error.
  SourceRequest too_long = missing;
  too_long.input = std::string(5000, 'x');
  EXPECT_EQ(options_error(too_long).rfind("--input: file '" + too_long.input + "' cannot be looked up (", 0), 0u);

  SourceRequest bad_format = no_rate;
  bad_format.fs_hz = 4.0e6;
  bad_format.format = "int7";
  EXPECT_EQ(options_error(bad_format).rfind("--format: unknown sample format 'int7'", 0), 0u)
      << options_error(bad_format);
}

TEST(FileSourceOptions, MetadataProblemsAreNamed) {
  const auto no_file = edited_metadata("no_file.xml", "");
  EXPECT_EQ(options_error(metadata_request(no_file)),
            "--metadata '" + no_file.string() + "' names no <file>: give the samples with --input");

  const auto elsewhere = edited_metadata("elsewhere.xml", "  <file><url>gone.bin</url><lane id=\"L1\"/></file>\n");
  EXPECT_EQ(options_error(metadata_request(elsewhere)), "--metadata '" + elsewhere.string() + "': its sample file '" +
                                                            (elsewhere.parent_path() / "gone.bin").string() +
                                                            "' does not exist");

  // Not metadata at all: the reader's own message, naming the file, as an InputError.
  const std::string not_xml = options_error(metadata_request(kIqCapture));
  EXPECT_NE(not_xml.find(kIqCapture.string()), std::string::npos) << not_xml;
}

TEST(OpenSampleSource, RefusesFlagsTheInputCannotUse) {
  SourceRequest raw_file = metadata_request(kIqMetadata);
  raw_file.raw = true;
  EXPECT_EQ(open_error(raw_file), "--raw applies to tcp:// and udp:// inputs only");

  // Each is refused before any connection is tried (nothing listens on port 9).
  SourceRequest stream;
  stream.input = "tcp://127.0.0.1:9";
  SourceRequest skip = stream;
  skip.skip_s = 1.0;
  EXPECT_EQ(open_error(skip), "--skip applies to files only, not to streams");
  SourceRequest metadata = stream;
  metadata.metadata = kIqMetadata.string();
  EXPECT_EQ(open_error(metadata), "--metadata describes files; a stream says its own format");

  SourceRequest raw = stream;
  raw.raw = true;
  raw.format = "packed2";
  raw.fs_hz = 4.0e6;
  EXPECT_EQ(open_error(raw),
            "--format packed2: streams carry ibyte, ishort, gr_complex, byte or cu8 (packed formats are read from "
            "files)");
  raw.format = "ibyte";
  raw.fs_hz = 0.0;
  EXPECT_EQ(open_error(raw), "--input 'tcp://127.0.0.1:9': a raw stream needs --fs");
  raw.format = "int7";
  EXPECT_EQ(open_error(raw).rfind("--format: unknown sample format 'int7'", 0), 0u) << open_error(raw);
}

TEST(OpenSampleSource, RefusesRtlTcpFlagsThatDoNotApply) {
  SourceRequest rtl;
  rtl.input = "rtltcp://127.0.0.1:9";
  SourceRequest raw = rtl;
  raw.raw = true;
  EXPECT_EQ(open_error(raw), "--raw does not apply to rtltcp:// (the stream is always bare cu8)");
  SourceRequest format = rtl;
  format.format = "ibyte";
  format.format_given = true;
  EXPECT_EQ(open_error(format), "--format ibyte: an rtl_tcp server sends cu8 (leave --format out)");
  SourceRequest inverted = rtl;
  inverted.inverted = true;
  EXPECT_EQ(open_error(inverted), "--inverted-spectrum does not apply to rtltcp:// (an RTL-SDR's spectrum is upright)");
  SourceRequest fractional_rate = rtl;
  fractional_rate.fs_hz = 2048000.5;
  fractional_rate.fs_given = true;
  EXPECT_EQ(open_error(fractional_rate), "--fs 2048000.5: not a sample rate in Hz");
  SourceRequest gain = rtl;
  gain.rtl_gain = "loud";
  EXPECT_EQ(open_error(gain), "--rtl-gain 'loud': expected a gain in dB or 'auto' (the tuner's AGC)");
  gain.rtl_gain = "";
  EXPECT_EQ(open_error(gain), "--rtl-gain '': expected a gain in dB or 'auto' (the tuner's AGC)");
}

TEST(OpenSampleSource, MalformedStreamAddressesAreInputErrors) {
  SourceRequest r;
  r.input = "udp://:5000";
  EXPECT_EQ(open_error(r), "--input 'udp://:5000': the host is missing");
}

/// The first `count` bytes of the 4 MHz capture as I/Q pairs.
std::vector<std::int8_t> capture_bytes(std::size_t count) {
  std::vector<std::int8_t> bytes(count);
  std::ifstream in(kIqCapture, std::ios::binary);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(count));
  return bytes;
}

TEST(OpenSampleSource, ReadsARealCaptureThroughItsMetadata) {
  std::atomic<bool> stop{false};
  SourceRequest r = metadata_request(kIqMetadata);
  r.skip_s = 0.001;  // 4000 samples
  r.stop = &stop;
  OpenedSource opened = open_sample_source(r);
  EXPECT_FALSE(opened.is_stream);
  EXPECT_EQ(opened.input, kIqCapture.string());
  ASSERT_TRUE(opened.duration_s);
  EXPECT_DOUBLE_EQ(*opened.duration_s, 0.5);
  EXPECT_TRUE(opened.report().is_null());
  EXPECT_FALSE(opened.failure());
  SampleSource& source = *opened.source;
  EXPECT_EQ(source.sample_rate_hz(), 4.0e6);
  EXPECT_FALSE(source.is_real());
  EXPECT_EQ(source.next_sample_index(), 4000);

  std::vector<Sample> samples(100);
  ASSERT_EQ(source.read(samples), samples.size());
  const std::vector<std::int8_t> bytes = capture_bytes(2 * (4000 + samples.size()));
  for (std::size_t k = 0; k < samples.size(); ++k) {
    // The metadata says the spectrum is inverted: Q comes negated.
    ASSERT_EQ(samples[k], Sample(bytes[2 * (4000 + k)], -bytes[2 * (4000 + k) + 1])) << k;
  }

  stop = true;  // Ctrl-C: the file ends early and says it was interrupted
  EXPECT_EQ(source.read(samples), 0u);
  EXPECT_TRUE(source.at_end());
  EXPECT_TRUE(opened.interrupted());
}

/// A `deepnav serve` of the 4 MHz capture (framed, as fast as read) on a free loopback port,
/// for one session.
struct CaptureServer {
  std::unique_ptr<StreamServer> server;
  std::atomic<bool> stop{false};
  std::thread thread;

  CaptureServer() {
    IfFileStreamOptions file;
    file.path = kIqCapture;
    file.format = SampleFormat::ibyte;
    file.sample_rate_hz = 4.0e6;
    StreamServerOptions o;
    o.tcp_port = 0;
    o.pace = 0.0;
    o.open_stream = [file] { return std::make_unique<IfFileStream>(file); };
    server = std::make_unique<StreamServer>(o);
    thread = std::thread([this] { server->run(stop, 1); });
  }
  ~CaptureServer() {
    stop = true;
    thread.join();
  }
  std::string url() const { return "tcp://127.0.0.1:" + std::to_string(server->tcp_port()); }
};

TEST(OpenSampleSource, ReadsAFramedTcpStream) {
  CaptureServer served;
  SourceRequest r;
  r.input = served.url();
  r.fs_hz = 4.0e6;  // agrees with the stream's header
  r.reconnect_timeout_s = 0.0;
  OpenedSource opened = open_sample_source(r);
  EXPECT_TRUE(opened.is_stream);
  EXPECT_EQ(opened.input, r.input);
  EXPECT_FALSE(opened.duration_s);
  EXPECT_EQ(opened.source->sample_rate_hz(), 4.0e6);

  std::vector<Sample> samples(2000);
  std::size_t got = 0;
  while (got < samples.size()) {
    const std::size_t n = opened.source->read(std::span<Sample>(samples).subspan(got));
    ASSERT_GT(n, 0u);
    got += n;
  }
  const std::vector<std::int8_t> bytes = capture_bytes(2 * samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k)
    ASSERT_EQ(samples[k], Sample(bytes[2 * k], bytes[2 * k + 1])) << k;  // served as recorded: not inverted
  const nlohmann::json report = opened.report();
  EXPECT_EQ(report.at("url"), r.input);
  EXPECT_EQ(report.at("format"), "ibyte");
  EXPECT_GT(report.at("bytes_received").get<std::int64_t>(), 0);
  EXPECT_FALSE(opened.failure());
}

TEST(OpenSampleSource, RefusesAStreamWhoseRateDisagreesWithFs) {
  CaptureServer served;
  SourceRequest r;
  r.input = served.url();
  r.fs_hz = 8.0e6;
  r.reconnect_timeout_s = 0.0;
  EXPECT_EQ(open_error(r), "--fs 8000000 Hz disagrees with the sample rate 4000000 Hz of the stream " + r.input);
}

}  // namespace
}  // namespace deepnav
