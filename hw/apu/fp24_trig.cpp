// SIN/COS approximation core; the algorithm and its error bound are in
// docs/fp24-func.md. Every step is an exact integer operation (or a floor
// of one) that apu_rtl/fp24_func.sv repeats bit for bit.
#include "fp24_trig.hpp"

namespace mc1::fp24::trig {
namespace {

using u128 = unsigned __int128;

constexpr int kFracBits = 16;
constexpr int kBias = 63;

// floor(a * b / 2^64): the one multiplier shape of the polynomial datapath.
std::uint64_t mulhi(std::uint64_t a, std::uint64_t b) {
  return static_cast<std::uint64_t>((static_cast<u128>(a) * b) >> 64);
}

int msb128(u128 v) {
  const auto hi = static_cast<std::uint64_t>(v >> 64);
  if (hi != 0) return 127 - __builtin_clzll(hi);
  const auto lo = static_cast<std::uint64_t>(v);
  return lo != 0 ? 63 - __builtin_clzll(lo) : -1;
}

// The reduced argument z in radians as a float with a 64-bit significand,
// z = sig * 2^(exp - 63), plus what the reduction says about the quadrant.
struct Reduced {
  std::uint64_t sig;
  int exp;
  unsigned quadrant;  // x * 2/pi rounded to the nearest integer, mod 4
  bool z_neg;         // x * 2/pi was rounded up: z = -(that) in [-pi/4, 0)
};

// |x| = m * 2^(E - 16) with E >= kReduceMinExp. The window W holds the 128
// bits of 2/pi from weight 2^-(E-17) on, so m * W mod 2^128 is x * 2/pi mod 4
// with 126 fraction bits: the bits of 2/pi before the window give multiples
// of 4, and the bits after it less than 2^-109.
Reduced reduce_large(std::uint32_t m, int e_unb, const Tables& t) {
  const Word128& w = t.two_over_pi[e_unb - kReduceMinExp];
  const u128 window = (static_cast<u128>(w.hi) << 64) | w.lo;
  const u128 v = static_cast<u128>(m) * window;  // mod 2^128
  constexpr u128 kFracMask = (static_cast<u128>(1) << 126) - 1;
  constexpr u128 kHalf = static_cast<u128>(1) << 125;
  Reduced r{};
  r.quadrant = static_cast<unsigned>(v >> 126);
  u128 frac = v & kFracMask;
  if (frac >= kHalf) {
    r.quadrant = (r.quadrant + 1) & 3;
    r.z_neg = true;
    frac = (static_cast<u128>(1) << 126) - frac;
  }
  // |r| = frac * 2^-126 in quarter turns; make it a float, then times pi/2.
  // frac == 0 would need x to be a multiple of pi/2: impossible for x != 0.
  const int lead = msb128(frac);
  const auto r_sig = static_cast<std::uint64_t>(lead >= 63 ? frac >> (lead - 63) : frac << (63 - lead));
  const int r_exp = lead - 126;
  const std::uint64_t z = mulhi(r_sig, t.half_pi);  // in [2^62, 2^64)
  const bool top = (z >> 63) != 0;
  r.sig = top ? z : z << 1;
  r.exp = r_exp + (top ? 1 : 0);
  return r;
}

Reduced reduce(std::uint32_t a, const Tables& t) {
  const int e_unb = static_cast<int>((a >> kFracBits) & 0x7F) - kBias;
  const std::uint32_t m = (1u << kFracBits) | (a & 0xFFFF);
  if (e_unb >= kReduceMinExp) return reduce_large(m, e_unb, t);
  // |x| < 0.5: x itself is the reduced argument, exactly.
  return {static_cast<std::uint64_t>(m) << (63 - kFracBits), e_unb, 0, false};
}

// t = u * (c1 - u * (c2 - ... - u * c8)) in 0.64, u = z^2 < 1 in 0.64; so
// that sin(z)/z = 1 - t or cos(z) = 1 - t. Every partial sum is positive
// (the coefficients fall faster than u < 1 can grow them), so the Horner
// steps stay in unsigned fixed point.
std::uint64_t series_tail(std::uint64_t u, const std::uint64_t* coef) {
  std::uint64_t h = coef[kTerms - 1];
  for (int k = kTerms - 2; k >= 0; --k) h = coef[k] - mulhi(u, h);
  return mulhi(u, h);
}

// u = z^2 in 0.64 fixed point; z < 1 so exp <= -1.
std::uint64_t square(const Reduced& z) {
  const int shift = -2 - 2 * z.exp;
  return shift >= 64 ? 0 : mulhi(z.sig, z.sig) >> shift;
}

}  // namespace

Approx approximate(bool is_cos, std::uint32_t a, const Tables& t) {
  const Reduced z = reduce(a, t);
  // cos(x) = sin(x + pi/2): one more quarter turn. Then the quarter k picks
  // +sin(z), +cos(z), -sin(z), -cos(z).
  const unsigned k = (z.quadrant + (is_cos ? 1u : 0u)) & 3;
  const bool use_cos = (k & 1) != 0;
  const std::uint64_t tail = series_tail(square(z), use_cos ? t.cos_coef : t.sin_coef);
  Approx y{};
  y.neg = ((k & 2) != 0) != (!use_cos && z.z_neg);
  // sin(-x) = -sin(x); cos is even.
  if (!is_cos && (a & 0x800000) != 0) y.neg = !y.neg;
  if (use_cos) {
    // cos(z) = 1 - tail in [0.70, 1]; tail == 0 only when z < 2^-32.
    y.sig = tail == 0 ? std::uint64_t{1} << 63 : ~tail + 1;  // 2^64 - tail
    y.exp = tail == 0 ? 0 : -1;
  } else {
    // sin(z) = z * (1 - tail) in [0.89 z, z]: at most one bit to renormalize.
    const std::uint64_t s = z.sig - mulhi(z.sig, tail);
    const bool top = (s >> 63) != 0;
    y.sig = top ? s : s << 1;
    y.exp = z.exp - (top ? 0 : 1);
  }
  return y;
}

}  // namespace mc1::fp24::trig
