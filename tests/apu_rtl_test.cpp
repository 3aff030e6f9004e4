// The verilated APU core (RtlEngine) against hand-timed programs: exact cycle
// counts, stall reasons, commit cycles and faults, each derived from
// docs/apu-isa.md ("Timing" and "Clarifications"), not from the ISS.
#include <gtest/gtest.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "Vapu_core.h"
#include "apu_driver.hpp"
#include "apu_rtl_engine.hpp"
#include "apu_test_program.hpp"
#include "fp24.hpp"
#include "verilated.h"

namespace mc1::apu {
namespace {

using namespace apu_test;

// A program on the RTL, which also checks each unit's timing against
// docs/fp24-rtl.md as it runs.
struct Program : EngineProgram<RtlEngine> {
  using EngineProgram::EngineProgram;
  ~Program() { EXPECT_FALSE(apu->unit_mismatch()) << "a unit's timing differs from docs/fp24-rtl.md"; }
};

using K = Commit::Kind;
using Commits = std::vector<Commit>;
constexpr Stall N = Stall::None;

TEST(ApuRtl, ResetStateIsIdleAndZero) {
  RtlEngine apu;
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

TEST(ApuRtl, RawStallAtDistanceOneThenDrain) {
  // 0 LIF F1  1 LIF F2  2 MUL F3=F1*F2 (visible at 4)  3 ADD F4=F3+F1: raw at
  // cycle 3, issues at 4 (visible at 6)  4 HALT: drain at 5, issues at 6.
  Program r({lif(1, 0x3F00), lif(2, 0x4000), mul(3, 1, 2), addu(AddOp::Add, 4, 3, 1), halt()});
  r.go();
  ASSERT_EQ(r.apu->state(), RunState::Halted);
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, Stall::Raw, N, Stall::Drain, N}));
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, 2, -1, 3, -1, 4}));
  EXPECT_EQ(r.recs[3].pc, 3);
  EXPECT_EQ(r.recs[5].pc, 4);
  EXPECT_TRUE(r.recs[0].commits.empty());
  EXPECT_EQ(r.recs[1].commits, (Commits{{K::FReg, 1, kOne}}));
  EXPECT_EQ(r.recs[2].commits, (Commits{{K::FReg, 2, kTwo}}));
  EXPECT_TRUE(r.recs[3].commits.empty());
  EXPECT_EQ(r.recs[4].commits, (Commits{{K::FReg, 3, kTwo}}));
  EXPECT_TRUE(r.recs[5].commits.empty());
  EXPECT_EQ(r.recs[6].commits, (Commits{{K::FReg, 4, kThree}}));
  EXPECT_EQ(r.apu->freg(4), kThree);
  EXPECT_EQ(r.apu->flags(), 0);
  EXPECT_EQ(r.apu->cycle(), 7u);
}

TEST(ApuRtl, ResultAtDistanceTwoIsBypassed) {
  // MUL at 1 is read at 3 = t + 2 with no stall: the bypass from the unit.
  Program r({lif(1, 0x3F00), mul(2, 1, 1), nop(), addu(AddOp::Add, 3, 2, 2), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, N, Stall::Drain, N}));
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::FReg, 2, kOne}}));
  EXPECT_EQ(r.apu->freg(3), kTwo);
}

TEST(ApuRtl, WawStallWaitsForTheFirstWrite) {
  // MUL F3 at 1 (visible 3); LIF F3 at 2 is waw, issues at 3 (visible 4).
  Program r({lif(1, 0x3F00), mul(3, 1, 1), lif(3, 0x4000), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Waw, N, N}));
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, -1, 2, 3}));
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::FReg, 3, kOne}}));
  EXPECT_EQ(r.recs[4].commits, (Commits{{K::FReg, 3, kTwo}}));
  EXPECT_EQ(r.apu->freg(3), kTwo);
}

TEST(ApuRtl, RawHasPriorityOverWaw) {
  Program r({lif(1, 0x3F00), mul(3, 1, 1), addu(AddOp::Add, 3, 3, 1), halt()});
  r.go();
  EXPECT_EQ(r.stalls()[2], Stall::Raw);
  EXPECT_EQ(r.apu->freg(3), kTwo);
}

TEST(ApuRtl, OneOperandAdderOpsDoNotReadB) {
  // NEG reads `a` only: its `b` (F3, in flight) causes no stall.
  Program r({lif(1, 0x3F00), mul(3, 1, 1), addu(AddOp::Neg, 4, 1, 3), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, Stall::Drain, N}));
  EXPECT_EQ(r.apu->freg(4), 0xBF0000u);
}

TEST(ApuRtl, SinCosAndOtherFunctionOpsIssueBackToBack) {
  // SIN at 1 (visible 4), COS at 2 (visible 5), RECIP at 3 (visible 5: the
  // unit returns it on its other port in the COS's cycle); ADD reading the
  // SIN result issues at 4.
  Program r({lif(1, 0x3F00), func(FuncOp::Sin, 2, 1), func(FuncOp::Cos, 3, 1), func(FuncOp::Recip, 4, 1),
             addu(AddOp::Add, 5, 2, 2), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, N, N, Stall::Drain, N}));
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, 2, 3, 4, -1, 5}));
  const auto s = fp24::sin(kOne), c = fp24::cos(kOne);
  const auto twice = fp24::add(s.value, s.value);
  Commits at4{{K::FReg, 2, s.value}};
  if (s.flags) at4.push_back({K::Flags, 0, s.flags});
  EXPECT_EQ(r.recs[4].commits, at4);
  EXPECT_EQ(r.recs[5].commits, (Commits{{K::FReg, 3, c.value}, {K::FReg, 4, kOne}}));
  EXPECT_EQ(r.recs[6].commits[0], (Commit{K::FReg, 5, twice.value}));
  EXPECT_EQ(r.apu->freg(3), c.value);
  EXPECT_EQ(r.apu->freg(4), kOne);
  EXPECT_EQ(r.apu->freg(5), twice.value);
  EXPECT_EQ(r.apu->flags(), s.flags | c.flags | twice.flags);
}

TEST(ApuRtl, RecipAfterSinIntoTheSameRegisterWaitsForIt) {
  // SIN F2 at 1 is in flight at 2 and 3 (u_func's s1, then s2): RECIP F2 is
  // a waw stall twice, issues at 4 (visible 6).
  Program r({lif(1, 0x3F00), func(FuncOp::Sin, 2, 1), func(FuncOp::Recip, 2, 1), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Waw, Stall::Waw, N, Stall::Drain, N}));
  EXPECT_EQ(r.recs[4].commits[0], (Commit{K::FReg, 2, fp24::sin(kOne).value}));
  EXPECT_EQ(r.recs[6].commits, (Commits{{K::FReg, 2, kOne}}));
  EXPECT_EQ(r.apu->freg(2), kOne);
}

TEST(ApuRtl, CosReaderStallsRawTwice) {
  Program r({lif(1, 0x3F00), func(FuncOp::Cos, 2, 1), mul(3, 2, 2), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Raw, Stall::Raw, N, Stall::Drain, N}));
  const auto c = fp24::cos(kOne);
  EXPECT_EQ(r.apu->freg(2), c.value);
  EXPECT_EQ(r.apu->freg(3), fp24::mul(c.value, c.value).value);
}

TEST(ApuRtl, FunctionUnitTakesAnOpEveryCycle) {
  // SQRT at 1 (visible 3), COS at 2 and 3 (visible 5, 6), SQRT at 4 (visible
  // 6, with the second COS). HALT at 5 drains: the COS of 3 is in s2, the
  // SQRT of 4 in s1; both complete at 6, where HALT issues.
  Program r({lif(1, 0x4000), func(FuncOp::Sqrt, 2, 1), func(FuncOp::Cos, 3, 1), func(FuncOp::Cos, 4, 1),
             func(FuncOp::Sqrt, 5, 1), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, N, N, Stall::Drain, N}));
  const auto c = fp24::cos(kTwo), q = fp24::sqrt(kTwo);
  EXPECT_EQ(r.recs[3].commits[0], (Commit{K::FReg, 2, q.value}));
  EXPECT_EQ(r.recs[5].commits[0], (Commit{K::FReg, 3, c.value}));
  EXPECT_EQ(r.recs[6].commits, (Commits{{K::FReg, 4, c.value}, {K::FReg, 5, q.value}}));
  EXPECT_EQ(r.apu->freg(5), q.value);
}

TEST(ApuRtl, DrainAtHaltWaitsForTheLastResult) {
  // COS at 1 is visible at 4: HALT waits at 2 and 3, issues at 4.
  Program r({lif(1, 0x3F00), func(FuncOp::Cos, 2, 1), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Drain, Stall::Drain, N}));
  EXPECT_EQ(r.recs[4].commits[0], (Commit{K::FReg, 2, fp24::cos(kOne).value}));
  EXPECT_EQ(r.apu->state(), RunState::Halted);
}

TEST(ApuRtl, HaltWordsOwnOpsLandAfterIt) {
  Program r({lif(1, 0x3F00), mul(2, 1, 1) | li(3, 9) | halt()});
  r.go(100, 2);
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, -1, -1}));
  EXPECT_EQ(r.recs[2].commits, (Commits{{K::AReg, 3, 9}}));
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::FReg, 2, kOne}}));
  EXPECT_EQ(r.recs[3].pc, 1);  // PC stays at the HALT
}

TEST(ApuRtl, StateBetweenStepsIsWhatTheNextWordReads) {
  // MUL at 1 and CMP at 1 complete at 3: after step 2 the observers already
  // show them (Clarification 2), although the record of cycle 3 lists them.
  Program r({lif(1, 0x4000), mul(2, 1, 1) | addu(AddOp::Cmp, 0, 1, 1), nop(), halt()});
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

TEST(ApuRtl, BranchOnCcWaitsForTheCompare) {
  // CMP 1 < 2 at 2 (CC visible 4); BCC LT at 3 is a cc stall, issues at 4.
  Program r({lif(1, 0x3F00), lif(2, 0x4000), addu(AddOp::Cmp, 0, 1, 2), seq(SeqOp::Bcc, fp24::kLT, 6), halt(), halt(),
         li(5, 7) | halt()});
  r.go(100, 1);
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, Stall::Cc, N, N, N}));
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, 2, -1, 3, 6, -1}));
  EXPECT_EQ(r.recs[4].commits, (Commits{{K::Cc, 0, fp24::kLT}}));
  EXPECT_EQ(r.apu->cc(), fp24::kLT);
  EXPECT_EQ(r.apu->areg(5), 7);
}

TEST(ApuRtl, CompareWithNanSetsUnorderedAndInvalid) {
  // LIF 0x7F80 is the canonical NaN. BNCC UN at 4 (CC visible at 4): not taken.
  Program r({lif(1, 0x7F80), addu(AddOp::Cmp, 0, 1, 1), nop(), seq(SeqOp::Bncc, fp24::kUN, 0), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, N, N}));
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::Cc, 0, fp24::kUN}, {K::Flags, 0, fp24::kNV}}));
  EXPECT_EQ(r.apu->flags(), fp24::kNV);
}

TEST(ApuRtl, BankStallUntilTheMpuHandsOverData) {
  RtlEngine apu;
  ApuDriver drv(apu);
  drv.load_program(encode({seq(SeqOp::Swapd), mem(MemOp::Ld, 1, 0, 5), mem(MemOp::St, 1, 0, 6), seq(SeqOp::Swapd),
                           halt()}));
  drv.load_data(5, {0x123456});
  drv.hand_over_program();
  drv.start(0);
  CycleRecord rec;
  for (int i = 0; i < 10; ++i) {
    apu.step(rec);
    EXPECT_EQ(rec.stall, Stall::Bank);
    EXPECT_EQ(rec.pc, 0);
    EXPECT_FALSE(rec.issued);
  }
  drv.hand_over_data();
  EXPECT_TRUE(apu.data_ready());
  apu.step(rec);  // cycle 10: SWAPD issues
  EXPECT_TRUE(rec.issued);
  EXPECT_EQ(rec.dsel, 0);  // the select in effect during the swap cycle
  EXPECT_FALSE(apu.data_ready());
  apu.step(rec);  // cycle 11: LD F1 <- [5] of bank 1
  EXPECT_EQ(rec.dsel, 1);
  apu.step(rec);  // cycle 12: ST [6] <- F1; F1 visible
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
  EXPECT_EQ(apu.cycle(), 10u + 3 + 3 + 2 + ApuDriver::kSettleCycles);
  EXPECT_FALSE(apu.unit_mismatch());
}

TEST(ApuRtl, ProgramBankHandOverContinuesInTheNewBank) {
  RtlEngine apu;
  ApuDriver drv(apu);
  drv.load_program(encode({li(1, 11), seq(SeqOp::Swapp, 0, 2), halt()}));
  drv.hand_over_program();
  drv.start(0);
  EXPECT_FALSE(apu.program_ready());  // the start took the hand-over
  drv.load_program(encode({halt(), halt(), li(2, 22), halt()}));  // into bank 0
  CycleRecord rec;
  for (int i = 0; i < 5; ++i) apu.step(rec);
  EXPECT_EQ(rec.stall, Stall::Bank);
  EXPECT_EQ(rec.pc, 1);
  EXPECT_EQ(rec.psel, 1);
  drv.hand_over_program();
  EXPECT_EQ(drv.run_until_done(100), 3u);  // SWAPP, LI, HALT
  EXPECT_EQ(apu.areg(1), 11);
  EXPECT_EQ(apu.areg(2), 22);
}

TEST(ApuRtl, DbnzLoopCommitsItsCounterEachCycle) {
  // 0 LI A1=3  1 ADDI A2+=1 ; DBNZ A1 -> 1  2 HALT. The loop word issues at
  // 1, 2, 3 (A1: 2, 1, 0); HALT at 4; every A write is visible a cycle later.
  Program r({li(1, 3), ialu(IntOp::Addi, 2, 2, 0, 1) | seq(SeqOp::Dbnz, 1, 1), halt()});
  r.go(100, 1);
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, 1, 1, 2, -1}));
  EXPECT_EQ(r.recs[1].commits, (Commits{{K::AReg, 1, 3}}));
  EXPECT_EQ(r.recs[2].commits, (Commits{{K::AReg, 1, 2}, {K::AReg, 2, 1}}));
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::AReg, 1, 1}, {K::AReg, 2, 2}}));
  EXPECT_EQ(r.recs[4].commits, (Commits{{K::AReg, 1, 0}, {K::AReg, 2, 3}}));
  EXPECT_TRUE(r.recs[5].commits.empty());
  EXPECT_EQ(r.apu->areg(2), 3);
}

TEST(ApuRtl, IntegerOpsWrapAndShift) {
  Program r({li(1, 0x8001), ialu(IntOp::Sra, 2, 1, 0, 4), ialu(IntOp::Shr, 3, 1, 0, 4), ialu(IntOp::Muli, 4, 1, 0, 3),
         ialu(IntOp::Shl, 5, 1, 0, 17), ialu(IntOp::Sub, 6, 0, 1, 0), ialu(IntOp::Xor, 7, 1, 2, 0),
         ialu(IntOp::Andi, 8, 1, 0, 0xFF), ialu(IntOp::Ori, 9, 1, 0, 0x10), ialu(IntOp::Add, 10, 1, 1, 0),
         ialu(IntOp::Li, 16 + 11, 0, 0, 0x77), ialu(IntOp::Li, 0, 0, 0, 5), halt()});
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

TEST(ApuRtl, FloatFixAndRegisterMoves) {
  // A1 = -3 -> F1 -> FLOAT -> F2 = -3.0; F4 = F2 * 2.5 = -7.5; FIX -> -7.
  Program r({li(1, 0xFFFD), ialu(IntOp::Movaf, 1, 1, 0, 0), addu(AddOp::Float, 2, 1, 0), lif(3, 0x4040), nop(),
         mul(4, 2, 3), nop(), addu(AddOp::Fix, 5, 4, 0), nop(), ialu(IntOp::Movfa, 6, 0, 0, 5), halt()});
  r.go(100, 1);
  EXPECT_EQ(r.stalls(), std::vector<Stall>(12, N));
  EXPECT_EQ(r.apu->freg(1), 0xFFFDu);
  EXPECT_EQ(r.apu->freg(2), 0xC08000u);
  EXPECT_EQ(r.apu->freg(4), 0xC1E000u);
  EXPECT_EQ(r.apu->freg(5), 0xFFF9u);
  EXPECT_EQ(r.apu->areg(6), 0xFFF9);
  EXPECT_EQ(r.apu->flags(), fp24::kNX);
  EXPECT_EQ(r.recs[9].commits, (Commits{{K::FReg, 5, 0xFFF9}, {K::Flags, 0, fp24::kNX}}));
}

TEST(ApuRtl, MovfaSourceIsCheckedForRaw) {
  Program r({lif(1, 0x3F00), addu(AddOp::Fix, 2, 1, 1), ialu(IntOp::Movfa, 3, 0, 0, 64 + 2), halt()});
  r.go(100, 1);
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Raw, N, N, N}));
  EXPECT_EQ(r.apu->areg(3), 1);
}

TEST(ApuRtl, CallAndReturn) {
  Program r({seq(SeqOp::Call, 0, 4), li(2, 2), seq(SeqOp::Call, 0, 4), halt(), li(1, 1) | seq(SeqOp::Ret)});
  r.go(100, 1);
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 4, 1, 2, 4, 3, -1}));
  EXPECT_EQ(r.apu->areg(1), 1);
  EXPECT_EQ(r.apu->areg(2), 2);
}

TEST(ApuRtl, CallStackOverflowFaultsOnTheNinthCall) {
  Program r({seq(SeqOp::Call, 0, 0)});
  r.go();
  EXPECT_EQ(r.apu->state(), RunState::Faulted);
  EXPECT_EQ(r.apu->fault(), Fault::CallOverflow);
  ASSERT_EQ(r.recs.size(), 9u);
  EXPECT_FALSE(r.recs[8].issued);
  EXPECT_EQ(r.recs[8].stall, N);
  EXPECT_EQ(r.recs[8].pc, 0);
}

TEST(ApuRtl, ReturnWithEmptyStackFaults) {
  Program r({li(1, 1), seq(SeqOp::Ret)});
  r.go(100, 1);
  EXPECT_EQ(r.apu->fault(), Fault::CallUnderflow);
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, -1, -1}));
  EXPECT_EQ(r.recs[1].pc, 1);
  EXPECT_EQ(r.recs[2].pc, 1);
  EXPECT_EQ(r.recs[1].commits, (Commits{{K::AReg, 1, 1}}));  // the LI still lands
}

TEST(ApuRtl, DataAddressFaultHasNoEffectButInFlightResultsLand) {
  // MUL at 1 completes at 3 although the store at 2 (4000 + 96) faults.
  Program r({lif(1, 0x4000), li(1, 4000) | mul(2, 1, 1), mem(MemOp::St, 1, 1, 96) | li(3, 3), nop()});
  r.go(100, 3);
  EXPECT_EQ(r.apu->fault(), Fault::DataAddress);
  ASSERT_EQ(r.recs.size(), 6u);
  EXPECT_FALSE(r.recs[2].issued);
  EXPECT_EQ(r.recs[2].stall, N);
  EXPECT_EQ(r.recs[3].commits, (Commits{{K::FReg, 2, 0x410000}}));
  EXPECT_EQ(r.apu->areg(3), 0);
  EXPECT_EQ(r.recs[5].pc, 2);
}

TEST(ApuRtl, DataAddressWrapsModulo16Bits) {
  Program r({li(1, 0xFFFF), lif(1, 0x3F00), mem(MemOp::St, 1, 1, 5), halt()});
  r.go();
  EXPECT_EQ(r.apu->state(), RunState::Halted);
  EXPECT_EQ(r.recs[2].commits, (Commits{{K::FReg, 1, kOne}, {K::Mem, 4, kOne}}));
}

TEST(ApuRtl, EveryReservedOpFaults) {
  MicroWord a = nop();
  a.a = {true, AddOp(7), 1, 2, 3};
  MicroWord d = nop();
  d.d = {MemOp(3), 1, 0, 0};
  MicroWord i = nop();
  i.i = {IntOp::Reserved, 1, 0, 0, 0};
  for (const MicroWord& bad : {a, d, i, seq(SeqOp::Reserved13), seq(SeqOp::Reserved14), seq(SeqOp::Reserved15)}) {
    Program r({li(1, 1), bad, halt()});
    r.go();
    EXPECT_EQ(r.apu->fault(), Fault::ReservedOp);
    EXPECT_EQ(r.recs.size(), 2u);
  }
  MicroWord off = nop();  // a disabled A slot with op 7 is no op at all
  off.a = {false, AddOp(7), 1, 2, 3};
  Program r({off, halt()});
  r.go();
  EXPECT_EQ(r.apu->state(), RunState::Halted);
}

TEST(ApuRtl, ReservedSlotTakesPartInNoHazard) {
  // The reserved A slot names F2 (in flight) but faults at once, no raw.
  MicroWord bad = nop();
  bad.a = {true, AddOp(7), 2, 2, 2};
  Program r({lif(1, 0x3F00), mul(2, 1, 1), bad});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N}));
  EXPECT_EQ(r.apu->fault(), Fault::ReservedOp);
}

TEST(ApuRtl, StallBeforeFault) {
  MicroWord bad = mul(5, 2, 2);
  bad.i = {IntOp::Reserved, 1, 0, 0, 0};
  Program r({lif(1, 0x3F00), mul(2, 1, 1), bad});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Raw, N}));
  EXPECT_EQ(r.apu->fault(), Fault::ReservedOp);
}

TEST(ApuRtl, PcPast1023Faults) {
  RtlEngine apu;
  ApuDriver drv(apu);
  std::vector<Encoded> prog(kProgramWords);
  prog[0] = seq(SeqOp::Jmp, 0, 1022).encode();
  prog[1022] = li(1, 1).encode();
  prog[1023] = seq(SeqOp::Bz, 1, 0).encode();  // A1 != 0: not taken, would fall off
  drv.load_program(prog);
  drv.hand_over_program();
  drv.start(0);
  CycleRecord rec;
  for (int i = 0; i < 3; ++i) apu.step(rec);
  EXPECT_EQ(apu.fault(), Fault::PcOverflow);
  EXPECT_EQ(rec.cycle, 2u);
  EXPECT_EQ(rec.pc, 1023);
  EXPECT_FALSE(rec.issued);
  // CALL at 1023 would push 1024: also a PC overflow; a taken branch is fine.
  prog[1023] = seq(SeqOp::Call, 0, 5).encode();
  prog[5] = halt().encode();
  drv.load_program(prog);
  drv.hand_over_program();
  drv.start(1023);
  apu.step(rec);
  EXPECT_EQ(apu.fault(), Fault::PcOverflow);
  prog[1023] = seq(SeqOp::Bnz, 1, 5).encode();
  drv.load_program(prog);
  drv.hand_over_program();
  drv.start(1023);
  EXPECT_EQ(drv.run_until_done(10), 2u);
}

TEST(ApuRtl, StartAfterHaltKeepsStateAndEmptiesTheStack) {
  // 0 CALL 2  1 HALT  2 LI A1=5; HALT (in the subroutine, stack depth 1)  3 RET
  Program r({seq(SeqOp::Call, 0, 2), halt(), li(1, 5) | halt(), seq(SeqOp::Ret)});
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
  EXPECT_EQ(r.recs.size() - before, 1020u);
  EXPECT_EQ(r.recs.back().pc, 1023);
}

TEST(ApuRtl, MpuPortsOfTheCoreFillAndReadTheIdleBanks) {
  // The core's own MPU ports, clocked, without RtlEngine: program and data
  // into bank 1, hand over, start; refill bank 0 while the APU runs.
  VerilatedContext ctx;
  ctx.randReset(0);
  Vapu_core top(&ctx);
  const auto edge = [&] {
    top.clk = 1;
    top.eval();
    top.mpu2apu_pmem_we = top.mpu2apu_dmem_we = 0;
    top.mpu2apu_hand_over_program = top.mpu2apu_hand_over_data = 0;
    top.mpu2apu_start = top.mpu2apu_start_new_program = 0;
    top.clk = 0;
    top.eval();
  };
  top.rst_n = 0;
  edge();
  top.rst_n = 1;
  top.eval();
  const auto put_data = [&](int addr, std::uint32_t v) {
    top.mpu2apu_dmem_we = 1;
    top.mpu2apu_dmem_addr = addr;
    top.mpu2apu_dmem_wdata = v;
    edge();
  };
  const auto get_data = [&](int addr) {
    top.mpu2apu_dmem_addr = addr;
    top.eval();
    return top.apu2mpu_dmem_rdata;
  };
  const auto prog = encode({seq(SeqOp::Swapd), mem(MemOp::Ld, 1, 0, 7), mul(2, 1, 1), nop(),
                            mem(MemOp::St, 2, 0, 8), seq(SeqOp::Swapd), halt()});
  for (std::size_t i = 0; i < prog.size(); ++i) {
    top.mpu2apu_pmem_we = 1;
    top.mpu2apu_pmem_addr = i;
    top.mpu2apu_pmem_wdata[0] = static_cast<std::uint32_t>(prog[i].lo);
    top.mpu2apu_pmem_wdata[1] = static_cast<std::uint32_t>(prog[i].lo >> 32);
    top.mpu2apu_pmem_wdata[2] = static_cast<std::uint32_t>(prog[i].hi);
    top.mpu2apu_pmem_wdata[3] = static_cast<std::uint32_t>(prog[i].hi >> 32);
    edge();
  }
  put_data(7, kTwo);
  EXPECT_EQ(get_data(7), kTwo);
  top.mpu2apu_hand_over_program = top.mpu2apu_hand_over_data = 1;
  edge();
  EXPECT_TRUE(top.apu2mpu_program_ready && top.apu2mpu_data_ready);
  top.mpu2apu_start = top.mpu2apu_start_new_program = 1;
  top.mpu2apu_start_pc = 0;
  top.eval();
  EXPECT_EQ(top.apu2mpu_psel, 1);
  EXPECT_TRUE(top.dbg_issue);  // the SWAPD issues in the start cycle
  edge();
  EXPECT_EQ(top.apu2mpu_dsel, 1);
  put_data(7, 0x123456);  // the MPU owns bank 0 now: the APU does not see this
  // (that port write was APU cycle 1, the LD.) The second SWAPD (cycle 5)
  // waits for a hand-over; presented in that cycle, it lets it issue there.
  int cycles = 2, bank_stalls = 0;
  for (; cycles < 50 && top.apu2mpu_run_state == 1; ++cycles) {
    if (top.dbg_stall_reason == static_cast<int>(Stall::Bank)) {
      ++bank_stalls;
      EXPECT_EQ(top.dbg_pc, 5);
      top.mpu2apu_hand_over_data = 1;
      top.eval();
      EXPECT_TRUE(top.dbg_issue);
    }
    edge();
  }
  EXPECT_EQ(top.apu2mpu_run_state, 2);  // halted
  EXPECT_EQ(cycles, 7);                 // 7 words, no stall left
  EXPECT_EQ(bank_stalls, 1);
  EXPECT_EQ(top.apu2mpu_dsel, 0);
  EXPECT_EQ(get_data(8), 0x410000u);  // 2 * 2, stored in bank 1, handed back
  EXPECT_EQ(get_data(7), kTwo);
  EXPECT_FALSE(top.dbg_unit_mismatch);
  top.final();
}

TEST(ApuRtl, WaveformHasTheDocumentedSignals) {
  const std::string path = testing::TempDir() + "apu_rtl_test.fst";
  {
    Program r({lif(1, 0x3F00), func(FuncOp::Sin, 2, 1), func(FuncOp::Cos, 3, 1), mul(4, 2, 3), halt()}, path.c_str());
    r.go();
    EXPECT_EQ(r.apu->state(), RunState::Halted);
  }
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  ASSERT_TRUE(f.good());
  EXPECT_GT(f.tellg(), 1000);
  std::remove(path.c_str());
}

TEST(ApuRtl, Throughput) {
  // A two-word loop keeping all three units and the D slot busy every cycle.
  Program r({li(1, 1) | lif(1, 0x3F00), li(2, 40) | lif(2, 0x4000),
         mul(3, 1, 2) | addu(AddOp::Add, 4, 1, 2) | func(FuncOp::Sqrt, 5, 2) | mem(MemOp::St, 1, 2, 0) |
             ialu(IntOp::Addi, 1, 1, 0, 1),
         mul(6, 1, 2) | addu(AddOp::Sub, 7, 1, 2) | func(FuncOp::Recip, 8, 2) | mem(MemOp::Ld, 9, 2, 0) |
             seq(SeqOp::Jmp, 0, 2)});
  // Process CPU time: the rate on one core, whatever else the machine runs.
  const std::clock_t c0 = std::clock();
  const std::uint64_t n = r.apu->run(2'000'000);
  const double s = double(std::clock() - c0) / CLOCKS_PER_SEC;
  EXPECT_EQ(n, 2'000'000u);
  EXPECT_EQ(r.apu->state(), RunState::Running);
  const double rate = n / s;
  RecordProperty("run_cycles_per_cpu_second", static_cast<int>(rate));
  std::printf("RtlEngine::run:  %.2f M cycles per CPU second\n", rate / 1e6);
  CycleRecord rec;
  const std::clock_t c1 = std::clock();
  for (int i = 0; i < 1'000'000; ++i) r.apu->step(rec);
  const double s1 = double(std::clock() - c1) / CLOCKS_PER_SEC;
  RecordProperty("step_cycles_per_cpu_second", static_cast<int>(1e6 / s1));
  std::printf("RtlEngine::step: %.2f M cycles per CPU second\n", 1.0 / s1);
  EXPECT_TRUE(rec.issued);
}

}  // namespace
}  // namespace mc1::apu
