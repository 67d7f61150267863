#include "signals/if_metadata.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <string_view>
#include <vector>

#include "ins/input_file.hpp"
#include "ins/iso_date_time.hpp"
#include "signals/gps_constants.hpp"
#include "signals/sample_packing.hpp"
#include "signals/xml_nesting.hpp"

namespace deepnav {
namespace {

namespace pt = boost::property_tree;
using namespace std::string_view_literals;

/// Bounds of what is read as a metadata file: the standard's descriptions are a few
/// kilobytes nested about 8 deep; these bounds leave room for comments and extensions while
/// keeping the tree parser's memory and recursion small.
constexpr std::uintmax_t kMaxMetadataBytes = std::uintmax_t{1} << 20;
constexpr int kMaxMetadataDepth = 64;

/// The largest chunk the reader lays out (bytes, bits).
constexpr std::uint64_t kMaxChunkBytes = 64;
constexpr std::uint64_t kMaxChunkBits = 8 * kMaxChunkBytes;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

/// One element of the document with the path that names it in messages
/// (lane[GPS]/block/chunk/lump/stream[L1]).
struct Element {
  const pt::ptree* tree = nullptr;
  std::string name;  ///< the element's tag
  std::string path;

  std::optional<std::string> attribute(const std::string& key) const {
    if (const auto attrs = tree->get_child_optional("<xmlattr>"))
      for (const auto& [k, v] : *attrs)
        if (lower(k) == lower(key)) return trimmed(v.data());
    return std::nullopt;
  }
  std::string id() const { return attribute("id").value_or(""); }
  std::string text() const { return trimmed(tree->data()); }
  /// Child elements of a tag (case-insensitive: the standard's schema spells sizeWord, its
  /// examples sizeword).
  std::vector<Element> children(const std::string& tag) const {
    std::vector<Element> out;
    for (const auto& [k, v] : *tree) {
      if (k == "<xmlattr>" || k == "<xmlcomment>" || lower(k) != lower(tag)) continue;
      Element e{&v, k, path + "/" + k};
      if (const auto i = e.attribute("id")) e.path += "[" + *i + "]";
      out.push_back(e);
    }
    return out;
  }
  /// True when the element holds nothing but an id (a reference to a top-level element).
  bool is_reference() const {
    for (const auto& [k, v] : *tree)
      if (k != "<xmlattr>" && k != "<xmlcomment>" && lower(k) != "comment" && lower(k) != "artifact") return false;
    return text().empty() && attribute("id").has_value();
  }
};

/// The metadata file's text, once it is known to be one the tree parser can take: of a
/// sensible size, UTF-8 (no UTF-16 or UTF-32, no NUL byte) and not nested absurdly deep.
std::string metadata_text(const std::filesystem::path& path) {
  const std::string name = path.string();
  try {
    check_input_file(name, "metadata file", kMaxMetadataBytes);
  } catch (const std::runtime_error& e) {
    throw MetadataError(e.what());
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MetadataError(fmt::format("cannot open metadata file '{}'", name));
  const std::string text(std::istreambuf_iterator<char>(in), {});
  const std::string_view start(text.data(), std::min<std::size_t>(text.size(), 4));
  const char* wide = start.starts_with("\xFF\xFE\0\0"sv) || start.starts_with("\0\0\xFE\xFF"sv) ? "UTF-32"
                     : start.starts_with("\xFF\xFE"sv) || start.starts_with("\xFE\xFF"sv) ||
                             start.starts_with("<\0"sv) || start.starts_with("\0<"sv)
                         ? "UTF-16"
                         : nullptr;
  if (wide != nullptr)
    throw MetadataError(fmt::format(
        "metadata file '{}' is encoded in {}: metadata files are read as UTF-8 (convert it, e.g. iconv -f {} -t UTF-8)",
        name, wide, wide));
  if (const auto nul = text.find('\0'); nul != std::string::npos)
    throw MetadataError(
        fmt::format("metadata file '{}':{}: a NUL byte: not a text file", name,
                    1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(nul), '\n')));
  if (const auto line = line_nested_deeper_than(text, kMaxMetadataDepth))
    throw MetadataError(fmt::format(
        "metadata file '{}':{}: elements nested more than {} deep: not a metadata description (the standard's "
        "descriptions nest about 8 deep)",
        name, *line, kMaxMetadataDepth));
  return text;
}

class Reader {
 public:
  explicit Reader(std::filesystem::path path) : path_(std::move(path)) {
    try {
      std::istringstream text(metadata_text(path_));
      pt::read_xml(text, doc_, pt::xml_parser::trim_whitespace | pt::xml_parser::no_comments);
    } catch (const pt::xml_parser_error& e) {
      if (e.line() == 0) throw MetadataError(fmt::format("metadata file '{}': {}", path_.string(), e.message()));
      throw MetadataError(
          fmt::format("metadata file '{}':{}: not well-formed XML: {}", path_.string(), e.line(), e.message()));
    }
    for (const auto& [k, v] : doc_) {
      if (k == "<xmlcomment>") continue;
      if (lower(k) != "metadata")
        fail(k, fmt::format("the root element is <{}>, expected <metadata> (ION GNSS SDR Metadata Standard)", k));
      root_ = Element{&v, k, k};
    }
    if (root_.tree == nullptr) fail("metadata", "no <metadata> root element");
  }

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw MetadataError(fmt::format("metadata file '{}': <{}>: {}", path_.string(), where, what));
  }
  [[noreturn]] void fail(const Element& e, const std::string& what) const { fail(e.path, what); }

  const Element& root() const { return root_; }

  /// A referenced element (<band id="L1"/>) replaced by the top-level one it names.
  Element resolve(const Element& e) const {
    if (!e.is_reference()) return e;
    for (const Element& top : root_.children(e.name))
      if (top.id() == e.id()) return top;  // a top-level element is a definition, even an empty one
    fail(e, fmt::format("refers to <{} id=\"{}\">, which the file does not define", e.name, e.id()));
  }

  /// The one child of a tag (resolved); missing or repeated: an error naming both.
  Element one(const Element& parent, const std::string& tag, const std::string& why_one = "") const {
    const auto c = parent.children(tag);
    if (c.empty()) fail(parent, fmt::format("has no <{}>", tag));
    if (c.size() > 1)
      fail(c[1], fmt::format("{} <{}> elements in <{}>: {}", c.size(), tag, parent.name,
                             why_one.empty() ? "one is supported" : why_one));
    return resolve(c.front());
  }
  std::optional<Element> optional_one(const Element& parent, const std::string& tag) const {
    const auto c = parent.children(tag);
    if (c.empty()) return std::nullopt;
    if (c.size() > 1) fail(c[1], fmt::format("{} <{}> elements in <{}>: one is expected", c.size(), tag, parent.name));
    return resolve(c.front());
  }

  /// A whole number, at most `max`: what the reader narrows or multiplies it into holds it.
  std::uint64_t unsigned_value(const Element& e, std::uint64_t max, const std::string& why_max) const {
    const std::string t = e.text();
    std::uint64_t v = 0;
    const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (error == std::errc::result_out_of_range || (error == std::errc() && end == t.data() + t.size() && v > max))
      fail(e, fmt::format("{} is too large: at most {} ({})", t, max, why_max));
    if (t.empty() || error != std::errc() || end != t.data() + t.size())
      fail(e, fmt::format("'{}' is not a whole number", t));
    return v;
  }
  std::uint64_t unsigned_child(const Element& parent, const std::string& tag, std::optional<std::uint64_t> fallback,
                               std::uint64_t max, const std::string& why_max) const {
    const auto c = optional_one(parent, tag);
    if (!c) {
      if (fallback) return *fallback;
      fail(parent, fmt::format("has no <{}>", tag));
    }
    return unsigned_value(*c, max, why_max);
  }
  std::string word_child(const Element& parent, const std::string& tag, const std::string& fallback,
                         const std::vector<std::string>& allowed) const {
    const auto c = optional_one(parent, tag);
    if (!c) return fallback;
    const std::string t = c->text();
    for (const auto& a : allowed)
      if (lower(a) == lower(t)) return a;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    fail(*c, fmt::format("'{}' is not one of {}", t, list));
  }
  /// A frequency in Hz from its text and unit attribute (format= in the standard's
  /// examples, units= in its schema; Hz when absent).
  double frequency_hz(const Element& e) const {
    const std::string t = e.text();
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0' || !std::isfinite(v)) fail(e, fmt::format("'{}' is not a number", t));
    const std::string unit = lower(e.attribute("format").value_or(e.attribute("units").value_or("Hz")));
    static const std::map<std::string, double> kHzPerUnit = {{"hz", 1.0}, {"khz", 1e3}, {"mhz", 1e6}, {"ghz", 1e9}};
    const auto scale = kHzPerUnit.find(unit);
    if (scale == kHzPerUnit.end())
      fail(e, fmt::format("frequency unit '{}' is not supported (Hz, kHz, MHz, GHz)", unit));
    if (!std::isfinite(v * scale->second)) fail(e, fmt::format("{} {} is not a finite frequency", t, unit));
    return v * scale->second;
  }

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  pt::ptree doc_;
  Element root_;
};

/// The recording's start: the file's <timestamp>, else the one session's <toa>. A date
/// that is given but unreadable is an error: it would otherwise date the run silently wrong.
std::optional<MetadataStartTime> start_time_of(const Reader& r, const std::optional<Element>& file) {
  std::optional<Element> date;
  if (file) date = r.optional_one(*file, "timestamp");
  if (!date) {
    const auto sessions = r.root().children("session");
    if (sessions.size() == 1) date = r.optional_one(r.resolve(sessions.front()), "toa");
  }
  if (!date) return std::nullopt;
  const std::optional<IsoDateTime> written = parse_iso_date_time(date->text(), true);
  if (!written || !is_valid_calendar(written->calendar) || written->calendar.year < 1980)
    r.fail(*date, fmt::format("'{}' is not a date and time after the GPS epoch: expected UTC like 2021-12-02T08:47:00Z",
                              date->text()));
  return MetadataStartTime{written->calendar, date->path};
}

/// Bit positions of one value: global bit index (byte * 8 + bit) of each of its bits, from
/// its least significant bit up.
using ValueBits = std::vector<int>;
struct SampleBits {
  ValueBits i, q;  ///< q empty for real samples
  friend bool operator==(const SampleBits&, const SampleBits&) = default;
};

/// Where each sample of a chunk of `chunk_bytes` sits in a format of ours.
std::optional<std::vector<SampleBits>> format_bits(const SampleFormat& f, std::size_t chunk_bytes) {
  const std::size_t bpw = bytes_per_word(f);
  if (chunk_bytes % bpw != 0) return std::nullopt;
  auto contiguous = [](std::size_t first_byte, int bits) {
    ValueBits v(static_cast<std::size_t>(bits));
    for (int j = 0; j < bits; ++j) v[static_cast<std::size_t>(j)] = static_cast<int>(first_byte) * 8 + j;
    return v;
  };
  std::vector<SampleBits> out;
  const std::size_t words = chunk_bytes / bpw;
  if (f.kind != SampleKind::packed) {
    const int value = f.kind == SampleKind::gr_complex ? 32 : f.kind == SampleKind::ishort ? 16 : 8;
    for (std::size_t s = 0; s < words; ++s) {
      SampleBits b;
      b.i = contiguous(s * bpw, value);
      if (is_complex(f)) b.q = contiguous(s * bpw + static_cast<std::size_t>(value / 8), value);
      out.push_back(b);
    }
    return out;
  }
  const PackedLayout& l = f.packed;
  const std::size_t vpw = values_per_word(l);
  auto value_bits = [&](std::size_t w, std::size_t k) {
    ValueBits v;
    const int shift = packed_value_shift(l, k);
    for (int j = 0; j < l.bits; ++j) {
      const int bit = shift + j;
      const int byte = l.big_endian ? l.word_bytes - 1 - bit / 8 : bit / 8;
      v.push_back((static_cast<int>(w) * l.word_bytes + byte) * 8 + bit % 8);
    }
    return v;
  };
  for (std::size_t w = 0; w < words; ++w) {
    if (!l.complex) {
      for (std::size_t k = 0; k < vpw; ++k) out.push_back({value_bits(w, k), {}});
    } else {
      for (std::size_t k = 0; k + 1 < vpw; k += 2) {
        const std::size_t at_i = l.q_first ? k + 1 : k, at_q = l.q_first ? k : k + 1;
        out.push_back({value_bits(w, at_i), value_bits(w, at_q)});
      }
    }
  }
  return out;
}

/// The formats of ours a stream's quantization and encoding could be.
std::vector<SampleFormat> candidates(int q, const std::string& encoding, bool complex) {
  const std::string enc = lower(encoding);
  const bool tc = enc == "tc" || enc == "tca" || enc == "int8" || (q == 1 && enc == "sign");
  const bool sm = enc == "sm" || enc == "sma";
  const bool ob = enc == "ob" || enc == "oba";
  std::vector<SampleFormat> out;
  if (q == 8 && tc) out.push_back(complex ? SampleFormat::ibyte : SampleFormat::byte);
  if (q == 8 && ob && complex) out.push_back(SampleFormat::cu8);
  if (q == 16 && tc && complex) out.push_back(SampleFormat::ishort);
  if (q == 32 && (enc == "fp" || enc == "float") && complex) out.push_back(SampleFormat::gr_complex);
  if ((q == 1 || q == 2 || q == 4) && (tc || sm || ob)) {
    PackedLayout l;
    l.bits = q;
    l.complex = complex;
    l.encoding = tc   ? PackedEncoding::twos_complement
                 : sm ? PackedEncoding::sign_magnitude
                      : PackedEncoding::offset_binary;
    for (const int wb : {1, 2, 4})
      for (const bool big : {false, true}) {
        if (wb == 1 && big) continue;
        for (const PackedOrder order : {PackedOrder::lsb, PackedOrder::msb, PackedOrder::byte_msb}) {
          if (wb == 1 && order == PackedOrder::byte_msb) continue;
          for (const bool q_first : {false, true}) {
            if (q_first && !complex) continue;
            l.word_bytes = wb;
            l.big_endian = big;
            l.order = order;
            l.q_first = q_first;
            out.push_back(SampleFormat::packed_format(l));
          }
        }
      }
  }
  return out;
}

struct StreamFormat {
  bool complex = false;
  bool first_is_q = false;  ///< complex: the upper (first) half of a sample is Q
  bool negate_i = false, negate_q = false;
};

std::optional<StreamFormat> parse_stream_format(const std::string& text) {
  static const std::map<std::string, StreamFormat> kFormats = {
      {"IF", {false, false, false, false}}, {"IFn", {false, false, true, false}}, {"IQ", {true, false, false, false}},
      {"IQn", {true, false, false, true}},  {"InQ", {true, false, true, false}},  {"InQn", {true, false, true, true}},
      {"QI", {true, true, false, false}},   {"QIn", {true, true, true, false}},   {"QnI", {true, true, false, true}},
      {"QnIn", {true, true, true, true}},
  };
  const auto it = kFormats.find(text);
  if (it == kFormats.end()) return std::nullopt;
  return it->second;
}

}  // namespace

IfMetadata read_if_metadata(const std::filesystem::path& xml_path) {
  Reader r(xml_path);
  const Element& root = r.root();
  IfMetadata m;
  m.metadata_path = xml_path;

  // The file and its lane.
  if (!root.children("fileset").empty())
    r.fail(root.children("fileset").front(), "file sets (a recording split over several files) are not supported");
  std::optional<Element> file;
  if (const auto files = root.children("file"); !files.empty()) {
    if (files.size() > 1)
      r.fail(files[1], fmt::format("{} <file> elements: one file per metadata file is supported", files.size()));
    file = files.front();
    const Element url = r.one(*file, "url");
    if (url.text().empty()) r.fail(url, "is empty: it names the sample file");
    m.data_path = std::filesystem::path(url.text());
    if (m.data_path.is_relative()) m.data_path = xml_path.parent_path() / m.data_path;
  }
  m.start_time = start_time_of(r, file);
  const auto lanes = root.children("lane");
  if (lanes.empty()) r.fail(root, "has no <lane>: the layout of the samples is not described");
  std::optional<Element> lane;
  if (file) {
    if (const auto ref = r.optional_one(*file, "lane")) {
      for (const Element& l : lanes)
        if (l.id() == ref->id()) lane = l;
      if (!lane) r.fail(*ref, fmt::format("names lane '{}', which the file does not define", ref->id()));
    }
  }
  if (!lane) {
    if (lanes.size() > 1)
      r.fail(lanes[1], fmt::format("{} <lane> elements and no <file><lane id=...> to choose one", lanes.size()));
    lane = lanes.front();
  }

  // Sample rate: the lane's system's base frequency times the stream's rate factor.
  std::optional<Element> system = r.optional_one(*lane, "system");
  if (!system) {
    const auto systems = root.children("system");
    if (systems.size() != 1) r.fail(*lane, "names no <system> (with the <freqbase> the sample rate is built on)");
    system = systems.front();
  }
  const Element freqbase = r.one(*system, "freqbase");
  const double freqbase_hz = r.frequency_hz(freqbase);

  const Element block = r.one(*lane, "block", "one block per lane is supported");
  constexpr auto kMaxOffset = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  // Checked against the chunk's size below, where a count of bytes can overflow.
  const std::uint64_t cycles =
      r.unsigned_child(block, "cycles", 0, std::numeric_limits<std::uint64_t>::max(), "a 64-bit count");
  m.header_bytes = r.unsigned_child(block, "sizeheader", 0, kMaxOffset, "a position in a file");
  m.footer_bytes = r.unsigned_child(block, "sizefooter", 0, kMaxOffset, "a position in a file");
  const Element chunk = r.one(block, "chunk", "a block of one chunk is supported");
  const Element lump = r.one(chunk, "lump", "a chunk of one lump (repeated to fill the chunk) is supported");
  const Element stream = r.one(lump, "stream", "a lump of one stream is supported (no interleaved bands)");
  m.stream_id = stream.id();

  // Chunk: words, their byte order and order in the chunk, padding.
  const std::uint64_t size_word =
      r.unsigned_child(chunk, "sizeword", std::nullopt, kMaxChunkBytes, "words of 1, 2, 4 or 8 bytes are supported");
  if (size_word != 1 && size_word != 2 && size_word != 4 && size_word != 8)
    r.fail(*r.optional_one(chunk, "sizeword"),
           fmt::format("{} bytes: words of 1, 2, 4 or 8 bytes are supported", size_word));
  const std::uint64_t count_words =
      r.unsigned_child(chunk, "countwords", std::nullopt, kMaxChunkBytes, "chunks of 1 to 64 bytes are supported");
  if (count_words == 0 || count_words * size_word > kMaxChunkBytes)
    r.fail(*r.optional_one(chunk, "countwords"),
           fmt::format("{} words of {} bytes: chunks of 1 to {} bytes are supported", count_words, size_word,
                       kMaxChunkBytes));
  const std::string endian = r.word_child(chunk, "endian", "Undefined", {"Undefined", "Little", "Big"});
  const std::string padding = r.word_child(chunk, "padding", "None", {"None", "Head", "Tail"});
  std::string word_shift = r.word_child(chunk, "wordshift", "Left", {"Left", "Right"});
  if (chunk.children("wordshift").empty())
    word_shift = r.word_child(chunk, "shift", "Left", {"Left", "Right", "Undefined"});
  const std::string lump_shift = r.word_child(lump, "shift", "Left", {"Left", "Right", "Undefined"});

  // Stream: values and their code.
  const std::string in_a_chunk = fmt::format("a chunk holds at most {} bits", kMaxChunkBits);
  const std::uint64_t rate_factor = r.unsigned_child(stream, "ratefactor", 1, kMaxChunkBits, in_a_chunk);
  if (rate_factor == 0) r.fail(*r.optional_one(stream, "ratefactor"), "must be at least 1");
  const std::uint64_t quantization = r.unsigned_child(stream, "quantization", std::nullopt, 64, "bits of one value");
  const std::uint64_t packed_bits = r.unsigned_child(stream, "packedbits", std::nullopt, kMaxChunkBits, in_a_chunk);
  const std::string alignment = r.word_child(stream, "alignment", "Undefined", {"Undefined", "Left", "Right"});
  const std::string stream_shift = r.word_child(stream, "shift", "Left", {"Left", "Right", "Undefined"});
  const Element format_element = r.one(stream, "format");
  const auto sf = parse_stream_format(format_element.text());
  if (!sf)
    r.fail(format_element, fmt::format("'{}' is not a sample format of the standard (IF, IFn, IQ, IQn, InQ, InQn, QI, "
                                       "QIn, QnI, QnIn)",
                                       format_element.text()));
  const Element encoding = r.one(stream, "encoding");
  const std::vector<SampleFormat> formats = candidates(static_cast<int>(quantization), encoding.text(), sf->complex);
  if (formats.empty())
    r.fail(encoding, fmt::format("{} samples of {}-bit '{}' values are not supported (supported: 8-bit TC/INT8 "
                                 "(I/Q or real), 8-bit OB (I/Q), 16-bit TC (I/Q), 32-bit FP (I/Q); 1, 2 or 4-bit TC, "
                                 "SM, OB, SIGN)",
                                 sf->complex ? "I/Q" : "real", quantization, encoding.text()));

  // Lay the chunk out as the standard's converter does: fields from the most significant
  // bit of the first word on, each lump repeat in turn, padding where the alignment and the
  // chunk's padding put it; then order the samples in time by the lump's and stream's shifts.
  const int word_bits = static_cast<int>(8 * size_word);
  const int chunk_bits = word_bits * static_cast<int>(count_words);
  const int q = static_cast<int>(quantization);
  const int unit = q * (sf->complex ? 2 : 1);
  const int samples_bits = static_cast<int>(rate_factor) * unit;
  if (static_cast<int>(packed_bits) < samples_bits)
    r.fail(*r.optional_one(stream, "packedbits"),
           fmt::format("{} bits cannot hold {} sample(s) of {} bits", packed_bits, rate_factor, unit));
  const int stream_pad = static_cast<int>(packed_bits) - samples_bits;
  if (stream_pad > 0 && alignment == "Undefined")
    r.fail(stream, fmt::format("{} of its {} packed bits are padding, but <alignment> does not say on which side",
                               stream_pad, packed_bits));
  const int repeats = chunk_bits / static_cast<int>(packed_bits);
  if (repeats == 0)
    r.fail(chunk, fmt::format("{} bits cannot hold the stream's {} packed bits", chunk_bits, packed_bits));
  const int chunk_pad = chunk_bits - repeats * static_cast<int>(packed_bits);
  if (chunk_pad > 0 && padding == "None")
    r.fail(chunk,
           fmt::format("{} of its {} bits are left over by the lumps, but <padding> is None", chunk_pad, chunk_bits));

  struct Placed {
    int order_key;
    ValueBits first, second;
  };
  auto field_bits = [&](int offset) {
    const int a = offset / word_bits, rbit = offset % word_bits;
    if (rbit + q > word_bits) r.fail(chunk, "a value spans two words: not supported");
    const int word = word_shift == "Right" ? static_cast<int>(count_words) - 1 - a : a;
    const int shift = word_bits - rbit - q;
    ValueBits v;
    for (int j = 0; j < q; ++j) {
      const int bit = shift + j;
      const int byte = endian == "Big" ? static_cast<int>(size_word) - 1 - bit / 8 : bit / 8;
      v.push_back((word * static_cast<int>(size_word) + byte) * 8 + bit % 8);
    }
    return v;
  };
  std::vector<Placed> placed;
  int offset = padding == "Head" ? chunk_pad : 0;
  for (int lr = 0; lr < repeats; ++lr) {
    if (alignment == "Right") offset += stream_pad;
    for (int si = 0; si < static_cast<int>(rate_factor); ++si) {
      const int lr_key = lump_shift == "Right" ? repeats - 1 - lr : lr;
      const int si_key = stream_shift == "Right" ? static_cast<int>(rate_factor) - 1 - si : si;
      Placed p;
      p.order_key = lr_key * static_cast<int>(rate_factor) + si_key;
      p.first = field_bits(offset);
      if (sf->complex) p.second = field_bits(offset + q);
      placed.push_back(p);
      offset += unit;
    }
    if (alignment == "Left") offset += stream_pad;
  }
  std::sort(placed.begin(), placed.end(), [](const Placed& a, const Placed& b) { return a.order_key < b.order_key; });
  std::vector<SampleBits> layout;
  for (const Placed& p : placed)
    layout.push_back(sf->complex ? (sf->first_is_q ? SampleBits{p.second, p.first} : SampleBits{p.first, p.second})
                                 : SampleBits{p.first, {}});

  const auto chunk_bytes = static_cast<std::size_t>(size_word * count_words);
  bool found = false;
  for (const SampleFormat& f : formats) {
    if (format_bits(f, chunk_bytes) == layout) {
      m.format = f;
      found = true;
      break;
    }
  }
  if (!found)
    r.fail(stream, fmt::format("the layout ({} {}-bit '{}' value(s) a sample, {} in {} word(s) of {} bytes, endian {}, "
                               "word shift {}, lump shift {}, stream shift {}) is none of the sample formats this "
                               "program reads ({})",
                               sf->complex ? 2 : 1, q, encoding.text(), format_element.text(), count_words, size_word,
                               endian, word_shift, lump_shift, stream_shift, sample_format_choices()));
  if (cycles > kMaxOffset / chunk_bytes)
    r.fail(*r.optional_one(block, "cycles"),
           fmt::format("{} cycles of {}-byte chunks are more bytes than a 64-bit file offset counts (the product "
                       "overflows; at most {} cycles)",
                       cycles, chunk_bytes, kMaxOffset / chunk_bytes));
  if (cycles > 0) m.length_bytes = cycles * chunk_bytes;
  m.sample_rate_hz = freqbase_hz * static_cast<double>(rate_factor);
  m.sample_rate_element = freqbase.path;
  if (!(m.sample_rate_hz > 0.0) || !std::isfinite(m.sample_rate_hz))
    r.fail(freqbase,
           fmt::format("{} Hz x rate factor {} gives no finite positive sample rate", freqbase_hz, rate_factor));

  // Frequencies: the band's centre appears at <translatedfreq> in the samples (after the
  // format's negations); an inverted band runs the other way.
  const auto bands = stream.children("band");
  if (bands.empty()) r.fail(stream, "has no <band> (its centre and translated frequencies)");
  if (bands.size() > 1) r.fail(bands[1], "a stream of several bands is not supported");
  const Element band = r.resolve(bands.front());
  m.center_frequency_hz = r.frequency_hz(r.one(band, "centerfreq"));
  const double translated_hz = r.frequency_hz(r.one(band, "translatedfreq"));
  bool band_inverted = false;
  if (const auto inv = r.optional_one(band, "inverted")) {
    const std::string t = lower(inv->text());
    if (t == "true" || t == "1") {
      band_inverted = true;
    } else if (t != "false" && t != "0") {
      r.fail(*inv, fmt::format("'{}' is not true or false", inv->text()));
    }
  }
  const double l1_in_samples = translated_hz + (band_inverted ? -1.0 : 1.0) * (gps::kL1_Hz - m.center_frequency_hz);
  const bool format_conjugates = sf->complex && (sf->negate_i != sf->negate_q);
  m.inverted_spectrum = sf->complex && (format_conjugates != band_inverted);
  m.if_hz = band_inverted ? -l1_in_samples : l1_in_samples;
  const double half = m.sample_rate_hz / 2.0;
  if (sf->complex ? std::abs(m.if_hz) >= half : !(std::abs(m.if_hz) > 0.0 && std::abs(m.if_hz) < half))
    r.fail(band, fmt::format("GPS L1 (1575.42 MHz) falls at {} Hz in the samples, outside what {} Hz {} sampling holds "
                             "(centre {} Hz at {} Hz)",
                             m.if_hz, m.sample_rate_hz, sf->complex ? "complex" : "real", m.center_frequency_hz,
                             translated_hz));
  return m;
}

std::string if_metadata_xml(const IfMetadataDescription& d) {
  auto escaped = [](const std::string& s) {
    std::string out;
    for (const char c : s) {
      if (c == '&') out += "&amp;";
      else if (c == '<') out += "&lt;";
      else if (c == '>') out += "&gt;";
      else if (c == '"') out += "&quot;";
      else out += c;
    }
    return out;
  };
  // The chunk: one word of a packed format (or its bytes, for the per-byte order), the
  // bytes of one sample otherwise.
  int size_word = 1, count_words = 1, quantization = 8, packed_bits = 8;
  std::string endian = "Undefined", word_shift = "Left", lump_shift = "Left", stream_format, encoding = "TC";
  const bool complex = is_complex(d.format);
  switch (d.format.kind) {
    case SampleKind::ibyte:
    case SampleKind::cu8:
      count_words = 2;
      packed_bits = 16;
      encoding = d.format.kind == SampleKind::cu8 ? "OB" : "TC";
      break;
    case SampleKind::byte:
      break;
    case SampleKind::ishort:
      size_word = 2;
      count_words = 2;
      endian = "Little";
      quantization = 16;
      packed_bits = 32;
      break;
    case SampleKind::gr_complex:
      size_word = 4;
      count_words = 2;
      endian = "Little";
      quantization = 32;
      packed_bits = 64;
      encoding = "FP";
      break;
    case SampleKind::packed: {
      const PackedLayout& l = d.format.packed;
      quantization = l.bits;
      packed_bits = l.bits * (l.complex ? 2 : 1);
      encoding = l.encoding == PackedEncoding::twos_complement  ? "TC"
                 : l.encoding == PackedEncoding::sign_magnitude ? "SM"
                                                                : "OB";
      if (l.order == PackedOrder::byte_msb) {
        count_words = l.word_bytes;
        word_shift = l.big_endian ? "Right" : "Left";
      } else {
        size_word = l.word_bytes;
        if (size_word > 1) endian = l.big_endian ? "Big" : "Little";
        lump_shift = l.order == PackedOrder::lsb ? "Right" : "Left";
      }
      break;
    }
  }
  if (complex) {
    // A sample's first (upper) half is the earlier value in msb order, the later one in lsb order.
    const bool q_first = is_packed(d.format) && d.format.packed.q_first;
    const bool lsb = is_packed(d.format) && d.format.packed.order == PackedOrder::lsb;
    stream_format = (q_first != lsb) ? "QI" : "IQ";
  } else {
    stream_format = "IF";
  }
  return fmt::format(
      R"(<?xml version="1.0" encoding="UTF-8"?>
<metadata xmlns="http://www.ion.org/standards/sdrwg/schema/metadata.xsd">
  <!-- ION GNSS SDR Metadata Standard description of {url}: sample format {name} -->
  <system id="deepnav-sim">
    <comment format="text">{comment}</comment>
    <freqbase format="Hz">{fs:.1f}</freqbase>
    <equipment>deepnav sim</equipment>
    <types>Simulator</types>
  </system>
  <band id="L1">
    <centerfreq format="Hz">1575420000.0</centerfreq>
    <translatedfreq format="Hz">{if_hz:.3f}</translatedfreq>
    <inverted>false</inverted>
  </band>
  <lane id="IF">
    <system id="deepnav-sim"/>
    <block>
      <cycles>0</cycles>
      <sizeheader>0</sizeheader>
      <sizefooter>0</sizefooter>
      <chunk>
        <sizeword>{size_word}</sizeword>
        <countwords>{count_words}</countwords>
        <endian>{endian}</endian>
        <padding>None</padding>
        <wordshift>{word_shift}</wordshift>
        <lump>
          <shift>{lump_shift}</shift>
          <stream id="L1">
            <ratefactor>1</ratefactor>
            <quantization>{quantization}</quantization>
            <packedbits>{packed_bits}</packedbits>
            <alignment>Undefined</alignment>
            <shift>Left</shift>
            <format>{stream_format}</format>
            <encoding>{encoding}</encoding>
            <band id="L1"/>
          </stream>
        </lump>
      </chunk>
    </block>
  </lane>
  <file>
    <url>{url}</url>
    <lane id="IF"/>
  </file>
</metadata>
)",
      fmt::arg("url", escaped(d.data_file_name)), fmt::arg("name", to_string(d.format)),
      fmt::arg("comment", escaped(d.comment)), fmt::arg("fs", d.sample_rate_hz), fmt::arg("if_hz", d.if_hz),
      fmt::arg("size_word", size_word), fmt::arg("count_words", count_words), fmt::arg("endian", endian),
      fmt::arg("word_shift", word_shift), fmt::arg("lump_shift", lump_shift), fmt::arg("quantization", quantization),
      fmt::arg("packed_bits", packed_bits), fmt::arg("stream_format", stream_format), fmt::arg("encoding", encoding));
}

std::filesystem::path metadata_path_for(const std::filesystem::path& if_path) {
  std::filesystem::path p = if_path;
  p.replace_extension(".xml");
  return p;
}

}  // namespace deepnav
