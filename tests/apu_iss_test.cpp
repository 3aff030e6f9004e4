// The ISS against hand-timed programs (docs/apu-isa.md "Timing" and
// "Clarifications"): exact cycle counts, stall reasons, commits and faults.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <vector>

#include "apu_driver.hpp"
#include "apu_iss.hpp"
#include "apu_profile.hpp"
#include "apu_test_program.hpp"
#include "fp24.hpp"

namespace mc1::apu {
namespace {

using namespace apu_test;
using Prog = EngineProgram<Iss>;

using K = Commit::Kind;
constexpr Stall N = Stall::None;

TEST(ApuIss, RawAtDistanceOneStallsOneCycleAndHaltDrains) {
  Prog r({lif(1, 0x3F00), lif(2, 0x4000), mul(3, 1, 2), addu(AddOp::Add, 4, 3, 1), halt()});
  r.go();
  ASSERT_EQ(r.apu->state(), RunState::Halted);
  EXPECT_EQ(r.recs.size(), 7u);  // 5 words + raw + drain
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, Stall::Raw, N, Stall::Drain, N}));
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, 2, -1, 3, -1, 4}));
  EXPECT_EQ(r.recs[3].pc, 3);
  EXPECT_EQ(r.recs[5].pc, 4);
  EXPECT_EQ(r.recs[1].commits, (std::vector<Commit>{{K::FReg, 1, kOne}}));
  EXPECT_EQ(r.recs[2].commits, (std::vector<Commit>{{K::FReg, 2, kTwo}}));
  EXPECT_TRUE(r.recs[3].commits.empty());
  EXPECT_EQ(r.recs[4].commits, (std::vector<Commit>{{K::FReg, 3, kTwo}}));  // MUL at 2, visible at 4
  EXPECT_EQ(r.recs[6].commits, (std::vector<Commit>{{K::FReg, 4, kThree}}));
  EXPECT_EQ(r.apu->freg(4), kThree);
  EXPECT_EQ(r.apu->pc(), 4);
  EXPECT_EQ(r.apu->cycle(), 7u);
}

TEST(ApuIss, RawAtDistanceTwoDoesNotStall) {
  Prog r({lif(1, 0x3F00), mul(2, 1, 1), nop(), addu(AddOp::Add, 3, 2, 2), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, N, Stall::Drain, N}));
  EXPECT_EQ(r.apu->freg(3), kTwo);
}

TEST(ApuIss, SinCosAndOtherFunctionOpsIssueBackToBack) {
  // SIN at 1 (visible 4), COS at 2 (visible 5), RECIP at 3 (visible 5, with
  // the COS); the ADD reading the SIN result issues at 4 with no stall.
  Prog r({lif(1, 0x3F00), func(FuncOp::Sin, 2, 1), func(FuncOp::Cos, 3, 1), func(FuncOp::Recip, 4, 1),
          addu(AddOp::Add, 5, 2, 2), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, N, N, Stall::Drain, N}));
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, 2, 3, 4, -1, 5}));
  const auto sin1 = fp24::sin(kOne), cos1 = fp24::cos(kOne);
  const auto twice = fp24::add(sin1.value, sin1.value);
  EXPECT_EQ(r.recs[4].commits, (std::vector<Commit>{{K::FReg, 2, sin1.value}, {K::Flags, 0, sin1.flags}}));
  EXPECT_EQ(r.recs[5].commits, (std::vector<Commit>{{K::FReg, 3, cos1.value}, {K::FReg, 4, kOne}}));
  EXPECT_EQ(r.recs[6].commits, (std::vector<Commit>{{K::FReg, 5, twice.value}}));
  EXPECT_EQ(r.apu->flags(), sin1.flags | cos1.flags | twice.flags);
}

TEST(ApuIss, RecipAfterSinIntoTheSameRegisterWaitsForIt) {
  // SIN F2 at 1 is in flight at 2 and 3: RECIP F2 is a waw stall twice,
  // issues at 4 (visible 6), after the SIN result (visible 4).
  Prog r({lif(1, 0x3F00), func(FuncOp::Sin, 2, 1), func(FuncOp::Recip, 2, 1), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Waw, Stall::Waw, N, Stall::Drain, N}));
  EXPECT_EQ(r.recs[4].commits[0], (Commit{K::FReg, 2, fp24::sin(kOne).value}));
  EXPECT_EQ(r.recs[6].commits, (std::vector<Commit>{{K::FReg, 2, kOne}}));
}

TEST(ApuIss, SinThenReaderStallsRawTwice) {
  Prog r({lif(1, 0x3F00), func(FuncOp::Cos, 2, 1), mul(3, 2, 2), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Raw, Stall::Raw, N, Stall::Drain, N}));
}

TEST(ApuIss, WriteAfterWriteWaitsForTheFirstResult) {
  Prog r({lif(1, 0x3F00), mul(3, 1, 1), lif(3, 0x4000), halt()});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Waw, N, N}));
  EXPECT_EQ(r.recs[3].commits, (std::vector<Commit>{{K::FReg, 3, kOne}}));
  EXPECT_EQ(r.recs[4].commits, (std::vector<Commit>{{K::FReg, 3, kTwo}}));
  EXPECT_EQ(r.apu->freg(3), kTwo);
}

TEST(ApuIss, RawBeatsWawInPriority) {
  // MUL F3 in flight; the next word reads F3 and writes F3.
  Prog r({lif(1, 0x3F00), mul(3, 1, 1), addu(AddOp::Add, 3, 3, 1), halt()});
  r.go();
  EXPECT_EQ(r.stalls()[2], Stall::Raw);
  EXPECT_EQ(r.apu->freg(3), kTwo);
}

TEST(ApuIss, BranchOnCcWaitsForTheCompare) {
  // CMP 1 < 2 at 2 (CC visible at 4); BCC LT at 3 stalls once, is taken.
  Prog r({lif(1, 0x3F00), lif(2, 0x4000), addu(AddOp::Cmp, 0, 1, 2), seq(SeqOp::Bcc, fp24::kLT, 6), halt(),
         halt(), li(5, 7) | halt()});
  r.go(100, 1);
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, N, Stall::Cc, N, N, N}));
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 1, 2, -1, 3, 6, -1}));
  EXPECT_EQ(r.recs[4].commits, (std::vector<Commit>{{K::Cc, 0, fp24::kLT}}));
  EXPECT_EQ(r.apu->cc(), fp24::kLT);
  EXPECT_EQ(r.apu->areg(5), 7);  // the HALT word's own LI lands the cycle after
}

TEST(ApuIss, BnccNotTakenFallsThrough) {
  Prog r({lif(1, 0x3F00), addu(AddOp::Cmp, 0, 1, 1), nop(), seq(SeqOp::Bncc, fp24::kEQ, 6), li(4, 1), halt(),
         li(4, 2) | halt()});
  r.go(100, 1);
  EXPECT_EQ(r.apu->cc(), fp24::kEQ);
  EXPECT_EQ(r.apu->areg(4), 1);
  EXPECT_EQ(r.recs.size(), 7u);  // no stall: CMP at 1 is visible at 3
}

TEST(ApuIss, BankStallUntilTheMpuHandsOver) {
  auto iss = std::make_unique<Iss>();
  ApuDriver drv(*iss);
  drv.load_program({seq(SeqOp::Swapd).encode(), (mem(MemOp::Ld, 1, 0, 5)).encode(),
                    (mem(MemOp::St, 1, 0, 6)).encode(), seq(SeqOp::Swapd).encode(), halt().encode()});
  drv.load_data(5, {0x123456});
  drv.hand_over_program();
  drv.start(0);
  CycleRecord rec;
  for (int i = 0; i < 10; ++i) {
    iss->step(rec);
    EXPECT_EQ(rec.stall, Stall::Bank);
    EXPECT_EQ(rec.pc, 0);
  }
  EXPECT_EQ(iss->counters().stalls[static_cast<int>(Stall::Bank)], 10u);
  drv.hand_over_data();
  EXPECT_TRUE(iss->data_ready());
  iss->step(rec);  // cycle 10: SWAPD issues
  EXPECT_TRUE(rec.issued);
  EXPECT_EQ(rec.dsel, 0);
  EXPECT_FALSE(iss->data_ready());
  EXPECT_EQ(iss->dsel(), 1);
  iss->step(rec);  // LD
  iss->step(rec);  // ST, F1 visible
  EXPECT_EQ(rec.commits, (std::vector<Commit>{{K::FReg, 1, 0x123456}, {K::Mem, 6, 0x123456}}));
  for (int i = 0; i < 3; ++i) {
    iss->step(rec);
    EXPECT_EQ(rec.stall, Stall::Bank);
  }
  // The MPU now owns bank 0 and refills it; the results wait in bank 1.
  drv.load_data(0, {0xABCDEF});
  drv.hand_over_data();
  EXPECT_EQ(drv.run_until_done(100), 2u);  // SWAPD, HALT
  EXPECT_EQ(drv.read_results(5, 2), (std::vector<std::uint32_t>{0x123456, 0x123456}));
  EXPECT_EQ(iss->cycle(), 10u + 3 + 3 + 2 + ApuDriver::kSettleCycles);
}

TEST(ApuIss, ProgramBankHandOverContinuesInTheNewBank) {
  auto iss = std::make_unique<Iss>();
  ApuDriver drv(*iss);
  drv.load_program({li(1, 11).encode(), seq(SeqOp::Swapp, 0, 2).encode(), halt().encode()});
  drv.hand_over_program();
  drv.start(0);
  EXPECT_EQ(iss->psel(), 1);
  drv.load_program({halt().encode(), halt().encode(), li(2, 22).encode(), halt().encode()});
  EXPECT_EQ(drv.run(5), 5u);  // stuck at the SWAPP
  EXPECT_EQ(iss->pc(), 1);
  drv.hand_over_program();
  EXPECT_EQ(drv.run_until_done(100), 3u);
  EXPECT_EQ(iss->psel(), 0);
  EXPECT_EQ(iss->pc(), 3);
  EXPECT_EQ(iss->areg(1), 11);
  EXPECT_EQ(iss->areg(2), 22);
}

TEST(ApuIss, DbnzLoopRunsItsCount) {
  Prog r({li(1, 5), ialu(IntOp::Addi, 2, 2, 0, 3) | seq(SeqOp::Dbnz, 1, 1), halt()});
  r.go(100, 1);
  EXPECT_EQ(r.recs.size(), 8u);  // LI, 5 loop words, HALT, +1
  EXPECT_EQ(r.apu->areg(2), 15);
  EXPECT_EQ(r.apu->areg(1), 0);
  EXPECT_EQ(r.recs[2].commits, (std::vector<Commit>{{K::AReg, 1, 4}, {K::AReg, 2, 3}}));
}

TEST(ApuIss, IntegerOpsWrapAndShift) {
  Prog r({li(1, 0x8001), ialu(IntOp::Sra, 2, 1, 0, 4), ialu(IntOp::Shr, 3, 1, 0, 4),
         ialu(IntOp::Muli, 4, 1, 0, 3), ialu(IntOp::Shl, 5, 1, 0, 17), ialu(IntOp::Sub, 6, 0, 1, 0),
         ialu(IntOp::Xor, 7, 1, 2, 0), ialu(IntOp::Andi, 8, 1, 0, 0xFF), ialu(IntOp::Ori, 9, 1, 0, 0x10),
         ialu(IntOp::Add, 10, 1, 1, 0), ialu(IntOp::Li, 0, 0, 0, 5), halt()});
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
  EXPECT_EQ(r.apu->areg(0), 0);
  EXPECT_TRUE(r.recs[11].commits.empty());  // A0 write dropped, not recorded
}

TEST(ApuIss, FloatFixAndRegisterMoves) {
  // A1 = -3 -> F1 (integer bits) -> FLOAT -> F2 = -3.0; FIX(F2 * 2.5) -> -7.
  Prog r({li(1, 0xFFFD), ialu(IntOp::Movaf, 1, 1, 0, 0), addu(AddOp::Float, 2, 1, 0), lif(3, 0x4040), nop(),
         mul(4, 2, 3), nop(), addu(AddOp::Fix, 5, 4, 0), nop(), ialu(IntOp::Movfa, 6, 0, 0, 5), halt()});
  r.go(100, 1);
  EXPECT_EQ(r.apu->freg(1), 0xFFFDu);
  EXPECT_EQ(r.apu->freg(2), 0xC08000u);   // -3.0
  EXPECT_EQ(r.apu->freg(4), 0xC1E000u);   // -7.5
  EXPECT_EQ(r.apu->freg(5), 0xFFF9u);     // FIX toward zero: -7, zero-extended
  EXPECT_EQ(r.apu->areg(6), 0xFFF9);
  EXPECT_EQ(r.apu->flags(), fp24::kNX);
}

TEST(ApuIss, CallAndReturn) {
  Prog r({seq(SeqOp::Call, 0, 4), li(2, 2), seq(SeqOp::Call, 0, 4), halt(), li(1, 1) | seq(SeqOp::Ret)});
  r.go(100, 1);
  EXPECT_EQ(r.pcs(), (std::vector<int>{0, 4, 1, 2, 4, 3, -1}));
  EXPECT_EQ(r.apu->areg(1), 1);
  EXPECT_EQ(r.apu->areg(2), 2);
  EXPECT_EQ(r.apu->call_depth(), 0);
}

TEST(ApuIss, CallStackOverflowFaultsOnTheNinthCall) {
  Prog r({seq(SeqOp::Call, 0, 0)});
  r.go();
  EXPECT_EQ(r.apu->state(), RunState::Faulted);
  EXPECT_EQ(r.apu->fault(), Fault::CallOverflow);
  EXPECT_EQ(r.recs.size(), 9u);
  EXPECT_FALSE(r.recs[8].issued);
  EXPECT_EQ(r.recs[8].stall, Stall::None);
  EXPECT_EQ(r.apu->call_depth(), 8);
}

TEST(ApuIss, ReturnWithEmptyStackFaults) {
  Prog r({li(1, 1), seq(SeqOp::Ret)});
  r.go();
  EXPECT_EQ(r.apu->fault(), Fault::CallUnderflow);
  EXPECT_EQ(r.recs.size(), 2u);
  EXPECT_EQ(r.apu->pc(), 1);
}

TEST(ApuIss, DataAddressFaultHasNoEffectButInFlightResultsLand) {
  // MUL at 1 still completes at 3 although the store at 2 (4000 + 96) faults.
  Prog r({lif(1, 0x4000), li(1, 4000) | mul(2, 1, 1), mem(MemOp::St, 1, 1, 96) | li(3, 3), nop()});
  r.go(100, 3);
  EXPECT_EQ(r.apu->fault(), Fault::DataAddress);
  EXPECT_EQ(r.recs.size(), 6u);
  EXPECT_EQ(r.recs[3].commits, (std::vector<Commit>{{K::FReg, 2, 0x410000}}));
  EXPECT_EQ(r.apu->areg(3), 0);  // the faulting word's LI did not issue
  EXPECT_EQ(r.apu->pc(), 2);
}

TEST(ApuIss, DataAddressWrapsModulo16Bits) {
  Prog r({li(1, 0xFFFF), lif(1, 0x3F00), mem(MemOp::St, 1, 1, 5), halt()});
  r.go();
  EXPECT_EQ(r.apu->state(), RunState::Halted);
  EXPECT_EQ(r.recs[2].commits, (std::vector<Commit>{{K::FReg, 1, kOne}, {K::Mem, 4, kOne}}));
}

TEST(ApuIss, PcPast1023Faults) {
  auto iss = std::make_unique<Iss>();
  ApuDriver drv(*iss);
  std::vector<Encoded> prog(kProgramWords);
  prog[0] = seq(SeqOp::Jmp, 0, 1022).encode();
  prog[1023] = seq(SeqOp::Bz, 1, 0).encode();  // A1 != 0: not taken, falls off
  prog[1022] = li(1, 1).encode();
  drv.load_program(prog);
  drv.hand_over_program();
  drv.start(0);
  try {
    drv.run_until_done(100);
    FAIL() << "no fault";
  } catch (const ApuError& e) {
    EXPECT_EQ(e.kind(), ApuError::Kind::Fault);
    EXPECT_EQ(e.fault(), Fault::PcOverflow);
    EXPECT_EQ(e.cycle(), 2u);
    EXPECT_EQ(e.pc(), 1023);
    EXPECT_NE(std::string(e.what()).find("pc-overflow at cycle 2, pc 0x3ff"), std::string::npos) << e.what();
  }
}

TEST(ApuIss, EveryReservedOpFaults) {
  MicroWord a = nop(); a.a = {true, AddOp(7), 1, 2, 3};
  MicroWord d = nop(); d.d = {MemOp(3), 1, 0, 0};
  MicroWord i = nop(); i.i = {IntOp::Reserved, 1, 0, 0, 0};
  for (const MicroWord& bad : {a, d, i, seq(SeqOp::Reserved13), seq(SeqOp::Reserved14), seq(SeqOp::Reserved15)}) {
    Prog r({li(1, 1), bad, halt()});
    r.go();
    EXPECT_EQ(r.apu->fault(), Fault::ReservedOp);
    EXPECT_EQ(r.recs.size(), 2u);
  }
  // A disabled A slot with op 7 is no op at all.
  MicroWord off = nop(); off.a = {false, AddOp(7), 1, 2, 3};
  Prog r({off, halt()});
  r.go();
  EXPECT_EQ(r.apu->state(), RunState::Halted);
}

TEST(ApuIss, StallBeforeFault) {
  // A faulting word first waits out its stalls, then faults (Clarification 6).
  MicroWord bad = mul(5, 2, 2); bad.i = {IntOp::Reserved, 1, 0, 0, 0};
  Prog r({lif(1, 0x3F00), mul(2, 1, 1), bad});
  r.go();
  EXPECT_EQ(r.stalls(), (std::vector<Stall>{N, N, Stall::Raw, N}));
  EXPECT_EQ(r.apu->fault(), Fault::ReservedOp);
}

TEST(ApuIss, CycleLimitThrowsWithTheStall) {
  auto iss = std::make_unique<Iss>();
  ApuDriver drv(*iss);
  drv.load_program({seq(SeqOp::Swapd).encode(), halt().encode()});
  drv.hand_over_program();
  drv.start(0);
  try {
    drv.run_until_done(50);
    FAIL() << "no limit";
  } catch (const ApuError& e) {
    EXPECT_EQ(e.kind(), ApuError::Kind::CycleLimit);
    EXPECT_EQ(e.cycle(), 49u);
    EXPECT_NE(std::string(e.what()).find("stalled: bank"), std::string::npos) << e.what();
  }
  EXPECT_EQ(iss->cycle(), 50u);
}

TEST(ApuIss, MpuHookHandsOverDuringTheRun) {
  auto iss = std::make_unique<Iss>();
  ApuDriver drv(*iss);
  drv.load_program({seq(SeqOp::Swapd).encode(), seq(SeqOp::Swapd).encode(), halt().encode()});
  drv.hand_over_program();
  drv.start(0);
  int calls = 0;
  const auto cycles = drv.run_until_done(1000, [&] {
    ++calls;
    if (!drv.data_ready() && iss->cycle() >= 20) drv.hand_over_data();
  }, 10);
  EXPECT_EQ(cycles, 32u);  // hand-overs at cycles 20 and 30, HALT at 31
  EXPECT_EQ(calls, 4);     // at cycles 0, 10, 20, 30
}

TEST(ApuIss, StepAndRunAgreeOnCounters) {
  std::vector<MicroWord> prog = {li(1, 20), lif(1, 0x3F00), func(FuncOp::Sqrt, 2, 1) | mul(3, 1, 1),
                                 addu(AddOp::Add, 4, 3, 2) | seq(SeqOp::Dbnz, 1, 2), halt()};
  Prog stepped(prog);
  stepped.go();
  Prog fast(prog);
  EXPECT_EQ(fast.apu->run(10000), stepped.recs.size());
  EXPECT_EQ(fast.apu->counters().issued, stepped.apu->counters().issued);
  EXPECT_EQ(fast.apu->counters().unit_ops[2], 20u);
  EXPECT_EQ(fast.apu->counters().stalls[int(Stall::Raw)], 20u);
  EXPECT_EQ(stepped.recs.size(), 2u + 20 * 3 + 2);  // loop: word, raw, word; HALT: drain, word
}

TEST(ApuProfile, CountsUnitsStallsAndHotWords) {
  auto iss = std::make_unique<Iss>();
  ApuDriver drv(*iss);
  const std::vector<MicroWord> prog = {lif(1, 0x3F00), lif(2, 0x4000), mul(3, 1, 2) | func(FuncOp::Sin, 4, 1),
                                       addu(AddOp::Add, 5, 3, 1), halt()};
  std::vector<Encoded> words;
  for (const auto& w : prog) words.push_back(w.encode());
  drv.load_program(words);
  drv.hand_over_program();
  drv.start(0);
  Profile prof([&drv](int bank, std::uint16_t pc) { return drv.program_word(bank, pc); });
  drv.set_observer([&](const CycleRecord& r) { prof.add(r); });
  EXPECT_EQ(drv.run_until_done(100), 7u);  // raw at 3, drain at 5 (SIN done at 5, ADD at 6)
  EXPECT_EQ(prof.cycles(), 7u);
  EXPECT_EQ(prof.issued(), 5u);
  EXPECT_EQ(prof.unit_ops(0), 1u);
  EXPECT_EQ(prof.unit_ops(1), 1u);
  EXPECT_EQ(prof.unit_ops(2), 1u);
  EXPECT_EQ(prof.stalls(Stall::Raw), 1u);
  EXPECT_EQ(prof.stalls(Stall::Drain), 1u);
  EXPECT_EQ(prof.at(1, 3).stalls[int(Stall::Raw)], 1u);
  EXPECT_EQ(prof.at(1, 4).stalls[int(Stall::Drain)], 1u);
  EXPECT_NEAR(prof.utilization(0), 1.0 / 7, 1e-12);
  EXPECT_NEAR(prof.mflops(), 3.0 / 7 * 4, 1e-9);
  const std::string rep = prof.report(1);
  EXPECT_NE(rep.find("APU profile: 7 cycles"), std::string::npos) << rep;
  EXPECT_NE(rep.find("raw          1           14.3%"), std::string::npos) << rep;
  EXPECT_NE(rep.find("1    0x003 1         50.0% 1"), std::string::npos) << rep;
  EXPECT_EQ(rep.find("0x004 1"), std::string::npos) << rep;  // --top 1
}

TEST(ApuDriverFiles, DataFileAddressesAndErrors) {
  const std::string path = ::testing::TempDir() + "apu_iss_test_data.txt";
  {
    std::ofstream f(path);
    f << "# a block\n@10 3f0000 400000  # two words\n@0 7\n";
  }
  const auto words = read_data_file(path);
  ASSERT_EQ(words.size(), 3u);
  EXPECT_EQ(words[0], (std::pair<std::uint16_t, std::uint32_t>{0x10, 0x3F0000}));
  EXPECT_EQ(words[1], (std::pair<std::uint16_t, std::uint32_t>{0x11, 0x400000}));
  EXPECT_EQ(words[2], (std::pair<std::uint16_t, std::uint32_t>{0x0, 0x7}));
  {
    std::ofstream f(path);
    f << "1\n2 1000000\n";
  }
  try {
    read_data_file(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":2: '1000000' is wider than 24 bits"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace mc1::apu
