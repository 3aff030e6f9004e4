// SIN/COS as the RTL computes them (apu_rtl/fp24_func_trig.sv,
// docs/fp24-func.md "SIN and COS (RTL)"): the C++ twin of the pipeline, bit
// for bit, that the ROM generator runs on every input to find the inputs it
// cannot round (the hard cases) and to prove that it rounds all others as the
// model does. Like the RECIP/SQRT seed table it serves only the RTL: the
// model (hw/apu/fp24_trig.cpp) keeps its 64-bit algorithm, and the two agree
// on every input because both round correctly.
#pragma once

#include <array>
#include <cstdint>

namespace mc1::fp24::trig_rtl {

using u128 = unsigned __int128;

// Windows of 2/pi, kWinBits each: one per unbiased exponent kMinExp..63
// (index E - kMinExp) and, at index kDirect, the leading bits of 2/pi for
// the inputs below 2^kMinExp, which are scaled rather than reduced.
constexpr int kMinExp = -9;
constexpr int kMaxExp = 63;
constexpr int kWinBits = 90;
constexpr int kDirect = kMaxExp - kMinExp + 1;
constexpr int kWindows = kDirect + 1;
// x * 2/pi mod 4 keeps kWinBits - 2 fraction bits; the table index takes 8.
constexpr int kFracBits = kWinBits - 2;
constexpr int kIndexBits = 8;
// Bits of the remainder below the index, and how many of them the
// polynomial keeps (phi, a 44-bit significand).
constexpr int kRemBits = kFracBits - kIndexBits - 1;  // |delta| < 2^79
constexpr int kPhiBits = 44;
constexpr int kPhiDrop = kRemBits - kPhiBits;         // 35
constexpr int kMaxNorm = 31;                           // largest left shift of a small |delta|
// Table of sin, cos at j/256 quarter turns, j = 0..128.
constexpr int kTableEntries = (1 << (kIndexBits - 1)) + 1;
constexpr int kTabFrac = 52;   // S_j, C_j: 1.52
constexpr int kTabHiDrop = 16; // their top 1.36 multiply T_c
constexpr int kHalfFrac = 44;  // pi/2 * S_j, pi/2 * C_j: 1.44
// Polynomial constants (k2 = (pi/2)^2/2, k3 = (pi/2)^2/6, k4 = (pi/2)^4/24).
constexpr int kKFrac = 40;
constexpr int kK4Frac = 24;
// The result: a 53-bit significand, 36 bits below the FP24 one.
constexpr int kSigBits = 53;
constexpr int kDropBits = kSigBits - 17;
// Within kHardMargin units (of bit 0 of the 53-bit significand) of a
// rounding midpoint the error bound (docs/fp24-func.md) cannot decide.
constexpr std::uint64_t kHardMargin = std::uint64_t{1} << 15;

struct Tables {
  std::array<u128, kWindows> window;
  std::array<std::uint64_t, kTableEntries> sin_tab, cos_tab;    // 1.52
  std::array<std::uint64_t, kTableEntries> hsin_tab, hcos_tab;  // 1.44, times pi/2
  std::uint64_t k2, k3;  // 1.40
  std::uint64_t k4;      // 0.24
};

// |y| ~= sig * 2^(exp - 52), sig with bit 52 set.
struct Approx {
  bool neg;
  int exp;
  std::uint64_t sig;
};

// a: FP24 encoding with 1 <= e <= 126. Throws std::logic_error if an
// internal range assumption (documented in the source) fails.
Approx approximate(bool is_cos, std::uint32_t a, const Tables& t);

inline std::uint64_t midpoint_distance(const Approx& y) {
  constexpr std::uint64_t kMid = std::uint64_t{1} << (kDropBits - 1);
  const std::uint64_t low = y.sig & ((std::uint64_t{1} << kDropBits) - 1);
  return low > kMid ? low - kMid : kMid - low;
}

}  // namespace mc1::fp24::trig_rtl
