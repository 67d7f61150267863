// RINEX 2/3 observation files (receiver/observations/rinex_obs_reader.hpp), read from the
// input as from a file.
#include <sstream>

#include "receiver/observations/rinex_obs_reader.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr const char* kName = "fuzz.obs";
  std::istringstream in(deepnav::fuzz::as_text(data, size));
  deepnav::fuzz::guarded([&] { (void)deepnav::read_rinex_obs(in, kName); }, deepnav::fuzz::names_input(kName));
  return 0;
}
