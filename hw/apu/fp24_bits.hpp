// FP24 field access, DAZ flushing and the one rounding rule of docs/fp24.md,
// shared by the multiplier/adder model (fp24_arith.cpp) and the function unit.
// Header-only, integer arithmetic only.
//
// Rounding contract: a unit computes its exact result (or a truncation of it
// with every lost nonzero bit OR-ed into bit 0, "sticky") as a normalized
// significand m in 1.63 fixed point (bit 63 set) and a biased exponent e, so
// that |r| = 2^(e - kBias) * m / 2^63. round_pack() then applies steps 2-5 of
// the rounding rule: RNE to 17 bits with an unbounded exponent, overflow,
// tininess after rounding. Jamming sticky into bit 0 is exact enough because
// the rounding point is 46 bits higher: the jammed and the true value always
// share the same RNE result and the same inexactness.
#pragma once

#include <cassert>
#include <cstdint>

#include "fp24.hpp"

namespace mc1::fp24::bits {

constexpr Bits kMask24 = 0xFFFFFF;
constexpr Bits kFracMask = 0xFFFF;
constexpr Bits kMagMask = 0x7FFFFF;
constexpr int kExpMax = 127;  // e of infinities and NaNs
constexpr std::uint32_t kHidden = 1u << kFracBits;

inline bool sign_of(Bits a) { return (a & kSignBit) != 0; }
inline int exp_of(Bits a) { return static_cast<int>((a >> kFracBits) & 0x7F); }
inline Bits frac_of(Bits a) { return a & kFracMask; }
// 17-bit significand 1.f of a normal number.
inline std::uint32_t sig_of(Bits a) { return kHidden | frac_of(a); }

inline bool is_nan(Bits a) { return exp_of(a) == kExpMax && frac_of(a) != 0; }
inline bool is_inf(Bits a) { return (a & kMagMask) == kPosInf; }
// DAZ: every zero-exponent encoding reads as a signed zero.
inline bool is_zero(Bits a) { return exp_of(a) == 0; }
// Biased exponent in 1..126; one unsigned compare keeps the hot path short.
inline bool is_normal(Bits a) { return static_cast<unsigned>(exp_of(a) - 1) < 126u; }

inline Bits signed_zero(bool s) { return s ? kSignBit : 0; }
inline Bits signed_inf(bool s) { return signed_zero(s) | kPosInf; }
// Inputs are flushed (DAZ) and outputs with e = 0 always carry f = 0.
inline Bits flush(Bits a) {
  a &= kMask24;
  return is_zero(a) ? (a & kSignBit) : a;
}

inline int clz64(std::uint64_t m) {
  assert(m != 0);
  return __builtin_clzll(m);
}

// A nonzero value m * 2^k (any k) as the (e, 1.63) pair round_pack() takes:
// biased exponent e = 63 - clz + k + kBias and m shifted so bit 63 is set.
struct Normalized {
  int exp;
  std::uint64_t sig;
};
inline Normalized normalize(std::uint64_t m, int k) {
  const int lz = clz64(m);
  return {63 - lz + k + kBias, m << lz};
}

// Steps 2-5 of the rounding rule. Requires bit 63 of m set (see file comment).
inline Result round_pack(bool s, int e, std::uint64_t m) {
  assert(m >> 63);
  constexpr int kDrop = 63 - kFracBits;  // bits below the 17-bit significand
  constexpr std::uint64_t kRemMask = (std::uint64_t{1} << kDrop) - 1;
  constexpr std::uint64_t kHalf = std::uint64_t{1} << (kDrop - 1);
  std::uint32_t sig = static_cast<std::uint32_t>(m >> kDrop);
  const std::uint64_t rem = m & kRemMask;
  const bool up = rem > kHalf || (rem == kHalf && (sig & 1));
  sig += up;
  // Carry out of 1.1111...1 gives exactly 2.0: renormalize, exponent + 1.
  const int carry = static_cast<int>(sig >> (kFracBits + 1));
  sig >>= carry;
  e += carry;
  const std::uint8_t nx = rem != 0 ? kNX : 0;
  if (e > 126) return {signed_inf(s), static_cast<std::uint8_t>(kOF | kNX)};
  // Tiny after rounding: a value that rounded up to 2^-62 has e = 1 here.
  if (e < 1) return {signed_zero(s), static_cast<std::uint8_t>(kUF | kNX)};
  const Bits enc = signed_zero(s) | (static_cast<Bits>(e) << kFracBits) | (sig & kFracMask);
  return {enc, nx};
}

}  // namespace mc1::fp24::bits
