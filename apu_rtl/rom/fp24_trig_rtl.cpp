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

  // s3 also: phi_u = |delta| (or x * 2/pi) unnormalized, scale 2^-53,
  // floor(phi / 2^s), for u; 0 for s >= 23 (u then below 2^-56).
  const std::uint64_t phiu = s >= 23 ? 0 : phi >> s;
  // s4: u = phi^2 in quarter turns squared, 2^-56, from the top 36 bits of
  // phi_u (36 x 36).
  const std::uint64_t pu = phiu >> kUsqDrop;
  const std::uint64_t u = static_cast<std::uint64_t>((static_cast<u128>(pu) * pu) >> kUDrop);
  require(u < (std::uint64_t{1} << 38), "u width");

  // s5: T_s = k3 u (sin e = (pi/2) phi (1 - T_s)), 2^-48; w = k2 - k4 u,
  // 2^-36 (constant multiplies by u's top 26 and 18 bits).
  const std::uint64_t ts = ((u >> kUtDrop) * t.k3) >> kTsDrop;
  const std::uint64_t w = t.k2 - (((u >> kUwDrop) * t.k4) >> kK4uDrop);
  // s5 also: the table entry (A, B) = (S_i, pi/2 C_i), i = j for a sine,
  // 256 - j for a cosine (the address registered in s4).
  const unsigned k = (quad + (is_cos ? 1u : 0u)) & 3;
  const bool use_cos = (k & 1) != 0;
  const unsigned i = use_cos ? 256 - j : j;
  const std::uint64_t av = t.sin_tab[i];
  const std::uint64_t bv = t.hcos_tab[i];

  // s6: T_c = u w (cos e = 1 - T_c), 2^-54; q = phi T_s, 2^-56; the two
  // halves of P1 = B phi (B phi_hi, B phi_lo), exact.
  const std::uint64_t tc = static_cast<std::uint64_t>((static_cast<u128>(u) * w) >> kTcDrop);
  require(tc < (std::uint64_t{1} << 37), "T_c width");
  const std::uint64_t q = ((phi >> kPhiQDrop) * ts) >> kQDrop;
  const u128 p1 = (static_cast<u128>(bv) * (phi >> kPhiSplit) << kPhiSplit) +
                  static_cast<u128>(bv) * (phi & mask(kPhiSplit));

  // s7: A T_c and B q (2^-52, A's top 1.37 and B's top 1.25), Z = A +- B
  // phi (1.52, one three-operand sum floored once).
  const std::uint64_t at = static_cast<std::uint64_t>((static_cast<u128>(av >> kATabDrop) * tc) >> kAtDrop);
  const std::uint64_t bq = ((bv >> kBqTabDrop) * q) >> kBqDrop;
  const bool bplus = use_cos ? eneg : !eneg;
  const u128 a_sh = static_cast<u128>(av) << kP1Drop;
  require(bplus || a_sh >= p1, "A - B phi >= 0");
  const std::uint64_t z = static_cast<std::uint64_t>((bplus ? a_sh + p1 : a_sh - p1) >> kP1Drop);

  // s8: y = A cos(e) +- B sin(e) = Z - A T_c -+ B q in 1.52; s9:
  // normalized, rounded.
  require(z > at + (bplus ? bq : 0), "y > 0");
  const std::uint64_t y = bplus ? z - at - bq : z - at + bq;
  require(y <= (std::uint64_t{1} << kTabFrac), "y <= 1");
  const int p = msb(y);
  // y >= 2^-11 (tables: sin(pi/2 2^-9) > 2^-8.4; a sine at j = 0:
  // B phi (1 - T_s) >= 2^42 units; a cosine: > 0.7): the normalizer shifts
  // by at most 15.
  require(kTabFrac - p <= 15, "y beyond the normalizer");
  Approx r{};
  r.sig = (y << (kSigBits - 1 - p)) & mask(kSigBits);
  r.exp = p - kTabFrac - ((small && !use_cos) ? s : 0);
  r.neg = ((k & 2) != 0) != (!use_cos && z_neg);
  if (!is_cos && x_neg) r.neg = !r.neg;
  return r;
}

}  // namespace mc1::fp24::trig_rtl
