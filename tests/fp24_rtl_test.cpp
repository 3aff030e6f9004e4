// The verilated FP24 units against the C++ model and against the timing of
// docs/fp24-rtl.md: one issue per cycle on every unit, each result sampled
// exactly `latency` edges after its issue, never before an earlier op's.
#include "fp24_rtl.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

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

// Operands that reach every path: any encoding, or a value near 1.0 so
// adds cancel and align, and trig arguments stay in the main range.
Bits random_operand(std::mt19937& rng) {
  const Bits r = Bits(rng()) & 0xFFFFFF;
  return (rng() & 1) ? r : (r & (kSignBit | 0xFFFF)) | Bits(56 + rng() % 16) << 16;
}

std::vector<Issue> random_ops(std::mt19937& rng, std::size_t n, const std::vector<Op>& kinds) {
  std::vector<Issue> ops;
  for (std::size_t i = 0; i < n; ++i) {
    const Op op = kinds[rng() % kinds.size()];
    const Bits a = op == Op::Float ? Bits(rng()) & 0xFFFF : random_operand(rng);
    ops.push_back({op, a, random_operand(rng)});
  }
  return ops;
}

std::vector<Op> all_ops() {
  std::vector<Op> ops;
  for (int i = 0; i < kOpCount; ++i) ops.push_back(static_cast<Op>(i));
  return ops;
}

void expect_model_results(const std::vector<Issue>& ops, const std::vector<Result>& got) {
  ASSERT_EQ(got.size(), ops.size());
  for (std::size_t i = 0; i < ops.size(); ++i) {
    const Result want = execute(ops[i].op, ops[i].a, ops[i].b);
    EXPECT_EQ(got[i], want) << info(ops[i].op).name << " " << std::hex << ops[i].a << " " << ops[i].b << ": rtl "
                            << got[i].value << "/" << int(got[i].flags) << ", model " << want.value << "/"
                            << int(want.flags);
  }
}

// Every op's result edge is its issue edge + latency, and within a unit's
// result port issues are in order and no result comes before an earlier
// op's (the function unit's SIN/COS port has a latency of its own).
void expect_timing(const std::vector<Issue>& ops, const std::vector<Timing>& t) {
  std::array<const Timing*, 4> last{};
  std::array<Op, 4> last_op{};
  for (std::size_t i = 0; i < ops.size(); ++i) {
    EXPECT_EQ(t[i].result_edge - t[i].issue_edge, std::uint64_t(info(ops[i].op).latency)) << "op " << i;
    const bool trig = ops[i].op == Op::Sin || ops[i].op == Op::Cos;
    const int u = trig ? 3 : int(info(ops[i].op).unit);
    if (last[u] != nullptr) {
      EXPECT_GE(t[i].issue_edge, last[u]->issue_edge + std::uint64_t(info(last_op[u]).interval)) << "op " << i;
      EXPECT_GE(t[i].result_edge, last[u]->result_edge) << "op " << i;
    }
    last[u] = &t[i];
    last_op[u] = ops[i].op;
  }
}

TEST(Fp24Rtl, EachOpBackToBackMatchesModel) {
  std::mt19937 rng(11);
  for (int k = 0; k < kOpCount; ++k) {
    const Op op = static_cast<Op>(k);
    const std::vector<Issue> ops = random_ops(rng, 3000, {op});
    std::vector<Bits> a, b;
    for (const Issue& v : ops) a.push_back(v.a), b.push_back(v.b);
    std::vector<Result> got(ops.size());
    RtlUnit unit(info(op).unit);
    const std::uint64_t start = unit.edges();
    unit.run(op, a.data(), b.data(), got.data(), ops.size());
    SCOPED_TRACE(std::string(info(op).name));
    expect_model_results(ops, got);
    // Full throughput: n ops take n * interval issue edges, plus the drain.
    EXPECT_EQ(unit.edges() - start,
              std::uint64_t((ops.size() - 1) * info(op).interval + info(op).latency));
  }
}

TEST(Fp24Rtl, AllUnitsAtOnceBackToBack) {
  std::mt19937 rng(12);
  const std::vector<Issue> ops = random_ops(rng, 20000, all_ops());
  RtlUnits units;
  std::vector<Timing> timing;
  const std::vector<Result> got = units.run(ops, {}, &timing);
  expect_model_results(ops, got);
  expect_timing(ops, timing);
}

TEST(Fp24Rtl, AllUnitsWithRandomBubbles) {
  std::mt19937 rng(13);
  const std::vector<Issue> ops = random_ops(rng, 20000, all_ops());
  RtlUnits units;
  for (double bubble : {0.1, 0.5, 0.9}) {
    std::vector<Timing> timing;
    const std::vector<Result> got = units.run(ops, {bubble, 7}, &timing);
    SCOPED_TRACE(bubble);
    expect_model_results(ops, got);
    expect_timing(ops, timing);
  }
}

// sin, recip, cos, sqrt, sin back to back: one issue per cycle; SIN/COS
// (out_trig_*) and RECIP/SQRT (out_*) are two pipes of their own latencies
// (9 and 3), each port's results one per edge in its issue order.
TEST(Fp24Rtl, SinCosIssueBackToBackWithTheOtherFunctionOps) {
  const std::vector<Issue> ops = {{Op::Sin, 0x3F0000, 0},
                                  {Op::Recip, 0x408000, 0},
                                  {Op::Cos, 0x3F0000, 0},
                                  {Op::Sqrt, 0x400000, 0},
                                  {Op::Sin, 0x3F0000, 0}};
  RtlUnits units;
  std::vector<Timing> t;
  const std::vector<Result> got = units.run(ops, {}, &t);
  const std::uint64_t e = t[0].issue_edge;
  for (std::uint64_t i = 0; i < ops.size(); ++i) EXPECT_EQ(t[i].issue_edge, e + i) << "op " << i;
  for (std::uint64_t i = 0; i < ops.size(); ++i)
    EXPECT_EQ(t[i].result_edge, e + i + std::uint64_t(info(ops[i].op).latency)) << "op " << i;
  EXPECT_EQ(units.edges() - e, 4u + std::uint64_t(info(Op::Sin).latency));
  EXPECT_EQ(got[0], (Result{0x3EAED5, kNX}));  // sin 1
  EXPECT_EQ(got[1], (Result{0x3D5555, kNX}));  // 1/3
  EXPECT_EQ(got[2], (Result{0x3E14A3, kNX}));  // cos 1
  EXPECT_EQ(got[3], (Result{0x3F6A0A, kNX}));  // sqrt 2
  EXPECT_EQ(got[4], got[0]);
}

// The three units work in parallel: one op each per cycle.
TEST(Fp24Rtl, ThreeUnitsIssueOnTheSameEdge) {
  const std::vector<Issue> ops = {{Op::Mul, 0x400000, 0x408000}, {Op::Add, 0x3F0000, 0x3F0000},
                                  {Op::Recip, 0x400000, 0}};
  RtlUnits units;
  std::vector<Timing> t;
  const std::vector<Result> got = units.run(ops, {}, &t);
  EXPECT_EQ(t[0].issue_edge, t[1].issue_edge);
  EXPECT_EQ(t[1].issue_edge, t[2].issue_edge);
  EXPECT_EQ(got[0], (Result{0x410000 | 0x8000, 0}));  // 2 * 3 = 6
  EXPECT_EQ(got[1], (Result{0x400000, 0}));
  EXPECT_EQ(got[2], (Result{0x3E0000, 0}));
}

TEST(Fp24Rtl, WritesAnFstWaveform) {
  const std::string path = testing::TempDir() + "fp24_rtl_test.fst";
  std::remove(path.c_str());
  {
    RtlUnits units(path);
    units.run({{Op::Mul, 0x400000, 0x400000}, {Op::Sin, 0x3F0000, 0}});
  }
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  ASSERT_TRUE(f.good()) << path;
  EXPECT_GT(f.tellg(), 200);
}

}  // namespace
}  // namespace mc1::fp24::tb
