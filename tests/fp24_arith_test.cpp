// Hand-derived vectors for the multiplier and adder-unit ops (docs/fp24.md).
//
// Reading the encodings: s | e(7, bias 63) | f(16). 1.0 = 0x3F0000, 2.0 =
// 0x400000, 1.5 = 0x3F8000, 2^k = (63 + k) << 16. "ulp" is that of the result's
// binade: 2^-16 in [1, 2). MAX = 0x7EFFFF = (2 - 2^-16) * 2^63, whose ulp is
// 2^47; MIN = 0x010000 = 2^-62.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <string>

#include "fp24.hpp"
#include "fp24_convert.hpp"

namespace mc1::fp24 {
// Lets GoogleTest print a failing Result as "value/flags" in hex.
static void PrintTo(const Result& r, std::ostream* os) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06X/%02X", r.value, r.flags);
  *os << buf;
}
}  // namespace mc1::fp24

namespace {

using namespace mc1::fp24;

constexpr std::uint8_t kOFNX = kOF | kNX;
constexpr std::uint8_t kUFNX = kUF | kNX;

struct Binary {
  Bits a, b;
  Result want;
};
struct Unary {
  Bits a;
  Result want;
};

void expect_binary(Result (*fn)(Bits, Bits), const char* op, std::initializer_list<Binary> cases) {
  for (const Binary& c : cases) {
    char where[48];
    std::snprintf(where, sizeof where, "%s %06X %06X", op, c.a, c.b);
    EXPECT_EQ(fn(c.a, c.b), c.want) << where;
  }
}

void expect_unary(Result (*fn)(Bits), const char* op, std::initializer_list<Unary> cases) {
  for (const Unary& c : cases) {
    char where[32];
    std::snprintf(where, sizeof where, "%s %06X", op, c.a);
    EXPECT_EQ(fn(c.a), c.want) << where;
  }
}

// ---- MUL ------------------------------------------------------------------

TEST(Fp24Mul, ExactProducts) {
  expect_binary(mul, "mul", {
      {0x3F8000, 0x3F8000, {0x402000, 0}},  // 1.5 * 1.5 = 2.25 = 2 * 1.125, f = 0x2000
      {0x408000, 0xBF0000, {0xC08000, 0}},  // 3 * -1 = -3
      {0xBE0000, 0xC00000, {0x3F0000, 0}},  // -0.5 * -2 = 1
      {0x7EFFFF, 0x3F0000, {0x7EFFFF, 0}},  // MAX * 1
      {0x3FFFFF, 0x3E0000, {0x3EFFFF, 0}},  // (2 - 2^-16) * 0.5: exponent only
  });
}

TEST(Fp24Mul, RoundingToNearestEven) {
  expect_binary(mul, "mul", {
      // (1 + 2^-16) * 1.5 = 1.5 + 1.5 ulp: tie between f 0x8001 (odd) and 0x8002.
      {0x3F0001, 0x3F8000, {0x3F8002, kNX}},
      // (1 + 3*2^-16) * 1.5 = 1.5 + 4.5 ulp: tie between 0x8004 (even) and 0x8005.
      {0x3F0003, 0x3F8000, {0x3F8004, kNX}},
      // (1 + 2^-16)^2 = 1 + 2 ulp + 2^-32: far below the half, rounds down.
      {0x3F0001, 0x3F0001, {0x3F0002, kNX}},
      // (2 - 2^-16)^2 = 4 - 2^-14 + 2^-32 = 2 * (2 - 2^-15) + 2^-32, in [2, 4)
      // with ulp 2^-15: rounds down to f = 0xFFFE.
      {0x3FFFFF, 0x3FFFFF, {0x40FFFE, kNX}},
  });
  // 0x3F8001 * 0x3F0001 = (1.5 + 2^-16)(1 + 2^-16) = 1.5 + 1.5*2^-16 + 2^-16 + 2^-32
  //   = 1.5 + 2.5 ulp + 2^-32: just above the tie, rounds up to f = 0x8003.
  EXPECT_EQ(mul(0x3F8001, 0x3F0001), (Result{0x3F8003, kNX}));
  // 0x3F8001 * 0xBF0001 is the same magnitude, negative: rounding is symmetric.
  EXPECT_EQ(mul(0x3F8001, 0xBF0001), (Result{0xBF8003, kNX}));
}

// 0x1FF00 * 0x10080 = (511 * 2^8) * (513 * 2^7) = (2^18 - 1) * 2^15 = 2^33 - 2^15:
// significands 1.99609375 and 1.001953125 multiply to exactly 2 - 2^-17, the
// tie between 2 - 2^-16 (f = 0xFFFF, odd) and 2.0 (even): rounds up with a
// carry out of the significand into the exponent.
TEST(Fp24Mul, CarryOutOnRounding) {
  expect_binary(mul, "mul", {
      {0x3FFF00, 0x3F0080, {0x400000, kNX}},
      {0xBFFF00, 0x3F0080, {0xC00000, kNX}},
  });
}

TEST(Fp24Mul, OverflowBoundary) {
  expect_binary(mul, "mul", {
      // (2^17 - 3)(2^16 + 1) = 2^33 - 2^16 - 3: (MAX - 2 ulp) * (1 + 2^-16) =
      // MAX - 3 * 2^31, far below the tie: MAX.
      {0x7EFFFD, 0x3F0001, {0x7EFFFF, kNX}},
      // (2^17 - 1)(2^16 + 1) = 2^33 + 2^16 - 1: MAX * (1 + 2^-16) is past 2^64.
      {0x7EFFFF, 0x3F0001, {0x7F0000, kOFNX}},
      // The carry-out tie above, scaled to 2^63: (2 - 2^-17) * 2^63 = MAX + half
      // ulp, ties to even = 2^64 > MAX: overflow.
      {0x7EFF00, 0x3F0080, {0x7F0000, kOFNX}},
      {0x7EFF00, 0xBF0080, {0xFF0000, kOFNX}},
      {0x7E0000, 0x400000, {0x7F0000, kOFNX}},  // 2^63 * 2 = 2^64
      {0x7EFFFF, 0x7EFFFF, {0x7F0000, kOFNX}},
      {0x7EFFFF, 0xFEFFFF, {0xFF0000, kOFNX}},
      {0x7E0000, 0x3FFFFF, {0x7EFFFF, 0}},  // 2^63 * (2 - 2^-16) = MAX exactly
  });
}

TEST(Fp24Mul, UnderflowBoundary) {
  expect_binary(mul, "mul", {
      // 2^-62 * (1 - 2^-17) = (2 - 2^-16) * 2^-63: exact at 17 bits but below
      // MIN, so tiny: signed zero with UF|NX.
      {0x010000, 0x3EFFFF, {0x000000, kUFNX}},
      {0x810000, 0x3EFFFF, {0x800000, kUFNX}},
      // The 2 - 2^-17 tie scaled to 2^-63: (2 - 2^-17) * 2^-63 rounds up to
      // exactly 2^-62 = MIN, which is not tiny (tininess after rounding).
      {0x01FF00, 0x3E0080, {0x010000, kNX}},
      {0x81FF00, 0x3E0080, {0x810000, kNX}},
      // 1.99609375 * 1.001953125 - 2^-16 * 1.99609375 is below the tie:
      // 0x1FF00 * 0x1007F = 2^33 - 2^15 - 0x1FF00 = 2^33 - 163584, i.e. 2.496
      // ulp below 2, nearest 2 - 2 ulp (f = 0xFFFE); at 2^-63 that is tiny.
      {0x01FF00, 0x3E007F, {0x000000, kUFNX}},
      {0x3FFF00, 0x3F007F, {0x3FFFFE, kNX}},  // same product at 2^0
      // As in OverflowBoundary, scaled to 2^-63: (2 - 2^-16 - 3 * 2^-32) rounds
      // to 2 - 2^-16, tiny; (2 + 2^-16 - 2^-32) * 2^-63 = MIN + half its ulp
      // - 2^-95 rounds down to MIN, not tiny.
      {0x01FFFD, 0x3E0001, {0x000000, kUFNX}},
      {0x01FFFF, 0x3E0001, {0x010000, kNX}},
      {0x010000, 0x3F0000, {0x010000, 0}},     // MIN * 1 = MIN
      {0x010000, 0x010000, {0x000000, kUFNX}},  // 2^-124
  });
}

TEST(Fp24Mul, ZerosInfinitiesNaNs) {
  expect_binary(mul, "mul", {
      {0x000000, 0x408000, {0x000000, 0}},
      {0x800000, 0x408000, {0x800000, 0}},  // -0 * 3 = -0
      {0x800000, 0xC08000, {0x000000, 0}},  // -0 * -3 = +0
      {0x7F0000, 0xC00000, {0xFF0000, 0}},  // inf * -2 = -inf, exact
      {0xFF0000, 0xFF0000, {0x7F0000, 0}},
      {0x000000, 0x7F0000, {kCanonicalNaN, kNV}},  // 0 * inf
      {0xFF0000, 0x800000, {kCanonicalNaN, kNV}},
      {0x7F8000, 0x000000, {kCanonicalNaN, 0}},  // NaN in: no flag, not even with 0
      {0x7FFFFF, 0x3F0000, {kCanonicalNaN, 0}},  // payload dropped
      {0xFF0001, 0x7F0000, {kCanonicalNaN, 0}},  // negative NaN * inf
  });
}

TEST(Fp24Mul, DenormalInputsReadAsZero) {
  expect_binary(mul, "mul", {
      {0x00FFFF, 0x3F0000, {0x000000, 0}},  // e = 0 is +0: no flag
      {0x80ABCD, 0x3F0000, {0x800000, 0}},  // sign kept
      {0x00ABCD, 0xBF0000, {0x800000, 0}},
      {0x000001, 0x7F0000, {kCanonicalNaN, kNV}},  // flushed zero * inf
  });
}

// ---- ADD / SUB ------------------------------------------------------------

TEST(Fp24Add, ExactSums) {
  expect_binary(add, "add", {
      {0x3F0000, 0x3F0000, {0x400000, 0}},  // 1 + 1 = 2
      {0x3F8000, 0x3F8000, {0x408000, 0}},  // 1.5 + 1.5 = 3
      {0x3F0000, 0x2F0000, {0x3F0001, 0}},  // 1 + 2^-16 = 1 + ulp
      {0x3FFFFF, 0x3FFFFF, {0x40FFFF, 0}},  // 2 * (2 - 2^-16)
      {0x3F8000, 0xBD0000, {0x3F4000, 0}},  // 1.5 - 0.25 = 1.25
      {0x3F8000, 0xBF4000, {0x3D0000, 0}},  // 1.5 - 1.25 = 0.25 (cancellation)
      {0x3F0001, 0xBF0000, {0x2F0000, 0}},  // (1 + 2^-16) - 1 = 2^-16
      {0xC08000, 0x000000, {0xC08000, 0}},  // x + 0 = x
      {0x000000, 0x3F0001, {0x3F0001, 0}},
  });
}

TEST(Fp24Add, RoundingToNearestEven) {
  expect_binary(add, "add", {
      {0x3F0000, 0x2E0000, {0x3F0000, kNX}},  // 1 + 2^-17: tie, f 0 is even
      {0x3F0001, 0x2E0000, {0x3F0002, kNX}},  // 1 + 1.5 ulp: tie, up to f 2
      {0x3F0000, 0x2E0001, {0x3F0001, kNX}},  // 1 + 2^-17 + 2^-33: above the tie
      {0x3F0000, 0x030000, {0x3F0000, kNX}},  // 1 + 2^-60: only the sticky bit
      {0xBF0000, 0xAE0001, {0xBF0001, kNX}},  // negative mirror of the third case
      // 1 + (1 + 2^-16) = 2 + 2^-16, ulp 2^-15 in [2, 4): tie, down to 2.
      {0x3F0001, 0x3F0000, {0x400000, kNX}},
      // 1 + (1 + 3 * 2^-16) = 2 + 1.5 ulp: tie, up to f 2.
      {0x3F0003, 0x3F0000, {0x400002, kNX}},
  });
}

TEST(Fp24Sub, RoundingBelowAPowerOfTwo) {
  // Below 1.0 the ulp halves to 2^-17, so the tie sits at 1 - 2^-18.
  expect_binary(sub, "sub", {
      {0x3F0000, 0x2E0000, {0x3EFFFF, 0}},     // 1 - 2^-17 = 1 - ulp, exact
      {0x3F0000, 0x2D0000, {0x3F0000, kNX}},   // 1 - 2^-18: tie, f 0xFFFF odd, so 1
      {0x3F0000, 0x2D0001, {0x3EFFFF, kNX}},   // 1 - 2^-18 - 2^-34: below the tie
      {0x3F0000, 0x030000, {0x3F0000, kNX}},   // 1 - 2^-60 rounds back to 1
      {0x3F0000, 0x2CFFFF, {0x3F0000, kNX}},   // 1 - (2^-18 - 2^-35): above the tie
  });
}

TEST(Fp24Add, CarryOutOnRounding) {
  expect_binary(add, "add", {
      // (2 - 2^-16) + 2^-17: tie between f 0xFFFF (odd) and 2.0.
      {0x3FFFFF, 0x2E0000, {0x400000, kNX}},
      {0xBFFFFF, 0xAE0000, {0xC00000, kNX}},
      // (2 - 2^-16) + (2^-17 - 2^-34) = 2 - 2^-16 + below half: stays.
      {0x3FFFFF, 0x2DFFFF, {0x3FFFFF, kNX}},
  });
}

// MAX = (2 - 2^-16) * 2^63, ulp 2^47, half ulp 2^46 = 0x6D0000.
TEST(Fp24Add, OverflowBoundary) {
  expect_binary(add, "add", {
      {0x7EFFFF, 0x6CFFFF, {0x7EFFFF, kNX}},   // + (2^46 - 2^29): below half
      {0x7EFFFF, 0x6D0000, {0x7F0000, kOFNX}}, // + 2^46: tie, even is 2^64
      {0x7EFFFF, 0x6D0001, {0x7F0000, kOFNX}}, // above half
      {0xFEFFFF, 0xED0000, {0xFF0000, kOFNX}},
      {0x7EFFFF, 0x7EFFFF, {0x7F0000, kOFNX}},
      {0x7EFFFE, 0x6E0000, {0x7EFFFF, 0}},     // MAX - ulp + ulp = MAX exactly
  });
  expect_binary(sub, "sub", {
      {0xFEFFFF, 0x6D0000, {0xFF0000, kOFNX}}, // -MAX - half ulp
      {0x7EFFFF, 0x6D0000, {0x7EFFFE, kNX}},   // MAX - half ulp: tie, f 0xFFFE even
  });
}

// Every FP24 number is a multiple of 2^-78 (MIN's ulp), so every sum is; one
// below 2^-62 then has at most 16 significant bits and is exact: a sum never
// rounds up to MIN (the mul tests cover that case). Tiny sums still flush to
// a signed zero with UF|NX.
TEST(Fp24Add, UnderflowBoundary) {
  expect_binary(sub, "sub", {
      {0x020000, 0x010000, {0x010000, 0}},      // 2^-61 - 2^-62 = MIN: not tiny
      {0x010001, 0x010000, {0x000000, kUFNX}},  // 2^-78
      {0x810000, 0x810001, {0x000000, kUFNX}},  // -MIN + (MIN + 2^-78): +tiny
      {0x810001, 0x810000, {0x800000, kUFNX}},  // -tiny keeps its sign
      // 2^-61 - (2^-62 + 2^-78) = 2^-62 - 2^-78: exact at 17 bits, but tiny.
      {0x020000, 0x010001, {0x000000, kUFNX}},
  });
  expect_binary(add, "add", {
      {0x020001, 0x820000, {0x000000, kUFNX}},  // 2^-61 * 2^-16 = 2^-77
      {0x820001, 0x020000, {0x800000, kUFNX}},
  });
}

TEST(Fp24Add, SignedZeros) {
  expect_binary(add, "add", {
      {0x000000, 0x000000, {0x000000, 0}},
      {0x800000, 0x800000, {0x800000, 0}},  // (-0) + (-0) = -0
      {0x000000, 0x800000, {0x000000, 0}},
      {0x800000, 0x000000, {0x000000, 0}},
      {0x3F0000, 0xBF0000, {0x000000, 0}},  // x + (-x) = +0
      {0xBF0000, 0x3F0000, {0x000000, 0}},
      {0xFEFFFF, 0x7EFFFF, {0x000000, 0}},
  });
  expect_binary(sub, "sub", {
      {0x800000, 0x000000, {0x800000, 0}},  // (-0) - (+0) = -0
      {0x000000, 0x000000, {0x000000, 0}},
      {0x800000, 0x800000, {0x000000, 0}},
      {0x000000, 0x800000, {0x000000, 0}},
      {0x3F0000, 0x3F0000, {0x000000, 0}},  // x - x = +0
      {0xBF0000, 0xBF0000, {0x000000, 0}},
  });
}

TEST(Fp24Add, DenormalInputsReadAsZero) {
  expect_binary(add, "add", {
      {0x80FFFF, 0x800001, {0x800000, 0}},  // (-0) + (-0) after flushing
      {0x00FFFF, 0x800001, {0x000000, 0}},
      {0x000005, 0x3F0000, {0x3F0000, 0}},  // no NX: the input is exactly 0
      {0x3F0000, 0x8000FF, {0x3F0000, 0}},
  });
  expect_binary(sub, "sub", {
      {0x80FFFF, 0x000001, {0x800000, 0}},  // (-0) - (+0)
      {0x00FFFF, 0x3F0000, {0xBF0000, 0}},
  });
}

TEST(Fp24Add, InfinitiesAndNaNs) {
  expect_binary(add, "add", {
      {0x7F0000, 0x7F0000, {0x7F0000, 0}},
      {0xFF0000, 0xFF0000, {0xFF0000, 0}},
      {0x7F0000, 0xFF0000, {kCanonicalNaN, kNV}},  // inf - inf
      {0xFF0000, 0x7F0000, {kCanonicalNaN, kNV}},
      {0x7F0000, 0xFEFFFF, {0x7F0000, 0}},
      {0x800000, 0xFF0000, {0xFF0000, 0}},
      {0x7F0000, 0x7F8000, {kCanonicalNaN, 0}},  // NaN wins, no flag
      {0x3F0000, 0xFFFFFF, {kCanonicalNaN, 0}},
  });
  expect_binary(sub, "sub", {
      {0x3F0000, 0x7F0000, {0xFF0000, 0}},  // 1 - inf = -inf
      {0x7F0000, 0x7F0000, {kCanonicalNaN, kNV}},
      {0xFF0000, 0xFF0000, {kCanonicalNaN, kNV}},
      {0x7F0000, 0xFF0000, {0x7F0000, 0}},
      {0x7F8001, 0x7F8001, {kCanonicalNaN, 0}},
      {0x3F0000, 0xFFFFFF, {kCanonicalNaN, 0}},
  });
}

// ---- CMP ------------------------------------------------------------------

TEST(Fp24Cmp, EveryOutcome) {
  expect_binary(cmp, "cmp", {
      {0x3F0000, 0x400000, {kLT, 0}},  // 1 < 2
      {0x400000, 0x3F0000, {kGT, 0}},
      {0x3F0000, 0x3F0000, {kEQ, 0}},
      {0x3F0000, 0x3F0001, {kLT, 0}},  // one ulp apart
      {0xBF0000, 0xC00000, {kGT, 0}},  // -1 > -2
      {0xC00000, 0x3F0000, {kLT, 0}},
      {0x800000, 0x000000, {kEQ, 0}},  // -0 == +0
      {0x000000, 0x800000, {kEQ, 0}},
      {0x000001, 0x80FFFF, {kEQ, 0}},  // both flush to zero
      {0x800000, 0x010000, {kLT, 0}},  // -0 < MIN
      {0x810000, 0x00FFFF, {kLT, 0}},  // -MIN < flushed zero
      {0xFF0000, 0xFEFFFF, {kLT, 0}},  // -inf < -MAX
      {0x7F0000, 0x7EFFFF, {kGT, 0}},
      {0x7F0000, 0x7F0000, {kEQ, 0}},
      {0xFF0000, 0x7F0000, {kLT, 0}},
      {0x7F8000, 0x3F0000, {kUN, kNV}},
      {0x3F0000, 0xFF8001, {kUN, kNV}},
      {0x7F8000, 0x7F8000, {kUN, kNV}},
      {0x7FFFFF, 0x7F0000, {kUN, kNV}},
  });
}

// ---- FLOAT ----------------------------------------------------------------

TEST(Fp24Float, Extremes) {
  const auto float_op = [](Bits i) { return from_int(static_cast<std::uint16_t>(i)); };
  expect_unary(float_op, "float", {
      {0x0000, {0x000000, 0}},  // +0
      {0x0001, {0x3F0000, 0}},
      {0xFFFF, {0xBF0000, 0}},  // -1
      {0x0003, {0x408000, 0}},
      {0xFFFD, {0xC08000, 0}},  // -3
      // 32767 = 2^14 * (2 - 2^-14): e = 77, f = 0xFFFF - 3 = 0xFFFC.
      {0x7FFF, {0x4DFFFC, 0}},
      {0x7FFE, {0x4DFFF8, 0}},
      {0x8000, {0xCE0000, 0}},  // -32768 = -2^15, e = 78
      {0x8001, {0xCDFFFC, 0}},  // -32767
      {0x0064, {0x459000, 0}},  // 100 = 2^6 * 1.5625, f = 0.5625 * 2^16 = 0x9000
  });
}

// ---- FIX ------------------------------------------------------------------

TEST(Fp24Fix, InRange) {
  expect_unary(to_int, "fix", {
      {0x000000, {0x0000, 0}},
      {0x800000, {0x0000, 0}},
      {0x00ABCD, {0x0000, 0}},  // flushed zero: no NX
      {0x3F0000, {0x0001, 0}},
      {0xBF0000, {0xFFFF, 0}},     // -1
      {0x3F8000, {0x0001, kNX}},   // 1.5 -> 1
      {0xBF8000, {0xFFFF, kNX}},   // -1.5 -> -1 (toward zero)
      {0x3E0000, {0x0000, kNX}},   // 0.5
      {0xBE0000, {0x0000, kNX}},   // -0.5
      {0x010000, {0x0000, kNX}},   // MIN
      {0x459100, {0x0064, kNX}},   // 100.25 = 2^6 * (1 + 0x9100/2^16)
      {0xC59100, {0xFF9C, kNX}},   // -100.25 -> -100
      {0x4DFFFC, {0x7FFF, 0}},     // 32767
      {0x4DFFFE, {0x7FFF, kNX}},   // 32767.5
      {0x4DFFFF, {0x7FFF, kNX}},   // 32767.75
      {0xCE0000, {0x8000, 0}},     // -32768
      {0xCE0001, {0x8000, kNX}},   // -32768.5 truncates to -32768: in range
      {0xCDFFFF, {0x8001, kNX}},   // -32767.75 -> -32767
  });
}

TEST(Fp24Fix, OutOfRangeSaturates) {
  expect_unary(to_int, "fix", {
      {0x4E0000, {0x7FFF, kNV}},  // 32768: NV only, no NX
      {0x4E0001, {0x7FFF, kNV}},  // 32768.5
      {0xCE0002, {0x8000, kNV}},  // -32769 (ulp 0.5 at 2^15)
      {0x4EFFFF, {0x7FFF, kNV}},  // 65535.5
      {0x4F0000, {0x7FFF, kNV}},  // 2^16
      {0xCF0000, {0x8000, kNV}},
      {0x7EFFFF, {0x7FFF, kNV}},
      {0xFEFFFF, {0x8000, kNV}},
      {0x7F0000, {0x7FFF, kNV}},
      {0xFF0000, {0x8000, kNV}},
      {0x7F8000, {0x7FFF, kNV}},  // NaN: 0x7FFF whatever its sign
      {0xFF8001, {0x7FFF, kNV}},
  });
}

// FLOAT is exact and FIX of an integer drops nothing, so FIX(FLOAT(i)) is i
// for every int16, flags clear.
TEST(Fp24Fix, RoundTripsEveryInt16) {
  for (std::uint32_t i = 0; i <= 0xFFFF; ++i) {
    const Result f = from_int(static_cast<std::uint16_t>(i));
    ASSERT_EQ(f.flags, 0) << "float " << std::hex << i;
    ASSERT_EQ(to_int(f.value), (Result{i, 0})) << "float " << std::hex << i;
  }
}

// ---- NEG / ABS ------------------------------------------------------------

TEST(Fp24NegAbs, SignOnlyAndCanonicalNaN) {
  expect_unary(neg, "neg", {
      {0x3F0000, {0xBF0000, 0}},
      {0xBF0000, {0x3F0000, 0}},
      {0x000000, {0x800000, 0}},
      {0x800000, {0x000000, 0}},
      {0x000123, {0x800000, 0}},  // flushed to +0 first
      {0x800123, {0x000000, 0}},
      {0x7EFFFF, {0xFEFFFF, 0}},
      {0x7F0000, {0xFF0000, 0}},
      {0x7F8000, {kCanonicalNaN, 0}},
      {0xFFFFFF, {kCanonicalNaN, 0}},
  });
  expect_unary(mc1::fp24::abs, "abs", {
      {0xBF8000, {0x3F8000, 0}},
      {0x3F8000, {0x3F8000, 0}},
      {0x800000, {0x000000, 0}},
      {0x80FFFF, {0x000000, 0}},
      {0x00FFFF, {0x000000, 0}},
      {0xFF0000, {0x7F0000, 0}},
      {0x810000, {0x010000, 0}},
      {0xFF8001, {kCanonicalNaN, 0}},
  });
}

// ---- the decimal text of reports and waveforms ------------------------------

TEST(Fp24Decimal, ShortestTextThatReadsBack) {
  EXPECT_EQ(fp24_decimal(0x3F8000), "1.5");
  EXPECT_EQ(fp24_decimal(0xBD0000), "-0.25");
  EXPECT_EQ(fp24_decimal(0x3F0001), "1.00002");  // 1 + 2^-16: 6 digits read back
  EXPECT_EQ(fp24_decimal(0x000000), "0");
  EXPECT_EQ(fp24_decimal(0x800000), "-0");
  EXPECT_EQ(fp24_decimal(0x000123), "0 (DAZ)");
  EXPECT_EQ(fp24_decimal(0xFF0000), "-inf");
  EXPECT_EQ(fp24_decimal(0x7F8000), "nan");
  // Every 4099th normal word reads back from its text.
  for (std::uint32_t w = 0x010000; w < 0x7F0000; w += 4099) {
    for (std::uint32_t s : {0u, 0x800000u}) {
      const std::string t = fp24_decimal(w | s);
      EXPECT_EQ(fp24_from_double(std::strtod(t.c_str(), nullptr)), w | s) << t;
    }
  }
}

}  // namespace
