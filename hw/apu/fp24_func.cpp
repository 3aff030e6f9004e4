// Function-unit operations of the APU: RECIP, SQRT, SIN, COS
// (docs/fp24.md; algorithms and error analysis in docs/fp24-func.md).
// RECIP and SQRT are an exact integer quotient / square root plus a sticky
// remainder, so they are correctly rounded by construction. SIN and COS are
// the fixed-point core of fp24_trig.cpp plus the generator's hard-case ROM.
#include <algorithm>
#include <cmath>

#include "fp24.hpp"
#include "fp24_bits.hpp"
#include "fp24_rom.inc"
#include "fp24_trig.hpp"

namespace mc1::fp24 {
namespace {

using bits::exp_of;
using bits::is_inf;
using bits::is_nan;
using bits::is_zero;
using bits::sig_of;
using bits::sign_of;
using bits::signed_inf;
using bits::signed_zero;

constexpr Result kNaN{kCanonicalNaN, 0};
constexpr Result kInvalidNaN{kCanonicalNaN, kNV};

// The quotient or root as 18 bits (17 + the rounding bit) with an exact
// remainder, put in the 1.63 form round_pack() takes: bits 63..46 and a
// sticky in bit 0.
std::uint64_t to_sig63(std::uint64_t q18, bool sticky) { return (q18 << 46) | (sticky ? 1 : 0); }

// Integer square root of x < 2^36: floor(sqrt(x)) and whether x was not a
// square. The RTL computes it bit by bit (a restoring recurrence); the model
// takes the host's sqrt, which gives the same integer: the double is
// correctly rounded, and for x < 2^36 no non-square lies within half an ulp
// of the next integer's square root (sqrt(k^2 - 1) < k - 2^-19 for
// k <= 2^18, where an ulp is at most 2^-35). The check below fixes the root
// should that ever not hold; fp24-regress proves every input against MPFR
// and the RTL.
std::uint64_t isqrt36(std::uint64_t x, bool* inexact) {
  auto root = static_cast<std::uint64_t>(std::sqrt(static_cast<double>(x)));
  if (root * root > x) --root;
  if ((root + 1) * (root + 1) <= x) ++root;
  *inexact = root * root != x;
  return root;
}

Result recip_special(Bits a) {
  if (is_nan(a)) return kNaN;
  if (is_inf(a)) return {signed_zero(sign_of(a)), 0};
  return {signed_inf(sign_of(a)), kDZ};  // 1/+-0
}

Result sqrt_special(Bits a) {
  if (is_nan(a)) return kNaN;
  if (is_zero(a)) return {signed_zero(sign_of(a)), 0};  // sqrt(-0) = -0
  return sign_of(a) ? kInvalidNaN : Result{kPosInf, 0};
}

Result trig_special(bool is_cos, Bits a) {
  if (is_nan(a)) return kNaN;
  if (is_inf(a)) return kInvalidNaN;
  return is_cos ? Result{0x3F0000, 0} : Result{signed_zero(sign_of(a)), 0};  // cos 0 = 1, sin +-0 = +-0
}

// The generator's ROM of inputs whose approximation is too close to a
// rounding midpoint to decide it; nullptr if x is not one.
const rom::HardCase* find_hard_case(bool is_cos, Bits a) {
  const std::uint32_t key = (is_cos ? 1u << 24 : 0u) | a;
  const auto* end = rom::kHardCases.data() + rom::kHardCases.size();
  const auto* it = std::lower_bound(rom::kHardCases.data(), end, key,
                                    [](const rom::HardCase& h, std::uint32_t k) { return h.key < k; });
  return (it != end && it->key == key) ? it : nullptr;
}

constexpr trig::Tables kTables{rom::kTwoOverPi.data(), rom::kHalfPi, rom::kSinCoef.data(), rom::kCosCoef.data()};

Result sin_cos(bool is_cos, Bits a) {
  a = bits::flush(a);
  if (!bits::is_normal(a)) return trig_special(is_cos, a);
  if (const rom::HardCase* h = find_hard_case(is_cos, a)) return {h->result, kNX};
  const trig::Approx y = trig::approximate(is_cos, a, kTables);
  // Never exact, never a tie: sticky is 1 (bit 0).
  return bits::round_pack(y.neg, y.exp + kBias, y.sig | 1);
}

}  // namespace

// 1/(m 2^(E-16)) = (2^34 / m) 2^(-18-E): an 18-bit quotient for 2^16 < m < 2^17.
Result recip(Bits a) {
  a = bits::flush(a);
  if (!bits::is_normal(a)) return recip_special(a);
  const bool s = sign_of(a);
  const int e_unb = exp_of(a) - kBias;
  const std::uint64_t m = sig_of(a);
  // m = 2^16 (a power of two): the quotient 2^18 needs one bit more.
  if (m == bits::kHidden) return bits::round_pack(s, -e_unb + kBias, std::uint64_t{1} << 63);
  const std::uint64_t num = std::uint64_t{1} << 34;
  const std::uint64_t q = num / m;  // in (2^17, 2^18)
  return bits::round_pack(s, -1 - e_unb + kBias, to_sig63(q, num % m != 0));
}

// sqrt(m 2^(E-16)): with E even, sqrt(m 2^18) 2^(E/2 - 17); with E odd, the
// odd power moves into the radicand, sqrt(m 2^19) 2^((E-1)/2 - 17). Either
// radicand gives an 18-bit root.
Result sqrt(Bits a) {
  a = bits::flush(a);
  if (!bits::is_normal(a) || sign_of(a)) return sqrt_special(a);
  const int e_unb = exp_of(a) - kBias;
  const int odd = e_unb & 1;
  bool inexact = false;
  const std::uint64_t root = isqrt36(static_cast<std::uint64_t>(sig_of(a)) << (18 + odd), &inexact);
  return bits::round_pack(false, (e_unb - odd) / 2 + kBias, to_sig63(root, inexact));
}

Result sin(Bits a) { return sin_cos(false, a); }
Result cos(Bits a) { return sin_cos(true, a); }

}  // namespace mc1::fp24
