// Trajectory CSV files (ins/sim/trajectory_csv.hpp): read from the input as from a file,
// then sampled across its span as the synthesizer samples it.
#include <sstream>

#include "ins/sim/trajectory_csv.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

/// The file's last time is inside its span: any exception there is a finding. Earlier
/// times may precede the file's first one (the loader does not make it start at 0):
/// there the documented std::out_of_range is expected.
void sample(const deepnav::Trajectory& trajectory) {
  const double end = trajectory.duration_s();
  (void)trajectory.at(end);
  for (int i = 0; i < 8; ++i)
    deepnav::fuzz::guarded([&] { (void)trajectory.at(end * i / 8.0); }, deepnav::fuzz::is_a<std::out_of_range>);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr const char* kName = "fuzz_trajectory.csv";
  std::istringstream in(deepnav::fuzz::as_text(data, size));
  std::unique_ptr<deepnav::Trajectory> trajectory;
  if (deepnav::fuzz::guarded([&] { trajectory = deepnav::load_csv_trajectory(in, kName); },
                             deepnav::fuzz::names_input(kName)))
    sample(*trajectory);
  return 0;
}
