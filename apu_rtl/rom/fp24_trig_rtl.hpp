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
// Table of {sin, pi/2 cos} at i/256 quarter turns, i = 0..256: a cosine at
// index j reads entry 256 - j (cos(pi j/512) = sin(pi (256 - j)/512)).
constexpr int kTableEntries = (1 << kIndexBits) + 1;
constexpr int kTabFrac = 52;   // A = S_i: 1.52
constexpr int kHalfFrac = 44;  // B = pi/2 C_i: 1.44
// The datapath's fixed-point formats (docs/fp24-func.md "SIN and COS
// (RTL)"); every multiply at most 38 x 37 bits (or 45 x 22), so that every
// stage fits the adder's depth. phi and phi_u have scale 2^-53 quarter
// turns; the others are named by the power of two of their bit 0.
constexpr int kUsqDrop = 8;    // phi_u' = phi_u >> 8: 36 bits, 2^-45; phi_u'^2: 2^-90
constexpr int kUDrop = 34;     // U = phi_u'^2 >> 34: 38 bits, 2^-56 (quarter turns squared)
constexpr int kUtDrop = 12;    // U >> 12: 26 bits, 2^-44, times K3
constexpr int kK3Frac = 26;    // K3 = k3 in 0.26
constexpr int kTsDrop = 22;    // T_s = (U_t K3) >> 22: 2^-48
constexpr int kUwDrop = 20;    // U >> 20: 18 bits, 2^-36, times K4
constexpr int kK4Frac = 20;    // K4 = k4 in 0.20
constexpr int kK4uDrop = 20;   // (U_w K4) >> 20: 2^-36
constexpr int kK2Frac = 36;    // K2 = k2 in 1.36; w = K2 - k4 u: 2^-36
constexpr int kTcDrop = 38;    // T_c = (U w) >> 38: 2^-54
constexpr int kPhiQDrop = 18;  // phi >> 18: 26 bits, 2^-35, times T_s
constexpr int kQDrop = 27;     // q = (phi_q T_s) >> 27: 2^-56
constexpr int kPhiSplit = 22;  // P1 = B phi as B phi_hi 2^22 + B phi_lo
constexpr int kP1Drop = 45;    // Z = (A 2^45 +- P1) >> 45: 1.52
constexpr int kATabDrop = 15;  // A >> 15: 1.37, times T_c
constexpr int kAtDrop = 39;    // A T_c >> 39: 2^-52
constexpr int kBqTabDrop = 19; // B >> 19: 1.25, times q
constexpr int kBqDrop = 29;    // B q >> 29: 2^-52
// The result: a 53-bit significand, 36 bits below the FP24 one.
constexpr int kSigBits = 53;
constexpr int kDropBits = kSigBits - 17;
// Within kHardMargin units (of bit 0 of the 53-bit significand) of a
// rounding midpoint the error bound (docs/fp24-func.md) cannot decide.
constexpr std::uint64_t kHardMargin = std::uint64_t{1} << 15;

struct Tables {
  std::array<u128, kWindows> window;
  std::array<std::uint64_t, kTableEntries> sin_tab;   // S_i, 1.52
  std::array<std::uint64_t, kTableEntries> hcos_tab;  // pi/2 C_i, 1.44
  std::uint64_t k2;  // (pi/2)^2/2, 1.36
  std::uint64_t k3;  // (pi/2)^2/6, 0.26
  std::uint64_t k4;  // (pi/2)^4/24, 0.20
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
