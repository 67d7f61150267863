// Sample format names (signals/sample_format.hpp, parse_sample_format): every name that
// parses must print back (to_string) as a name that parses to the same format.
#include "signals/sample_format.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string name = deepnav::fuzz::as_text(data, size);
  deepnav::SampleFormat format;
  if (!deepnav::fuzz::guarded([&] { format = deepnav::parse_sample_format(name); },
                              deepnav::fuzz::is_a<std::invalid_argument>))
    return 0;
  const std::string canonical = deepnav::to_string(format);
  if (!(deepnav::parse_sample_format(canonical) == format))
    deepnav::fuzz::broken_promise("'" + name + "' prints as '" + canonical + "', which names another format");
  return 0;
}
