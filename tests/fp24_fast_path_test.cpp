// The adder's branch-free normal path (fp24_arith_inline.hpp add_normal(),
// what fp24::add/sub and the ISS compute) against the general rule it
// replaces, add_normal_generic() (exact sum, normalize(), round_pack()): the
// same bits and flags on edge and random operands. The vector set is also
// run against a rounding rule with one deliberate flaw, which it must catch:
// a comparison that cannot fail proves nothing.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <algorithm>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "fp24_arith_inline.hpp"

namespace {

using namespace mc1::fp24;
using AddFn = std::function<Result(Bits, Bits)>;

Bits encode(bool neg, int e, std::uint32_t frac) {
  return (neg ? kSignBit : 0u) | (static_cast<Bits>(e) << kFracBits) | (frac & 0xFFFF);
}

// Normal operands: exponents at the edges of the range and around every
// alignment distance that changes the sticky or the normalization, fractions
// with carries, ties and borrows, both signs; all pairs.
std::vector<Bits> edge_operands() {
  const int exps[] = {1, 2, 3, 17, 18, 40, 41, 42, 60, 62, 63, 64, 65, 80, 104, 105, 124, 125, 126};
  const std::uint32_t fracs[] = {0x0000, 0x0001, 0x0002, 0x0003, 0x7FFF, 0x8000, 0x8001,
                                 0xFFFE, 0xFFFF, 0x5555, 0xAAAA, 0x00FF, 0xFF00};
  std::vector<Bits> v;
  for (int e : exps)
    for (std::uint32_t f : fracs)
      for (bool neg : {false, true}) v.push_back(encode(neg, e, f));
  return v;
}

struct Mismatch {
  Bits a, b;
  Result fast, reference;
};

std::string describe(const Mismatch& m) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "add %06x %06x: fast %06x/%02x, reference %06x/%02x", m.a, m.b, m.fast.value,
                m.fast.flags, m.reference.value, m.reference.flags);
  return buf;
}

// Compares on all edge pairs, then `random` pairs: a third with exponents at
// most 20 apart (cancellation, ties), a third at most 50 apart, the rest
// anywhere. The first mismatch, if any.
std::optional<Mismatch> first_mismatch(const AddFn& fast, const AddFn& reference, std::uint64_t random) {
  const auto check = [&](Bits a, Bits b) -> std::optional<Mismatch> {
    const Result f = fast(a, b), r = reference(a, b);
    if (f != r) return Mismatch{a, b, f, r};
    return std::nullopt;
  };
  const std::vector<Bits> edges = edge_operands();
  for (Bits a : edges)
    for (Bits b : edges)
      if (auto m = check(a, b)) return m;
  std::mt19937_64 rng(16);
  for (std::uint64_t i = 0; i < random; ++i) {
    const std::uint64_t r = rng();
    const int ea = 1 + static_cast<int>((r >> 32) % 126);
    const int spread = i % 3 == 0 ? 20 : i % 3 == 1 ? 50 : 125;
    const int eb = std::clamp(ea + static_cast<int>((r >> 40) % (2 * spread + 1)) - spread, 1, 126);
    const Bits a = encode((r >> 62) & 1, ea, static_cast<std::uint32_t>(r));
    const Bits b = encode((r >> 63) & 1, eb, static_cast<std::uint32_t>(r >> 16));
    if (auto m = check(a, b)) return m;
  }
  return std::nullopt;
}

// All 2^17 signed fractions of b against a few a, at the alignment distances
// where the sticky, the guard bit or the normalization change.
std::optional<Mismatch> first_mismatch_sweep(const AddFn& fast, const AddFn& reference) {
  const Bits as[] = {encode(false, 63, 0), encode(false, 63, 0xFFFF), encode(true, 63, 0x8000),
                     encode(false, 63, 0x1234), encode(true, 63, 0xFFFE), encode(false, 63, 1)};
  const int ds[] = {0, 1, 2, 16, 17, 18, 19, 41};
  for (Bits a : as)
    for (int d : ds)
      for (std::uint32_t sf = 0; sf < 0x20000; ++sf) {
        const Bits b = encode(sf >> 16, 63 - d, sf);
        const Result f = fast(a, b), r = reference(a, b);
        if (f != r) return Mismatch{a, b, f, r};
      }
  return std::nullopt;
}

Result fast_add(Bits a, Bits b) { return detail::add_normal(a, b); }
Result generic_add(Bits a, Bits b) { return detail::add_normal_generic(a, b); }

// The general rule with a classic flaw: the bits of the smaller operand
// shifted out are dropped instead of kept as a sticky bit (wrong flags when
// they are lost, wrong rounding when they break a tie).
Result flawed_add(Bits a, Bits b) {
  constexpr int kPos = 40;
  if ((b & bits::kMagMask) > (a & bits::kMagMask)) std::swap(a, b);
  const int d = std::min(bits::exp_of(a) - bits::exp_of(b), 63);
  const std::uint64_t big = std::uint64_t{bits::sig_of(a)} << kPos;
  const std::uint64_t small = (std::uint64_t{bits::sig_of(b)} << kPos) >> d;
  const std::uint64_t m = bits::sign_of(a) == bits::sign_of(b) ? big + small : big - small;
  if (m == 0) return {0, 0};
  const auto n = bits::normalize(m, bits::exp_of(a) - kBias - kPos - kFracBits);
  return bits::round_pack(bits::sign_of(a), n.exp, n.sig);
}

TEST(Fp24FastPath, BranchFreeAddEqualsTheGeneralRule) {
  const auto m = first_mismatch(fast_add, generic_add, 4'000'000);
  EXPECT_FALSE(m) << describe(*m);
}

TEST(Fp24FastPath, BranchFreeAddEqualsTheGeneralRuleOnAllFractionsAtTheAlignmentEdges) {
  const auto m = first_mismatch_sweep(fast_add, generic_add);
  EXPECT_FALSE(m) << describe(*m);
}

TEST(Fp24FastPath, SubtractionIsAdditionOfTheNegatedOperand) {
  std::mt19937_64 rng(17);
  for (int i = 0; i < 200'000; ++i) {
    const std::uint64_t r = rng();
    const Bits a = encode(r & 1, 1 + static_cast<int>((r >> 8) % 126), static_cast<std::uint32_t>(r >> 16));
    const Bits b = encode((r >> 1) & 1, 1 + static_cast<int>((r >> 32) % 126), static_cast<std::uint32_t>(r >> 40));
    ASSERT_EQ(inl::sub24(a, b), detail::add_normal_generic(a, b ^ kSignBit)) << std::hex << a << " " << b;
  }
}

// The zero paths inline in mul24/add24/sub24 (a zero operand, no infinity or
// NaN) against the cold routines they stand in for, which take every operand
// that is not normal: all fractions and both signs of a at the exponents 0,
// 1, 126 and 127 (zeros with subnormal encodings, normals, infinities and
// NaNs) against zeros, subnormals, infinities and NaNs of either sign, both
// orders.
TEST(Fp24FastPath, InlineZeroPathsEqualTheColdRoutines) {
  const Bits others[] = {0x000000, 0x800000, 0x00ABCD, 0x80ABCD, 0x000001, 0x7F0000, 0xFF0000, 0x7F1234, 0xFF8000};
  const auto check = [](Bits a, Bits b) {
    if (inl::both_normal(a, b)) return;
    const Bits fa = bits::flush(a), fb = bits::flush(b);
    ASSERT_EQ(inl::mul24(a, b), detail::mul_special(fa, fb)) << "mul " << std::hex << a << " " << b;
    ASSERT_EQ(inl::add24(a, b), detail::add_special(fa, fb)) << "add " << std::hex << a << " " << b;
    ASSERT_EQ(inl::sub24(a, b), detail::add_special(fa, bits::flush(b ^ kSignBit))) << "sub " << std::hex << a << " " << b;
  };
  for (int e : {0, 1, 126, 127})
    for (std::uint32_t sf = 0; sf < 0x20000; ++sf) {
      const Bits a = encode(sf >> 16, e, sf);
      for (Bits b : others) {
        ASSERT_NO_FATAL_FAILURE(check(a, b));
        ASSERT_NO_FATAL_FAILURE(check(b, a));
      }
    }
}

// The vectors above reach the operands whose low bits are shifted out: a
// flaw there is caught.
TEST(Fp24FastPath, TheComparisonCatchesAFlawedSticky) {
  const auto m = first_mismatch(fast_add, flawed_add, 4'000'000);
  ASSERT_TRUE(m);
  EXPECT_NE(m->fast, m->reference);
}

}  // namespace
