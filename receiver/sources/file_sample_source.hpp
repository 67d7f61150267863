#pragma once
// Samples from a recorded IF file in any of the sample formats (signals/sample_format.hpp),
// read in bounded pieces so memory stays small whatever the file length. The bytes come from the
// one IF file reader (signals/if_file_stream: opening, size, partial samples, seeking);
// this adds the skip, the spectrum inversion and the conversion to samples.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "receiver/sources/sample_converter.hpp"
#include "receiver/sources/sample_source.hpp"
#include "signals/if_file_stream.hpp"
#include "signals/sample_format.hpp"

namespace deepnav {

struct FileSampleSourceOptions {
  std::filesystem::path path;
  SampleFormat format = SampleFormat::ibyte;
  double sample_rate_hz = 0.0;
  double intermediate_frequency_hz = 0.0;
  /// Seconds skipped at the start of the file; the first delivered sample keeps
  /// its absolute index round(skip_s * fs), so time still counts from the file start.
  double skip_s = 0.0;
  /// Deliver I - jQ instead of I + jQ (front ends that mix with the high-side LO).
  bool inverted_spectrum = false;
  /// Bytes before the first sample and after the last, and at most this many bytes of
  /// samples (a metadata file's block header, footer and cycles).
  std::uint64_t header_bytes = 0;
  std::uint64_t footer_bytes = 0;
  std::optional<std::uint64_t> length_bytes;
};

class FileSampleSource final : public SampleSource {
 public:
  /// Opens the file and checks it; throws std::runtime_error naming the file for
  /// an unreadable path, an empty file, or a skip past the end, and
  /// std::invalid_argument for an impossible sample rate or skip.
  explicit FileSampleSource(FileSampleSourceOptions options);

  double sample_rate_hz() const override { return options_.sample_rate_hz; }
  double intermediate_frequency_hz() const override { return options_.intermediate_frequency_hz; }
  bool is_real() const override { return !is_complex(options_.format); }
  std::size_t read(std::span<Sample> out) override;
  std::int64_t next_sample_index() const override {
    return file_.next_sample_index() - static_cast<std::int64_t>(pending_.size() - pending_at_);
  }
  bool at_end() const override { return at_end_; }

  /// Whole samples in the file (including skipped ones).
  std::int64_t total_samples() const { return *file_.total_samples(); }
  /// Factor applied to gr_complex values before rounding to int16 (1 for the integer formats).
  float float_scale() const { return converter_.float_scale(); }
  /// Problems that do not stop reading (a trailing partial sample), one sentence each.
  const std::vector<std::string>& warnings() const { return file_.warnings(); }

 private:
  void choose_float_scale();
  /// Reads the next word of a packed file into pending_.
  void fill_pending();
  /// Samples from the file into `out` (whole words; a word into pending_ when `out` is
  /// shorter than one); 0 at its end.
  std::size_t read_file(std::span<Sample> out);
  void convert(std::span<Sample> out, std::int64_t first_index) const;

  FileSampleSourceOptions options_;
  IfFileStream file_;
  bool at_end_ = false;
  SampleConverter converter_;
  std::vector<std::byte> raw_;
  std::vector<Sample> pending_;  ///< converted samples of a packed word not delivered yet
  std::size_t pending_at_ = 0;
};

}  // namespace deepnav
