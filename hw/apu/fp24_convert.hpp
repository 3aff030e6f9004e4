// Conversion between host doubles and FP24 encodings (docs/fp24.md): the
// RC's conversion of the scene, done once before the broadcast, and the
// Python module's float <-> FP24 (docs/library.md). Integer bit manipulation of
// the IEEE binary64 encoding only, rounded by the very function every FP24
// op's result goes through (bits::round(), fp24_bits.hpp: 17 significant
// bits, nearest, ties to even; overflow to inf; tiny after rounding to a
// signed zero).
#pragma once

#include <cstdint>
#include <string>

namespace mc1::fp24 {

std::uint32_t fp24_from_double(double x);
// Exact: every FP24 value is a double. For host-side checks and reports.
double fp24_to_double(std::uint32_t bits);
// A word as a person reads it, for reports and waveforms: the fewest
// decimal digits that read back to the same word ("0.1", "-3", "inf",
// "nan"); "0 (DAZ)" or "-0 (DAZ)" for a zero exponent with a fraction (the
// APU reads it as zero).
std::string fp24_decimal(std::uint32_t bits);

}  // namespace mc1::fp24

namespace mc1::render {  // the renderer's names for them (firmware/render/scene_image.cpp)
using fp24::fp24_from_double;
using fp24::fp24_to_double;
}  // namespace mc1::render
