// Synthesizer truth files (receiver/products/truth_file.hpp): read from the input as from a file,
// then interpolated across its span as the run statistics do.
#include <sstream>

#include "receiver/products/truth_file.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr const char* kName = "fuzz_truth.csv";
  std::istringstream in(deepnav::fuzz::as_text(data, size));
  std::optional<deepnav::TruthFile> truth;
  if (!deepnav::fuzz::guarded([&] { truth.emplace(in, kName); }, deepnav::fuzz::names_input(kName))) return 0;
  for (double t : {-1.0, 0.0, 0.5, 1.0, 10.0, 1e6}) (void)truth->at(t);
  return 0;
}
