// ION GNSS SDR metadata files (signals/if_metadata.hpp): the input is written to a file and
// read as `--metadata FILE` reads it. Errors must be MetadataError naming the file; a
// description that reads gives what the file source computes with: a finite positive rate,
// L1 inside the band it holds, byte counts a file offset holds.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "signals/if_metadata.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

void check_promises(const deepnav::IfMetadata& m) {
  constexpr auto kMaxOffset = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  if (!std::isfinite(m.sample_rate_hz) || !(m.sample_rate_hz > 0.0))
    deepnav::fuzz::broken_promise("sample rate " + std::to_string(m.sample_rate_hz) + " Hz read");
  if (!(std::abs(m.if_hz) < m.sample_rate_hz / 2.0))
    deepnav::fuzz::broken_promise("IF " + std::to_string(m.if_hz) + " Hz read at a rate of " +
                                  std::to_string(m.sample_rate_hz) + " Hz");
  if (m.header_bytes > kMaxOffset || m.footer_bytes > kMaxOffset || m.length_bytes.value_or(0) > kMaxOffset)
    deepnav::fuzz::broken_promise("a byte count beyond a file offset read");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const deepnav::fuzz::InputFile file("deepnav_fuzz_metadata_", ".xml");
  const std::filesystem::path& path = file.write(data, size);
  const auto expected = [&](const std::exception& e) {
    return deepnav::fuzz::is_a<deepnav::MetadataError>(e) && deepnav::fuzz::names_input(path.string())(e);
  };
  deepnav::IfMetadata m;
  if (deepnav::fuzz::guarded([&] { m = deepnav::read_if_metadata(path); }, expected)) check_promises(m);
  return 0;
}
