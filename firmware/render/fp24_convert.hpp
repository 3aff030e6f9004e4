// RC-side conversion between the host scene's doubles and FP24 encodings
// (docs/fp24.md), done once before the broadcast. Integer bit manipulation of
// the IEEE binary64 encoding only: the same rounding rule as every FP24 op
// (round to 17 significant bits, nearest, ties to even; overflow to inf;
// tiny after rounding to a signed zero).
#pragma once

#include <cstdint>

namespace mc1::render {

std::uint32_t fp24_from_double(double x);
// Exact: every FP24 value is a double. For host-side checks and reports.
double fp24_to_double(std::uint32_t bits);

}  // namespace mc1::render
