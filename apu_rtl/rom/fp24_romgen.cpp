// fp24_romgen: makes the ROMs of the FP24 function unit, once, for both the
// C++ model and the RTL (docs/fp24-func.md, "ROMs").
//
//   fp24_romgen OUTDIR   writes OUTDIR/fp24_rom.inc (C++) and OUTDIR/fp24_rom.svh
//
// Like a designer's ROM script it may use MPFR: for the bits of 2/pi and
// pi/2, and for the correctly rounded value of each hard case. The hard
// cases are the inputs whose approximation (the same core the model runs,
// hw/apu/fp24_trig.cpp) lands within kHardMargin of a rounding midpoint.
#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fp24_trig.hpp"
#include "fp24_trig_rtl.hpp"

namespace {

using mc1::fp24::trig::Word128;
namespace trig = mc1::fp24::trig;

constexpr int kFracBits = 16;
constexpr int kBias = 63;

// RAII for one MPFR variable.
class Mpfr {
 public:
  explicit Mpfr(mpfr_prec_t prec) { mpfr_init2(v_, prec); }
  ~Mpfr() { mpfr_clear(v_); }
  Mpfr(const Mpfr&) = delete;
  Mpfr& operator=(const Mpfr&) = delete;
  mpfr_ptr get() { return v_; }

 private:
  mpfr_t v_;
};

// Bits 1..n after the binary point of 2/pi (index 0 unused).
std::vector<int> two_over_pi_bits(int n) {
  Mpfr x(n + 64);
  mpfr_const_pi(x.get(), MPFR_RNDN);
  mpfr_ui_div(x.get(), 2, x.get(), MPFR_RNDN);
  std::vector<int> bit(n + 1, 0);
  for (int i = 1; i <= n; ++i) {
    mpfr_mul_2ui(x.get(), x.get(), 1, MPFR_RNDN);  // exact
    bit[i] = mpfr_cmp_ui(x.get(), 1) >= 0;
    if (bit[i]) mpfr_sub_ui(x.get(), x.get(), 1, MPFR_RNDN);  // exact
  }
  return bit;
}

// Window for unbiased exponent E: bits E-17 .. E-17+127 of 2/pi, where bit
// i has weight 2^-i and bits i <= 0 (the integer part) are zero.
std::array<Word128, trig::kWindowCount> make_windows() {
  const std::vector<int> bit = two_over_pi_bits(trig::kTwoOverPiBits);
  std::array<Word128, trig::kWindowCount> w{};
  for (int e = trig::kReduceMinExp; e <= trig::kReduceMaxExp; ++e) {
    Word128 win{0, 0};
    for (int j = 0; j < trig::kWindowBits; ++j) {
      const int i = e - kFracBits - 1 + j;
      const std::uint64_t b = (i >= 1) ? static_cast<std::uint64_t>(bit.at(i)) : 0;
      win.hi = (win.hi << 1) | (win.lo >> 63);
      win.lo = (win.lo << 1) | b;
    }
    w[e - trig::kReduceMinExp] = win;
  }
  return w;
}

static_assert(sizeof(unsigned long) == 8, "mpfr_get_ui must return 64 bits");

std::uint64_t half_pi_1_63() {
  Mpfr x(256);
  mpfr_const_pi(x.get(), MPFR_RNDN);
  mpfr_mul_2si(x.get(), x.get(), 62, MPFR_RNDN);  // pi/2 * 2^63
  mpfr_round(x.get(), x.get());
  return mpfr_get_ui(x.get(), MPFR_RNDN);  // unsigned long is 64 bits here
}

// round(2^64 / n!) for n = first, first + 2, ...: exact integer arithmetic.
std::array<std::uint64_t, trig::kTerms> inverse_factorials(int first) {
  std::array<std::uint64_t, trig::kTerms> c{};
  unsigned __int128 fact = 1;
  for (int n = 2; n < first; ++n) fact *= n;
  int n = first - 1;
  for (int k = 0; k < trig::kTerms; ++k) {
    while (n < first + 2 * k) fact *= ++n;
    const unsigned __int128 one = static_cast<unsigned __int128>(1) << 64;
    c[k] = static_cast<std::uint64_t>((one + fact / 2) / fact);
  }
  return c;
}

// ---- SIN/COS tables of the RTL (fp24_trig_rtl.hpp) ----------------------------
namespace rtl = mc1::fp24::trig_rtl;

// round(v * 2^frac) of an MPFR value v >= 0, as an integer below 2^64.
std::uint64_t fixed_round(mpfr_ptr v, int frac) {
  Mpfr x(256);
  mpfr_mul_2si(x.get(), v, frac, MPFR_RNDN);
  mpfr_round(x.get(), x.get());
  return mpfr_get_ui(x.get(), MPFR_RNDN);
}

rtl::Tables make_rtl_tables() {
  rtl::Tables t{};
  const std::vector<int> bit = two_over_pi_bits(rtl::kMaxExp + rtl::kWinBits);
  // Window of exponent E: bits E-17 .. E-17+89 of 2/pi (bit i of weight 2^-i,
  // bits i <= 0 zero); the direct entry: bits 1..90.
  for (int idx = 0; idx < rtl::kWindows; ++idx) {
    const int first = idx == rtl::kDirect ? 1 : idx + rtl::kMinExp - kFracBits - 1;
    rtl::u128 w = 0;
    for (int k = 0; k < rtl::kWinBits; ++k) {
      const int i = first + k;
      w = (w << 1) | static_cast<rtl::u128>(i >= 1 ? bit.at(i) : 0);
    }
    t.window[idx] = w;
  }
  Mpfr pi(256), ang(256), v(256), half(256);
  mpfr_const_pi(pi.get(), MPFR_RNDN);
  mpfr_div_2ui(half.get(), pi.get(), 1, MPFR_RNDN);  // pi/2
  for (int i = 0; i < rtl::kTableEntries; ++i) {
    mpfr_mul_ui(ang.get(), pi.get(), i, MPFR_RNDN);
    mpfr_div_2ui(ang.get(), ang.get(), 9, MPFR_RNDN);  // i/256 quarter turns
    mpfr_sin(v.get(), ang.get(), MPFR_RNDN);
    t.sin_tab[i] = fixed_round(v.get(), rtl::kTabFrac);
    mpfr_cos(v.get(), ang.get(), MPFR_RNDN);
    mpfr_mul(v.get(), v.get(), half.get(), MPFR_RNDN);
    t.hcos_tab[i] = fixed_round(v.get(), rtl::kHalfFrac);
  }
  mpfr_sqr(v.get(), half.get(), MPFR_RNDN);  // (pi/2)^2
  mpfr_div_ui(ang.get(), v.get(), 2, MPFR_RNDN);
  t.k2 = fixed_round(ang.get(), rtl::kK2Frac);
  mpfr_div_ui(ang.get(), v.get(), 6, MPFR_RNDN);
  t.k3 = fixed_round(ang.get(), rtl::kK3Frac);
  mpfr_sqr(v.get(), v.get(), MPFR_RNDN);
  mpfr_div_ui(ang.get(), v.get(), 24, MPFR_RNDN);
  t.k4 = fixed_round(ang.get(), rtl::kK4Frac);
  return t;
}

// ---- RECIP/SQRT seed table -----------------------------------------------------
// The RTL's RECIP and SQRT (docs/fp24-func.md) start from a piecewise-linear
// approximation q0 = floor((A * 2^(F-FA) + B * d) / 2^F) of the 18-bit
// quotient 2^34/m or root sqrt(m * 2^(18+odd)), with A and B from this ROM
// and d the low fraction bits of the input; the exact remainder then decides
// between q0 - 1 and q0. The generator proves, for every significand, that
// the true floor is one of the two; the build fails if it is not.
constexpr int kSeedF = 12;          // fraction bits of B (and of the sum)
constexpr int kSeedFA = 3;          // fraction bits of A
constexpr int kSeedAWidth = 22;     // A < 2^(19 + FA)
constexpr int kSeedBWidth = 16;     // B, two's complement
constexpr int kRecipIndexBits = 9;  // RECIP: segment = f[15:7], d = f[6:0]
constexpr int kSqrtIndexBits = 7;   // SQRT: segment = {odd, f[15:9]}, d = f[8:0]
constexpr int kSeedEntries = 768;   // 512 RECIP + 256 SQRT; address 512 + {odd, f[15:9]}

struct Seed {
  std::uint32_t a;
  std::int32_t b;
};

// The exact value the seed approximates, and its floor.
long double seed_target(bool is_sqrt, int odd, std::uint32_t m) {
  if (!is_sqrt) return std::ldexp(1.0L, 34) / static_cast<long double>(m);
  return std::sqrt(std::ldexp(static_cast<long double>(m), 18 + odd));
}

std::uint64_t exact_floor(bool is_sqrt, int odd, std::uint32_t m) {
  if (!is_sqrt) return (std::uint64_t{1} << 34) / m;
  const std::uint64_t x = static_cast<std::uint64_t>(m) << (18 + odd);
  auto r = static_cast<std::uint64_t>(std::sqrt(static_cast<long double>(x)));
  while (r * r > x) --r;
  while ((r + 1) * (r + 1) <= x) ++r;
  return r;
}

std::int64_t seed_q0(const Seed& s, std::uint32_t d) {
  const std::int64_t t = (static_cast<std::int64_t>(s.a) << (kSeedF - kSeedFA)) + static_cast<std::int64_t>(s.b) * d;
  return t >> kSeedF;  // t > 0: checked by the caller's range test
}

// One segment: the chord through its first and last point, moved half-way
// towards the curve (the curve's two extremes of distance to the chord are then
// equal and opposite), plus 1/2 so that the floor rounds.
Seed fit_segment(bool is_sqrt, int odd, std::uint32_t m0, int len) {
  const long double f0 = seed_target(is_sqrt, odd, m0);
  const long double f1 = seed_target(is_sqrt, odd, m0 + len - 1);
  const long double slope = (f1 - f0) / (len - 1);
  long double lo = 0, hi = 0;
  for (int d = 0; d < len; ++d) {
    const long double dev = seed_target(is_sqrt, odd, m0 + d) - (f0 + slope * d);
    lo = std::min(lo, dev);
    hi = std::max(hi, dev);
  }
  const long double a = f0 + (lo + hi) / 2 + 0.5L;
  return {static_cast<std::uint32_t>(std::llround(std::ldexp(a, kSeedFA))),
          static_cast<std::int32_t>(std::llround(std::ldexp(slope, kSeedF)))};
}

// Fits every segment and checks every significand it serves.
std::vector<Seed> make_seed_table() {
  std::vector<Seed> t(kSeedEntries, Seed{0, 0});
  auto fit = [&t](bool is_sqrt, int odd, int index_bits, int addr) {
    const int len = 1 << (kFracBits - index_bits);
    for (int seg = 0; seg < (1 << index_bits); ++seg) {
      const std::uint32_t m0 = (1u << kFracBits) + static_cast<std::uint32_t>(seg * len);
      const Seed s = fit_segment(is_sqrt, odd, m0, len);
      if (s.a >= (1u << kSeedAWidth) || s.b >= (1 << (kSeedBWidth - 1)) || s.b < -(1 << (kSeedBWidth - 1)))
        throw std::runtime_error("seed entry out of range");
      for (int d = 0; d < len; ++d) {
        const std::uint32_t m = m0 + static_cast<std::uint32_t>(d);
        if (!is_sqrt && m == (1u << kFracBits)) continue;  // exact power of two: the RTL's bypass
        const std::int64_t q0 = seed_q0(s, static_cast<std::uint32_t>(d));
        const auto fl = static_cast<std::int64_t>(exact_floor(is_sqrt, odd, m));
        if (q0 >= (1 << 18) || (fl != q0 && fl != q0 - 1))
          throw std::runtime_error("seed table: floor not in {q0-1, q0} for m=" + std::to_string(m) +
                                   (is_sqrt ? " (sqrt)" : " (recip)"));
      }
      t[static_cast<std::size_t>(addr + seg)] = s;
    }
  };
  fit(false, 0, kRecipIndexBits, 0);
  fit(true, 0, kSqrtIndexBits, 512);
  fit(true, 1, kSqrtIndexBits, 512 + (1 << kSqrtIndexBits));
  return t;
}

std::string hex(std::uint64_t v, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%0*llx", digits, static_cast<unsigned long long>(v));
  return buf;
}

struct HardCase {
  std::uint32_t key;     // is_cos << 24 | input encoding
  std::uint32_t result;  // correctly rounded encoding (flags: NX)
};

// Correctly rounded sin/cos of a finite nonzero normal input, by MPFR.
std::uint32_t correctly_rounded(bool is_cos, std::uint32_t a) {
  const int e = static_cast<int>((a >> kFracBits) & 0x7F);
  const long m = (1L << kFracBits) | (a & 0xFFFF);
  Mpfr x(kFracBits + 1), y(kFracBits + 1);
  mpfr_set_si_2exp(x.get(), (a & 0x800000) ? -m : m, e - kBias - kFracBits, MPFR_RNDN);
  if (is_cos) mpfr_cos(y.get(), x.get(), MPFR_RNDN);
  else mpfr_sin(y.get(), x.get(), MPFR_RNDN);
  // y = 0.1xxx * 2^ye with 17 bits: an FP24 normal (|sin|, |cos| >= 2^-62).
  const long ye = mpfr_get_exp(y.get());
  Mpfr sig(kFracBits + 1);
  mpfr_abs(sig.get(), y.get(), MPFR_RNDN);
  mpfr_mul_2si(sig.get(), sig.get(), kFracBits + 1 - ye, MPFR_RNDN);
  const std::uint32_t s = static_cast<std::uint32_t>(mpfr_get_ui(sig.get(), MPFR_RNDN));
  const long field = ye - 1 + kBias;
  if (field < 1 || field > 126) throw std::runtime_error("hard case outside the normal range");
  const std::uint32_t sign = mpfr_signbit(y.get()) ? 0x800000 : 0;
  return sign | static_cast<std::uint32_t>(field) << kFracBits | (s & 0xFFFF);
}

// FP24 encoding of an approximation |y| = sig * 2^(exp - (bits - 1)), bit
// bits-1 of sig set, rounded to 17 bits as both RTL and model do (RNE,
// sticky = 1: sin and cos are never representable nor a midpoint).
std::uint32_t encode(bool neg, int exp, std::uint64_t sig, int bits) {
  const int drop = bits - 1 - kFracBits;
  std::uint64_t r = (sig >> drop) + ((sig >> (drop - 1)) & 1);
  if (r >> (kFracBits + 1)) {
    r >>= 1;
    ++exp;
  }
  const int field = exp + kBias;
  if (field < 1 || field > 126) throw std::runtime_error("sin/cos result outside the normal range");
  return (neg ? 0x800000u : 0u) | static_cast<std::uint32_t>(field) << kFracBits | static_cast<std::uint32_t>(r & 0xFFFF);
}

struct TrigStats {
  std::uint64_t model_min_distance = ~std::uint64_t{0};  // model core, units of its bit 0
  std::uint64_t rtl_min_distance = ~std::uint64_t{0};    // RTL core, units of its bit 0
  double rtl_max_error = 0;                              // RTL core vs the model's, RTL units
  std::size_t model_hard = 0, rtl_hard = 0;              // positive inputs, both ops
};

// Every input that either core (the model's, hw/apu/fp24_trig.cpp, and the
// RTL's, fp24_trig_rtl.cpp) cannot round by its own error bound; both
// consult the one hard-case ROM. sin and cos are odd and even and both cores
// work on |x|, so each positive hard input brings its negative twin. Every
// other input is rounded by both cores, and they must agree: since the
// model's results are correctly rounded (the exhaustive regression against
// MPFR), this proves the RTL's are too, or the build stops.
std::vector<HardCase> find_hard_cases(const trig::Tables& t, const rtl::Tables& rt, TrigStats* st) {
  std::vector<HardCase> hard;
  for (int is_cos = 0; is_cos <= 1; ++is_cos) {
    for (std::uint32_t a = 0x010000; a < 0x7F0000; ++a) {
      const trig::Approx ym = trig::approximate(is_cos != 0, a, t);
      const rtl::Approx yr = rtl::approximate(is_cos != 0, a, rt);
      const std::uint64_t dm = trig::midpoint_distance(ym);
      const std::uint64_t dr = rtl::midpoint_distance(yr);
      st->model_min_distance = std::min(st->model_min_distance, dm);
      st->rtl_min_distance = std::min(st->rtl_min_distance, dr);
      // The RTL's error against the model's approximation (itself within
      // 2^-57 relative), in units of bit 0 of the RTL's 53-bit significand.
      if (ym.neg != yr.neg) throw std::runtime_error("sin/cos: RTL and model differ in sign at " + hex(a, 6));
      const int shift = ym.exp - yr.exp + 1;  // in {0, 1, 2}
      if (shift < 0 || shift > 2) throw std::runtime_error("sin/cos: RTL and model exponents apart at " + hex(a, 6));
      const auto scaled_r = static_cast<unsigned __int128>(yr.sig) << 12;
      const auto scaled_m = static_cast<unsigned __int128>(ym.sig) << shift;
      const double err = static_cast<double>(scaled_r > scaled_m ? scaled_r - scaled_m : scaled_m - scaled_r) / 4096.0;
      st->rtl_max_error = std::max(st->rtl_max_error, err);
      const bool model_hard = dm < trig::kHardMargin;
      const bool rtl_hard = dr < rtl::kHardMargin;
      st->model_hard += model_hard;
      st->rtl_hard += rtl_hard;
      if (!model_hard && !rtl_hard) {
        if (encode(ym.neg, ym.exp, ym.sig, 64) != encode(yr.neg, yr.exp, yr.sig, rtl::kSigBits))
          throw std::runtime_error("sin/cos: the RTL core rounds " + hex(a, 6) + (is_cos ? " (cos)" : " (sin)") +
                                   " unlike the model outside the hard-case margin");
        continue;
      }
      for (std::uint32_t s : {0u, 0x800000u}) {
        const std::uint32_t key = static_cast<std::uint32_t>(is_cos) << 24 | s | a;
        hard.push_back({key, correctly_rounded(is_cos != 0, s | a)});
      }
    }
  }
  std::sort(hard.begin(), hard.end(), [](const HardCase& x, const HardCase& y) { return x.key < y.key; });
  return hard;
}


struct Roms {
  std::array<Word128, trig::kWindowCount> windows;
  std::uint64_t half_pi;
  std::array<std::uint64_t, trig::kTerms> sin_coef;
  std::array<std::uint64_t, trig::kTerms> cos_coef;
  std::vector<HardCase> hard;
  std::vector<Seed> seed;
  rtl::Tables trig_rtl;
};

constexpr const char* kBanner =
    "Generated by fp24_romgen (apu_rtl/rom/fp24_romgen.cpp); do not edit.\n"
    "// ROMs of the FP24 function unit, docs/fp24-func.md.\n";

std::string cpp_rom(const Roms& r) {
  std::ostringstream o;
  o << "// " << kBanner << "#pragma once\n#include <array>\n#include <cstdint>\n#include \"fp24_trig.hpp\"\n\n"
    << "namespace mc1::fp24::rom {\n\n";
  o << "// 128-bit windows of 2/pi, one per unbiased exponent " << trig::kReduceMinExp << ".."
    << trig::kReduceMaxExp << ".\n";
  o << "constexpr std::array<trig::Word128, " << trig::kWindowCount << "> kTwoOverPi = {{\n";
  for (const Word128& w : r.windows) o << "    {0x" << hex(w.hi, 16) << "u, 0x" << hex(w.lo, 16) << "u},\n";
  o << "}};\n\nconstexpr std::uint64_t kHalfPi = 0x" << hex(r.half_pi, 16) << "u;\n\n";
  auto coef = [&o](const char* name, const std::array<std::uint64_t, trig::kTerms>& c) {
    o << "constexpr std::array<std::uint64_t, " << trig::kTerms << "> " << name << " = {{\n";
    for (std::uint64_t v : c) o << "    0x" << hex(v, 16) << "u,\n";
    o << "}};\n";
  };
  coef("kSinCoef", r.sin_coef);
  coef("kCosCoef", r.cos_coef);
  o << "\n// Hard cases: key = is_cos << 24 | input, sorted; result is correctly rounded, flags NX.\n"
    << "struct HardCase {\n  std::uint32_t key;\n  std::uint32_t result;\n};\n"
    << "constexpr std::array<HardCase, " << r.hard.size() << "> kHardCases = {{\n";
  for (const HardCase& h : r.hard) o << "    {0x" << hex(h.key, 7) << "u, 0x" << hex(h.result, 6) << "u},\n";
  o << "}};\n\n}  // namespace mc1::fp24::rom\n";
  return o.str();
}

std::string sv_rom(const Roms& r) {
  std::ostringstream o;
  o << "// " << kBanner << "// Included inside module fp24_func.\n\n";
  // SIN/COS of the RTL (fp24_func_trig.sv, apu_rtl/rom/fp24_trig_rtl.hpp);
  // the model's 64-bit tables are in fp24_rom.inc only.
  auto hex128 = [](rtl::u128 v, int bits) {
    const auto hi = static_cast<std::uint64_t>(v >> 64);
    const auto lo = static_cast<std::uint64_t>(v);
    return std::to_string(bits) + "'h" + hex(hi, (bits - 64 + 3) / 4) + "_" + hex(lo, 16);
  };
  const rtl::Tables& rt = r.trig_rtl;
  o << "// Windows of 2/pi (" << rtl::kWinBits << " bits): idx = unbiased exponent - (" << rtl::kMinExp
    << ") for exponents " << rtl::kMinExp << ".." << rtl::kMaxExp << ", idx " << rtl::kDirect
    << ": the leading bits (inputs below 2^" << rtl::kMinExp << ").\n"
    << "localparam int TRIG_WIN_W = " << rtl::kWinBits << ";\n"
    << "function automatic logic [" << rtl::kWinBits - 1 << ":0] rom_trig_window(input logic [6:0] idx);\n"
    << "  case (idx)\n";
  for (int i = 0; i < rtl::kWindows; ++i)
    o << "    7'd" << i << ": rom_trig_window = " << hex128(rt.window[i], rtl::kWinBits) << ";\n";
  o << "    default: rom_trig_window = '0;\n  endcase\nendfunction\n\n";
  // Entries 1..256 at address i - 1 (256 words); entry 0 is a constant.
  auto entry = [&rt](int i) {
    return "{53'h" + hex(rt.sin_tab[i], 14) + ", 45'h" + hex(rt.hcos_tab[i], 12) + "}";
  };
  o << "// sin, pi/2 cos at i/256 quarter turns: {S_i 1.52, pi/2 C_i 1.44};\n"
    << "// i = 1.." << rtl::kTableEntries - 1 << " at address i - 1, i = 0 in TRIG_TAB0.\n"
    << "localparam logic [97:0] TRIG_TAB0 = " << entry(0) << ";\n"
    << "function automatic logic [97:0] rom_trig_table(input logic [7:0] addr);\n"
    << "  case (addr)\n";
  for (int i = 1; i < rtl::kTableEntries; ++i)
    o << "    8'd" << i - 1 << ": rom_trig_table = " << entry(i) << ";\n";
  o << "    default: rom_trig_table = '0;\n  endcase\nendfunction\n\n";
  auto width = [](std::uint64_t v) { return 64 - __builtin_clzll(v); };
  auto konst = [&o, &width](const char* name, std::uint64_t v) {
    o << "localparam logic [" << width(v) - 1 << ":0] " << name << " = " << width(v) << "'h" << hex(v, (width(v) + 3) / 4)
      << ";\n";
  };
  o << "// (pi/2)^2/2 in 1." << rtl::kK2Frac << ", (pi/2)^2/6 in 0." << rtl::kK3Frac << ", (pi/2)^4/24 in 0."
    << rtl::kK4Frac << ".\n";
  konst("TRIG_K2", rt.k2);
  konst("TRIG_K3", rt.k3);
  konst("TRIG_K4", rt.k4);
  o << "\n";
  o << "// RECIP/SQRT seeds {A, B} (" << kSeedAWidth << " + " << kSeedBWidth
    << " bits): address f[15:7] (RECIP) or 512 + {odd, f[15:9]} (SQRT).\n"
    << "// Sum fraction bits F = " << kSeedF << ", A fraction bits FA = " << kSeedFA << ".\n"
    << "localparam int SEED_F = " << kSeedF << ";\nlocalparam int SEED_FA = " << kSeedFA << ";\n"
    << "localparam int SEED_A_W = " << kSeedAWidth << ";\nlocalparam int SEED_B_W = " << kSeedBWidth << ";\n"
    << "function automatic logic [" << kSeedAWidth + kSeedBWidth - 1 << ":0] rom_seed(input logic [9:0] addr);\n"
    << "  case (addr)\n";
  for (std::size_t i = 0; i < r.seed.size(); ++i) {
    const auto b = static_cast<std::uint32_t>(r.seed[i].b) & ((1u << kSeedBWidth) - 1);
    o << "    10'd" << i << ": rom_seed = {" << kSeedAWidth << "'h" << hex(r.seed[i].a, 6) << ", " << kSeedBWidth
      << "'h" << hex(b, 4) << "};\n";
  }
  o << "    default: rom_seed = '0;\n  endcase\nendfunction\n\n";
  o << "// Hard cases: key = {is_cos, input}; returns {hit, correctly rounded result}.\n"
    << "// " << r.hard.size() << " entries.\n"
    << "function automatic logic [24:0] rom_hard_case(input logic [24:0] key);\n"
    << "  case (key)\n";
  for (const HardCase& h : r.hard)
    o << "    25'h" << hex(h.key, 7) << ": rom_hard_case = {1'b1, 24'h" << hex(h.result, 6) << "};\n";
  o << "    default: rom_hard_case = '0;\n  endcase\nendfunction\n";
  return o.str();
}

// Write only when the content changed, so the model and RTL do not rebuild.
void write_if_changed(const std::string& path, const std::string& text) {
  {
    std::ifstream in(path, std::ios::binary);
    std::stringstream old;
    old << in.rdbuf();
    if (in && old.str() == text) return;
  }
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fp24_romgen OUTDIR\n";
    return 2;
  }
  try {
    Roms r{make_windows(), half_pi_1_63(), inverse_factorials(3), inverse_factorials(2), {}, {}, make_rtl_tables()};
    const trig::Tables t{r.windows.data(), r.half_pi, r.sin_coef.data(), r.cos_coef.data()};
    TrigStats st;
    r.hard = find_hard_cases(t, r.trig_rtl, &st);
    r.seed = make_seed_table();
    const std::string dir = argv[1];
    write_if_changed(dir + "/fp24_rom.inc", cpp_rom(r));
    write_if_changed(dir + "/fp24_rom.svh", sv_rom(r));
    std::cout << "fp24_romgen: " << r.hard.size() << " hard-case entries; model core: " << st.model_hard
              << " positive inputs within 2^" << __builtin_ctzll(trig::kHardMargin)
              << " units of a midpoint, closest " << st.model_min_distance << "; RTL core: " << st.rtl_hard
              << " within 2^" << __builtin_ctzll(rtl::kHardMargin) << ", closest " << st.rtl_min_distance
              << ", max error " << st.rtl_max_error << " units; all others rounded alike\n";
  } catch (const std::exception& e) {
    std::cerr << "fp24_romgen: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
