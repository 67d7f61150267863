#pragma once
// ION GNSS SDR Metadata Standard files: an XML description beside the samples (its <file>
// names them) of how they are laid out and what they hold. read_if_metadata() turns one
// into what the receiver needs (sample format, rate, IF, spectrum inversion, where the
// samples start); if_metadata_xml() writes the description of a file the synthesizer made.
//
// Supported: one <lane> with one <block> (any header and footer, cycles or to the end of the
// file) of one <chunk> of 1, 2, 4 or 8-byte words (either endian, either word shift, head or
// tail padding) holding one <lump> of one <stream>, repeated to fill the chunk; the stream
// (any rate factor, alignment and shift) must come out as one of the sample formats of
// signals/sample_format.hpp: IQ/IF formats of 8-bit TC/INT8 (ibyte, byte), 8-bit OB (cu8),
// 16-bit TC (ishort), 32-bit FP (gr_complex) values or 1/2/4-bit TC/SM/OB (and their
// "adjusted" A forms, SIGN for 1 bit) codes. Elements may be given in place or referenced
// by id (<system id="x"/>, <band id="L1"/>). Anything else is refused with an error naming
// the element: a number beyond what the reader computes with (a 64-bit byte count, a
// 64-byte chunk), and a file that is no such description (over 1 MiB, nested over 64 deep,
// UTF-16 or UTF-32 rather than UTF-8) before its XML is parsed.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "ins/gps_time.hpp"
#include "signals/sample_format.hpp"

namespace deepnav {

/// A metadata file that cannot be used: the message names the file and the element.
class MetadataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// When the recording's first sample was taken, as a metadata file dates it. The standard's
/// dates are UTC (its reference reader converts them with gmtime), with or without the "Z".
struct MetadataStartTime {
  CalendarTime utc;
  std::string element;  ///< where it was read, for messages: "file/timestamp" or "session[capture]/toa"
};

struct IfMetadata {
  std::filesystem::path metadata_path;
  /// The <file>'s <url>, taken from the metadata file's folder when relative; empty when
  /// the metadata names no file.
  std::filesystem::path data_path;
  SampleFormat format;
  double sample_rate_hz = 0.0;
  /// Where L1 (1575.42 MHz) sits in the samples the receiver sees (after inversion is undone).
  double if_hz = 0.0;
  /// The samples are to be read as I - jQ (the format's negated Q and the band's <inverted> combined).
  bool inverted_spectrum = false;
  double center_frequency_hz = 0.0;  ///< the band's <centerfreq>
  std::uint64_t header_bytes = 0;    ///< the block's <sizeheader>: skipped at the start of the file
  std::uint64_t footer_bytes = 0;    ///< the block's <sizefooter>: left out at the end
  /// <cycles> x chunk bytes when the block gives its cycles (0: to the end of the file).
  std::optional<std::uint64_t> length_bytes;
  std::string stream_id;  ///< the stream's id, for messages
  /// The <freqbase> the sample rate is built on (metadata/system[fe]/freqbase; times the
  /// stream's <ratefactor>), for messages about the rate.
  std::string sample_rate_element;
  /// The <file>'s <timestamp>, else the one <session>'s <toa> (time of acquisition; with
  /// several sessions none is taken); absent when the file gives neither.
  std::optional<MetadataStartTime> start_time;
};

/// Reads and checks the file; throws MetadataError naming the file and element.
IfMetadata read_if_metadata(const std::filesystem::path& xml_path);

struct IfMetadataDescription {
  std::string data_file_name;  ///< the <url>: the IF file's name, beside the XML
  SampleFormat format;
  double sample_rate_hz = 0.0;
  double if_hz = 0.0;
  std::string comment;  ///< free text (scenario name, ADC bits, start time)
};

/// The XML of a metadata file describing an IF file of the synthesizer (centre 1575.42 MHz
/// at `if_hz`, spectrum not inverted). read_if_metadata() of it gives the format back.
std::string if_metadata_xml(const IfMetadataDescription& d);

/// The metadata file name beside an IF file: the same name with .xml instead of its extension.
std::filesystem::path metadata_path_for(const std::filesystem::path& if_path);

}  // namespace deepnav
