// The one rounding rule in C++, bits::round_sig() (hw/apu/fp24_bits.hpp),
// which every FP24 operation's result goes through, against the RTL's one
// rounding rule, apu_rtl/fp24_round.sv verilated alone (Vfp24_round, at the
// units' parameters EXP_W 7, FRAC_W 16, SEXP_W 9). bits::round(), the rule
// with fp24_round's ports, equals the RTL on every input of the module:
// 2 signs x 512 exponents x 2^16 fractions x guard x sticky = 2^28 inputs,
// result and flags; and the rule at every tail width the units use equals
// that form. The same sweep against two rules with one deliberate flaw each
// (ties away from zero; tininess before rounding) must find them: a
// comparison that cannot fail proves nothing.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "Vfp24_round.h"
#include "rtl_coverage.hpp"
#include "fp24_bits.hpp"
#include "verilated.h"
#include "verilated_context.hpp"

namespace {

using namespace mc1::fp24;
using RoundFn = std::function<Result(Bits, int, std::uint32_t, bool, bool)>;

constexpr int kSexpW = 9;  // fp24_round's SEXP_W in every unit
constexpr int kExpMin = -(1 << (kSexpW - 1)), kExpMax = (1 << (kSexpW - 1)) - 1;

struct Input {
  bool sign;
  int exp;
  std::uint32_t frac;
  bool guard, sticky;
};

std::string describe(const Input& in) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "sign %d exp %d frac %04x guard %d sticky %d", in.sign, in.exp, in.frac, in.guard,
                in.sticky);
  return buf;
}

// fp24_round's exp + carry is SEXP_W bits wide: at the top exponent a carry
// wraps it to the most negative one (the RTL then says tiny where the
// unbounded rule says overflow). No unit comes near it (the multiplier's
// exponents reach 190 at most, the adder's 127, the function unit's 126), so
// these inputs are outside the module's contract, and the only ones where
// the two may differ.
bool rtl_exponent_wraps(const Input& in) {
  return in.exp == kExpMax && in.frac == bits::kFracMask && in.guard && (in.sticky || (in.frac & 1));
}

class RtlRound {
 public:
  RtlRound() : ctx_(mc1::rtl::new_context()), m_(std::make_unique<Vfp24_round>(ctx_.get(), "TOP")) {
    m_->en = 1;
  }
  ~RtlRound() { mc1::rtl_coverage::collect(*ctx_); }  // a coverage build's counts (apu_rtl/rtl_coverage.hpp)
  Result operator()(const Input& in) {
    m_->sign = in.sign;
    m_->exp = static_cast<std::uint32_t>(in.exp) & ((1u << kSexpW) - 1);
    m_->frac = in.frac;
    m_->guard = in.guard;
    m_->sticky = in.sticky;
    m_->eval();
    return {m_->result, m_->flags};
  }

 private:
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Vfp24_round> m_;
};

struct Sweep {
  std::uint64_t inputs = 0, mismatches = 0, wrapped = 0;
  std::vector<std::string> first;  // the first few mismatches, described
};

// Every input with an exponent in `exps` (every fraction, guard, sticky and
// sign) through `rule` and the RTL.
Sweep sweep(const RoundFn& rule, const std::vector<int>& exps) {
  RtlRound rtl;
  Sweep s;
  for (int exp : exps)
    for (int sign = 0; sign < 2; ++sign)
      for (std::uint32_t frac = 0; frac <= bits::kFracMask; ++frac)
        for (int gs = 0; gs < 4; ++gs) {
          const Input in{sign != 0, exp, frac, (gs & 2) != 0, (gs & 1) != 0};
          const Result want = rtl(in);
          const Result got = rule(in.sign ? kSignBit : 0, in.exp, in.frac, in.guard, in.sticky);
          ++s.inputs;
          if (rtl_exponent_wraps(in)) {
            // The RTL's wrapped exponent reads as tiny; the rule is unbounded.
            ++s.wrapped;
            EXPECT_EQ(want.value, in.sign ? kSignBit : 0u) << describe(in);
            EXPECT_EQ(want.flags, kUF | kNX) << describe(in);
            continue;
          }
          if (got == want) continue;
          if (++s.mismatches <= 5) {
            char buf[64];
            std::snprintf(buf, sizeof buf, ": C++ %06x/%02x, RTL %06x/%02x", got.value, got.flags, want.value,
                          want.flags);
            s.first.push_back(describe(in) + buf);
          }
        }
  return s;
}

std::vector<int> every_exponent() {
  std::vector<int> v;
  for (int e = kExpMin; e <= kExpMax; ++e) v.push_back(e);
  return v;
}

std::string listing(const Sweep& s) {
  std::string out;
  for (const auto& line : s.first) out += "\n  " + line;
  return out;
}

Result the_rule(Bits s, int exp, std::uint32_t frac, bool guard, bool sticky) {
  return bits::round(s, exp, frac, guard, sticky);
}

TEST(Fp24Round, EqualsTheRtlOnEveryInput) {
  const Sweep s = sweep(the_rule, every_exponent());
  EXPECT_EQ(s.inputs, std::uint64_t{1} << 28);
  EXPECT_EQ(s.wrapped, 4u);  // exp 255, frac ffff, guard 1: sticky 0/1, sign 0/1
  EXPECT_EQ(s.mismatches, 0u) << listing(s);
}

// Exponents where each flaw shows: around the normal range's ends and 1.0.
const std::vector<int> kEdgeExps = {-1, 0, 1, 2, 63, 125, 126, 127};

TEST(Fp24Round, FindsTiesAwayFromZero) {
  // A tie (guard, no sticky) always rounds up, magnitude away from zero.
  const auto ties_away = [](Bits s, int exp, std::uint32_t frac, bool guard, bool sticky) {
    return bits::round(s, exp, frac, guard, sticky || guard);
  };
  const Sweep s = sweep(ties_away, kEdgeExps);
  // Every tie with an even fraction (2^15 of them, both signs) at the five
  // exponents whose results stay finite and normal (1 2 63 125 126).
  EXPECT_EQ(s.mismatches, 5u * 2 * (1u << 15)) << listing(s);
}

TEST(Fp24Round, FindsTininessBeforeRounding) {
  const auto before = [](Bits s, int exp, std::uint32_t frac, bool guard, bool sticky) {
    if (exp < 1) return Result{s, static_cast<std::uint8_t>(kUF | kNX)};
    return bits::round(s, exp, frac, guard, sticky);
  };
  const Sweep s = sweep(before, kEdgeExps);
  // exp 0, frac ffff rounded up to 2^-62: guard set, sticky 0 (a tie, the
  // fraction odd) or 1, both signs.
  EXPECT_EQ(s.mismatches, 4u) << listing(s);
}

// round() is round_sig<2>(): the tail is the guard and the sticky. The units
// call round_sig() with longer tails (the multiplier 17 bits, the adder 46,
// the host's conversion 36; round_pack() takes 47 and jams the lowest two
// into one): the same rule, its RNE by one
// add whatever the width, must give what round() gives for the tail's guard
// and sticky, at every tail that matters (zero, one, just below, at and
// above half, all ones, random) x fractions x exponents around the range.
template <int kDrop, class Rule>
void expect_width_agrees(std::mt19937_64& rng, Rule rule) {
  constexpr std::uint64_t kHalf = std::uint64_t{1} << (kDrop - 1), kTailMask = 2 * kHalf - 1;
  std::vector<std::uint64_t> tails = {0, 1, 2, kHalf - 1, kHalf, kHalf + 1, kTailMask - 1, kTailMask};
  for (int i = 0; i < 8; ++i) tails.push_back(rng() & kTailMask);
  for (int i = 0; i < 4; ++i) tails.push_back(kHalf | (rng() & (kHalf - 1)));
  const std::uint32_t fracs[] = {0x0000, 0x0001, 0x0002, 0x7FFF, 0x8000, 0xFFFE, 0xFFFF, 0x1234, 0xABCD};
  const int exps[] = {-300, -62, -1, 0, 1, 2, 63, 125, 126, 127, 128, 300};
  for (std::uint64_t tail : tails)
    for (std::uint32_t frac : fracs)
      for (int exp : exps)
        for (Bits s : {0u, kSignBit}) {
          const std::uint64_t q = (std::uint64_t{bits::kHidden | frac} << kDrop) | tail;
          const Result want = bits::round(s, exp, frac, (tail >> (kDrop - 1)) & 1, (tail & (kHalf - 1)) != 0);
          ASSERT_EQ(rule(s, exp, q), want)
              << "kDrop " << kDrop << " exp " << exp << " frac " << std::hex << frac << " tail " << tail;
        }
}

TEST(Fp24Round, EveryTailWidthInUseEqualsTheGuardAndStickyForm) {
  std::mt19937_64 rng(40);
  expect_width_agrees<17>(rng, bits::round_sig<17>);
  expect_width_agrees<36>(rng, bits::round_sig<36>);
  expect_width_agrees<46>(rng, bits::round_sig<46>);
  expect_width_agrees<47>(rng, [](Bits s, int exp, std::uint64_t m) { return bits::round_pack(s != 0, exp, m); });
}

// The spec's rule on hand-worked cases, whatever the RTL says.
TEST(Fp24Round, WorkedCases) {
  const auto r = [](int exp, std::uint32_t frac, bool g, bool st) { return bits::round(0, exp, frac, g, st); };
  EXPECT_EQ(r(63, 0x0000, true, false), (Result{0x3F0000, kNX}));   // tie, even: down
  EXPECT_EQ(r(63, 0x0001, true, false), (Result{0x3F0002, kNX}));   // tie, odd: up to even
  EXPECT_EQ(r(63, 0x0000, true, true), (Result{0x3F0001, kNX}));    // above the tie: up
  EXPECT_EQ(r(63, 0x0001, false, true), (Result{0x3F0001, kNX}));   // below: down
  EXPECT_EQ(r(63, 0xFFFF, true, false), (Result{0x400000, kNX}));   // carry into the exponent
  EXPECT_EQ(r(63, 0x1234, false, false), (Result{0x3F1234, 0}));    // exact
  EXPECT_EQ(r(126, 0xFFFF, false, true), (Result{0x7EFFFF, kNX}));  // largest finite
  EXPECT_EQ(r(126, 0xFFFF, true, false), (Result{0x7F0000, kOF | kNX}));  // rounds to 2^64
  EXPECT_EQ(r(127, 0x0000, false, false), (Result{0x7F0000, kOF | kNX}));
  EXPECT_EQ(r(0, 0xFFFF, true, false), (Result{0x010000, kNX}));    // up to 2^-62: not tiny
  EXPECT_EQ(r(0, 0xFFFF, false, true), (Result{0x000000, kUF | kNX}));  // stays below: tiny
  EXPECT_EQ(r(1, 0x0000, false, false), (Result{0x010000, 0}));     // smallest normal, exact
  EXPECT_EQ(bits::round(kSignBit, -300, 0, false, false), (Result{kSignBit, kUF | kNX}));
}

}  // namespace
