#include "tools/cli/cli_checks.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace deepnav::cli {
namespace {

CLI::Validator finite_check(double lo, double hi, bool lo_open, const std::string& what) {
  const std::string range = fmt::format("{}{:g}, {:g}]", lo_open ? "(" : "[", lo, hi);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || errno == ERANGE)
          return fmt::format("'{}' is not a finite number ({} in {})", text, what, range);
        if (v < lo || v > hi || (lo_open && v == lo)) return fmt::format("{} is outside {} ({})", text, range, what);
        return {};
      },
      fmt::format("{} in {}", what, range));
}

}  // namespace

CLI::Validator finite_in(double lo, double hi, const std::string& what) { return finite_check(lo, hi, false, what); }
CLI::Validator finite_above(double lo, double hi, const std::string& what) { return finite_check(lo, hi, true, what); }

}  // namespace deepnav::cli
