// deepnav IMU CSV files (ins/imu_file.hpp), read from the input as from a file.
#include <sstream>

#include "ins/imu_file.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr const char* kName = "fuzz_imu.csv";
  std::istringstream in(deepnav::fuzz::as_text(data, size));
  deepnav::fuzz::guarded([&] { (void)deepnav::read_imu_csv(in, kName); }, deepnav::fuzz::names_input(kName));
  return 0;
}
