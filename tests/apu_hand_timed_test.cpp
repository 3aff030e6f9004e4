// Both APU engines (the ISS and the verilated RTL core) against hand-timed
// programs: exact cycle counts, stall reasons, commit cycles and values,
// faults, each derived from docs/apu-isa.md ("Timing" and "Clarifications"),
// not from either engine. Every case runs on each engine (suffix /iss, /rtl).
// What only one engine has: tests/apu_iss_test.cpp, tests/apu_rtl_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "apu_driver.hpp"
#include "apu_iss.hpp"
#include "apu_rtl_engine.hpp"
#include "apu_test_program.hpp"
#include "fp24.hpp"

namespace mc1::apu {
namespace {

using namespace apu_test;

using K = Commit::Kind;
using Commits = std::vector<Commit>;
constexpr Stall N = Stall::None;

// The bubble after a mispredicted branch or a SWAPP (docs/apu-isa.md
// "Timing"): BRANCH_MISS cycles of `fetch` that issue nothing.
const std::vector<Stall> kMiss(kBranchMissCycles, Stall::Fetch);
const std::vector<int> kMissPcs(kBranchMissCycles, -1);

// The concatenation of vectors (stall and pc sequences around a bubble).
template <class T>
std::vector<T> cat(std::initializer_list<std::vector<T>> parts) {
  std::vector<T> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

enum class EngineKind { Iss, Rtl };

class ApuHandTimed : public ::testing::TestWithParam<EngineKind> {
 protected:
  // A fresh engine of the kind under test, alive until the test ends.
  ApuEngine& engine() {
    if (GetParam() == EngineKind::Iss) {
      engines_.push_back(std::make_unique<Iss>());
    } else {
      engines_.push_back(std::make_unique<RtlEngine>());
    }
    return *engines_.back();
  }
  // `prog` handed over and started at 0 on a fresh engine.
  EngineProgram program(const std::vector<MicroWord>& prog) { return EngineProgram(engine(), prog); }

  // The ISS's observers beyond ApuEngine (PC, call depth, counters); null on
  // the RTL, whose cases check the same through the cycle records.
  static const Iss* iss(const ApuEngine* e) { return dynamic_cast<const Iss*>(e); }

  // The RTL also checks each unit's timing against docs/fp24-rtl.md as it runs.
  void TearDown() override {
    for (const auto& e : engines_) {
      if (const auto* rtl = dynamic_cast<const RtlEngine*>(e.get())) {
        EXPECT_FALSE(rtl->unit_mismatch()) << "a unit's timing differs from docs/fp24-rtl.md";
      }
    }
  }

 private:
  std::vector<std::unique_ptr<ApuEngine>> engines_;
};

INSTANTIATE_TEST_SUITE_P(Engines, ApuHandTimed, ::testing::Values(EngineKind::Iss, EngineKind::Rtl),
                         [](const ::testing::TestParamInfo<EngineKind>& info) {
                           return std::string(info.param == EngineKind::Iss ? "iss" : "rtl");
                         });

TEST_P(ApuHandTimed, ResetStateIsIdleAndZero) {
  ApuEngine& apu = engine();
  EXPECT_EQ(apu.state(), RunState::Idle);
  EXPECT_EQ(apu.fault(), Fault::None);
  EXPECT_EQ(apu.cycle(), 0u);
  EXPECT_FALSE(apu.program_ready());
  EXPECT_FALSE(apu.data_ready());
  for (int i = 0; i < kNumFRegs; ++i) EXPECT_EQ(apu.freg(i), 0u);
  for (int i = 0; i < kNumARegs; ++i) EXPECT_EQ(apu.areg(i), 0);
  EXPECT_EQ(apu.read_data(4095), 0u);
  CycleRecord rec;
  apu.step(rec);  // an idle cycle still counts
  EXPECT_EQ(rec.cycle, 0u);
  EXPECT_FALSE(rec.issued);
  EXPECT_EQ(rec.stall, N);
  EXPECT_TRUE(rec.commits.empty());
  EXPECT_EQ(apu.cycle(), 1u);
}

TEST_P(ApuHandTimed, RawAtDistanceOneStallsOneCycleAndHaltDrains) {
  // 0 LIF F1  1 LIF F2  2 MUL F3=F1*F2 (visible at 4)  3 ADD F4=F3+F1: raw at
  // cycle 3, issues at 4 (visible at 6)  4 HALT: drain at 5, issues at 6.
  auto r = program({lif(1, 0x3F00), lif(2, 0x4000), mul(3, 1, 2), addu(AddOp::Add, 4, 3, 1), halt()});
  r.go();
  ASSERT_EQ(r.apu->state(), RunState::Halted);
  EXPECT_EQ(r.recs.size(), 7u);  // 5 words + raw + drain
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, Stall::Raw, N, Stall::Drain, N}));
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, 2, -1, 3, -1, 4}));
  EXPECT_EQ(r.recs[3].pc, 3);
  EXPECT_EQ(r.recs[5].pc, 4);
  EXPECT_TRUE(r.recs[0].commits.empty());
  EXPECT_EQ(r.recs[1].commits, (Commits{{K::FReg, 1, kOne}}));
  EXPECT_EQ(r.recs[2].commits, (Commits{{K::FReg, 2, kTwo}}));
  EXPECT_TRUE(r.recs[3].commits.empty());
  EXPECT_EQ(r.recs[4].commits, (Commits{{K::FReg, 3, kTwo}}));  // MUL at 2, visible at 4
  EXPECT_TRUE(r.recs[5].commits.empty());
  EXPECT_EQ(r.recs[6].commits, (Commits{{K::FReg, 4, kThree}}));
  EXPECT_EQ(r.apu->freg(4), kThree);
  EXPECT_EQ(r.apu->flags(), 0);
  EXPECT_EQ(r.apu->cycle(), kStartFetchCycles + 7u);  // the start's fetch and decode, then the 7 records
  if (const Iss* s = iss(r.apu)) {
    EXPECT_EQ(s->pc(), 4);  // PC stays at the HALT
  }
}

TEST_P(ApuHandTimed, ResultAtDistanceTwoIsBypassed) {
  // MUL at 1 is read at 3 = t + 2 with no stall: the bypass from the unit.
  auto r = program({lif(1, 0x3F00), mul(2, 1, 1), nop(), addu(AddOp::Add, 3, 2, 2), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, N, Stall::Drain, N}));
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::FReg, 2, kOne}}));
  EXPECT_EQ(r.apu->freg(3), kTwo);
}

TEST_P(ApuHandTimed, WawStallWaitsForTheFirstWrite) {
  // MUL F3 at 1 (visible 3); LIF F3 at 2 is waw, issues at 3 (visible 4).
  auto r = program({lif(1, 0x3F00), mul(3, 1, 1), lif(3, 0x4000), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Waw, N, N}));
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, -1, 2, 3}));
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::FReg, 3, kOne}}));
  EXPECT_EQ(r.recs[4].commits, (Commits{{K::FReg, 3, kTwo}}));
  EXPECT_EQ(r.apu->freg(3), kTwo);
}

TEST_P(ApuHandTimed, RawHasPriorityOverWaw) {
  // MUL F3 in flight; the next word reads F3 and writes F3.
  auto r = program({lif(1, 0x3F00), mul(3, 1, 1), addu(AddOp::Add, 3, 3, 1), halt()});
  r.go();
  EXPECT_EQ(r.stalls()[2], Stall::Raw);
  EXPECT_EQ(r.apu->freg(3), kTwo);
}

TEST_P(ApuHandTimed, OneOperandAdderOpsDoNotReadB) {
  // NEG reads `a` only: its `b` (F3, in flight) causes no stall.
  auto r = program({lif(1, 0x3F00), mul(3, 1, 1), addu(AddOp::Neg, 4, 1, 3), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, Stall::Drain, N}));
  EXPECT_EQ(r.apu->freg(4), 0xBF0000u);
}

TEST_P(ApuHandTimed, SinCosAndOtherFunctionOpsIssueBackToBack) {
  // SIN at 1 (visible 10), COS at 2 (visible 11), RECIP at 3 (visible 6,
  // before them: each pipe has its own latency, FUNC 3, TRIG 9); the ADD
  // reading the SIN result waits (raw) at 4..9 and issues at 10 (visible
  // 12). HALT at 11 drains (the ADD in flight), issues at 12.
  auto r = program({lif(1, 0x3F00), func(FuncOp::Sin, 2, 1), func(FuncOp::Cos, 3, 1), func(FuncOp::Recip, 4, 1),
                    addu(AddOp::Add, 5, 2, 2), halt()});
  r.go();
  const Stall R = Stall::Raw;
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, N, R, R, R, R, R, R, N, Stall::Drain, N}));
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, 2, 3, -1, -1, -1, -1, -1, -1, 4, -1, 5}));
  const auto s = fp24::sin(kOne), c = fp24::cos(kOne);
  const auto twice = fp24::add(s.value, s.value);
  EXPECT_EQ(s.flags, fp24::kNX);  // so FLAGS changes with the SIN result
  EXPECT_EQ(r.recs[6].commits, (Commits{{K::FReg, 4, kOne}}));
  EXPECT_EQ(r.recs[10].commits, (Commits{{K::FReg, 2, s.value}, {K::Flags, 0, s.flags}}));
  EXPECT_EQ(r.recs[11].commits, (Commits{{K::FReg, 3, c.value}}));
  EXPECT_EQ(r.recs[12].commits, (Commits{{K::FReg, 5, twice.value}}));
  EXPECT_EQ(r.apu->freg(3), c.value);
  EXPECT_EQ(r.apu->freg(4), kOne);
  EXPECT_EQ(r.apu->freg(5), twice.value);
  EXPECT_EQ(r.apu->flags(), s.flags | c.flags | twice.flags);
}

TEST_P(ApuHandTimed, RecipAfterSinIntoTheSameRegisterWaitsUntilItLandsLater) {
  // SIN F2 at 1 is visible at 10; RECIP F2 (FUNC 3 < TRIG 9) at c would
  // land at c + 3 <= 10 for c <= 7: waw at 2..7, issues at 8 and lands at 11,
  // after the SIN. HALT drains at 9 and 10.
  auto r = program({lif(1, 0x3F00), func(FuncOp::Sin, 2, 1), func(FuncOp::Recip, 2, 1), halt()});
  r.go();
  const Stall W = Stall::Waw, D = Stall::Drain;
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, W, W, W, W, W, W, N, D, D, N}));
  EXPECT_EQ(r.recs[10].commits[0], (Commit{K::FReg, 2, fp24::sin(kOne).value}));
  EXPECT_EQ(r.recs[11].commits, (Commits{{K::FReg, 2, kOne}}));
  EXPECT_EQ(r.apu->freg(2), kOne);
}

TEST_P(ApuHandTimed, BackToBackWritesOfOneLatencyDoNotStall) {
  // MUL F3 at 1 and 2 (visible 3 and 4), ADD F3 at 3 (visible 5): equal
  // latencies in order cannot reorder, so no waw; each write is recorded in
  // its own cycle and the last one stays.
  auto r = program({lif(1, 0x3F00), mul(3, 1, 1), mul(3, 1, 1) | lif(2, 0x4000), addu(AddOp::Add, 3, 2, 2),
                    halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, N, Stall::Drain, N}));
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::FReg, 2, kTwo}, {K::FReg, 3, kOne}}));
  EXPECT_EQ(r.recs[4].commits, (Commits{{K::FReg, 3, kOne}}));
  EXPECT_EQ(r.recs[5].commits, (Commits{{K::FReg, 3, 0x410000u}}));
  EXPECT_EQ(r.apu->freg(3), 0x410000u);
}

TEST_P(ApuHandTimed, ShorterWriteAfterLongerOneWaitsUntilItLandsLater) {
  // SIN F2 at 1 (visible 10); MUL F2 at c would land at c + 2 <= 10 for
  // c <= 8: waw at 2..8; at 9 it lands at 11. A longer write after a shorter
  // one (MUL F4 at 10, visible 12; COS F4 at 11, visible 20) never waits.
  auto r = program({lif(1, 0x3F00), func(FuncOp::Sin, 2, 1), mul(2, 1, 1), mul(4, 1, 1),
                    func(FuncOp::Cos, 4, 1), halt()});
  r.go();
  const Stall W = Stall::Waw, D = Stall::Drain;
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, W, W, W, W, W, W, W, N, N, N, D, D, D, D, D, D, D, D, N}));
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, -1, -1, -1, -1, -1, -1, -1, 2, 3, 4, -1, -1, -1, -1, -1, -1, -1, -1, 5}));
  EXPECT_EQ(r.recs[10].commits[0], (Commit{K::FReg, 2, fp24::sin(kOne).value}));
  EXPECT_EQ(r.recs[11].commits, (Commits{{K::FReg, 2, kOne}}));
  EXPECT_EQ(r.recs[12].commits, (Commits{{K::FReg, 4, kOne}}));
  EXPECT_EQ(r.recs[20].commits[0], (Commit{K::FReg, 4, fp24::cos(kOne).value}));
  EXPECT_EQ(r.apu->freg(2), kOne);
  EXPECT_EQ(r.apu->freg(4), fp24::cos(kOne).value);
}

TEST_P(ApuHandTimed, OneWordLoopOfAllUnitsRunsAtOneCycleAnIteration) {
  // docs/apu-isa.md's example: each unit rewrites its own register every
  // cycle. 100 iterations, 100 cycles, no stall; HALT drains the last ones.
  const MicroWord loop =
      mul(1, 2, 3) | addu(AddOp::Add, 4, 5, 6) | func(FuncOp::Recip, 7, 8) | seq(SeqOp::Dbnz, 1, 2);
  auto r = program({li(1, 100), lif(8, 0x4000), loop, halt()});
  r.go();
  ASSERT_EQ(r.apu->state(), RunState::Halted);
  const auto st = r.stalls();
  // 2 words, the loop (its back edge predicted taken: no cycle), the exit's
  // miss, HALT draining the last RECIP (issued at 101, visible at 101 +
  // kFuncLatency: the bubble's cycles count towards that), HALT
  const std::size_t miss = kBranchMissCycles;
  const std::size_t drain = std::max<std::size_t>(kFuncLatency - 1, miss) - miss;
  ASSERT_EQ(st.size(), 2u + 100u + miss + drain + 1u);
  for (std::size_t c = 0; c < 102; ++c) EXPECT_EQ(st[c], N) << "cycle " << c;
  for (std::size_t c = 102; c < 102 + miss; ++c) EXPECT_EQ(st[c], Stall::Fetch) << "cycle " << c;
  for (std::size_t c = 102 + miss; c < 102 + miss + drain; ++c) EXPECT_EQ(st[c], Stall::Drain) << "cycle " << c;
  EXPECT_EQ(st.back(), N);
  EXPECT_EQ(r.apu->freg(7), 0x3E0000u);  // 1/2
  EXPECT_EQ(r.apu->areg(1), 0);
}

TEST_P(ApuHandTimed, CosReaderStallsRawUntilTheResultLands) {
  // COS at 1 is visible at 10: the MUL reading it waits at 2..9 (TRIG 9).
  auto r = program({lif(1, 0x3F00), func(FuncOp::Cos, 2, 1), mul(3, 2, 2), halt()});
  r.go();
  const Stall R = Stall::Raw;
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, R, R, R, R, R, R, R, R, N, Stall::Drain, N}));
  const auto c = fp24::cos(kOne);
  EXPECT_EQ(r.apu->freg(2), c.value);
  EXPECT_EQ(r.apu->freg(3), fp24::mul(c.value, c.value).value);
}

TEST_P(ApuHandTimed, FunctionUnitTakesAnOpEveryCycle) {
  // SQRT at 1 (visible 4), COS at 2 and 3 (visible 11, 12), SQRT at 4
  // (visible 7): an op every cycle, each pipe's results in its issue order.
  // HALT at 5 drains until the last COS lands (5..11), issues at 12.
  auto r = program({lif(1, 0x4000), func(FuncOp::Sqrt, 2, 1), func(FuncOp::Cos, 3, 1), func(FuncOp::Cos, 4, 1),
                    func(FuncOp::Sqrt, 5, 1), halt()});
  r.go();
  const Stall D = Stall::Drain;
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, N, N, D, D, D, D, D, D, D, N}));
  const auto c = fp24::cos(kTwo), q = fp24::sqrt(kTwo);
  EXPECT_EQ(r.recs[4].commits[0], (Commit{K::FReg, 2, q.value}));
  EXPECT_EQ(r.recs[7].commits, (Commits{{K::FReg, 5, q.value}}));
  EXPECT_EQ(r.recs[11].commits[0], (Commit{K::FReg, 3, c.value}));
  EXPECT_EQ(r.recs[12].commits, (Commits{{K::FReg, 4, c.value}}));
  EXPECT_EQ(r.apu->freg(5), q.value);
}

TEST_P(ApuHandTimed, DrainAtHaltWaitsForTheLastResult) {
  // COS at 1 is visible at 10: HALT waits at 2..9, issues at 10.
  auto r = program({lif(1, 0x3F00), func(FuncOp::Cos, 2, 1), halt()});
  r.go();
  const Stall D = Stall::Drain;
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, D, D, D, D, D, D, D, D, N}));
  EXPECT_EQ(r.recs[10].commits[0], (Commit{K::FReg, 2, fp24::cos(kOne).value}));
  EXPECT_EQ(r.apu->state(), RunState::Halted);
}

TEST_P(ApuHandTimed, HaltWordsOwnOpsLandAfterIt) {
  auto r = program({lif(1, 0x3F00), mul(2, 1, 1) | li(3, 9) | halt()});
  r.go(100, 2);
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, -1, -1}));
  EXPECT_EQ(r.recs[2].commits, (Commits{{K::AReg, 3, 9}}));
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::FReg, 2, kOne}}));
  EXPECT_EQ(r.recs[3].pc, 1);  // PC stays at the HALT
}

TEST_P(ApuHandTimed, StateBetweenStepsIsWhatTheNextWordReads) {
  // MUL at 1 and CMP at 1 complete at 3: after step 2 the observers already
  // show them (Clarification 2), although the record of cycle 3 lists them.
  auto r = program({lif(1, 0x4000), mul(2, 1, 1) | addu(AddOp::Cmp, 0, 1, 1), nop(), halt()});
  r.step();
  r.step();
  EXPECT_EQ(r.apu->freg(1), kTwo);  // LIF at 0, visible at 1
  EXPECT_EQ(r.apu->freg(2), 0u);
  EXPECT_EQ(r.apu->cc(), 0);
  r.step();  // cycle 2
  EXPECT_EQ(r.apu->freg(2), 0x410000u);
  EXPECT_EQ(r.apu->cc(), fp24::kEQ);
  EXPECT_EQ(r.apu->flags(), 0);
  const CycleRecord& rec = r.step();  // cycle 3
  EXPECT_EQ(rec.commits, (Commits{{K::FReg, 2, 0x410000}, {K::Cc, 0, fp24::kEQ}}));
  EXPECT_EQ(r.apu->freg(2), 0x410000u);
  EXPECT_EQ(r.apu->cc(), fp24::kEQ);
}

TEST_P(ApuHandTimed, LoadedWordIsVisibleBetweenStepsAndToTheNextWord) {
  // ST F1 at 1, LD F2 from the same word at 2 (visible at 3): after step 3
  // freg(2) shows it, and the MUL at 3 reads it with no stall.
  auto r = program({lif(1, 0x4000), mem(MemOp::St, 1, 0, 9), mem(MemOp::Ld, 2, 0, 9), mul(3, 2, 2), halt()});
  r.step();
  r.step();
  EXPECT_EQ(r.apu->freg(2), 0u);
  r.step();  // cycle 2: the LD
  EXPECT_EQ(r.apu->freg(2), kTwo);
  const CycleRecord& rec = r.step();  // cycle 3
  EXPECT_TRUE(rec.issued);
  EXPECT_EQ(rec.commits, (Commits{{K::FReg, 2, kTwo}}));
  r.go();
  EXPECT_EQ(r.apu->freg(3), 0x410000u);
}

TEST_P(ApuHandTimed, BranchOnCcWaitsForTheCompare) {
  // CMP 1 < 2 at 2 (CC visible at 4); BCC LT at 3 stalls once, is taken:
  // forward, so predicted not taken, a miss.
  auto r = program({lif(1, 0x3F00), lif(2, 0x4000), addu(AddOp::Cmp, 0, 1, 2), seq(SeqOp::Bcc, fp24::kLT, 6), halt(),
                    halt(), li(5, 7) | halt()});
  r.go(100, 1);
  EXPECT_EQ(r.stalls(), cat<Stall>({{N, N, N, Stall::Cc, N}, kMiss, {N, N}}));
  EXPECT_EQ(r.pcs(), cat<int>({{0, 1, 2, -1, 3}, kMissPcs, {6, -1}}));
  EXPECT_EQ(r.recs[4].commits, (Commits{{K::Cc, 0, fp24::kLT}}));
  EXPECT_EQ(r.apu->cc(), fp24::kLT);
  EXPECT_EQ(r.apu->areg(5), 7);  // the HALT word's own LI lands the cycle after
}

TEST_P(ApuHandTimed, BnccNotTakenFallsThrough) {
  auto r = program({lif(1, 0x3F00), addu(AddOp::Cmp, 0, 1, 1), nop(), seq(SeqOp::Bncc, fp24::kEQ, 6), li(4, 1),
                    halt(), li(4, 2) | halt()});
  r.go(100, 1);
  EXPECT_EQ(r.apu->cc(), fp24::kEQ);
  EXPECT_EQ(r.apu->areg(4), 1);
  EXPECT_EQ(r.recs.size(), 7u);  // no stall: CMP at 1 is visible at 3
}

TEST_P(ApuHandTimed, CompareWithNanSetsUnorderedAndInvalid) {
  // LIF 0x7F80 is the canonical NaN. BNCC UN at 3 (CC visible at 3): not
  // taken, but backward, so predicted taken: a miss before the HALT.
  auto r = program({lif(1, 0x7F80), addu(AddOp::Cmp, 0, 1, 1), nop(), seq(SeqOp::Bncc, fp24::kUN, 0), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), cat<Stall>({{N, N, N, N}, kMiss, {N}}));
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::Cc, 0, fp24::kUN}, {K::Flags, 0, fp24::kNV}}));
  EXPECT_EQ(r.apu->flags(), fp24::kNV);
}

TEST_P(ApuHandTimed, BankStallUntilTheMpuHandsOverData) {
  ApuEngine& apu = engine();
  ApuDriver drv(apu);
  drv.load_program(encode({seq(SeqOp::Swapd), mem(MemOp::Ld, 1, 0, 5), mem(MemOp::St, 1, 0, 6), seq(SeqOp::Swapd),
                           halt()}));
  drv.load_data(5, {0x123456});
  drv.hand_over_program();
  drv.start(0);
  CycleRecord rec;
  for (int i = 0; i < kStartFetchCycles; ++i) {  // the start's fetch and decode
    apu.step(rec);
    EXPECT_FALSE(rec.issued);
    EXPECT_EQ(rec.stall, Stall::Fetch);
  }
  for (int i = 0; i < 10; ++i) {
    apu.step(rec);
    EXPECT_EQ(rec.stall, Stall::Bank);
    EXPECT_EQ(rec.pc, 0);
    EXPECT_FALSE(rec.issued);
  }
  if (const Iss* s = iss(&apu)) {
    EXPECT_EQ(s->counters().stalls[static_cast<int>(Stall::Bank)], 10u);
  }
  drv.hand_over_data();
  EXPECT_TRUE(apu.data_ready());
  apu.step(rec);  // SWAPD issues
  EXPECT_TRUE(rec.issued);
  EXPECT_EQ(rec.dsel, 0);  // the select in effect during the swap cycle
  EXPECT_FALSE(apu.data_ready());
  if (const Iss* s = iss(&apu)) {
    EXPECT_EQ(s->dsel(), 1);
  }
  apu.step(rec);  // LD F1 <- [5] of bank 1
  EXPECT_EQ(rec.dsel, 1);
  apu.step(rec);  // ST [6] <- F1; F1 visible
  EXPECT_EQ(rec.commits, (Commits{{K::FReg, 1, 0x123456}, {K::Mem, 6, 0x123456}}));
  for (int i = 0; i < 3; ++i) {
    apu.step(rec);
    EXPECT_EQ(rec.stall, Stall::Bank);
    EXPECT_EQ(rec.pc, 3);
  }
  // The MPU owns bank 0 now and refills it; the results wait in bank 1.
  drv.load_data(0, {0xABCDEF});
  EXPECT_EQ(apu.read_data(0), 0xABCDEFu);
  drv.hand_over_data();
  EXPECT_EQ(drv.run_until_done(100), 2u);  // SWAPD, HALT
  EXPECT_EQ(drv.read_results(5, 2), (std::vector<std::uint32_t>{0x123456, 0x123456}));
  EXPECT_EQ(apu.cycle(), kStartFetchCycles + 10u + 3 + 3 + 2 + ApuDriver::kSettleCycles);  // the start's cycles first
}

TEST_P(ApuHandTimed, ProgramBankHandOverContinuesInTheNewBank) {
  ApuEngine& apu = engine();
  ApuDriver drv(apu);
  drv.load_program(encode({li(1, 11), seq(SeqOp::Swapp, 0, 2), halt()}));
  drv.hand_over_program();
  drv.start(0);
  EXPECT_FALSE(apu.program_ready());  // the start took the hand-over
  if (const Iss* s = iss(&apu)) {
    EXPECT_EQ(s->psel(), 1);
  }
  drv.load_program(encode({halt(), halt(), li(2, 22), halt()}));  // into bank 0
  CycleRecord rec;
  for (int i = 0; i < 5; ++i) apu.step(rec);
  EXPECT_EQ(rec.stall, Stall::Bank);
  EXPECT_EQ(rec.pc, 1);
  EXPECT_EQ(rec.psel, 1);
  EXPECT_EQ(drv.run(5), 5u);  // still stuck at the SWAPP
  if (const Iss* s = iss(&apu)) {
    EXPECT_EQ(s->pc(), 1);
  }
  drv.hand_over_program();
  EXPECT_EQ(drv.run_until_done(100), 3u + kBranchMissCycles);  // SWAPP, the new bank's fetch, LI, HALT
  if (const Iss* s = iss(&apu)) {
    EXPECT_EQ(s->psel(), 0);
    EXPECT_EQ(s->pc(), 3);
  }
  EXPECT_EQ(apu.areg(1), 11);
  EXPECT_EQ(apu.areg(2), 22);
}

TEST_P(ApuHandTimed, DbnzLoopRunsItsCount) {
  auto r = program({li(1, 5), ialu(IntOp::Addi, 2, 2, 0, 3) | seq(SeqOp::Dbnz, 1, 1), halt()});
  r.go(100, 1);
  EXPECT_EQ(r.recs.size(), 8u + kBranchMissCycles);  // LI, 5 loop words, the exit's miss, HALT, +1
  EXPECT_EQ(r.apu->areg(2), 15);
  EXPECT_EQ(r.apu->areg(1), 0);
  EXPECT_EQ(r.recs[2].commits, (Commits{{K::AReg, 1, 4}, {K::AReg, 2, 3}}));
}

TEST_P(ApuHandTimed, DbnzLoopCommitsItsCounterEachCycle) {
  // 0 LI A1=3  1 ADDI A2+=1 ; DBNZ A1 -> 1  2 HALT. The loop word issues at
  // 1, 2, 3 (A1: 2, 1, 0; the back edge is predicted taken); the exit
  // misses, HALT issues after the bubble; every A write is visible a cycle
  // later.
  auto r = program({li(1, 3), ialu(IntOp::Addi, 2, 2, 0, 1) | seq(SeqOp::Dbnz, 1, 1), halt()});
  r.go(100, 1);
  EXPECT_EQ(r.pcs(), cat<int>({{0, 1, 1, 1}, kMissPcs, {2, -1}}));
  EXPECT_EQ(r.recs[1].commits, (Commits{{K::AReg, 1, 3}}));
  EXPECT_EQ(r.recs[2].commits, (Commits{{K::AReg, 1, 2}, {K::AReg, 2, 1}}));
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::AReg, 1, 1}, {K::AReg, 2, 2}}));
  EXPECT_EQ(r.recs[4].commits, (Commits{{K::AReg, 1, 0}, {K::AReg, 2, 3}}));
  for (std::size_t c = 5; c < r.recs.size(); ++c) EXPECT_TRUE(r.recs[c].commits.empty()) << c;
  EXPECT_EQ(r.apu->areg(2), 3);
}

TEST_P(ApuHandTimed, IntegerOpsWrapAndShift) {
  auto r = program({li(1, 0x8001), ialu(IntOp::Sra, 2, 1, 0, 4), ialu(IntOp::Shr, 3, 1, 0, 4),
                    ialu(IntOp::Muli, 4, 1, 0, 3), ialu(IntOp::Shl, 5, 1, 0, 17), ialu(IntOp::Sub, 6, 0, 1, 0),
                    ialu(IntOp::Xor, 7, 1, 2, 0), ialu(IntOp::Andi, 8, 1, 0, 0xFF), ialu(IntOp::Ori, 9, 1, 0, 0x10),
                    ialu(IntOp::Add, 10, 1, 1, 0), ialu(IntOp::Li, 16 + 11, 0, 0, 0x77), ialu(IntOp::Li, 0, 0, 0, 5),
                    halt()});
  r.go(100, 1);
  EXPECT_EQ(r.apu->areg(2), 0xF800);
  EXPECT_EQ(r.apu->areg(3), 0x0800);
  EXPECT_EQ(r.apu->areg(4), 0x8003);
  EXPECT_EQ(r.apu->areg(5), 0x0002);
  EXPECT_EQ(r.apu->areg(6), 0x7FFF);
  EXPECT_EQ(r.apu->areg(7), 0x8001 ^ 0xF800);
  EXPECT_EQ(r.apu->areg(8), 0x0001);
  EXPECT_EQ(r.apu->areg(9), 0x8011);
  EXPECT_EQ(r.apu->areg(10), 0x0002);
  EXPECT_EQ(r.apu->areg(11), 0x77);  // an A destination is d & 15
  EXPECT_EQ(r.apu->areg(0), 0);
  EXPECT_TRUE(r.recs[12].commits.empty());  // the A0 write is dropped, not recorded
}

TEST_P(ApuHandTimed, FloatFixAndRegisterMoves) {
  // A1 = -3 -> F1 (integer bits) -> FLOAT -> F2 = -3.0; F4 = F2 * 2.5 = -7.5;
  // FIX -> -7.
  auto r = program({li(1, 0xFFFD), ialu(IntOp::Movaf, 1, 1, 0, 0), addu(AddOp::Float, 2, 1, 0), lif(3, 0x4040),
                    nop(), mul(4, 2, 3), nop(), addu(AddOp::Fix, 5, 4, 0), nop(), ialu(IntOp::Movfa, 6, 0, 0, 5),
                    halt()});
  r.go(100, 1);
  EXPECT_EQ(r.stalls(), std::vector<Stall>(12, N));
  EXPECT_EQ(r.apu->freg(1), 0xFFFDu);
  EXPECT_EQ(r.apu->freg(2), 0xC08000u);  // -3.0
  EXPECT_EQ(r.apu->freg(4), 0xC1E000u);  // -7.5
  EXPECT_EQ(r.apu->freg(5), 0xFFF9u);    // FIX toward zero: -7, zero-extended
  EXPECT_EQ(r.apu->areg(6), 0xFFF9);
  EXPECT_EQ(r.apu->flags(), fp24::kNX);
  EXPECT_EQ(r.recs[9].commits, (Commits{{K::FReg, 5, 0xFFF9}, {K::Flags, 0, fp24::kNX}}));
}

TEST_P(ApuHandTimed, MovfaSourceIsCheckedForRaw) {
  auto r = program({lif(1, 0x3F00), addu(AddOp::Fix, 2, 1, 1), ialu(IntOp::Movfa, 3, 0, 0, 64 + 2), halt()});
  r.go(100, 1);
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Raw, N, N, N}));
  EXPECT_EQ(r.apu->areg(3), 1);
}

TEST_P(ApuHandTimed, CallAndReturn) {
  auto r = program({seq(SeqOp::Call, 0, 4), li(2, 2), seq(SeqOp::Call, 0, 4), halt(), li(1, 1) | seq(SeqOp::Ret)});
  r.go(100, 1);
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 4, 1, 2, 4, 3, -1}));
  EXPECT_EQ(r.apu->areg(1), 1);
  EXPECT_EQ(r.apu->areg(2), 2);
  if (const Iss* s = iss(r.apu)) {
    EXPECT_EQ(s->call_depth(), 0);
  }
}

TEST_P(ApuHandTimed, CallStackOverflowFaultsOnTheNinthCall) {
  auto r = program({seq(SeqOp::Call, 0, 0)});
  r.go();
  EXPECT_EQ(r.apu->state(), RunState::Faulted);
  EXPECT_EQ(r.apu->fault(), Fault::CallOverflow);
  ASSERT_EQ(r.recs.size(), 9u);
  EXPECT_FALSE(r.recs[8].issued);
  EXPECT_EQ(r.recs[8].stall, N);
  EXPECT_EQ(r.recs[8].pc, 0);
  if (const Iss* s = iss(r.apu)) {
    EXPECT_EQ(s->call_depth(), 8);
  }
}

TEST_P(ApuHandTimed, ReturnWithEmptyStackFaults) {
  auto r = program({li(1, 1), seq(SeqOp::Ret)});
  r.go(100, 1);
  EXPECT_EQ(r.apu->fault(), Fault::CallUnderflow);
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, -1, -1}));  // the fault in cycle 1, then one idle cycle
  EXPECT_EQ(r.recs[1].pc, 1);
  EXPECT_EQ(r.recs[2].pc, 1);
  EXPECT_EQ(r.recs[1].commits, (Commits{{K::AReg, 1, 1}}));  // the LI still lands
  if (const Iss* s = iss(r.apu)) {
    EXPECT_EQ(s->pc(), 1);
  }
}

TEST_P(ApuHandTimed, DataAddressFaultHasNoEffectButInFlightResultsLand) {
  // MUL at 1 still completes at 3 although the store at 2 (4000 + 96) faults.
  auto r = program({lif(1, 0x4000), li(1, 4000) | mul(2, 1, 1), mem(MemOp::St, 1, 1, 96) | li(3, 3), nop()});
  r.go(100, 3);
  EXPECT_EQ(r.apu->fault(), Fault::DataAddress);
  ASSERT_EQ(r.recs.size(), 6u);
  EXPECT_FALSE(r.recs[2].issued);
  EXPECT_EQ(r.recs[2].stall, N);
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::FReg, 2, 0x410000}}));
  EXPECT_EQ(r.apu->areg(3), 0);  // the faulting word's LI did not issue
  EXPECT_EQ(r.recs[5].pc, 2);
  if (const Iss* s = iss(r.apu)) {
    EXPECT_EQ(s->pc(), 2);
  }
}

TEST_P(ApuHandTimed, DataAddressWrapsModulo16Bits) {
  auto r = program({li(1, 0xFFFF), lif(1, 0x3F00), mem(MemOp::St, 1, 1, 5), halt()});
  r.go();
  EXPECT_EQ(r.apu->state(), RunState::Halted);
  EXPECT_EQ(r.recs[2].commits, (Commits{{K::FReg, 1, kOne}, {K::Mem, 4, kOne}}));
}

TEST_P(ApuHandTimed, EveryReservedOpFaults) {
  MicroWord a = nop();
  a.a = {true, AddOp(7), 1, 2, 3};
  MicroWord d = nop();
  d.d = {MemOp(3), 1, 0, 0};
  MicroWord i = nop();
  i.i = {IntOp::Reserved, 1, 0, 0, 0};
  for (const MicroWord& bad : {a, d, i, seq(SeqOp::Reserved13), seq(SeqOp::Reserved14), seq(SeqOp::Reserved15)}) {
    auto r = program({li(1, 1), bad, halt()});
    r.go();
    EXPECT_EQ(r.apu->fault(), Fault::ReservedOp);
    EXPECT_EQ(r.recs.size(), 2u);
  }
  MicroWord off = nop();  // a disabled A slot with op 7 is no op at all
  off.a = {false, AddOp(7), 1, 2, 3};
  auto r = program({off, halt()});
  r.go();
  EXPECT_EQ(r.apu->state(), RunState::Halted);
}

TEST_P(ApuHandTimed, ReservedSlotTakesPartInNoHazard) {
  // The reserved A slot names F2 (in flight) but faults at once, no raw
  // (Clarification 6).
  MicroWord bad = nop();
  bad.a = {true, AddOp(7), 2, 2, 2};
  auto r = program({lif(1, 0x3F00), mul(2, 1, 1), bad});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N}));
  EXPECT_EQ(r.apu->fault(), Fault::ReservedOp);
}

TEST_P(ApuHandTimed, StallBeforeFault) {
  // A faulting word first waits out its stalls, then faults (Clarification 6).
  MicroWord bad = mul(5, 2, 2);
  bad.i = {IntOp::Reserved, 1, 0, 0, 0};
  auto r = program({lif(1, 0x3F00), mul(2, 1, 1), bad});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Raw, N}));
  EXPECT_EQ(r.apu->fault(), Fault::ReservedOp);
}

TEST_P(ApuHandTimed, PcPast1023Faults) {
  std::vector<Encoded> prog(kProgramWords);
  prog[0] = seq(SeqOp::Jmp, 0, 1022).encode();
  prog[1022] = li(1, 1).encode();
  prog[1023] = seq(SeqOp::Bz, 1, 0).encode();  // A1 != 0: not taken, would fall off
  {  // as the driver reports it
    ApuEngine& apu = engine();
    ApuDriver drv(apu);
    drv.load_program(prog);
    drv.hand_over_program();
    drv.start(0);
    try {
      drv.run_until_done(100);
      FAIL() << "no fault";
    } catch (const ApuError& e) {
      EXPECT_EQ(e.kind(), ApuError::Kind::Fault);
      EXPECT_EQ(e.fault(), Fault::PcOverflow);
      // the start's cycles, JMP (exact: no cycle), LI, BZ
      const std::uint64_t at = kStartFetchCycles + 2u;
      EXPECT_EQ(e.cycle(), at);
      EXPECT_EQ(e.pc(), 1023);
      EXPECT_NE(std::string(e.what()).find("pc-overflow at cycle " + std::to_string(at) + ", pc 0x3ff"),
                std::string::npos)
          << e.what();
    }
  }
  // Cycle by cycle.
  ApuEngine& apu = engine();
  ApuDriver drv(apu);
  drv.load_program(prog);
  drv.hand_over_program();
  drv.start(0);
  CycleRecord rec;
  for (int i = 0; i < kStartFetchCycles + 3; ++i) apu.step(rec);
  EXPECT_EQ(apu.fault(), Fault::PcOverflow);
  EXPECT_EQ(rec.cycle, kStartFetchCycles + 2u);
  EXPECT_EQ(rec.pc, 1023);
  EXPECT_FALSE(rec.issued);
  // CALL at 1023 would push 1024: also a PC overflow; a taken branch is fine.
  prog[1023] = seq(SeqOp::Call, 0, 5).encode();
  prog[5] = halt().encode();
  drv.load_program(prog);
  drv.hand_over_program();
  drv.start(1023);
  for (int i = 0; i < kStartFetchCycles; ++i) apu.step(rec);  // fetch, decode
  EXPECT_EQ(apu.fault(), Fault::None);
  apu.step(rec);
  EXPECT_EQ(apu.fault(), Fault::PcOverflow);
  prog[1023] = seq(SeqOp::Bnz, 1, 5).encode();
  drv.load_program(prog);
  drv.hand_over_program();
  drv.start(1023);
  // fetch, decode, BNZ (taken backward to 5: predicted so, no cycle), HALT
  EXPECT_EQ(drv.run_until_done(10), kStartFetchCycles + 2u);
}

TEST_P(ApuHandTimed, StartAfterHaltKeepsStateAndEmptiesTheStack) {
  // 0 CALL 2  1 HALT  2 LI A1=5; HALT (in the subroutine, stack depth 1)  3 RET
  auto r = program({seq(SeqOp::Call, 0, 2), halt(), li(1, 5) | halt(), seq(SeqOp::Ret)});
  r.go(100, 1);
  EXPECT_EQ(r.apu->state(), RunState::Halted);
  r.apu->start(3);  // the stack was emptied: RET underflows (else it went to 1)
  EXPECT_EQ(r.apu->state(), RunState::Running);
  r.go(100);
  EXPECT_EQ(r.apu->fault(), Fault::CallUnderflow);
  EXPECT_EQ(r.recs.back().pc, 3);
  EXPECT_EQ(r.apu->areg(1), 5);
  const std::size_t before = r.recs.size();
  r.apu->start(4);  // words 4.. are 0 (no op): it runs up to 1023 and faults
  EXPECT_EQ(r.apu->fault(), Fault::None);
  r.go(2000);
  EXPECT_EQ(r.apu->fault(), Fault::PcOverflow);
  EXPECT_EQ(r.recs.size() - before, kStartFetchCycles + 1020u);  // the start's cycles, words 4..1023
  EXPECT_EQ(r.recs.back().pc, 1023);
}

TEST_P(ApuHandTimed, StartFetchesAndDecodesThenJumpsCallsAndReturnsCostNoCycle) {
  // LIF F1 | HALT at 0 (record 0, cycle S = kStartFetchCycles). start(2):
  // cycles S + 1 .. 2S fetch and decode word 2, the first records the LIF's
  // write; then JMP 5, CALL 8, RET (to 6), HALT issue in consecutive cycles:
  // the sequencer fetches their targets while they are in decode.
  std::vector<MicroWord> prog(9);
  prog[0] = lif(1, 0x3F00) | halt();
  prog[2] = seq(SeqOp::Jmp, 0, 5);
  prog[5] = seq(SeqOp::Call, 0, 8);
  prog[6] = halt();
  prog[8] = seq(SeqOp::Ret);
  auto r = program(prog);
  r.go();
  ASSERT_EQ(r.apu->state(), RunState::Halted);
  r.apu->start(2);
  for (int i = 0; i < kStartFetchCycles; ++i) {
    const CycleRecord& fetch = r.step();
    EXPECT_EQ(fetch.cycle, kStartFetchCycles + 1u + i);
    EXPECT_FALSE(fetch.issued);
    EXPECT_EQ(fetch.stall, Stall::Fetch);
    EXPECT_EQ(fetch.pc, 2);
    if (i == 0) {
      EXPECT_EQ(fetch.commits, (Commits{{K::FReg, 1, kOne}}));
    } else {
      EXPECT_TRUE(fetch.commits.empty());
    }
    EXPECT_EQ(r.apu->state(), RunState::Running);
  }
  const std::size_t first = r.recs.size();
  r.go();
  ASSERT_EQ(r.apu->state(), RunState::Halted);
  EXPECT_EQ(r.recs.size() - first, 4u);
  EXPECT_EQ(r.pcs(), cat<int>({{0}, std::vector<int>(kStartFetchCycles, -1), {2, 5, 8, 6}}));
  EXPECT_EQ(r.apu->cycle(), 2u * kStartFetchCycles + 5u);
}

TEST_P(ApuHandTimed, ConditionalBranchesArePredictedTakenBackward) {
  // 0 LI A1=1  1 BNZ A1 -> 3: forward and taken, a miss  3 BZ A1 -> 5:
  // forward, not taken, no cycle  4 BLTZ A1 -> 0: backward, not taken, a
  // miss  5 HALT. A bubble's record names the word that issues after it.
  auto r = program({li(1, 1), seq(SeqOp::Bnz, 1, 3), halt(), seq(SeqOp::Bz, 1, 5), seq(SeqOp::Bltz, 1, 0), halt()});
  r.go();
  ASSERT_EQ(r.apu->state(), RunState::Halted);
  EXPECT_EQ(r.stalls(), cat<Stall>({{N, N}, kMiss, {N, N}, kMiss, {N}}));
  EXPECT_EQ(r.pcs(), cat<int>({{0, 1}, kMissPcs, {3, 4}, kMissPcs, {5}}));
  EXPECT_EQ(r.recs[2].pc, 3);
  EXPECT_EQ(r.recs[3 + kBranchMissCycles + 1].pc, 5);
  if (const Iss* s = iss(r.apu)) {
    EXPECT_EQ(s->counters().stalls[int(Stall::Fetch)], std::uint64_t(kStartFetchCycles + 2 * kBranchMissCycles));
  }
}

TEST_P(ApuHandTimed, ReturnsBackToBackArePredictedExactly) {
  // 0 CALL 3  3 CALL 5  5 RET (to 4: the CALL in issue pushes it as the RET
  // is decoded)  4 RET (to 1: the RET in issue pops 4 as it is decoded)
  // 1 HALT: no cycle lost.
  auto r = program({seq(SeqOp::Call, 0, 3), halt(), nop(), seq(SeqOp::Call, 0, 5), seq(SeqOp::Ret), seq(SeqOp::Ret)});
  r.go();
  ASSERT_EQ(r.apu->state(), RunState::Halted);
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 3, 5, 4, 1}));
}

TEST_P(ApuHandTimed, CycleLimitThrowsWithTheStall) {
  auto r = program({seq(SeqOp::Swapd), halt()});
  try {
    r.drv->run_until_done(50);
    FAIL() << "no limit";
  } catch (const ApuError& e) {
    EXPECT_EQ(e.kind(), ApuError::Kind::CycleLimit);
    EXPECT_EQ(e.cycle(), kStartFetchCycles - 1u + 50u);  // the program's start took cycles 0 .. S - 1
    EXPECT_NE(std::string(e.what()).find("stalled: bank"), std::string::npos) << e.what();
  }
  // To name the stall, the driver steps a copy of the ISS, but any other
  // engine itself, once (a stuck APU stays stuck).
  EXPECT_EQ(r.apu->cycle(), kStartFetchCycles + (iss(r.apu) ? 50u : 51u));
}

TEST_P(ApuHandTimed, MpuHookHandsOverDuringTheRun) {
  auto r = program({seq(SeqOp::Swapd), seq(SeqOp::Swapd), halt()});
  ApuDriver& drv = *r.drv;
  int calls = 0;
  const auto cycles = drv.run_until_done(1000, [&] {
    ++calls;
    if (!drv.data_ready() && r.apu->cycle() >= 20) drv.hand_over_data();
  }, 10);
  // Cycles 0 .. S - 1 were the program's start (S = kStartFetchCycles): the
  // run clocks S..31, the hook at 10, 20 and 30, hand-overs at 20 and 30,
  // HALT at 31.
  EXPECT_EQ(cycles, 32u - kStartFetchCycles);
  EXPECT_EQ(calls, 3);
}

TEST_P(ApuHandTimed, StepAndRunAgreeOnCounters) {
  const std::vector<MicroWord> prog = {li(1, 20), lif(1, 0x3F00), func(FuncOp::Sqrt, 2, 1) | mul(3, 1, 1),
                                       addu(AddOp::Add, 4, 3, 2) | seq(SeqOp::Dbnz, 1, 2), halt()};
  auto stepped = program(prog);
  stepped.go();
  auto fast = program(prog);
  EXPECT_EQ(fast.apu->run(10000), stepped.recs.size());
  EXPECT_EQ(stepped.recs.size(), 2u + 20 * 4 + 2);  // loop: word, raw, raw (SQRT: t + 3), word; HALT: drain, word
  EXPECT_EQ(fast.apu->freg(4), stepped.apu->freg(4));
  EXPECT_EQ(fast.apu->flags(), stepped.apu->flags());
  const Iss* s = iss(stepped.apu);
  const Iss* f = iss(fast.apu);
  if (s && f) {
    EXPECT_EQ(f->counters().issued, s->counters().issued);
    EXPECT_EQ(f->counters().unit_ops[2], 20u);
    EXPECT_EQ(f->counters().stalls[int(Stall::Raw)], 40u);
  }
}

// The fast path takes a long bank stall's cycles at once (Iss::run, RtlEngine::run):
// the same state, cycle count and counters as clocking them one by one, with
// results still in flight when the stall begins.
TEST_P(ApuHandTimed, RunThroughABankStallAgreesWithSteps) {
  const std::vector<MicroWord> prog = {lif(1, 0x3F80), mul(3, 1, 1) | func(FuncOp::Sqrt, 2, 1),
                                       addu(AddOp::Add, 4, 1, 1), seq(SeqOp::Swapd),
                                       mul(5, 3, 2) | mem(MemOp::Ld, 6, 0, 7), halt()};
  ApuEngine& stepped = engine();
  ApuEngine& fast = engine();
  ApuDriver sd(stepped), fd(fast);
  for (ApuDriver* d : {&sd, &fd}) {
    d->load_program(encode(prog));
    d->hand_over_program();
    d->start(0);
  }
  CycleRecord rec;
  for (int i = 0; i < 500; ++i) stepped.step(rec);
  EXPECT_EQ(rec.stall, Stall::Bank);
  EXPECT_EQ(fast.run(500), 500u);
  EXPECT_EQ(fast.cycle(), stepped.cycle());
  EXPECT_EQ(fast.state(), RunState::Running);
  for (int r = 0; r < kNumFRegs; ++r) EXPECT_EQ(fast.freg(r), stepped.freg(r)) << "F" << r;
  EXPECT_EQ(fast.flags(), stepped.flags());
  if (const Iss* s = iss(&stepped)) {
    const Iss* f = iss(&fast);
    EXPECT_EQ(f->pc(), s->pc());
    EXPECT_EQ(f->counters().stalls[int(Stall::Bank)], s->counters().stalls[int(Stall::Bank)]);
    // the start's cycles, then lif, mul|sqrt, add issue first
    EXPECT_EQ(f->counters().stalls[int(Stall::Bank)], 500u - kStartFetchCycles - 3);
    EXPECT_EQ(f->counters().stalls[int(Stall::Fetch)], std::uint64_t(kStartFetchCycles));
    EXPECT_EQ(f->counters().issued, s->counters().issued);
  }
  // Hand the bank over: both finish alike.
  for (ApuDriver* d : {&sd, &fd}) {
    d->load_data(7, {0x123456});
    d->hand_over_data();
  }
  std::uint64_t n = 0;
  for (; stepped.state() == RunState::Running; ++n) stepped.step(rec);
  EXPECT_EQ(n, 4u);  // SWAPD, MUL|LD, drain, HALT
  EXPECT_EQ(fd.run_until_done(100), n);
  for (int i = 0; i < ApuDriver::kSettleCycles; ++i) stepped.step(rec);
  EXPECT_EQ(fast.cycle(), stepped.cycle());
  for (int r = 0; r < kNumFRegs; ++r) EXPECT_EQ(fast.freg(r), stepped.freg(r)) << "F" << r;
}

}  // namespace
}  // namespace mc1::apu
