// ION GNSS SDR Metadata Standard files: what the synthesizer writes reads back as the same
// format for every layout; hand-written files in the standard's styles (rate factors,
// shifts, padding, references, inversion, header and cycles) configure the source; and
// every unsupported or broken description is an error naming the element.
#include "signals/if_metadata.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "signals/sample_packing.hpp"

namespace deepnav {
namespace {

using namespace std::string_literals;

/// A scratch folder of this process: ctest runs every case as a process of its own, two at
/// once, and cases writing the same file name (bad.xml) into one folder raced.
std::filesystem::path write_xml(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / ("deepnav_if_metadata_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

/// A file of one lane, block, chunk, lump and stream with the given pieces.
std::string document(const std::string& chunk, const std::string& stream, const std::string& band = "",
                     const std::string& block_extra = "",
                     const std::string& freqbase = "<freqbase format=\"MHz\">4.092</freqbase>") {
  const std::string default_band =
      R"(<band id="L1"><centerfreq format="MHz">1575.42</centerfreq><translatedfreq format="Hz">0</translatedfreq></band>)";
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<metadata xmlns="http://www.ion.org/standards/sdrwg/schema/metadata.xsd">
  <system id="fe">)" +
         freqbase + R"(</system>
  )" + (band.empty() ? default_band : band) +
         R"(
  <lane id="A"><system id="fe"/>
    <block>)" +
         block_extra + R"(
      <chunk>)" +
         chunk + R"(
        <lump>
          <stream id="S">)" +
         stream + R"(<band id="L1"/></stream>
        </lump>
      </chunk>
    </block>
  </lane>
  <file><url>samples.bin</url><lane id="A"/></file>
</metadata>
)";
}

/// The levels of 16 fixed bytes in a packed format, in time order (I before Q).
std::vector<int> time_ordered(const SampleFormat& f) {
  std::vector<std::byte> bytes(16);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::byte>(37 * i + 11);
  std::vector<std::int16_t> levels(bytes.size() / bytes_per_word(f) * values_per_word(f.packed));
  unpack_levels(bytes, f.packed, levels);
  if (f.packed.q_first)
    for (std::size_t k = 0; k + 1 < levels.size(); k += 2) std::swap(levels[k], levels[k + 1]);
  return {levels.begin(), levels.end()};
}

IfMetadata read(const std::string& name, const std::string& text) { return read_if_metadata(write_xml(name, text)); }

std::string error_of(const std::string& text) {
  try {
    read("bad.xml", text);
  } catch (const MetadataError& e) {
    return e.what();
  }
  return "";
}

TEST(IfMetadata, WhatTheSynthesizerWritesReadsBackForEveryFormat) {
  std::set<std::string> names = {"ibyte", "ishort", "gr_complex", "byte", "cu8"};
  for (const int bits : {1, 2, 4})
    for (const char* type : {"", "_iq", "_qi"})
      for (const char* encoding : {"", "_sm", "_ob"})
        for (const char* order : {"", "_msb", "_bytemsb"})
          for (const char* word : {"", "_w16le", "_w16be", "_w32le", "_w32be"})
            names.insert(
                to_string(parse_sample_format("packed" + std::to_string(bits) + type + encoding + order + word)));
  EXPECT_EQ(names.size(), 5u + 405u - 27u);  // bytemsb is msb in 8-bit words
  for (const std::string& name : names) {
    IfMetadataDescription d;
    d.format = parse_sample_format(name);
    d.data_file_name = "if_" + name + ".bin";
    d.sample_rate_hz = 8184000.0;
    d.if_hz = is_complex(d.format) ? 0.0 : 2.046e6;
    d.comment = "a <test> & more";
    const IfMetadata m = read("if_" + name + ".xml", if_metadata_xml(d));
    if (is_packed(d.format)) {
      // Layouts of the same bits in the same places are one (packed1_msb_w16be is packed1_msb):
      // the reader names the one of the smallest word. The same bytes give the same samples.
      ASSERT_TRUE(is_packed(m.format)) << name;
      EXPECT_EQ(time_ordered(d.format), time_ordered(m.format)) << name << " read as " << to_string(m.format);
    } else {
      EXPECT_EQ(to_string(m.format), name);
    }
    EXPECT_EQ(m.sample_rate_hz, 8184000.0) << name;
    EXPECT_EQ(m.if_hz, d.if_hz) << name;
    EXPECT_FALSE(m.inverted_spectrum) << name;
    EXPECT_EQ(m.data_path.filename(), d.data_file_name);
    EXPECT_EQ(m.center_frequency_hz, 1575.42e6);
    EXPECT_EQ(m.header_bytes, 0u);
    EXPECT_FALSE(m.length_bytes);
  }
  EXPECT_EQ(metadata_path_for("out/if_ibyte.bin"), std::filesystem::path("out/if_ibyte.xml"));
}

TEST(IfMetadata, TwoBitSignMagnitudeFrontEndAtAnIntermediateFrequency) {
  // A MAX2769-style recording: real 2-bit sign/magnitude samples, four to a byte from the
  // top bits down (the default left shift), 16.368 Msps with L1 at 4.092 MHz.
  const IfMetadata m =
      read("max2769.xml", document("<sizeword>1</sizeword><countwords>1</countwords>",
                                   "<ratefactor>1</ratefactor><quantization>2</quantization>"
                                   "<packedbits>2</packedbits><format>IF</format><encoding>SM</encoding>",
                                   R"(<band id="L1"><centerfreq format="GHz">1.57542</centerfreq>
                                                       <translatedfreq format="kHz">4092</translatedfreq></band>)",
                                   "", R"(<freqbase units="MHz">16.368</freqbase>)"));
  EXPECT_EQ(to_string(m.format), "packed2_sm_msb");
  EXPECT_DOUBLE_EQ(m.sample_rate_hz, 16.368e6);
  EXPECT_DOUBLE_EQ(m.if_hz, 4.092e6);
  EXPECT_EQ(m.data_path, m.metadata_path.parent_path() / "samples.bin");
}

TEST(IfMetadata, RateFactorShiftsAndPadding) {
  // Two I/Q samples a byte in one lump of rate factor 2, the stream shifted right: the later
  // sample in the upper nibble, I above Q in each: from bit 0 up Q0 I0 Q1 I1.
  IfMetadata m =
      read("rate2.xml", document("<sizeword>1</sizeword><countwords>1</countwords>",
                                 "<ratefactor>2</ratefactor><quantization>2</quantization><packedbits>8</packedbits>"
                                 "<shift>Right</shift><format>IQ</format><encoding>TC</encoding>"));
  EXPECT_EQ(to_string(m.format), "packed2_qi");
  EXPECT_DOUBLE_EQ(m.sample_rate_hz, 2 * 4.092e6);
  // One sample a lump, the lump repeated with the default left shift: from the top bits down.
  m = read("lumpright.xml",
           document("<sizeword>1</sizeword><countwords>1</countwords>",
                    "<ratefactor>1</ratefactor><quantization>2</quantization><packedbits>4</packedbits>"
                    "<format>IQ</format><encoding>TC</encoding>"));
  EXPECT_EQ(to_string(m.format), "packed2_iq_msb");
  // 16-bit little-endian words, the lump's repeats from the low bits up, Q above I.
  const std::string right_lump =
      document("<sizeword>2</sizeword><countwords>1</countwords><endian>Little</endian>",
               "<ratefactor>1</ratefactor><quantization>4</quantization><packedbits>8</packedbits>"
               "<format>QI</format><encoding>OB</encoding>");
  std::string with_shift = right_lump;
  with_shift.replace(with_shift.find("<lump>"), 6, "<lump><shift>Right</shift>");
  EXPECT_EQ(to_string(read("w16.xml", with_shift).format), "packed4_iq_ob");  // same bits as 8-bit words
  // 1-bit I/Q samples in big-endian 16-bit words from the top bit down: the bytes in file
  // order, each from its top bit.
  m = read("pad.xml",
           document("<sizeword>2</sizeword><countwords>1</countwords><endian>Big</endian><padding>Tail</padding>",
                    "<ratefactor>1</ratefactor><quantization>1</quantization><packedbits>2</packedbits>"
                    "<format>IQ</format><encoding>SIGN</encoding>"));
  EXPECT_EQ(to_string(m.format), "packed1_iq_msb");
  // Odd padding cannot be any of our layouts: an error naming the stream.
  const std::string msg =
      error_of(document("<sizeword>2</sizeword><countwords>1</countwords><padding>Tail</padding>",
                        "<ratefactor>1</ratefactor><quantization>2</quantization><packedbits>5</packedbits>"
                        "<alignment>Right</alignment><format>IQ</format><encoding>TC</encoding>"));
  EXPECT_NE(msg.find("stream[S]>: the layout"), std::string::npos) << msg;
  EXPECT_NE(msg.find("none of the sample formats"), std::string::npos) << msg;
}

TEST(IfMetadata, InversionHeaderCyclesAndReferences) {
  // IQn: Q negated, i.e. read as I - jQ; InQn negates both (a sign, not an inversion).
  const std::string chunk = "<sizeword>1</sizeword><countwords>2</countwords>";
  auto stream = [](const std::string& format) {
    return "<ratefactor>1</ratefactor><quantization>8</quantization><packedbits>16</packedbits><format>" + format +
           "</format><encoding>INT8</encoding>";
  };
  EXPECT_TRUE(read("iqn.xml", document(chunk, stream("IQn"))).inverted_spectrum);
  EXPECT_FALSE(read("inqn.xml", document(chunk, stream("InQn"))).inverted_spectrum);
  EXPECT_NE(error_of(document(chunk, stream("QI"))).find("none of the sample formats"), std::string::npos)
      << "8-bit Q-first I/Q is not ibyte";
  // An inverted band below L1: L1 appears 1 MHz below the translated frequency in the
  // samples; undoing the inversion puts it 1 MHz above, read as I - jQ.
  const IfMetadata inv = read("inv.xml", document(chunk, stream("IQ"),
                                                  R"(<band id="L1"><centerfreq format="MHz">1574.42</centerfreq>
                                                     <translatedfreq format="Hz">250000</translatedfreq>
                                                     <inverted>true</inverted></band>)"));
  EXPECT_TRUE(inv.inverted_spectrum);
  EXPECT_DOUBLE_EQ(inv.if_hz, 750000.0);
  // Header, footer and cycles.
  const IfMetadata h =
      read("hdr.xml", document(chunk, stream("IQ"), "",
                               "<cycles>1000</cycles><sizeheader>512</sizeheader><sizefooter>16</sizefooter>"));
  EXPECT_EQ(h.header_bytes, 512u);
  EXPECT_EQ(h.footer_bytes, 16u);
  ASSERT_TRUE(h.length_bytes);
  EXPECT_EQ(*h.length_bytes, 2000u);
  // A stream defined at the top level and referenced from the lump (the standard's example style).
  std::string ref = document(chunk, "");
  ref.replace(ref.find("<stream id=\"S\">"), std::string("<stream id=\"S\"><band id=\"L1\"/></stream>").size(),
              "<stream id=\"S\"/>");
  ref.replace(ref.find("<lane"), 0, "<stream id=\"S\">" + stream("IQ") + "<band id=\"L1\"/></stream>\n  ");
  EXPECT_EQ(read("ref.xml", ref).format, SampleFormat::ibyte);
  // 16-bit TC I/Q little endian is ishort, 8-bit OB I/Q is cu8, 32-bit FP I/Q gr_complex.
  EXPECT_EQ(
      read("s16.xml", document("<sizeword>2</sizeword><countwords>2</countwords><endian>Little</endian>",
                               "<ratefactor>1</ratefactor><quantization>16</quantization><packedbits>32</packedbits>"
                               "<format>IQ</format><encoding>TC</encoding>"))
          .format,
      SampleFormat::ishort);
  EXPECT_EQ(read("u8.xml", document(chunk,
                                    "<ratefactor>1</ratefactor><quantization>8</quantization><packedbits>16"
                                    "</packedbits><format>IQ</format><encoding>OB</encoding>"))
                .format,
            SampleFormat::cu8);
}

TEST(IfMetadata, TheFileTimestampElseTheOneSessionsToaDatesTheRecording) {
  const std::string chunk = "<sizeword>1</sizeword><countwords>2</countwords>";
  const std::string stream =
      "<ratefactor>1</ratefactor><quantization>8</quantization><packedbits>16</packedbits><format>IQ</format>"
      "<encoding>INT8</encoding>";
  const std::string plain = document(chunk, stream);
  // Texts with a session (inserted before the lane) and a file timestamp (after the url).
  auto with = [&](const std::string& sessions, const std::optional<std::string>& timestamp) {
    std::string t = plain;
    t.insert(t.find("  <lane id=\"A\">"), sessions);
    if (timestamp) t.insert(t.find("</url>") + 6, "<timestamp>" + *timestamp + "</timestamp>");
    return t;
  };
  const std::string toa = R"(<session id="capture"><toa>2021-12-02T08:47:00Z</toa></session>
  )";
  EXPECT_FALSE(read("undated.xml", plain).start_time);

  const IfMetadata session = read("toa.xml", with(toa, std::nullopt));
  ASSERT_TRUE(session.start_time);
  EXPECT_EQ(session.start_time->element, "metadata/session[capture]/toa");
  EXPECT_EQ(session.start_time->utc.year, 2021);
  EXPECT_EQ(session.start_time->utc.month, 12);
  EXPECT_EQ(session.start_time->utc.day, 2);
  EXPECT_EQ(session.start_time->utc.hour, 8);
  EXPECT_EQ(session.start_time->utc.minute, 47);

  // The file's own timestamp comes first; without a Z it is still UTC (the standard's dates are).
  const IfMetadata file = read("timestamp.xml", with(toa, "2021-12-02T08:47:12.25"));
  ASSERT_TRUE(file.start_time);
  EXPECT_EQ(file.start_time->element, "metadata/file/timestamp");
  EXPECT_EQ(file.start_time->utc.minute, 47);
  EXPECT_DOUBLE_EQ(file.start_time->utc.second, 12.25);

  // Two sessions and no file timestamp: which one is the file's is not said, so none.
  EXPECT_FALSE(read("two.xml", with(toa + R"(<session id="other"><toa>2021-12-03T00:00:00Z</toa></session>
  )",
                                    std::nullopt))
                   .start_time);

  // A date given but unreadable or impossible is an error naming the element.
  for (const char* bad : {"2021-12-02 noon", "2021-02-30T00:00:00Z", "1979-12-31T23:59:59Z", ""}) {
    const std::string msg = error_of(with("", bad));
    EXPECT_NE(msg.find("<metadata/file/timestamp>"), std::string::npos) << bad << ": " << msg;
    EXPECT_NE(msg.find("expected UTC like 2021-12-02T08:47:00Z"), std::string::npos) << bad << ": " << msg;
  }
}

TEST(IfMetadata, UnsupportedAndBrokenDescriptionsNameTheElement) {
  const std::string chunk = "<sizeword>1</sizeword><countwords>1</countwords>";
  const std::string stream =
      "<ratefactor>1</ratefactor><quantization>2</quantization><packedbits>2</packedbits>"
      "<format>IF</format><encoding>TC</encoding>";
  auto expect = [](const std::string& msg, const std::string& part1, const std::string& part2) {
    EXPECT_NE(msg.find(part1), std::string::npos) << msg;
    EXPECT_NE(msg.find(part2), std::string::npos) << msg;
  };
  EXPECT_EQ(error_of(document(chunk, stream, R"(<band id="L1"><centerfreq format="MHz">1575.42</centerfreq>
      <translatedfreq format="MHz">1.0</translatedfreq></band>)")),
            "");
  expect(error_of("<metadata><lane>"), "bad.xml':", "not well-formed XML");
  expect(error_of("<other/>"), "root element is <other>", "<metadata>");
  std::string two_streams = document(chunk, stream);
  two_streams.replace(two_streams.find("</lump>"), 0, "<stream id=\"T\"/>");
  expect(error_of(two_streams), "lump/stream[T]>: 2 <stream> elements", "a lump of one stream");
  std::string og = document(chunk, stream);
  og.replace(og.find("<encoding>TC"), 12, "<encoding>OG");
  expect(error_of(og), "stream[S]/encoding>", "'OG' values are not supported");
  std::string fmt_bad = document(chunk, stream);
  fmt_bad.replace(fmt_bad.find("<format>IF"), 10, "<format>IQQ");
  expect(error_of(fmt_bad), "stream[S]/format>: 'IQQ'", "IQn");
  expect(error_of(document("<sizeword>3</sizeword><countwords>1</countwords>", stream)), "chunk/sizeword>",
         "1, 2, 4 or 8 bytes");
  expect(error_of(document("<sizeword>1</sizeword><countwords>1</countwords>",
                           "<ratefactor>1</ratefactor><quantization>2</quantization><packedbits>3</packedbits>"
                           "<alignment>Left</alignment><format>IF</format><encoding>TC</encoding>")),
         "block/chunk>: 2 of its 8 bits", "<padding> is None");
  expect(error_of(document(chunk,
                           "<ratefactor>1</ratefactor><quantization>2</quantization><packedbits>3</packedbits>"
                           "<format>IF</format><encoding>TC</encoding>")),
         "stream[S]>: 1 of its 3 packed bits are padding", "<alignment>");
  expect(error_of(document(chunk, stream, R"(<band id="L1"><centerfreq format="MHz">1227.6</centerfreq>
      <translatedfreq format="Hz">0</translatedfreq></band>)")),
         "band[L1]>: GPS L1", "outside");
  expect(error_of(document(chunk, stream,
                           R"(<band id="L2"><centerfreq>1</centerfreq><translatedfreq>0</translatedfreq></band>)")),
         "stream[S]/band[L1]>: refers to <band id=\"L1\">", "does not define");
  expect(error_of(document(chunk, stream, "", "", "")), "system[fe]>: has no <freqbase>", "");
  expect(error_of(document(chunk, stream, "", "", R"(<freqbase format="furlongs">4</freqbase>)")), "freqbase>",
         "unit 'furlongs'");
  std::string no_file = document(chunk, stream);
  no_file.replace(no_file.find("<file>"), no_file.find("</file>") + 7 - no_file.find("<file>"),
                  "<file><url>a.bin</url></file><file><url>b.bin</url></file>");
  expect(error_of(no_file), "<metadata/file>: 2 <file> elements", "one file per metadata file");
  std::string two_blocks = document(chunk, stream);
  two_blocks.replace(two_blocks.find("</lane>"), 0, "<block/>");
  expect(error_of(two_blocks), "lane[A]/block>: 2 <block> elements", "one block per lane");
  // 16-bit big-endian I/Q: none of our formats (ishort is little endian).
  expect(error_of(document("<sizeword>2</sizeword><countwords>2</countwords><endian>Big</endian>",
                           "<ratefactor>1</ratefactor><quantization>16</quantization><packedbits>32</packedbits>"
                           "<format>IQ</format><encoding>TC</encoding>")),
         "stream[S]>: the layout", "endian Big");
}

TEST(IfMetadata, NumbersBeyondWhatTheReaderComputesWithAreErrors) {
  const std::string chunk = "<sizeword>1</sizeword><countwords>2</countwords>";
  auto stream = [](const std::string& quantization, const std::string& rate_factor = "1",
                   const std::string& packed_bits = "16") {
    return "<ratefactor>" + rate_factor + "</ratefactor><quantization>" + quantization + "</quantization><packedbits>" +
           packed_bits + "</packedbits><format>IQ</format><encoding>TC</encoding>";
  };
  auto expect = [](const std::string& msg, const std::string& part1, const std::string& part2) {
    EXPECT_NE(msg.find(part1), std::string::npos) << msg;
    EXPECT_NE(msg.find(part2), std::string::npos) << msg;
  };
  EXPECT_EQ(read("q8.xml", document(chunk, stream("8"))).format, SampleFormat::ibyte);
  // 2^32 + 8 was narrowed to int as 8: an ibyte file.
  expect(error_of(document(chunk, stream("4294967304"))), "stream[S]/quantization>: 4294967304 is too large",
         "at most 64");
  expect(error_of(document(chunk, stream("8", "4294967297"))), "stream[S]/ratefactor>: 4294967297 is too large",
         "at most 512");
  expect(error_of(document(chunk, stream("8", "1", "4294967312"))), "stream[S]/packedbits>: 4294967312", "at most 512");
  expect(error_of(document(chunk, stream("99999999999999999999999"))), "quantization>: 99999999999999999999999",
         "too large");
  expect(error_of(document(chunk, stream("-8"))), "quantization>: '-8'", "not a whole number");
  expect(error_of(document(chunk, stream(" 8x"))), "quantization>: '8x'", "not a whole number");
  // 2^61 words of 8 bytes made 0 bytes.
  expect(error_of(document("<sizeword>8</sizeword><countwords>2305843009213693952</countwords>", stream("8"))),
         "chunk/countwords>: 2305843009213693952 is too large", "at most 64");
  expect(error_of(document("<sizeword>4</sizeword><countwords>32</countwords>", stream("8"))),
         "chunk/countwords>: 32 words of 4 bytes", "1 to 64 bytes");
  // 2^63 cycles of 2 bytes made 0 bytes: "holds no whole sample".
  expect(error_of(document(chunk, stream("8"), "", "<cycles>9223372036854775808</cycles>")),
         "block/cycles>: 9223372036854775808 cycles of 2-byte chunks", "overflows; at most 4611686018427387903");
  EXPECT_EQ(*read("c.xml", document(chunk, stream("8"), "", "<cycles>4611686018427387903</cycles>")).length_bytes,
            9223372036854775806u);
  // A header and a footer are file offsets (off_t): their sum no longer wraps either.
  expect(error_of(document(chunk, stream("8"), "", "<sizeheader>18446744073709551615</sizeheader>")),
         "block/sizeheader>: 18446744073709551615 is too large", "a position in a file");
  expect(error_of(document(chunk, stream("8"), "", "<sizefooter>9223372036854775808</sizefooter>")),
         "block/sizefooter>", "at most 9223372036854775807");
  // A frequency that scales to infinity.
  expect(error_of(document(chunk, stream("8"), "", "", R"(<freqbase format="GHz">1e305</freqbase>)")),
         "system[fe]/freqbase>: 1e305 ghz", "not a finite frequency");
  const IfMetadata m = read("rate.xml", document(chunk, stream("8")));
  EXPECT_EQ(m.sample_rate_element, "metadata/system[fe]/freqbase");
}

TEST(IfMetadata, FilesThatAreNoDescriptionAreRefusedBeforeTheyAreParsed) {
  auto expect = [](const std::string& msg, const std::string& part1, const std::string& part2) {
    EXPECT_NE(msg.find(part1), std::string::npos) << msg;
    EXPECT_NE(msg.find(part2), std::string::npos) << msg;
  };
  // 50,000 levels overflowed the stack of the recursive XML parser (SIGSEGV).
  std::string deep = "<?xml version=\"1.0\"?>\n<metadata>\n";
  for (int i = 0; i < 50000; ++i) deep += "<a>";
  expect(error_of(deep), "bad.xml':3: elements nested more than 64 deep", "not a metadata description");
  // 64 levels are read (and refused for what they hold, not for their depth).
  std::string deep64 = "<metadata>";
  for (int i = 1; i < 64; ++i) deep64 += "<a>";
  for (int i = 1; i < 64; ++i) deep64 += "</a>";
  deep64 += "</metadata>";
  expect(error_of(deep64), "bad.xml': <metadata>: has no <lane>", "");
  // UTF-16, with or without a byte-order mark: "expected <" said nothing of the encoding.
  auto utf16le = [](const std::string& ascii, bool bom) {
    std::string out = bom ? std::string("\xFF\xFE") : std::string();
    for (const char c : ascii) out += std::string{c, '\0'};
    return out;
  };
  const std::string good = document("<sizeword>1</sizeword><countwords>2</countwords>",
                                    "<quantization>8</quantization><packedbits>16</packedbits><format>IQ</format>"
                                    "<encoding>TC</encoding>");
  for (const bool bom : {true, false})
    expect(error_of(utf16le(good, bom)), "bad.xml' is encoded in UTF-16", "read as UTF-8");
  expect(error_of("\xFF\xFE\0\0<\0\0\0"s), "bad.xml' is encoded in UTF-32", "read as UTF-8");
  std::string with_nul = good;
  with_nul.insert(with_nul.find("<lane"), 1, '\0');
  expect(error_of(with_nul), "bad.xml':5: a NUL byte", "not a text file");
  // A UTF-8 byte-order mark is fine.
  EXPECT_EQ(read("bom.xml", "\xEF\xBB\xBF" + good).format, SampleFormat::ibyte);
  // More than 1 MiB is no description (the tree parser would hold it all).
  std::string big = good;
  big.insert(big.find("<lane"), "<!--" + std::string(1 << 20, 'x') + "-->");
  expect(error_of(big), "metadata file", "more than the 1048576 bytes");
}

}  // namespace
}  // namespace deepnav
