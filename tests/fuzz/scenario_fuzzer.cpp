// Scenario files (signals/sim/scenario.hpp): parsed and validated as `deepnav sim` does,
// then written back (scenario_to_yaml, stored beside every synthesis), which must parse
// again. Relative paths resolve against the source tree, so data/brdc0010.22n is there.
#include "signals/sim/scenario.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

constexpr const char* kName = "fuzz_scenario.yaml";

void round_trip(const deepnav::Scenario& scenario) {
  const std::string text = deepnav::scenario_to_yaml(scenario);
  try {
    deepnav::validate_scenario(deepnav::parse_scenario(text, "written", DEEPNAV_SOURCE_DIR, DEEPNAV_SOURCE_DIR));
  } catch (const std::exception& e) {
    deepnav::fuzz::finding(e, "a valid scenario, written back, does not read");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = deepnav::fuzz::as_text(data, size);
  deepnav::Scenario scenario;
  if (!deepnav::fuzz::guarded(
          [&] { scenario = deepnav::parse_scenario(text, kName, DEEPNAV_SOURCE_DIR, DEEPNAV_SOURCE_DIR); },
          deepnav::fuzz::names_input(kName)))
    return 0;
  // Cross-field checks name the field (the file was named above).
  if (deepnav::fuzz::guarded([&] { deepnav::validate_scenario(scenario); }, deepnav::fuzz::is_a<std::invalid_argument>))
    round_trip(scenario);
  return 0;
}
