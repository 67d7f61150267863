// RINEX 2/3 observation files (receiver/observations/rinex_obs_reader.hpp), read from the
// input as from a file. What a read that succeeds promises is checked: epochs in strictly
// increasing GPS time (event records and time systems applied, repeats skipped), GPS
// satellites 1-32 with finite values, a finite interval.
#include <cmath>
#include <sstream>

#include "receiver/observations/rinex_obs_reader.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

bool finite(const std::optional<double>& v) { return !v || std::isfinite(*v); }

void check_promises(const deepnav::ObservationFile& f) {
  if (f.epochs.empty() || f.report.epochs != static_cast<int>(f.epochs.size()))
    deepnav::fuzz::broken_promise("a read file without epochs, or a report that miscounts them");
  if (!std::isfinite(f.report.nominal_interval_s) || f.report.nominal_interval_s < 0.0)
    deepnav::fuzz::broken_promise("a nominal interval that is negative or not finite");
  for (std::size_t i = 0; i < f.epochs.size(); ++i) {
    const deepnav::ObservationEpoch& e = f.epochs[i];
    if (i > 0 && !(e.t.seconds_since(f.epochs[i - 1].t) > 0.0))
      deepnav::fuzz::broken_promise("epoch times do not increase");
    for (const deepnav::GpsL1Observation& o : e.gps)
      if (o.prn < 1 || o.prn > 32 || !finite(o.pseudorange_m) || !finite(o.carrier_phase_cycles) ||
          !finite(o.doppler_hz) || !finite(o.cn0_dbhz))
        deepnav::fuzz::broken_promise("a GPS observation out of range or not finite");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr const char* kName = "fuzz.obs";
  std::istringstream in(deepnav::fuzz::as_text(data, size));
  deepnav::ObservationFile f;
  if (deepnav::fuzz::guarded([&] { f = deepnav::read_rinex_obs(in, kName); }, deepnav::fuzz::names_input(kName)))
    check_promises(f);
  return 0;
}
