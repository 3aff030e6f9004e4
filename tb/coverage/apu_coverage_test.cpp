// The functional coverage collector (tb/coverage): operand and result
// classes, rounding outcomes against hand-computed cases, bins and waivers,
// and every waived bin of a one-operand FP24 op unreachable on all 2^24
// operands (argv[1]: the waiver file).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "apu_coverage.hpp"
#include "coverage_bins.hpp"
#include "fp24_coverage.hpp"

namespace {

using mc1::fp24::Op;
std::string g_waivers;
const char* const kFlags[] = {"nx", "uf", "of", "dz", "nv"};

TEST(Fp24Coverage, OperandClasses) {
  EXPECT_STREQ(mc1::cov::fp24_operand_class(0x000000), "+zero");
  EXPECT_STREQ(mc1::cov::fp24_operand_class(0x800001), "-sub");
  EXPECT_STREQ(mc1::cov::fp24_operand_class(0x3F0000), "+norm");
  EXPECT_STREQ(mc1::cov::fp24_operand_class(0xFEFFFF), "-max");
  EXPECT_STREQ(mc1::cov::fp24_operand_class(0x7F0000), "+inf");
  EXPECT_STREQ(mc1::cov::fp24_operand_class(0xFF8000), "-nan");
  EXPECT_STREQ(mc1::cov::fp24_int_class(0x8000), "min");
  EXPECT_STREQ(mc1::cov::fp24_expdiff_class(0x3F0000, 0x400000), "1");
  EXPECT_STREQ(mc1::cov::fp24_expdiff_class(0x3F0000, 0x2E0000), "17");
  EXPECT_EQ(mc1::cov::fp24_expdiff_class(0x3F0000, 0x000000), nullptr);
}

TEST(Fp24Coverage, RoundingOutcomes) {
  mc1::cov::Bins bins;
  mc1::cov::Fp24Coverage cov(bins);
  auto round = [&](Op op, mc1::fp24::Bits a, mc1::fp24::Bits b) {
    const char* r = cov.rounding(op, a, b, mc1::fp24::execute(op, a, b));
    return std::string(r ? r : "n/a");
  };
  EXPECT_EQ(round(Op::Mul, 0x3F8000, 0x3F8000), "exact");  // 1.5 x 1.5 = 2.25
  EXPECT_EQ(round(Op::Add, 0x3F0000, 0x2E0000), "tie");    // 1 + 2^-17: halfway, to even (1)
  EXPECT_EQ(round(Op::Add, 0x3F0001, 0x2E0000), "tie");    // (1 + 2^-16) + 2^-17: halfway, to even (up)
  EXPECT_EQ(round(Op::Add, 0x3F0000, 0x2E8000), "up");     // 1 + 1.5 x 2^-17
  EXPECT_EQ(round(Op::Add, 0x3F0000, 0x2D8000), "down");   // 1 + 0.75 x 2^-17
  EXPECT_EQ(round(Op::Mul, 0x7E0000, 0x7E0000), "up");     // overflow to inf
  EXPECT_EQ(round(Op::Mul, 0x010000, 0x010000), "down");   // flushed to zero
  EXPECT_EQ(round(Op::Recip, 0x408000, 0), "down");        // 1/3 = 0.0101...: below the midpoint
  EXPECT_EQ(round(Op::Add, 0x7F0000, 0x3F0000), "n/a");    // inf involved
  EXPECT_EQ(round(Op::Float, 0x000007, 0), "exact");
  cov.sample(Op::Add, 0x3F0000, 0x2E0000);
  EXPECT_EQ(bins.count("fp24.add.round.tie"), 1u);
  EXPECT_EQ(bins.count("fp24.add.expdiff.17"), 1u);
  EXPECT_EQ(bins.count("fp24.add.flag.nx"), 1u);
  EXPECT_EQ(bins.count("fp24.add.a.+norm"), 1u);
}

TEST(Bins, UndeclaredBinIsAnError) {
  mc1::cov::Bins bins;
  bins.declare("x.y");
  bins.hit("x.y", 2);
  EXPECT_EQ(bins.count("x.y"), 2u);
  EXPECT_THROW(bins.hit("x.z"), std::logic_error);
  EXPECT_NE(bins.json().find("\"x.y\": 2"), std::string::npos);
}

TEST(Waivers, AReasonIsRequiredAndErrorsNameTheLine) {
  const std::string path = ::testing::TempDir() + "waivers_test.txt";
  std::ofstream(path) << "# comment\nfp24.neg.flag.* NEG raises no flag\ncore.x\n";
  try {
    mc1::cov::read_waivers(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3:"), std::string::npos) << e.what();
  }
  std::ofstream(path) << "fp24.neg.flag.* NEG raises no flag  # trailing\n";
  const auto w = mc1::cov::read_waivers(path);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].reason, "NEG raises no flag");
  EXPECT_NE(mc1::cov::waiver_for(w, "fp24.neg.flag.nx"), nullptr);
  EXPECT_EQ(mc1::cov::waiver_for(w, "fp24.abs.flag.nx"), nullptr);
}

// Every bin the waiver file waives for a one-operand op (result, flag and
// operand bins) is unreachable: no operand of the 2^24 reaches it.
TEST(Waivers, WaivedOneOperandBinsAreUnreachable) {
  ASSERT_FALSE(g_waivers.empty()) << "usage: apu_coverage_test WAIVERS";
  const auto waivers = mc1::cov::read_waivers(g_waivers);
  for (Op op : {Op::Recip, Op::Sqrt, Op::Sin, Op::Cos, Op::Fix, Op::Neg, Op::Abs}) {
    const std::string p = "fp24." + std::string(mc1::fp24::info(op).name) + ".";
    std::vector<const char*> results;  // the classes' names are static strings
    unsigned flags = 0;
    bool none = false;
    for (mc1::fp24::Bits a = 0; a < (1u << 24); ++a) {
      const auto r = mc1::fp24::execute(op, a);
      const char* c = mc1::cov::fp24_result_class(op, r);
      if (std::find(results.begin(), results.end(), c) == results.end()) results.push_back(c);
      flags |= r.flags;
      none |= r.flags == 0;
    }
    std::set<std::string> reached;
    for (const char* c : results) reached.insert(p + "result." + c);
    if (none) reached.insert(p + "flag.none");
    for (int f = 0; f < 5; ++f)
      if (flags >> f & 1) reached.insert(p + "flag." + kFlags[f]);
    for (const auto& bin : reached)
      EXPECT_EQ(mc1::cov::waiver_for(waivers, bin), nullptr) << bin << " is waived but reachable";
  }
}

TEST(ApuCoverage, DeclaresEveryCoreAndUnitBin) {
  mc1::cov::ApuCoverage cov;
  const auto& bins = cov.bins();
  EXPECT_TRUE(bins.has("core.op.s.seq.op15"));
  EXPECT_TRUE(bins.has("core.slots.MAFDIS"));
  EXPECT_TRUE(bins.has("core.slots.------"));
  EXPECT_TRUE(bins.has("core.stall.waw"));
  EXPECT_TRUE(bins.has("core.bypass.trig.d.st"));
  EXPECT_TRUE(bins.has("core.branch.bltz.not-taken"));
  EXPECT_TRUE(bins.has("core.handover.data.faulted"));
  EXPECT_TRUE(bins.has("core.fault.call-underflow"));
  EXPECT_TRUE(bins.has("fp24.sin.round.up"));
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (argc > 1) g_waivers = argv[1];
  return RUN_ALL_TESTS();
}
