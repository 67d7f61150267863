#include "tools/cli/cli_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "tools/cli/commands.hpp"

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

std::vector<GnssSystem> parse_systems_option(const std::string& text) {
  std::vector<GnssSystem> systems;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string name = text.substr(begin, end - begin);
    const auto system = parse_system_name(name);
    if (!system)
      throw UserError(
          fmt::format("--systems {}: unknown system '{}' (expected gps and/or galileo, comma-separated)", text, name));
    if (std::find(systems.begin(), systems.end(), *system) != systems.end())
      throw UserError(fmt::format("--systems {}: '{}' is listed twice", text, name));
    systems.push_back(*system);
    begin = end + 1;
  }
  return systems;
}

void add_systems_option(CLI::App& cmd, std::vector<GnssSystem>& systems) {
  cmd.add_option_function<std::string>(
         "--systems", [&systems](const std::string& text) { systems = parse_systems_option(text); },
         "gps or gps,galileo: the systems the receiver tracks (the scenario must carry them)")
      ->default_str("gps");
}

}  // namespace deepnav::cli
