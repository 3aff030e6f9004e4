// SIN/COS approximation core of the function unit (docs/fp24-func.md).
//
// This is the part of the algorithm that both the model (fp24_func.cpp) and
// the ROM generator (apu_rtl/rom/fp24_romgen.cpp) run: the generator calls it
// on every input to find the hard cases, the model calls it and then consults
// the hard-case ROM the generator wrote. Its constants come in through
// `Tables` so that the generator can make them in memory first: no build
// cycle between the generator and the model.
//
// Integer arithmetic only; apu_rtl/fp24_func.sv does the same steps bit for bit.
#pragma once

#include <cstdint>

namespace mc1::fp24::trig {

// A 128-bit constant as the ROM holds it.
struct Word128 {
  std::uint64_t hi;
  std::uint64_t lo;
};

// Range reduction by 2/pi (Payne-Hanek) serves every input with unbiased
// exponent >= kReduceMinExp (|x| >= 0.5); smaller inputs are their own
// reduced argument. One 128-bit window of 2/pi per exponent.
constexpr int kReduceMinExp = -1;
constexpr int kReduceMaxExp = 63;
constexpr int kWindowCount = kReduceMaxExp - kReduceMinExp + 1;
constexpr int kWindowBits = 128;
// Bits of 2/pi after the binary point that the windows reach into.
constexpr int kTwoOverPiBits = kReduceMaxExp - 16 - 2 + kWindowBits;

// Taylor terms u^1..u^kTerms of sin(z)/z and cos(z) in u = z^2.
constexpr int kTerms = 8;

// The result significand keeps 64 bits, the FP24 significand its top 17:
// bits 46..0 decide the rounding, and 2^46 is the rounding midpoint.
constexpr int kDropBits = 47;
// An approximation within kHardMargin (in units of bit 0 of the 64-bit
// significand) of the midpoint is a hard case: its error bound (< 2^7 units,
// docs/fp24-func.md) cannot decide the rounding, so the ROM supplies it.
constexpr std::uint64_t kHardMargin = std::uint64_t{1} << 20;

struct Tables {
  const Word128* two_over_pi;       // [kWindowCount]; [E - kReduceMinExp] for exponent E
  std::uint64_t half_pi;            // pi/2 in 1.63 fixed point, rounded
  const std::uint64_t* sin_coef;    // [kTerms]: 1/(2k+1)! in 0.64, k = 1..kTerms
  const std::uint64_t* cos_coef;    // [kTerms]: 1/(2k)!   in 0.64, k = 1..kTerms
};

// Unrounded SIN/COS of a finite nonzero input: |y| ~= sig * 2^(exp - 63),
// sig normalized (bit 63 set); exp is unbiased. The true value is never a
// representable number or a midpoint (y is transcendental), so the rounding
// always has sticky = 1.
struct Approx {
  bool neg;
  int exp;
  std::uint64_t sig;
};

// a: FP24 encoding with 1 <= e <= 126 (the caller handles zero/inf/NaN).
Approx approximate(bool is_cos, std::uint32_t a, const Tables& t);

// Distance of the approximation from the rounding midpoint in bit-0 units
// (what the hard-case search compares with kHardMargin).
inline std::uint64_t midpoint_distance(const Approx& y) {
  constexpr std::uint64_t kMid = std::uint64_t{1} << (kDropBits - 1);
  const std::uint64_t low = y.sig & ((std::uint64_t{1} << kDropBits) - 1);
  return low > kMid ? low - kMid : kMid - low;
}

}  // namespace mc1::fp24::trig
