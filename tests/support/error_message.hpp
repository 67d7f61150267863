#pragma once
// The message of the exception a call throws, or "" when it throws none: what the tests of
// bad input compare with the expected wording.
#include <exception>
#include <functional>
#include <string>

namespace deepnav::testing {

inline std::string error_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace deepnav::testing
