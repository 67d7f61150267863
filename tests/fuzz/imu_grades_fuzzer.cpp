// IMU grade files (ins/imu_model.hpp, `--imu-grades-file`): the input is written to a file
// and loaded as the commands load it. Errors must name the file.
#include "ins/imu_model.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const deepnav::fuzz::InputFile file("deepnav_fuzz_imu_grades_", ".yaml");
  const std::string path = file.write(data, size).string();
  deepnav::fuzz::guarded([&] { (void)deepnav::load_imu_grades(path); }, deepnav::fuzz::names_input(path));
  return 0;
}
