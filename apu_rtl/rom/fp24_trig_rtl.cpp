// SIN/COS as the RTL computes them, stage by stage (apu_rtl/fp24_func_trig.sv;
// docs/fp24-func.md "SIN and COS (RTL)"). Integer arithmetic only: every
// product is exact and every shift a floor, as in the RTL.
#include "fp24_trig_rtl.hpp"

#include <stdexcept>

namespace mc1::fp24::trig_rtl {
namespace {

constexpr std::uint64_t mask(int bits) { return bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1; }

int msb(std::uint64_t v) { return 63 - __builtin_clzll(v); }

int msb128(u128 v) {
  const auto hi = static_cast<std::uint64_t>(v >> 64);
  return hi != 0 ? 64 + msb(hi) : msb(static_cast<std::uint64_t>(v));
}

void require(bool ok, const char* what) {
  if (!ok) throw std::logic_error(what);
}

}  // namespace

Approx approximate(bool is_cos, std::uint32_t a, const Tables& t) {
  const int e_unb = static_cast<int>((a >> 16) & 0x7F) - 63;
  const std::uint64_t m = (1u << 16) | (a & 0xFFFF);
  const bool x_neg = (a & 0x800000) != 0;

  // s1: the window (synchronous ROM read). s2: v = m * window, exact.
  const bool direct = e_unb < kMinExp;
  const u128 v = static_cast<u128>(m) * t.window[direct ? kDirect : e_unb - kMinExp];

  // s3: nearest 1/256 quarter turn N, remainder delta (|delta| <= 2^-9 qt,
  // sign-magnitude, the magnitude by ones' complement), table index j,
  // quadrant; phi = |delta| (or, direct, x * 2/pi) as a 44-bit significand
  // phi_sig * 2^(-53 - s).
  unsigned quad = 0, j = 0;
  bool small = true, z_neg = false, eneg = false;
  std::uint64_t phi = 0;
  int s = 0;
  if (!direct) {
    const unsigned n = static_cast<unsigned>((v >> (kRemBits + 1)) + ((v >> kRemBits) & 1)) & 1023;
    const unsigned j8 = n & 255;
    const bool flip = j8 >= 128;
    quad = ((n >> 8) + (flip ? 1 : 0)) & 3;
    j = flip ? 256 - j8 : j8;
    const bool sd = ((v >> kRemBits) & 1) != 0;
    const u128 rem_mask = (static_cast<u128>(1) << kRemBits) - 1;
    const u128 mag = sd ? (~v & rem_mask) : (v & rem_mask);
    small = j == 0;
    if (small) {
      // |delta| >= 2^-41 qt for every input (x is never that close to a
      // multiple of pi/2): a shift of at most kMaxNorm normalizes it.
      require(mag != 0 && msb128(mag) >= kRemBits - 1 - kMaxNorm, "small |delta| beyond the normalizer");
      s = kRemBits - 1 - msb128(mag);
      phi = static_cast<std::uint64_t>((mag << s) >> kPhiDrop);
    } else {
      phi = static_cast<std::uint64_t>(mag >> kPhiDrop);
    }
    z_neg = small ? sd : flip;
    eneg = !small && (sd != flip);
  } else {
    // x * 2/pi = v * 2^(E - 106), v in [2^105, 2^107).
    const bool top = ((v >> 106) & 1) != 0;
    phi = static_cast<std::uint64_t>(top ? v >> 63 : v >> 62);
    s = top ? -e_unb - 10 : -e_unb - 9;
  }
  require(phi < (std::uint64_t{1} << kPhiBits), "phi width");

  // s4: phi^2; s5: u = phi^2 shifted, in 0.64 (quarter turns squared), < 2^46.
  const u128 sq = static_cast<u128>(phi) * phi;
  const int sh = 42 + 2 * s;
  const std::uint64_t u = sh >= 88 ? 0 : static_cast<std::uint64_t>(sq >> sh);
  require(u < (std::uint64_t{1} << 46), "u width");

  // s5: T_s = k3 u (sin e = (pi/2) phi (1 - T_s)); w = k2 - k4 u.
  const std::uint64_t ts = static_cast<std::uint64_t>((static_cast<u128>(u) * t.k3) >> kKFrac);
  const std::uint64_t w = t.k2 - (((u >> 24) * t.k4) >> kK4Frac);

  // s6: T_c = u w (cos e = 1 - T_c); X = phi (1 - T_s).
  const std::uint64_t tc = static_cast<std::uint64_t>((static_cast<u128>(u) * w) >> kKFrac);
  // One multiply-subtract, floored once: floor((phi 2^64 - phi T_s) / 2^64).
  const std::uint64_t x = static_cast<std::uint64_t>(((static_cast<u128>(phi) << 64) - static_cast<u128>(phi) * ts) >> 64);
  require(tc < (std::uint64_t{1} << 47), "T_c width");

  // s6: (A, B) = (S_j, C_j) for a sine, (C_j, -S_j) for a cosine; s7: the
  // products A T_c and (pi/2) B X (the table holds pi/2 B).
  const unsigned k = (quad + (is_cos ? 1u : 0u)) & 3;
  const bool use_cos = (k & 1) != 0;
  const std::uint64_t av = use_cos ? t.cos_tab[j] : t.sin_tab[j];
  const std::uint64_t bv = use_cos ? t.hsin_tab[j] : t.hcos_tab[j];
  const std::uint64_t at = static_cast<std::uint64_t>((static_cast<u128>(av >> kTabHiDrop) * (tc >> 12)) >> 36);
  const std::uint64_t bx = static_cast<std::uint64_t>((static_cast<u128>(bv) * x) >> 45);

  // s8: y = A cos(e) +- B sin(e) in 1.52; s9: normalized, rounded.
  const bool bplus = use_cos ? eneg : !eneg;
  const std::uint64_t pos = av - at + (bplus ? bx : 0);
  require(pos > (bplus ? 0 : bx), "y > 0");
  const std::uint64_t y = pos - (bplus ? 0 : bx);
  require(y <= (std::uint64_t{1} << kTabFrac), "y <= 1");
  const int p = msb(y);
  // y >= 2^-11 (tables: sin(pi/2 2^-9) > 2^-8.4; a sine at j = 0: B X >= 2^42
  // units; a cosine: > 0.7): the normalizer shifts by at most 15.
  require(kTabFrac - p <= 15, "y beyond the normalizer");
  Approx r{};
  r.sig = (y << (kSigBits - 1 - p)) & mask(kSigBits);
  r.exp = p - kTabFrac - ((small && !use_cos) ? s : 0);
  r.neg = ((k & 2) != 0) != (!use_cos && z_neg);
  if (!is_cos && x_neg) r.neg = !r.neg;
  return r;
}

}  // namespace mc1::fp24::trig_rtl
