#pragma once
// Integer division rounding toward minus infinity: the chunk, table or segment that a
// sample or draw index falls in, for indices before zero too (a filter's history, a
// jammer starting before the block).
#include <cstdint>

namespace deepnav {

inline std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0))); }

}  // namespace deepnav
