// FP24 field access, DAZ flushing and the one rounding rule of docs/fp24.md,
// shared by every operation of the model (fp24_arith*.cpp, fp24_func.cpp),
// the ISS (through fp24_arith_inline.hpp) and the host's conversion
// (fp24_convert.cpp). Header-only, integer arithmetic only.
//
// Rounding contract: round_sig() is the rule, the only place in C++ where a
// result is rounded; round() is the same with the ports of
// apu_rtl/fp24_round.sv (a nonzero value (-1)^s * 1.frac * 2^(exp - kBias)
// with an unbounded biased exponent, its guard bit and its sticky bit). Both
// apply steps 2-5 of the rounding rule: RNE to 17 bits, overflow, tininess
// after rounding, NX. A unit computes its exact result (or a truncation of it
// with every lost nonzero bit OR-ed into a sticky bit) as a normalized
// significand of any width and hands it to round_sig() (or to round_pack(),
// the 1.63 form). tests/fp24_round_test.cpp proves round() equal to the
// verilated fp24_round on every input.
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

// The rounding rule, steps 2-5, on a normalized significand of any width:
// q holds (-1)^s * 1.f * 2^(exp - kBias), its leading one at bit
// kDrop + kFracBits, the 16 fraction bits above bit kDrop and kDrop bits of
// tail below them (the guard at kDrop - 1, the sticky bits under it; bit 63
// clear, so that adding half cannot overflow). exp is
// biased and unbounded (|exp| < 2^15); s is the sign bit in place (0 or
// kSignBit).
// 1. round to nearest, ties to even: adding half - 1 plus the fraction's lsb
//    to q carries into the lsb exactly when the tail is above half, or is
//    half and the lsb is odd; sig is then the rounded 17-bit significand, or
//    2^17 when 1.1...1 + ulp carried into 10.0...0;
// 2. the exponent and the significand as one number, (exp - 1) * 2^16 + sig:
//    the hidden bit adds the 1 back and a carry moves the exponent up; it is
//    then the magnitude's encoding;
// 3. rounded exponent >= 127: +-inf, OF|NX;
// 4. rounded exponent <= 0 (tiny after rounding: a value rounded up to
//    exactly 2^-62 has exponent 1 and is not tiny): +-0, UF|NX;
// 5. otherwise the encoding, NX if the tail is not zero.
// Steps 3 and 4 are one unsigned compare on the hot path. No assert here:
// the ISS calls it on every MUL, ADD and SUB, and Release keeps asserts.
template <int kDrop>
[[gnu::always_inline]] inline Result round_sig(Bits s, int exp, std::uint64_t q) {
  static_assert(kDrop >= 2 && kDrop + kFracBits <= 62, "a guard, a sticky, and q + half in 64 bits");
  constexpr std::uint64_t kHalf = std::uint64_t{1} << (kDrop - 1);
  const auto sig = static_cast<std::int32_t>((q + (kHalf - 1) + ((q >> kDrop) & 1)) >> kDrop);
  const std::int32_t mag = (exp - 1) * (1 << kFracBits) + sig;
  constexpr std::uint32_t kMinNormal = 1u << kFracBits;
  if (__builtin_expect(static_cast<std::uint32_t>(mag) - kMinNormal >= kPosInf - kMinNormal, 0)) {
    if (mag >= static_cast<std::int32_t>(kPosInf)) return {s | kPosInf, static_cast<std::uint8_t>(kOF | kNX)};
    return {s, static_cast<std::uint8_t>(kUF | kNX)};
  }
  const bool inexact = (q & (2 * kHalf - 1)) != 0;
  return {s | static_cast<Bits>(mag), static_cast<std::uint8_t>(inexact ? kNX : 0)};
}

// The same rule with fp24_round.sv's ports: sign bit s, biased unbounded
// exp, the 16-bit frac below the leading one, the guard bit and the sticky
// bit (the OR of every bit below the guard). It is round_sig() with a
// two-bit tail, guard and sticky; tests/fp24_round_test.cpp proves it equal
// to the verilated fp24_round on every input, and round_sig() of every
// width in use equal to it.
[[gnu::always_inline]] inline Result round(Bits s, int exp, std::uint32_t frac, bool guard, bool sticky) {
  const std::uint64_t q = (std::uint64_t{kHidden | frac} << 2) | (std::uint64_t{guard} << 1) | std::uint64_t{sticky};
  return round_sig<2>(s, exp, q);
}

// round_sig() of the 1.63 form (bit 63 of m set), as normalize() gives it:
// shifted down one bit, the bit shifted out OR-ed into the sticky bits.
inline Result round_pack(bool s, int e, std::uint64_t m) {
  assert(m >> 63);
  return round_sig<62 - kFracBits>(signed_zero(s), e, (m >> 1) | (m & 1));
}

}  // namespace mc1::fp24::bits
