// Multiplier and adder-unit operations of the APU (docs/fp24.md, "Operations").
// Each op checks for "both operands normal" first and otherwise hands off to
// a cold special-case routine, so the common path is a few integer ops and
// one call to the shared rounding rule (fp24_bits.hpp).
#include <algorithm>
#include <cstdint>
#include <utility>

#include "fp24.hpp"
#include "fp24_bits.hpp"

namespace mc1::fp24 {
namespace {

using bits::flush;
using bits::is_inf;
using bits::is_nan;
using bits::is_normal;
using bits::is_zero;
using bits::sign_of;
using bits::signed_inf;
using bits::signed_zero;

constexpr Result kNaN{kCanonicalNaN, 0};
constexpr Result kInvalidNaN{kCanonicalNaN, kNV};

Result exact(Bits v) { return {v, 0}; }

// --- Multiplier -----------------------------------------------------------

// Some operand is a zero, infinity or NaN (after DAZ).
Result mul_special(Bits a, Bits b) {
  if (is_nan(a) || is_nan(b)) return kNaN;
  const bool s = sign_of(a) != sign_of(b);
  if (is_inf(a) || is_inf(b)) return (is_zero(a) || is_zero(b)) ? kInvalidNaN : exact(signed_inf(s));
  return exact(signed_zero(s));
}

// --- Adder ----------------------------------------------------------------

// Some operand is a zero, infinity or NaN (after DAZ); b already carries
// the sign it is added with.
Result add_special(Bits a, Bits b) {
  if (is_nan(a) || is_nan(b)) return kNaN;
  if (is_inf(a) && is_inf(b)) return sign_of(a) == sign_of(b) ? exact(a) : kInvalidNaN;
  if (is_inf(a)) return exact(a);
  if (is_inf(b)) return exact(b);
  // Exact zero sum: -0 only when both zeros are -0 (covers (-0) - (+0)).
  if (is_zero(a) && is_zero(b)) return exact(signed_zero(sign_of(a) && sign_of(b)));
  // x + 0 = x exactly: x is normal, so it needs no rounding.
  return exact(is_zero(a) ? b : a);
}

// Sum of two normal numbers of any sign. Significands are placed at bit 40
// (msb at 56) so that an alignment shift of up to 40 loses nothing and a
// larger one is caught by the sticky bit; the result msb stays at >= 55
// whenever bits were lost, far above the sticky bit.
Result add_normal(Bits a, Bits b) {
  constexpr int kPos = 40;
  // Order by magnitude so the difference of significands is never negative.
  if ((b & bits::kMagMask) > (a & bits::kMagMask)) std::swap(a, b);
  const int d = std::min(bits::exp_of(a) - bits::exp_of(b), 63);
  const std::uint64_t big = std::uint64_t{bits::sig_of(a)} << kPos;
  const std::uint64_t small_full = std::uint64_t{bits::sig_of(b)} << kPos;
  std::uint64_t small = small_full >> d;
  small |= (small << d) != small_full;  // sticky
  const std::uint64_t m = sign_of(a) == sign_of(b) ? big + small : big - small;
  if (m == 0) return exact(0);  // x + (-x) = +0
  // big stands for 2^(ea - kBias) * big / 2^(kPos + 16).
  const auto n = bits::normalize(m, bits::exp_of(a) - kBias - kPos - kFracBits);
  return bits::round_pack(sign_of(a), n.exp, n.sig);
}

// Condition of a versus b, both non-NaN after DAZ.
Cond compare_ordered(Bits a, Bits b) {
  // Signed magnitudes order like the values; zeros of either sign map to 0.
  const auto key = [](Bits x) {
    const auto mag = static_cast<std::int32_t>(x & bits::kMagMask);
    return sign_of(x) ? -mag : mag;
  };
  const std::int32_t ka = key(a), kb = key(b);
  return ka < kb ? kLT : (ka == kb ? kEQ : kGT);
}

// FIX saturation value, NV: the integer limit on the operand's side.
Result fix_invalid(bool negative) { return {negative ? 0x8000u : 0x7FFFu, kNV}; }

}  // namespace

Result mul(Bits a, Bits b) {
  a &= bits::kMask24;
  b &= bits::kMask24;
  if (!(is_normal(a) && is_normal(b))) return mul_special(flush(a), flush(b));
  // Product of two 17-bit significands: 2^32 <= p < 2^34, exact in 64 bits.
  const std::uint64_t p = std::uint64_t{bits::sig_of(a)} * bits::sig_of(b);
  const int k = bits::exp_of(a) + bits::exp_of(b) - 2 * kBias - 2 * kFracBits;
  const auto n = bits::normalize(p, k);
  return bits::round_pack(sign_of(a) != sign_of(b), n.exp, n.sig);
}

Result add(Bits a, Bits b) {
  a &= bits::kMask24;
  b &= bits::kMask24;
  if (!(is_normal(a) && is_normal(b))) return add_special(flush(a), flush(b));
  return add_normal(a, b);
}

// a - b is a + (-b) exactly, signed zeros included: (-0) - (+0) = (-0) + (-0).
// Flipping the sign of a NaN leaves a NaN, which add() turns canonical.
Result sub(Bits a, Bits b) { return add(a, b ^ kSignBit); }

Result cmp(Bits a, Bits b) {
  a = flush(a);
  b = flush(b);
  if (is_nan(a) || is_nan(b)) return {kUN, kNV};
  return exact(compare_ordered(a, b));
}

Result from_int(std::uint16_t i) {
  if (i == 0) return exact(0);
  const bool s = (i & 0x8000) != 0;
  // Magnitude of a two's-complement int16: 1..32768, exact in 17 bits.
  const std::uint32_t mag = s ? 0x10000u - i : i;
  const auto n = bits::normalize(mag, 0);
  return bits::round_pack(s, n.exp, n.sig);
}

Result to_int(Bits a) {
  a = flush(a);
  if (is_nan(a)) return {0x7FFF, kNV};
  if (is_zero(a)) return exact(0);
  const bool s = sign_of(a);
  // |a| >= 2^16 (infinity included) cannot fit whatever the sign.
  const int e = bits::exp_of(a);
  if (e >= kBias + kFracBits) return fix_invalid(s);
  // |a| = sig * 2^-(shift); shift >= 17 leaves only a fraction (clamped so
  // the shift stays defined).
  const int shift = std::min(kBias + kFracBits - e, 31);
  const std::uint32_t sig = bits::sig_of(a);
  const std::uint32_t mag = sig >> shift;
  const bool dropped = (mag << shift) != sig;
  if (mag > (s ? 0x8000u : 0x7FFFu)) return fix_invalid(s);
  const std::uint32_t value = (s ? 0x10000u - mag : mag) & 0xFFFFu;
  return {value, static_cast<std::uint8_t>(dropped ? kNX : 0)};
}

Result neg(Bits a) {
  a = flush(a);
  return is_nan(a) ? kNaN : exact(a ^ kSignBit);
}

Result abs(Bits a) {
  a = flush(a);
  return is_nan(a) ? kNaN : exact(a & ~kSignBit & bits::kMask24);
}

}  // namespace mc1::fp24
