// The multiplier's and the adder unit's operations (docs/fp24.md,
// "Operations") as inline functions: fp24_arith.cpp's mul(), add(), sub() and
// cmp() are these, and the ISS calls them directly so that its hot loop has no
// call per FP op. One definition, so the model and the ISS cannot differ; the
// fp24 exhaustive and random regressions test it through either.
//
// Each op checks for "both operands normal" first; then for a zero with no
// infinity or NaN; anything else goes to a cold out-of-line routine.
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>

#include "fp24.hpp"
#include "fp24_bits.hpp"

namespace mc1::fp24 {
namespace detail {

// fp24_arith.cpp. Some operand is a zero, infinity or NaN (after DAZ); for
// add, b already carries the sign it is added with.
Result mul_special(Bits a, Bits b);
Result add_special(Bits a, Bits b);

// Sum of two normal numbers of any sign, by the general rule: exact sum
// (with sticky), normalize(), round_pack(). Significands are placed at bit 40
// (msb at 56) so that an alignment shift of up to 40 loses nothing and a
// larger one is caught by the sticky bit; the result msb stays at >= 55
// whenever bits were lost, far above the sticky bit. add_normal() must give
// the same bits and flags (tests/fp24_fast_path_test.cpp).
inline Result add_normal_generic(Bits a, Bits b) {
  constexpr int kPos = 40;
  // Order by magnitude so the difference of significands is never negative.
  if ((b & bits::kMagMask) > (a & bits::kMagMask)) std::swap(a, b);
  const int d = std::min(bits::exp_of(a) - bits::exp_of(b), 63);
  const std::uint64_t big = std::uint64_t{bits::sig_of(a)} << kPos;
  const std::uint64_t small_full = std::uint64_t{bits::sig_of(b)} << kPos;
  std::uint64_t small = small_full >> d;
  small |= (small << d) != small_full;  // sticky
  const std::uint64_t m = bits::sign_of(a) == bits::sign_of(b) ? big + small : big - small;
  if (m == 0) return {0, 0};  // x + (-x) = +0
  // big stands for 2^(ea - kBias) * big / 2^(kPos + 16).
  const auto n = bits::normalize(m, bits::exp_of(a) - kBias - kPos - kFracBits);
  return bits::round_pack(bits::sign_of(a), n.exp, n.sig);
}

// The same sum with no branch on the data but the rare ones (exact
// cancellation, overflow, tininess): which operand is larger, whether the
// signs differ and whether the rounding goes up are random to a branch
// predictor, and the ISS's hot loop paid a misprediction for each.
// No sticky bit: the alignment distance is clamped to kMaxShift, so the
// shift never loses a bit. That gives the same result as the true distance:
// for d >= 19 the smaller operand is below 2^38 (kPos = 40) while the sum's
// round bit is at 2^39 or higher (msb 55..57) and big has no bits below 2^40,
// so any nonzero small below 2^38 rounds the same way (down for a sum, up
// for a difference) and is inexact (tests/fp24_fast_path_test.cpp).
// Rounded by the one rule, bits::round_sig(), q's 46 bits below the
// significand its tail.
[[gnu::always_inline]] inline Result add_normal(Bits a, Bits b) {
  constexpr int kPos = 40;
  constexpr int kMaxShift = 24;  // any value in 19..kPos
  constexpr int kDrop = 46;      // q's bits below the 17-bit significand (msb at 62)
  const Bits swap = 0u - static_cast<Bits>((b & bits::kMagMask) > (a & bits::kMagMask));
  const Bits x = a ^ ((a ^ b) & swap), y = b ^ ((a ^ b) & swap);  // |x| >= |y|
  const int ex = bits::exp_of(x);
  const int d = std::min(ex - bits::exp_of(y), kMaxShift);
  const std::uint64_t big = std::uint64_t{bits::sig_of(x)} << kPos;
  const std::uint64_t small = (std::uint64_t{bits::sig_of(y)} << kPos) >> d;  // exact
  const std::uint64_t differ = 0 - static_cast<std::uint64_t>(((a ^ b) >> 23) & 1);
  const std::uint64_t m = big + ((small ^ differ) - differ);  // big - small if the signs differ
  if (__builtin_expect(m == 0, 0)) return {0, 0};           // x + (-x) = +0
  const int lz = __builtin_clzll(m);                         // 6..63; 7 when m's msb is big's
  const std::uint64_t q = m << (lz - 1);
  // Biased exponent of m: ex + 7 - lz.
  return bits::round_sig<kDrop>(x & kSignBit, ex + 7 - lz, q);
}

// Some operand is a zero, infinity or NaN (after DAZ). Without an infinity
// or NaN some operand is a zero, the frequent case (a product with a zero
// coordinate, a sum with one), settled here as the cold routines settle it:
// the product a zero of the signs' xor; the sum the other operand, exact, or
// for two zeros -0 only when both are. Operands within 24 bits; for add, b
// already carries the sign it is added with.
[[gnu::always_inline]] inline Result mul_not_normal(Bits a, Bits b) {
  if (__builtin_expect(bits::exp_of(a) != bits::kExpMax && bits::exp_of(b) != bits::kExpMax, 1))
    return {(a ^ b) & kSignBit, 0};
  return mul_special(bits::flush(a), bits::flush(b));
}

[[gnu::always_inline]] inline Result add_not_normal(Bits a, Bits b) {
  if (__builtin_expect(bits::exp_of(a) != bits::kExpMax && bits::exp_of(b) != bits::kExpMax, 1)) {
    if (!bits::is_zero(b)) return {b, 0};  // then a is the zero
    return {bits::is_zero(a) ? a & b & kSignBit : a, 0};
  }
  return add_special(bits::flush(a), bits::flush(b));
}

}  // namespace detail

namespace inl {

// Both operands normal (exponent 1..126) in two tests: adding 1 to the
// exponent field takes 0 and 127, and only them, to a field with bits 1..6
// clear (127 carries out of it).
[[gnu::always_inline]] inline bool both_normal(Bits a, Bits b) {
  constexpr Bits kOne = 1u << kFracBits, kTop = 0x7Eu << kFracBits;
  return ((a + kOne) & kTop) != 0 && ((b + kOne) & kTop) != 0;
}

// The ops on operands already within 24 bits (the ISS's registers always
// are): mul24, add24, sub24. mul, add, sub mask first.
[[gnu::always_inline]] inline Result mul24(Bits a, Bits b) {
  if (__builtin_expect(!both_normal(a, b), 0)) return detail::mul_not_normal(a, b);
  // Product of two 17-bit significands: 2^32 <= p < 2^34, exact in 64 bits;
  // q is p at [2^33, 2^34), its biased exponent ea + eb - kBias + hi, and
  // the one rule, bits::round_sig(), rounds it (the 17 bits below the
  // result's significand are its tail).
  const std::uint64_t p = std::uint64_t{bits::sig_of(a)} * bits::sig_of(b);
  const int hi = static_cast<int>(p >> (2 * kFracBits + 1));
  const std::uint64_t q = p << (hi ^ 1);
  return bits::round_sig<kFracBits + 1>((a ^ b) & kSignBit, bits::exp_of(a) + bits::exp_of(b) - kBias + hi, q);
}

[[gnu::always_inline]] inline Result add24(Bits a, Bits b) {
  if (__builtin_expect(!both_normal(a, b), 0)) return detail::add_not_normal(a, b);
  return detail::add_normal(a, b);
}

[[gnu::always_inline]] inline Result mul(Bits a, Bits b) { return mul24(a & bits::kMask24, b & bits::kMask24); }
[[gnu::always_inline]] inline Result add(Bits a, Bits b) { return add24(a & bits::kMask24, b & bits::kMask24); }

// a - b is a + (-b) exactly, signed zeros included: (-0) - (+0) = (-0) + (-0).
// Flipping the sign of a NaN leaves a NaN, which add() turns canonical.
[[gnu::always_inline]] inline Result sub(Bits a, Bits b) { return add(a, b ^ kSignBit); }
[[gnu::always_inline]] inline Result sub24(Bits a, Bits b) { return add24(a, b ^ kSignBit); }

// With no branch but the NaN test: magnitudes below 2^16 (e = 0) read as
// 0 (DAZ), a NaN is a magnitude above infinity's; signed magnitudes order
// like the values and the condition is 2 - LT + 2 GT.
[[gnu::always_inline]] inline Result cmp(Bits a, Bits b) {
  std::int32_t ma = static_cast<std::int32_t>(a & bits::kMagMask), mb = static_cast<std::int32_t>(b & bits::kMagMask);
  if (__builtin_expect(std::max(ma, mb) > static_cast<std::int32_t>(kPosInf), 0)) return {kUN, kNV};
  ma = ma < (1 << kFracBits) ? 0 : ma;
  mb = mb < (1 << kFracBits) ? 0 : mb;
  const std::int32_t sa = -static_cast<std::int32_t>((a >> 23) & 1), sb = -static_cast<std::int32_t>((b >> 23) & 1);
  const std::int32_t ka = (ma ^ sa) - sa, kb = (mb ^ sb) - sb;
  return {static_cast<Bits>(2 - (ka < kb) + 2 * (ka > kb)), 0};
}

}  // namespace inl
}  // namespace mc1::fp24
