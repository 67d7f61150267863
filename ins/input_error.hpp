#pragma once
// The one error type for a wrong input a user gave: a flag, a file, a configuration key, a
// stream's address. Its message says which input and what was expected, so the command line
// prints it as it is ("deepnav: <message>", exit 1); any other exception is reported as an
// error of the program. Defined at the bottom layer so that every library can throw it.
#include <stdexcept>
#include <string>

namespace deepnav {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace deepnav
