// Function unit of the FP24 model: RECIP, SQRT, SIN, COS (docs/fp24.md,
// docs/fp24-func.md). Every expected encoding below was computed with MPFR
// (precision 17, round to nearest even, then the spec's overflow/underflow
// rule) and written down here; the exhaustive comparison over all 2^24
// inputs is the regression's job (tb/).
#include <gtest/gtest.h>

#include <cstdint>

#include "fp24.hpp"
#include "fp24_rom.inc"
#include "fp24_trig.hpp"

namespace mc1::fp24 {
namespace {

constexpr std::uint8_t kNone = 0;
constexpr std::uint8_t kUFNX = kUF | kNX;

struct Case {
  Bits a;
  Bits value;
  std::uint8_t flags;
};

void expect_all(Result (*op)(Bits), const char* name, std::initializer_list<Case> cases) {
  for (const Case& c : cases) {
    const Result r = op(c.a);
    EXPECT_EQ(r.value, c.value) << name << " " << std::hex << c.a;
    EXPECT_EQ(static_cast<int>(r.flags), static_cast<int>(c.flags)) << name << " " << std::hex << c.a;
  }
}

TEST(Fp24Recip, KnownValues) {
  expect_all(recip, "recip",
             {
                 {0x400000, 0x3E0000, kNone},  // 1/2 = 0.5 exactly
                 {0x408000, 0x3D5555, kNX},    // 1/3
                 {0xC08000, 0xBD5555, kNX},    // 1/-3
                 {0x3F5555, 0x3E8000, kNX},    // 1/1.33331 rounds to 0.75
                 {0x010000, 0x7D0000, kNone},  // 1/2^-62 = 2^62: no overflow in this format
             });
}

TEST(Fp24Recip, LargestInputsUnderflow) {
  // 1/2^63 = 2^-63 is exact but tiny: the spec's rule 4 still gives UF|NX.
  expect_all(recip, "recip",
             {
                 {0x7E0000, 0x000000, kUFNX},
                 {0x7DFFFF, 0x000000, kUFNX},  // 2^-63 (1 + 2^-16) after rounding: still tiny
                 {0x7EFFFF, 0x000000, kUFNX},
                 {0xFEFFFF, 0x800000, kUFNX},  // the sign survives
             });
}

TEST(Fp24Recip, Specials) {
  expect_all(recip, "recip",
             {
                 {0x000000, 0x7F0000, kDZ},
                 {0x800000, 0xFF0000, kDZ},
                 {0x00ABCD, 0x7F0000, kDZ},  // e = 0 reads as +0 (DAZ)
                 {0x7F0000, 0x000000, kNone},
                 {0xFF0000, 0x800000, kNone},
                 {0x7F1234, kCanonicalNaN, kNone},
                 {0xFFFFFF, kCanonicalNaN, kNone},
             });
}

TEST(Fp24Sqrt, KnownValues) {
  expect_all(fp24::sqrt, "sqrt",
             {
                 {0x410000, 0x400000, kNone},  // sqrt 4 = 2
                 {0x400000, 0x3F6A0A, kNX},    // sqrt 2
                 {0x3FFFFF, 0x3F6A0A, kNX},    // sqrt(2 - 2^-16) rounds to sqrt 2's encoding
                 {0x3F0001, 0x3F0000, kNX},    // sqrt(1 + 2^-16) = 1 + 2^-17 - ...: rounds down
                 {0x010000, 0x200000, kNone},  // sqrt 2^-62 = 2^-31
                 {0x7EFFFF, 0x5EFFFF, kNX},    // largest finite
             });
}

TEST(Fp24Sqrt, Specials) {
  expect_all(fp24::sqrt, "sqrt",
             {
                 {0x000000, 0x000000, kNone},
                 {0x800000, 0x800000, kNone},  // sqrt(-0) = -0
                 {0x008000, 0x000000, kNone},  // DAZ
                 {0xBF0000, kCanonicalNaN, kNV},
                 {0x810000, kCanonicalNaN, kNV},
                 {0x7F0000, 0x7F0000, kNone},
                 {0xFF0000, kCanonicalNaN, kNV},
                 {0x7F0001, kCanonicalNaN, kNone},
             });
}

TEST(Fp24Sin, KnownValues) {
  expect_all(fp24::sin, "sin",
             {
                 {0x3F0000, 0x3EAED5, kNX},  // sin 1
                 {0xBF0000, 0xBEAED5, kNX},  // sin -1 = -sin 1
                 {0x3E0000, 0x3DEAEF, kNX},  // sin 0.5: last input without reduction is 0x3DFFFF
                 {0x3D8000, 0x3D7710, kNX},  // sin 0.375
                 {0x409220, 0xAE2AEF, kNX},  // sin 3.1416015625 = -8.9e-6
                 {0x4C3880, 0xBD38F3, kNX},  // sin 10000
             });
}

TEST(Fp24Sin, TinyArguments) {
  // sin x = x (1 - x^2/6 ...) rounds back to x; 2^-62 stays normal.
  expect_all(fp24::sin, "sin",
             {
                 {0x010000, 0x010000, kNX},
                 {0x01FFFF, 0x01FFFF, kNX},
                 {0x810000, 0x810000, kNX},
             });
}

TEST(Fp24Sin, HugeArguments) {
  expect_all(fp24::sin, "sin",
             {
                 {0x7EFFFF, 0xBB6A26, kNX},  // largest finite, ~1.8e19
                 {0x7E0000, 0x3EFFF7, kNX},  // 2^63
                 // The input closest to a multiple of pi (~2^49): |sin| ~ 1.5 * 2^-23.
                 {0x70206A, 0x287B15, kNX},
                 {0xF0206A, 0xA87B15, kNX},
             });
}

TEST(Fp24Cos, KnownValues) {
  expect_all(fp24::cos, "cos",
             {
                 {0x3F0000, 0x3E14A3, kNX},  // cos 1
                 {0xBF0000, 0x3E14A3, kNX},  // cos is even
                 {0x3E0000, 0x3EC153, kNX},  // cos 0.5
                 {0x3FC910, 0xBCB425, kNX},  // cos 1.5708 (just above pi/2)
                 {0x010000, 0x3F0000, kNX},  // cos 2^-62 rounds to 1, inexactly
                 {0x4C3880, 0xBEE781, kNX},  // cos 10000
                 {0x7EFFFF, 0x3EFDFF, kNX},
                 {0x7E0000, 0x3882AA, kNX},
                 {0x6F206A, 0x277B15, kNX},  // closest to an odd multiple of pi/2
             });
}

TEST(Fp24SinCos, Specials) {
  expect_all(fp24::sin, "sin",
             {
                 {0x000000, 0x000000, kNone},
                 {0x800000, 0x800000, kNone},
                 {0x80FFFF, 0x800000, kNone},  // DAZ: -0
                 {0x7F0000, kCanonicalNaN, kNV},
                 {0xFF0000, kCanonicalNaN, kNV},
                 {0x7FFFFF, kCanonicalNaN, kNone},
             });
  expect_all(fp24::cos, "cos",
             {
                 {0x000000, 0x3F0000, kNone},
                 {0x800000, 0x3F0000, kNone},
                 {0x80FFFF, 0x3F0000, kNone},
                 {0x7F0000, kCanonicalNaN, kNV},
                 {0xFF0000, kCanonicalNaN, kNV},
                 {0xFF8001, kCanonicalNaN, kNone},
             });
}

TEST(Fp24Func, DispatchByOp) {
  EXPECT_EQ(execute(Op::Recip, 0x400000), (Result{0x3E0000, kNone}));
  EXPECT_EQ(execute(Op::Sqrt, 0x410000), (Result{0x400000, kNone}));
  EXPECT_EQ(execute(Op::Sin, 0x3F0000), (Result{0x3EAED5, kNX}));
  EXPECT_EQ(execute(Op::Cos, 0x3F0000), (Result{0x3E14A3, kNX}));
}

// The generated ROMs: the bits of 2/pi and pi/2 are well known, and the
// series coefficients are 1/n! in 0.64 fixed point.
TEST(Fp24FuncRom, Constants) {
  // 2/pi = 0.A2F9836E4E441529FC2757D1F534DDC0DB62...; the window of exponent
  // E starts at the bit of weight 2^-(E-17), so E = 18 starts at its first
  // fraction bit and E = 15 with three zeros.
  const trig::Word128& w18 = rom::kTwoOverPi[18 - trig::kReduceMinExp];
  EXPECT_EQ(w18.hi, 0xA2F9836E4E441529u);
  EXPECT_EQ(w18.lo, 0xFC2757D1F534DDC0u);
  EXPECT_EQ(rom::kTwoOverPi[15 - trig::kReduceMinExp].hi, 0x145F306DC9C882A5u);
  EXPECT_EQ(rom::kHalfPi, 0xC90FDAA22168C235u);  // pi/2 = 1.921FB54442D1846989... (1.63)
  EXPECT_EQ(rom::kSinCoef[0], 0x2AAAAAAAAAAAAAABu);  // 1/6
  EXPECT_EQ(rom::kCosCoef[0], 0x8000000000000000u);  // 1/2
  EXPECT_EQ(rom::kCosCoef[1], 0x0AAAAAAAAAAAAAABu);  // 1/24
}

// The hard-case ROM is sorted by key (the model binary-searches it) and
// every entry is a correctly rounded, inexact SIN/COS result of its input.
TEST(Fp24FuncRom, HardCasesAreConsistent) {
  for (std::size_t i = 0; i < rom::kHardCases.size(); ++i) {
    const rom::HardCase& h = rom::kHardCases[i];
    if (i > 0) {
      EXPECT_LT(rom::kHardCases[i - 1].key, h.key);
    }
    const bool is_cos = (h.key >> 24) != 0;
    const Result r = is_cos ? fp24::cos(h.key & 0xFFFFFF) : fp24::sin(h.key & 0xFFFFFF);
    EXPECT_EQ(r, (Result{h.result, kNX})) << std::hex << h.key;
  }
}

}  // namespace
}  // namespace mc1::fp24
