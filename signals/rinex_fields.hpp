#pragma once
// Fixed-column fields of RINEX files (observation and navigation alike): a column cut
// from a line, blanks trimmed, and Fortran-style numbers (D or E exponents). Errors are
// bare messages; the reader adds the file, line and field it was reading.
#include <cstddef>
#include <optional>
#include <string_view>

namespace deepnav::rinex {

/// Columns [start, start + width) of `line`, shorter or empty where the line ends first.
std::string_view column(std::string_view line, std::size_t start, std::size_t width);

/// `s` without leading and trailing blanks.
std::string_view trim(std::string_view s);

/// A number, or nullopt for a blank field; throws std::invalid_argument for anything else
/// that is not a finite number (letters, "nan", "inf", hex floats, embedded blanks).
std::optional<double> parse_number(std::string_view field);

}  // namespace deepnav::rinex
