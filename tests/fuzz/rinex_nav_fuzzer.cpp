// RINEX 2/3 navigation files (signals/rinex_nav.hpp): the input is read as a file; what
// was read is used as a run uses it and written back as RINEX 3.04 as the products do.
#include <sstream>

#include "signals/rinex_nav.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

constexpr const char* kName = "fuzz.22n";

bool documented(const std::exception& e) {
  return deepnav::fuzz::is_a<std::runtime_error>(e) || deepnav::fuzz::is_a<std::invalid_argument>(e);
}

/// What a run does with the file: picks each satellite's data set at its toe and computes
/// the orbit and clock there.
void use(const deepnav::NavData& nav) {
  for (const auto& eph : nav.ephemerides) {
    const deepnav::GpsTime toe = deepnav::GpsTime::normalized(eph.week, eph.toe_s);
    if (const deepnav::Ephemeris* chosen = nav.select(eph.prn, toe)) (void)deepnav::satellite_state(*chosen, toe);
  }
  std::ostringstream out;
  // The writer refuses values RINEX cannot hold (its documented error), and only that.
  deepnav::fuzz::guarded([&] { deepnav::write_rinex3_nav(out, nav, "deepnav-fuzz"); }, documented);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(deepnav::fuzz::as_text(data, size));
  deepnav::NavData nav;
  if (deepnav::fuzz::guarded([&] { nav = deepnav::read_rinex_nav(in, kName); }, deepnav::fuzz::names_input(kName)))
    use(nav);
  return 0;
}
