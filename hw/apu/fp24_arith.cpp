// Multiplier and adder-unit operations of the APU (docs/fp24.md, "Operations").
// mul, add, sub and cmp are the inline functions of fp24_arith_inline.hpp
// (the ISS calls those directly); here are their cold special cases and the
// other adder-unit ops.
#include <algorithm>
#include <cstdint>

#include "fp24.hpp"
#include "fp24_arith_inline.hpp"
#include "fp24_bits.hpp"

namespace mc1::fp24 {
namespace {

using bits::flush;
using bits::is_inf;
using bits::is_nan;
using bits::is_zero;
using bits::sign_of;
using bits::signed_inf;
using bits::signed_zero;

constexpr Result kNaN{kCanonicalNaN, 0};
constexpr Result kInvalidNaN{kCanonicalNaN, kNV};

Result exact(Bits v) { return {v, 0}; }

// FIX saturation value, NV: the integer limit on the operand's side.
Result fix_invalid(bool negative) { return {negative ? 0x8000u : 0x7FFFu, kNV}; }

}  // namespace

namespace detail {

// Multiplier: some operand is a zero, infinity or NaN (after DAZ).
Result mul_special(Bits a, Bits b) {
  if (is_nan(a) || is_nan(b)) return kNaN;
  const bool s = sign_of(a) != sign_of(b);
  if (is_inf(a) || is_inf(b)) return (is_zero(a) || is_zero(b)) ? kInvalidNaN : exact(signed_inf(s));
  return exact(signed_zero(s));
}

// Adder: some operand is a zero, infinity or NaN (after DAZ); b already carries
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

}  // namespace detail

Result mul(Bits a, Bits b) { return inl::mul(a, b); }
Result add(Bits a, Bits b) { return inl::add(a, b); }
Result sub(Bits a, Bits b) { return inl::sub(a, b); }
Result cmp(Bits a, Bits b) { return inl::cmp(a, b); }

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
