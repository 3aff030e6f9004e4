// fp24_lanes.hpp's batched MUL and ADD/SUB, each variant the host runs,
// against the scalar ops they stand for (fp24::inl::mul24, add24, sub24),
// lane by lane: every value of a lane in use, and the flags, both as the OR
// over the lanes in use and (one op under test among flagless ones) as that
// lane's own. Operands are biased to the classes where a batched rounding,
// alignment, sign or special-lane test goes wrong; padding lanes hold
// arbitrary operands whose flags must not count; results are sometimes
// written over the operands.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <numeric>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "fp24_arith_inline.hpp"
#include "fp24_lanes.hpp"

namespace mc1::fp24::lanes {
// GoogleTest names a variant in a failure by its name (found by ADL).
void PrintTo(Variant v, std::ostream* os) { *os << name(v); }
}  // namespace mc1::fp24::lanes

namespace {

using namespace mc1::fp24;
namespace lanes = mc1::fp24::lanes;
using lanes::kLanes;

enum class Kind { Mul, Add };

Bits encode(bool neg, int e, std::uint32_t frac) {
  return (neg ? kSignBit : 0u) | (static_cast<Bits>(e) << kFracBits) | (frac & 0xFFFF);
}

// One op: mul24(x, y), add24(x, y), or sub24(x, y) if sub; y is the word
// stored in V.
struct Lane {
  Bits x, y;
  bool sub;
};

Result reference(Kind kind, const Lane& l) {
  if (kind == Kind::Mul) return inl::mul24(l.x, l.y);
  return l.sub ? inl::sub24(l.x, l.y) : inl::add24(l.x, l.y);
}

// Operand pairs biased to the interesting classes. For Add the pair is the
// effective one (x + y); the caller makes a SUB lane of it by flipping y.
class Operands {
 public:
  explicit Operands(std::uint64_t seed) : rng_(seed) {}

  std::uint64_t next() { return rng_(); }
  std::mt19937_64& engine() { return rng_; }
  unsigned below(unsigned n) { return static_cast<unsigned>(rng_() % n); }
  bool coin() { return rng_() & 1; }

  Bits any() { return static_cast<Bits>(rng_()) & 0xFFFFFF; }
  // A zero with any fraction (DAZ), an infinity or a NaN, either sign.
  Bits special() {
    const std::uint32_t f = static_cast<std::uint32_t>(rng_()) & 0xFFFF;
    switch (below(4)) {
      case 0: return encode(coin(), 0, f);
      case 1: return encode(coin(), 0, 0);
      case 2: return encode(coin(), 127, 0);
      default: return encode(coin(), 127, f | 1);
    }
  }
  // Fractions with carries, ties and borrows half the time.
  std::uint32_t frac() {
    static constexpr std::uint32_t kTricky[] = {0x0000, 0x0001, 0x0002, 0x0003, 0x7FFF, 0x8000, 0x8001,
                                                0xFFFE, 0xFFFF, 0x5555, 0xAAAA, 0x6A0A, 0x00FF, 0xFF00};
    if (coin()) return static_cast<std::uint32_t>(rng_()) & 0xFFFF;
    return kTricky[below(std::size(kTricky))];
  }
  // Sometimes replaces an operand by a special or an arbitrary word.
  Bits maybe_odd(Bits v) {
    switch (below(16)) {
      case 0: return special();
      case 1: return any();
      default: return v;
    }
  }

  Lane mul_pair() {
    // Exponent of the product's leading one before rounding, t = ea + eb - 63
    // (+1 if the significands' product is >= 2): anywhere, or at the edges
    // where it rounds to overflow, to 2^-62 or below it.
    const unsigned mode = below(4);
    const int t = mode == 0 ? 124 + static_cast<int>(below(4)) : mode == 1 ? -2 + static_cast<int>(below(5)) : 0;
    int ea = 1 + static_cast<int>(below(126)), eb = 1 + static_cast<int>(below(126));
    if (mode <= 1) {
      ea = std::clamp(ea, std::max(1, t + 63 - 126), std::min(126, t + 63 - 1));
      eb = t + 63 - ea;
    }
    std::uint32_t fa = frac(), fb = frac();
    switch (below(4)) {
      case 0: {  // significands whose product is near 2: the hi and round-up edges
        const std::uint32_t near2 = static_cast<std::uint32_t>((std::uint64_t{1} << 33) / (0x10000 + fa)) - 0x10000;
        fb = std::min<std::uint32_t>(0xFFFF, near2 + below(5) - 2);
        break;
      }
      case 1:  // 1.5 times an odd significand below 2^18 / 3, or 2 mod 4 above: a tie
        fa = 0x8000;
        fb = coin() ? (below(0x5555) | 1) : std::max<std::uint32_t>(0x5556, below(0x10000)) / 4 * 4 + 2;
        if (fb > 0xFFFF) fb -= 4;
        break;
      default: break;
    }
    Lane l{encode(coin(), ea, fa), encode(coin(), eb, fb), false};
    if (coin()) std::swap(l.x, l.y);
    l.x = maybe_odd(l.x);
    l.y = maybe_odd(l.y);
    return l;
  }

  Lane add_pair() {
    const bool small_exp = below(4) == 0;  // where a cancellation ends below 2^-62
    const int ea = small_exp ? 1 + static_cast<int>(below(20)) : 1 + static_cast<int>(below(126));
    const Bits x = encode(coin(), ea, frac());
    Bits y;
    switch (below(6)) {
      case 0:  // near-cancellation: -x moved a few ulps, across exponents too
        y = ((x & 0x7FFFFF) + below(7) - 3) | (~x & kSignBit);
        if ((y & 0x7F0000) == 0 || (y & 0x7F0000) == 0x7F0000) y = x ^ kSignBit;
        break;
      case 1:  // equal exponents
        y = encode(coin(), ea, frac());
        break;
      case 2:  // overflow edge
        return {maybe_odd(encode(false, 125 + below(2), frac()) | (x & kSignBit)),
                maybe_odd(encode(false, 124 + below(3), frac()) | (coin() ? x & kSignBit : 0)), false};
      case 3:  // random word
        y = any();
        break;
      default:  // exponent differences 0..30 either way
        y = encode(coin(), std::clamp(ea + static_cast<int>(below(61)) - 30, 1, 126), frac());
        break;
    }
    Lane l{x, y, false};
    if (coin()) std::swap(l.x, l.y);
    l.x = maybe_odd(l.x);
    l.y = maybe_odd(l.y);
    return l;
  }

  Lane pair(Kind kind) { return kind == Kind::Mul ? mul_pair() : add_pair(); }

  // An exact normal op with no flags: x * 2^k, or x + x (as x - (-x) for a
  // SUB lane), x of exponent 40..90, k -23..23.
  Lane flagless(Kind kind) {
    const Bits x = encode(coin(), 40 + static_cast<int>(below(51)), static_cast<std::uint32_t>(rng_()));
    if (kind == Kind::Mul) return {x, encode(coin(), 40 + static_cast<int>(below(47)), 0), false};
    return coin() ? Lane{x, x, false} : Lane{x, x ^ kSignBit, true};
  }

 private:
  std::mt19937_64 rng_;
};

// Outcome classes the random stream must reach, counted from the reference.
struct Coverage {
  std::uint64_t nx = 0, of = 0, uf = 0, nv = 0, exact_zero = 0, rounded_to_min_normal = 0, special_in = 0;
  void count(const Lane& l, const Result& r) {
    nx += (r.flags & kNX) != 0;
    of += (r.flags & kOF) != 0;
    uf += (r.flags & kUF) != 0;
    nv += (r.flags & kNV) != 0;
    const bool normal = inl::both_normal(l.x, l.y);
    special_in += !normal;
    exact_zero += normal && (r.value & 0x7FFFFF) == 0 && r.flags == 0;
    rounded_to_min_normal += (r.value & 0x7FFFFF) == 0x010000 && (r.flags & kNX);
  }
};

std::string hex(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%06x", v);
  return buf;
}

// Runs lane[0..n-1] as one batch by `variant` and checks it. The operands
// sit at random places of V among arbitrary words (the padding lanes read
// those); out is a separate buffer or lies over V, operands included.
// isolated >= 0: the other lanes in use are flagless, so the flags returned
// must be exactly that lane's. Returns "" or what differs.
class Harness {
 public:
  Harness(lanes::Variant variant, Kind kind, std::uint64_t seed) : variant_(variant), kind_(kind), gen_(seed) {}

  Operands& gen() { return gen_; }
  const Coverage& coverage() const { return cov_; }

  std::string check(const Lane* lane, unsigned n, int isolated) {
    constexpr unsigned kSlots = 40;
    std::uint32_t V[kSlots + kLanes];
    for (auto& v : V) v = gen_.any();
    unsigned slot[kSlots];
    std::iota(slot, slot + kSlots, 0u);
    std::shuffle(slot, slot + kSlots, gen_.engine());
    lanes::Batch b;
    b.n = static_cast<std::uint8_t>(n);
    b.neg = static_cast<std::uint8_t>(gen_.next());  // the padding lanes' too
    for (unsigned i = 0; i < kLanes; ++i) {
      b.a[i] = static_cast<std::uint16_t>(slot[2 * i]);
      b.b[i] = static_cast<std::uint16_t>(slot[2 * i + 1]);
      if (i >= n) continue;
      V[b.a[i]] = lane[i].x;
      V[b.b[i]] = lane[i].y;
      b.neg = static_cast<std::uint8_t>((b.neg & ~(1u << i)) | (unsigned{lane[i].sub} << i));
      if (lane[i].x == lane[i].y && gen_.coin()) b.b[i] = b.a[i];  // one word read twice
    }
    std::uint32_t separate[kLanes];
    std::uint32_t* out = gen_.coin() ? separate : V + gen_.below(kSlots + 1);
    const std::uint32_t flags =
        kind_ == Kind::Mul ? lanes::mul(variant_, V, b, out) : lanes::add(variant_, V, b, out);
    std::uint32_t want_flags = 0;
    for (unsigned i = 0; i < n; ++i) {
      const Result r = reference(kind_, lane[i]);
      cov_.count(lane[i], r);
      want_flags |= r.flags;
      if (out[i] != r.value || (isolated == static_cast<int>(i) && flags != r.flags))
        return describe(lane[i], i, n, out[i], flags, r);
    }
    if (flags != want_flags) return "flags " + hex(flags) + ", the lanes' OR " + hex(want_flags) + ", n " + std::to_string(n);
    return "";
  }

  // `batches` random batches, n = 1..8, a quarter of them with one lane
  // under test among flagless ones. Returns "" or the first mismatch.
  std::string random(std::uint64_t batches) {
    Lane lane[kLanes];
    for (std::uint64_t k = 0; k < batches; ++k) {
      const unsigned n = 1 + static_cast<unsigned>(k % kLanes);
      const int isolated = k % 4 == 3 ? static_cast<int>(gen_.below(n)) : -1;
      for (unsigned i = 0; i < n; ++i) {
        const bool test_lane = isolated < 0 || static_cast<int>(i) == isolated;
        if (!test_lane) {
          lane[i] = gen_.flagless(kind_);
          continue;
        }
        lane[i] = gen_.pair(kind_);
        if (gen_.below(32) == 0) lane[i].y = lane[i].x;  // x * x, x + x, x - x
        // A SUB lane of the pair generated as x + y: it subtracts -y.
        if (kind_ == Kind::Add && gen_.coin()) lane[i] = {lane[i].x, lane[i].y ^ kSignBit, true};
      }
      const std::string m = check(lane, n, isolated);
      if (!m.empty()) return m;
    }
    return "";
  }

 private:
  std::string describe(const Lane& l, unsigned i, unsigned n, std::uint32_t got, std::uint32_t flags,
                       const Result& r) const {
    const char* op = kind_ == Kind::Mul ? "mul" : l.sub ? "sub" : "add";
    return std::string(lanes::name(variant_)) + " lane " + std::to_string(i) + " of " + std::to_string(n) + ": " +
           op + " " + hex(l.x) + " " + hex(l.y) + " = " + hex(got) + " (batch flags " + hex(flags) +
           "), scalar " + hex(r.value) + "/" + hex(r.flags);
  }

  lanes::Variant variant_;
  Kind kind_;
  Operands gen_;
  Coverage cov_;
};

class Fp24Lanes : public ::testing::TestWithParam<lanes::Variant> {
 protected:
  void SetUp() override {
    if (!lanes::supported(GetParam())) GTEST_SKIP() << lanes::name(GetParam()) << " not supported by this CPU";
  }
};

std::string variant_name(const ::testing::TestParamInfo<lanes::Variant>& info) { return lanes::name(info.param); }

INSTANTIATE_TEST_SUITE_P(Variants, Fp24Lanes, ::testing::ValuesIn(lanes::kVariants), variant_name);

constexpr std::uint64_t kRandomBatches = 1'000'000;  // about 3.6 M ops under test per kind and variant

TEST_P(Fp24Lanes, MulEqualsMul24OnRandomBatches) {
  Harness h(GetParam(), Kind::Mul, 24);
  const std::string m = h.random(kRandomBatches);
  EXPECT_EQ(m, "");
  const Coverage& c = h.coverage();
  EXPECT_GT(c.of, 1000u);
  EXPECT_GT(c.uf, 1000u);
  EXPECT_GT(c.nv, 100u);
  EXPECT_GT(c.rounded_to_min_normal, 100u);
  EXPECT_GT(c.special_in, 10000u);
}

TEST_P(Fp24Lanes, AddEqualsAdd24AndSub24OnRandomBatches) {
  Harness h(GetParam(), Kind::Add, 25);
  const std::string m = h.random(kRandomBatches);
  EXPECT_EQ(m, "");
  const Coverage& c = h.coverage();
  EXPECT_GT(c.of, 1000u);
  EXPECT_GT(c.uf, 1000u);
  EXPECT_GT(c.nv, 100u);
  EXPECT_GT(c.exact_zero, 1000u);
  EXPECT_GT(c.special_in, 10000u);
}

// Directed pairs, each at every lane position among flagless lanes (its
// flags exactly) and with n = 1.
void check_directed(lanes::Variant v, Kind kind, const std::vector<Lane>& pairs) {
  Harness h(v, kind, 7);
  for (const Lane& p : pairs)
    for (unsigned pos = 0; pos < kLanes; ++pos) {
      Lane lane[kLanes];
      for (unsigned i = 0; i <= pos; ++i) lane[i] = i == pos ? p : h.gen().flagless(kind);
      ASSERT_EQ(h.check(lane, pos + 1, static_cast<int>(pos)), "");
      ASSERT_EQ(h.check(&p, 1, 0), "");
    }
}

TEST_P(Fp24Lanes, MulDirectedEdges) {
  check_directed(GetParam(), Kind::Mul,
                 {
                     {0x3EFFFF, 0x010001, false},  // (2 - 2^-32) 2^-63 rounds to 2^-62: not tiny, NX
                     {0x3EFFFF, 0x010000, false},  // (2 - 2^-16) 2^-63: tiny, UF|NX
                     {0x3F8000, 0x3F0001, false},  // 1.5 (1 + 2^-16): a tie, up to even
                     {0x3F8000, 0x3F0003, false},  // 1.5 (1 + 3 2^-16): a tie, down to even
                     {0x3F8000, 0x3F5555, false},  // 1.5 * 0x15555: below 2, a tie
                     {0x3F8000, 0x3F5556, false},  // above 2, a tie
                     {0x7EFFFF, 0x3F0001, false},  // largest finite * (1 + 2^-16): overflow
                     {0x7EFFFF, 0x3F0000, false},  // largest finite * 1: exact
                     {0x001234, 0xFF0000, false},  // DAZ zero * -inf: NaN, NV
                     {0x800000, 0x3F0000, false},  // -0 * 1 = -0
                     {0x7F0001, 0x3F0000, false},  // NaN
                 });
}

TEST_P(Fp24Lanes, AddDirectedEdges) {
  check_directed(GetParam(), Kind::Add,
                 {
                     {0x3F0000, 0x3F0000, true},   // x - x = +0
                     {0xBF0000, 0xBF0000, false},  // -x + -x
                     {0xBF0000, 0x3F0000, false},  // -x + x = +0
                     {0x800000, 0x000000, true},   // (-0) - (+0) = -0
                     {0x80ABCD, 0x80FFFF, false},  // (-0) + (-0) = -0, DAZ
                     {0x7F0000, 0x7F0000, true},   // inf - inf: NaN, NV
                     {0x7EFFFF, 0x6D0000, false},  // largest finite + half an ulp: a tie, overflow
                     {0x7EFFFF, 0x6CFFFF, false},  // just below the tie: largest finite, NX
                     {0x010001, 0x010000, true},   // 2^-78 after cancellation: tiny
                     {0x020000, 0x01FFFF, true},   // 2^-78 across an exponent: tiny
                     {0x3F0000, 0x2E0000, false},  // 1 + 2^-17: a tie, down to even
                     {0x3F0001, 0x2E0000, false},  // a tie, up to even
                     {0x3F0000, 0x270001, false},  // exponent difference 24: the clamp
                     {0x3F0000, 0xA60001, false},  // difference 25, subtracted
                     {0x3F0000, 0x9E0001, true},   // difference 33, SUB of a negative
                 });
}

// Every signed fraction of y against a few x at the alignment distances
// where the guard bit, the clamp or the normalization change, eight at a
// time, SUB lanes among them.
TEST_P(Fp24Lanes, AddSweepsAllFractionsAtTheAlignmentEdges) {
  Harness h(GetParam(), Kind::Add, 9);
  const Bits xs[] = {encode(false, 63, 0), encode(true, 63, 0xFFFF), encode(false, 63, 0x8000), encode(true, 63, 1)};
  for (Bits x : xs)
    for (int d : {0, 1, 2, 16, 17, 18, 23, 24, 25, 40})
      for (std::uint32_t sf = 0; sf < 0x20000; sf += kLanes) {
        Lane lane[kLanes];
        for (unsigned i = 0; i < kLanes; ++i) lane[i] = {x, encode((sf + i) >> 16, 63 - d, sf + i), ((sf >> 3) + i) % 3 == 0};
        ASSERT_EQ(h.check(lane, kLanes, -1), "");
      }
}

// The public mul() and add() are the active variant's.
TEST(Fp24LanesDispatch, PublicOpsUseTheActiveVariant) {
  EXPECT_TRUE(lanes::supported(lanes::Variant::Generic));
  EXPECT_EQ(lanes::active() == lanes::Variant::Avx512, lanes::supported(lanes::Variant::Avx512));
  std::printf("fp24 lanes: active variant %s\n", lanes::name(lanes::active()));
  Operands gen(3);
  for (int k = 0; k < 20'000; ++k) {
    std::uint32_t V[2 * kLanes], out1[kLanes], out2[kLanes];
    lanes::Batch b;
    for (unsigned i = 0; i < kLanes; ++i) {
      V[2 * i] = gen.any();
      V[2 * i + 1] = gen.any();
      b.a[i] = static_cast<std::uint16_t>(2 * i);
      b.b[i] = static_cast<std::uint16_t>(2 * i + 1);
    }
    b.n = static_cast<std::uint8_t>(1 + k % kLanes);
    b.neg = static_cast<std::uint8_t>(gen.next());
    ASSERT_EQ(lanes::mul(V, b, out1), lanes::mul(lanes::active(), V, b, out2));
    ASSERT_TRUE(std::equal(out1, out1 + b.n, out2));
    ASSERT_EQ(lanes::add(V, b, out1), lanes::add(lanes::active(), V, b, out2));
    ASSERT_TRUE(std::equal(out1, out1 + b.n, out2));
  }
}

// Speed (not in the default run: the suite name ends in Bench): ns per full
// batch of eight normal ops, each variant and the scalar ops in the same
// loop. No figure is asserted.
// The fastest of several timed runs: the host is shared, the slower runs
// are other work's.
template <class Run>
double ns_per_batch(const std::vector<lanes::Batch>& batches, Run run) {
  std::uint32_t out[kLanes], sink = 0;
  double best = 1e9;
  for (int rep = 0; rep < 15; ++rep) {
    constexpr int kRounds = 40;
    const auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < kRounds; ++r)
      for (const lanes::Batch& b : batches) sink += run(b, out) + out[r & 7];
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double, std::nano>(t1 - t0).count() / (kRounds * batches.size()));
  }
  asm volatile("" : : "r"(sink));  // the results are used
  return best;
}

TEST(Fp24LanesBench, NsPerBatchOfEight) {
  Operands gen(5);
  std::vector<std::uint32_t> V(512);
  for (auto& v : V) v = encode(gen.coin(), 32 + static_cast<int>(gen.below(60)), static_cast<std::uint32_t>(gen.next()));
  std::vector<lanes::Batch> batches(1024);
  for (auto& b : batches) {
    for (unsigned i = 0; i < kLanes; ++i) {
      b.a[i] = static_cast<std::uint16_t>(gen.below(512));
      b.b[i] = static_cast<std::uint16_t>(gen.below(512));
    }
    b.n = kLanes;
    b.neg = static_cast<std::uint8_t>(gen.next());
  }
  const std::uint32_t* v = V.data();
  const auto scalar_mul = [v](const lanes::Batch& b, std::uint32_t* out) {
    std::uint32_t f = 0;
    for (unsigned i = 0; i < kLanes; ++i) {
      const Result r = inl::mul24(v[b.a[i]], v[b.b[i]]);
      out[i] = r.value;
      f |= r.flags;
    }
    return f;
  };
  const auto scalar_add = [v](const lanes::Batch& b, std::uint32_t* out) {
    std::uint32_t f = 0;
    for (unsigned i = 0; i < kLanes; ++i) {
      const Result r = (b.neg >> i) & 1 ? inl::sub24(v[b.a[i]], v[b.b[i]]) : inl::add24(v[b.a[i]], v[b.b[i]]);
      out[i] = r.value;
      f |= r.flags;
    }
    return f;
  };
  std::printf("fp24 lanes, ns per batch of 8: scalar inl ops inline: mul %.2f add %.2f\n",
              ns_per_batch(batches, scalar_mul), ns_per_batch(batches, scalar_add));
  for (lanes::Variant var : lanes::kVariants) {
    if (!lanes::supported(var)) continue;
    const double m = ns_per_batch(batches, [&](const lanes::Batch& b, std::uint32_t* o) { return lanes::mul(var, v, b, o); });
    const double a = ns_per_batch(batches, [&](const lanes::Batch& b, std::uint32_t* o) { return lanes::add(var, v, b, o); });
    std::printf("fp24 lanes, ns per batch of 8: %s: mul %.2f add %.2f\n", lanes::name(var), m, a);
  }
  const double m = ns_per_batch(batches, [&](const lanes::Batch& b, std::uint32_t* o) { return lanes::mul(v, b, o); });
  const double a = ns_per_batch(batches, [&](const lanes::Batch& b, std::uint32_t* o) { return lanes::add(v, b, o); });
  std::printf("fp24 lanes, ns per batch of 8: public mul/add (%s): mul %.2f add %.2f\n", lanes::name(lanes::active()), m, a);
}

}  // namespace
