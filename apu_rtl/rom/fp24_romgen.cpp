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

// Every input whose approximation cannot decide its own rounding. sin and
// cos are odd and even, and the core works on |x|, so each positive hard
// input brings its negative twin.
std::vector<HardCase> find_hard_cases(const trig::Tables& t, std::uint64_t* min_distance) {
  std::vector<HardCase> hard;
  *min_distance = ~std::uint64_t{0};
  for (int is_cos = 0; is_cos <= 1; ++is_cos) {
    for (std::uint32_t a = 0x010000; a < 0x7F0000; ++a) {
      const std::uint64_t d = trig::midpoint_distance(trig::approximate(is_cos != 0, a, t));
      if (d < *min_distance) *min_distance = d;
      if (d >= trig::kHardMargin) continue;
      for (std::uint32_t s : {0u, 0x800000u}) {
        const std::uint32_t key = static_cast<std::uint32_t>(is_cos) << 24 | s | a;
        hard.push_back({key, correctly_rounded(is_cos != 0, s | a)});
      }
    }
  }
  std::sort(hard.begin(), hard.end(), [](const HardCase& x, const HardCase& y) { return x.key < y.key; });
  return hard;
}

std::string hex(std::uint64_t v, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%0*llx", digits, static_cast<unsigned long long>(v));
  return buf;
}

struct Roms {
  std::array<Word128, trig::kWindowCount> windows;
  std::uint64_t half_pi;
  std::array<std::uint64_t, trig::kTerms> sin_coef;
  std::array<std::uint64_t, trig::kTerms> cos_coef;
  std::vector<HardCase> hard;
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
  // One constant vector indexed by a part-select rather than a case:
  // Verilator reads it as a constant, where a case becomes a decision tree
  // that makes the SIN/COS simulation ~12% slower. Not an unpacked array:
  // Yosys 0.23 takes no unpacked-array localparam (docs/fp24-rtl.md).
  o << "// 128-bit windows of 2/pi, entry idx at [128*idx +: 128]; idx = unbiased\n"
    << "// exponent - (" << trig::kReduceMinExp << "), 0 past the last.\n"
    << "localparam logic [128*128-1:0] ROM_TWO_OVER_PI = {\n";
  for (int i = 127; i >= 0; --i) {
    const Word128 w = i < trig::kWindowCount ? r.windows[i] : Word128{};
    o << "    128'h" << hex(w.hi, 16) << "_" << hex(w.lo, 16) << (i > 0 ? ",\n" : "\n");
  }
  o << "};\n\n"
    << "function automatic logic [127:0] rom_two_over_pi(input logic [6:0] idx);\n"
    << "  rom_two_over_pi = ROM_TWO_OVER_PI[128*idx+:128];\nendfunction\n\n";
  o << "localparam logic [63:0] ROM_HALF_PI = 64'h" << hex(r.half_pi, 16) << ";\n\n";
  o << "// Series coefficients 1/(2k+1)! (sin) and 1/(2k)! (cos), k = idx + 1, in 0.64.\n"
    << "function automatic logic [63:0] rom_coef(input logic use_cos, input logic [2:0] idx);\n"
    << "  case ({use_cos, idx})\n";
  for (int c = 0; c < 2; ++c)
    for (int k = 0; k < trig::kTerms; ++k)
      o << "    4'd" << (c * 8 + k) << ": rom_coef = 64'h" << hex((c ? r.cos_coef : r.sin_coef)[k], 16) << ";\n";
  o << "    default: rom_coef = '0;\n  endcase\nendfunction\n\n";
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
    Roms r{make_windows(), half_pi_1_63(), inverse_factorials(3), inverse_factorials(2), {}};
    const trig::Tables t{r.windows.data(), r.half_pi, r.sin_coef.data(), r.cos_coef.data()};
    std::uint64_t min_distance = 0;
    r.hard = find_hard_cases(t, &min_distance);
    const std::string dir = argv[1];
    write_if_changed(dir + "/fp24_rom.inc", cpp_rom(r));
    write_if_changed(dir + "/fp24_rom.svh", sv_rom(r));
    std::cout << "fp24_romgen: " << r.hard.size() << " hard cases (margin 2^" << __builtin_ctzll(trig::kHardMargin)
              << " units), closest approximation "
              << min_distance << " units from a midpoint\n";
  } catch (const std::exception& e) {
    std::cerr << "fp24_romgen: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
