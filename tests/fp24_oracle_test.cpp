// Known values of the MPFR oracle (tb/fp24_oracle.cpp), worked out by hand
// from docs/fp24.md: if the oracle is wrong, the regression's "model ==
// oracle" proves nothing, so the oracle gets its own independent checks.
#include "fp24_oracle.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include <algorithm>
#include <cmath>
#include <random>

namespace mc1::fp24 {
// GoogleTest prints a mismatching Result as `value/flags` in hex.
void PrintTo(const Result& r, std::ostream* os) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%06x/%02x", r.value, unsigned(r.flags));
  *os << buf;
}
}  // namespace mc1::fp24

namespace mc1::fp24::tb {
namespace {

Result run(Op op, Bits a, Bits b = 0) {
  static Oracle oracle;
  return oracle.run(op, a, b);
}

constexpr Bits kOne = 0x3F0000, kTwo = 0x400000, kNegOne = 0xBF0000;

TEST(Fp24Oracle, AddRoundsToNearestEven) {
  EXPECT_EQ(run(Op::Add, kOne, kOne), (Result{kTwo, 0}));
  EXPECT_EQ(run(Op::Add, kOne, 0x2F0000), (Result{0x3F0001, 0}));      // 1 + 2^-16: exact
  EXPECT_EQ(run(Op::Add, kOne, 0x2E0000), (Result{0x3F0000, kNX}));    // 1 + 2^-17: tie, down to even
  EXPECT_EQ(run(Op::Add, 0x3F0001, 0x2E0000), (Result{0x3F0002, kNX}));  // tie, up to even
  EXPECT_EQ(run(Op::Add, kOne, 0x2E0001), (Result{0x3F0001, kNX}));    // just above the tie
}

TEST(Fp24Oracle, SignedZerosOfSums) {
  EXPECT_EQ(run(Op::Add, kOne, kNegOne), (Result{0x000000, 0}));
  EXPECT_EQ(run(Op::Add, 0x800000, 0x800000), (Result{0x800000, 0}));
  EXPECT_EQ(run(Op::Sub, 0x800000, 0x000000), (Result{0x800000, 0}));
  EXPECT_EQ(run(Op::Sub, 0x000000, 0x000000), (Result{0x000000, 0}));
  EXPECT_EQ(run(Op::Add, 0x801234, 0x80ABCD), (Result{0x800000, 0}));  // DAZ inputs are -0
}

TEST(Fp24Oracle, AddSpecials) {
  EXPECT_EQ(run(Op::Add, kPosInf, 0xFF0000), (Result{kCanonicalNaN, kNV}));
  EXPECT_EQ(run(Op::Sub, kPosInf, kPosInf), (Result{kCanonicalNaN, kNV}));
  EXPECT_EQ(run(Op::Add, kPosInf, kPosInf), (Result{kPosInf, 0}));
  EXPECT_EQ(run(Op::Add, 0x7F1234, kOne), (Result{kCanonicalNaN, 0}));  // NaN in: no flag
  EXPECT_EQ(run(Op::Add, kMaxFinite, kMaxFinite), (Result{kPosInf, kOF | kNX}));
}

TEST(Fp24Oracle, MulOverflowUnderflow) {
  EXPECT_EQ(run(Op::Mul, 0x408000, 0x408000), (Result{0x422000, 0}));  // 3 * 3 = 9 = 1.125 * 2^3
  EXPECT_EQ(run(Op::Mul, kMaxFinite, kTwo), (Result{kPosInf, kOF | kNX}));
  EXPECT_EQ(run(Op::Mul, 0x810000, 0x3E0000), (Result{0x800000, kUF | kNX}));  // -2^-62 / 2
  EXPECT_EQ(run(Op::Mul, kPosInf, 0x000000), (Result{kCanonicalNaN, kNV}));
  EXPECT_EQ(run(Op::Mul, 0xFF0000, kTwo), (Result{0xFF0000, 0}));
  EXPECT_EQ(run(Op::Mul, 0x800000, kTwo), (Result{0x800000, 0}));
}

// 2^-62 * 1.5 times 0.5 * (1 + 0x5555/2^16) is 2^-62 - 2^-80: tiny before
// rounding, but it rounds (a tie, to even) up to 2^-62, so it is not tiny.
TEST(Fp24Oracle, TininessIsDetectedAfterRounding) {
  EXPECT_EQ(run(Op::Mul, 0x018000, 0x3E5555), (Result{0x010000, kNX}));
  EXPECT_EQ(run(Op::Mul, 0x018000, 0x3E5554), (Result{0x000000, kUF | kNX}));
}

TEST(Fp24Oracle, RecipAndSqrt) {
  EXPECT_EQ(run(Op::Recip, kTwo), (Result{0x3E0000, 0}));
  EXPECT_EQ(run(Op::Recip, 0x408000), (Result{0x3D5555, kNX}));  // 1/3
  EXPECT_EQ(run(Op::Recip, 0x000000), (Result{kPosInf, kDZ}));
  EXPECT_EQ(run(Op::Recip, 0x80FFFF), (Result{0xFF0000, kDZ}));  // DAZ -0
  EXPECT_EQ(run(Op::Recip, 0xFF0000), (Result{0x800000, 0}));
  EXPECT_EQ(run(Op::Recip, 0x010000), (Result{0x7D0000, 0}));  // 1/2^-62 = 2^62
  EXPECT_EQ(run(Op::Recip, 0x7EFFFF), (Result{0x000000, kUF | kNX}));  // ~2^-64: tiny
}

TEST(Fp24Oracle, Sqrt) {
  EXPECT_EQ(run(Op::Sqrt, 0x410000), (Result{kTwo, 0}));
  EXPECT_EQ(run(Op::Sqrt, kTwo), (Result{0x3F6A0A, kNX}));  // sqrt 2 = 1.4142133 -> 0x6A0A
  EXPECT_EQ(run(Op::Sqrt, 0x800000), (Result{0x800000, 0}));
  EXPECT_EQ(run(Op::Sqrt, kNegOne), (Result{kCanonicalNaN, kNV}));
  EXPECT_EQ(run(Op::Sqrt, 0xFF0000), (Result{kCanonicalNaN, kNV}));
  EXPECT_EQ(run(Op::Sqrt, kPosInf), (Result{kPosInf, 0}));
}

TEST(Fp24Oracle, SinCos) {
  EXPECT_EQ(run(Op::Sin, kOne), (Result{0x3EAED5, kNX}));  // sin 1 = 0.8414710 = 2^-1 * 1.68294
  EXPECT_EQ(run(Op::Cos, kOne), (Result{0x3E14A3, kNX}));  // cos 1 = 2^-1 * (1 + 5282.5038/2^16)
  EXPECT_EQ(run(Op::Sin, 0x800000), (Result{0x800000, 0}));
  EXPECT_EQ(run(Op::Cos, 0x800000), (Result{kOne, 0}));
  EXPECT_EQ(run(Op::Sin, kPosInf), (Result{kCanonicalNaN, kNV}));
  EXPECT_EQ(run(Op::Cos, 0x7FFFFF), (Result{kCanonicalNaN, 0}));
  EXPECT_EQ(run(Op::Sin, 0x010000), (Result{0x010000, kNX}));  // sin x = x - x^3/6
  EXPECT_EQ(run(Op::Cos, 0x010000), (Result{kOne, kNX}));
}

// sin 1 = 2^-1 * (1 + 44757.2849.../2^16): 0x3EAED5 is 0.2849 ulp below the
// exact value and 0x3EAED6 is 0.7151 ulp above.
TEST(Fp24Oracle, MeasuresUlpErrorAgainstTheExactValue) {
  Oracle oracle;
  EXPECT_NEAR(oracle.measure(Op::Sin, kOne, 0x3EAED5).ulp_error, 0.2849, 1e-4);
  EXPECT_NEAR(oracle.measure(Op::Sin, kOne, 0x3EAED6).ulp_error, 0.7151, 1e-4);
  EXPECT_NEAR(oracle.measure(Op::Sin, kOne, 0x3EAED3).ulp_error, 2.2849, 1e-4);
  EXPECT_EQ(oracle.measure(Op::Sin, kOne, 0x3EAED6).rounded, (Result{0x3EAED5, kNX}));
  EXPECT_EQ(oracle.measure(Op::Sin, kPosInf, kCanonicalNaN).ulp_error, 0.0);
  EXPECT_TRUE(std::isinf(oracle.measure(Op::Sin, kOne, kCanonicalNaN).ulp_error));
}

TEST(Fp24Oracle, Cmp) {
  EXPECT_EQ(run(Op::Cmp, kOne, kTwo), (Result{kLT, 0}));
  EXPECT_EQ(run(Op::Cmp, kTwo, kOne), (Result{kGT, 0}));
  EXPECT_EQ(run(Op::Cmp, 0x800000, 0x000000), (Result{kEQ, 0}));
  EXPECT_EQ(run(Op::Cmp, 0x000001, 0x800000), (Result{kEQ, 0}));  // DAZ
  EXPECT_EQ(run(Op::Cmp, 0xFF0000, kNegOne), (Result{kLT, 0}));
  EXPECT_EQ(run(Op::Cmp, kOne, 0xFFC000), (Result{kUN, kNV}));
}

TEST(Fp24Oracle, Float) {
  EXPECT_EQ(run(Op::Float, 0x0000), (Result{0x000000, 0}));
  EXPECT_EQ(run(Op::Float, 0x0001), (Result{kOne, 0}));
  EXPECT_EQ(run(Op::Float, 0xFFFF), (Result{kNegOne, 0}));
  EXPECT_EQ(run(Op::Float, 0x7FFF), (Result{0x4DFFFC, 0}));  // 32767 = 1.11..1b * 2^14
  EXPECT_EQ(run(Op::Float, 0x8000), (Result{0xCE0000, 0}));  // -32768
}

TEST(Fp24Oracle, Fix) {
  EXPECT_EQ(run(Op::Fix, 0x3F8000), (Result{0x0001, kNX}));   // 1.5
  EXPECT_EQ(run(Op::Fix, 0xBF8000), (Result{0xFFFF, kNX}));   // -1.5
  EXPECT_EQ(run(Op::Fix, 0x3E0000), (Result{0x0000, kNX}));   // 0.5
  EXPECT_EQ(run(Op::Fix, 0xCE0000), (Result{0x8000, 0}));     // -32768 = -2^15
  EXPECT_EQ(run(Op::Fix, 0xCE0001), (Result{0x8000, kNX}));   // -32768.5
  EXPECT_EQ(run(Op::Fix, 0xCE0002), (Result{0x8000, kNV}));   // -32769
  EXPECT_EQ(run(Op::Fix, 0x4E0000), (Result{0x7FFF, kNV}));   // 32768
  EXPECT_EQ(run(Op::Fix, 0x4DFFFF), (Result{0x7FFF, kNX}));   // 32767.75
  EXPECT_EQ(run(Op::Fix, 0xFF0000), (Result{0x8000, kNV}));
  EXPECT_EQ(run(Op::Fix, 0xFF8000), (Result{0x7FFF, kNV}));   // NaN: 0x7FFF whatever its sign
  EXPECT_EQ(run(Op::Fix, 0x80ABCD), (Result{0x0000, 0}));     // DAZ -0
}

TEST(Fp24Oracle, NegAbs) {
  EXPECT_EQ(run(Op::Neg, kOne), (Result{kNegOne, 0}));
  EXPECT_EQ(run(Op::Neg, 0x001234), (Result{0x800000, 0}));  // DAZ: output f = 0
  EXPECT_EQ(run(Op::Neg, 0xFF8001), (Result{kCanonicalNaN, 0}));
  EXPECT_EQ(run(Op::Abs, 0x801234), (Result{0x000000, 0}));
  EXPECT_EQ(run(Op::Abs, 0xFF0000), (Result{kPosInf, 0}));
  EXPECT_EQ(run(Op::Abs, 0x7F0001), (Result{kCanonicalNaN, 0}));
}

// A second, independent reference: binary64 arithmetic rounded once to 17
// bits (docs/fp24.md: exact for + - * / sqrt since 53 >= 2*17 + 2), with the
// exactness of the binary64 step taken from an error-free transformation.
// It checks MPFR's use in the oracle (decoding, ternary, range rule) on
// random operands rather than on hand-picked ones.
double fp24_value(Bits a) {  // finite nonzero a only
  const double mag = std::ldexp(double(0x10000 | (a & 0xFFFF)), int((a >> 16) & 0x7F) - kBias - kFracBits);
  return (a & kSignBit) ? -mag : mag;
}

Result round_binary64(double d, bool inexact) {
  if (d == 0) return {std::signbit(d) ? kSignBit : 0, 0};
  int e;
  const double m = std::frexp(std::fabs(d), &e);    // |d| = m * 2^e, m in [0.5, 1)
  double sig = std::nearbyint(std::ldexp(m, 17));   // 17 bits, ties to even
  inexact = inexact || sig != std::ldexp(m, 17);
  if (sig == 131072.0) sig = 65536.0, ++e;           // rounded up to the next binade
  const int biased = e - 1 + kBias;                  // |r'| in [2^(e-1), 2^e)
  const Bits sign = std::signbit(d) ? kSignBit : 0;
  if (biased > 126) return {sign | kPosInf, kOF | kNX};
  if (biased < 1) return {sign, kUF | kNX};
  return {sign | Bits(biased) << 16 | (Bits(sig) & 0xFFFF), std::uint8_t(inexact ? kNX : 0)};
}

Result reference(Op op, Bits a, Bits b) {
  const double x = fp24_value(a), y = fp24_value(b);
  switch (op) {
    case Op::Add: {
      const double s = x + y, bb = s - x;  // TwoSum: the exact error of x + y
      return round_binary64(s, ((x - (s - bb)) + (y - bb)) != 0);
    }
    case Op::Mul: return round_binary64(x * y, false);  // 34-bit product: exact
    case Op::Recip: {
      const double q = 1 / x;
      return round_binary64(q, std::fma(-q, x, 1.0) != 0);
    }
    case Op::Sqrt: {
      const double r = std::sqrt(x);
      return round_binary64(r, std::fma(-r, r, x) != 0);
    }
    default: return {0, 0};
  }
}

// Finite, nonzero operands: the special-case table is checked above.
Bits random_finite(std::mt19937& rng, bool positive) {
  const Bits e = 1 + rng() % 126;
  return ((positive ? 0 : rng() & 1) ? kSignBit : 0) | e << 16 | (Bits(rng()) & 0xFFFF);
}

TEST(Fp24Oracle, AgreesWithBinary64RoundedOnce) {
  Oracle oracle;
  std::mt19937 rng(2024);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    Bits a = random_finite(rng, false), b = random_finite(rng, false);
    if (i % 2) b = (b & (kSignBit | 0xFFFF)) | Bits(std::clamp(int((a >> 16) & 0x7F) + int(rng() % 41) - 20, 1, 126)) << 16;
    for (Op op : {Op::Add, Op::Mul, Op::Recip, Op::Sqrt}) {
      if (op == Op::Sqrt) a &= ~kSignBit;
      const Result want = reference(op, a, b), got = oracle.run(op, a, b);
      ASSERT_EQ(got, want) << info(op).name << " " << std::hex << a << " " << b;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 800000);
}

}  // namespace
}  // namespace mc1::fp24::tb
