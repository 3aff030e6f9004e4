// What only the RTL has: the core's own MPU ports driven on the raw verilated
// model, the FST waveform and RtlEngine's speed. The hand-timed programs run
// on both engines in tests/apu_hand_timed_test.cpp.
#include <gtest/gtest.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "apu_core_ports.hpp"
#include "apu_driver.hpp"
#include "apu_rtl_engine.hpp"
#include "apu_test_program.hpp"
#include "verilated.h"

namespace mc1::apu {
namespace {

using namespace apu_test;

TEST(ApuRtl, MpuPortsOfTheCoreFillAndReadTheIdleBanks) {
  // The core's own MPU ports, clocked, without RtlEngine: program and data
  // into bank 1, hand over, start; refill bank 0 while the APU runs.
  CorePorts core;
  Vapu_core& top = core.top;
  const auto prog = encode({seq(SeqOp::Swapd), mem(MemOp::Ld, 1, 0, 7), mul(2, 1, 1), nop(),
                            mem(MemOp::St, 2, 0, 8), seq(SeqOp::Swapd), halt()});
  for (std::size_t i = 0; i < prog.size(); ++i) core.write_program(static_cast<std::uint16_t>(i), prog[i]);
  core.write_data(7, kTwo);
  EXPECT_EQ(core.read_data(7), kTwo);
  top.mpu2apu_hand_over_program = top.mpu2apu_hand_over_data = 1;
  core.edge();
  EXPECT_TRUE(top.apu2mpu_program_ready && top.apu2mpu_data_ready);
  top.mpu2apu_start = top.mpu2apu_start_new_program = 1;
  top.mpu2apu_start_pc = 0;
  top.eval();
  EXPECT_EQ(top.apu2mpu_psel, 1);
  // The start's cycles fetch word 0, then decode it (`fetch`).
  for (int i = 0; i < kStartFetchCycles; ++i) {
    EXPECT_FALSE(top.dbg_issue);
    EXPECT_EQ(top.dbg_stall_reason, static_cast<int>(Stall::Fetch));
    EXPECT_EQ(top.dbg_pc, 0);
    core.edge();
  }
  EXPECT_TRUE(top.dbg_issue);  // the SWAPD issues in the next
  core.edge();
  EXPECT_EQ(top.apu2mpu_dsel, 1);
  core.write_data(7, 0x123456);  // the MPU owns bank 0 now: the APU does not see this
  // (that port write was the LD's cycle.) The second SWAPD (5 words on)
  // waits for a hand-over; presented in that cycle, it lets it issue there.
  int cycles = kStartFetchCycles + 2, bank_stalls = 0;
  for (; cycles < 50 && top.apu2mpu_run_state == 1; ++cycles) {
    if (top.dbg_stall_reason == static_cast<int>(Stall::Bank)) {
      ++bank_stalls;
      EXPECT_EQ(top.dbg_pc, 5);
      top.mpu2apu_hand_over_data = 1;
      top.eval();
      EXPECT_TRUE(top.dbg_issue);
    }
    core.edge();
  }
  EXPECT_EQ(top.apu2mpu_run_state, 2);  // halted
  EXPECT_EQ(cycles, kStartFetchCycles + 7);  // the start's cycles, 7 words, no stall left
  EXPECT_EQ(bank_stalls, 1);
  EXPECT_EQ(top.apu2mpu_dsel, 0);
  EXPECT_EQ(core.read_data(8), 0x410000u);  // 2 * 2, stored in bank 1, handed back
  EXPECT_EQ(core.read_data(7), kTwo);
  EXPECT_FALSE(top.dbg_unit_mismatch);
}

TEST(ApuRtl, StallCauseSignalsNameTheSlotAndTheUnit) {
  // dbg_raw_* / dbg_waw_* say which slot of the stalled word waits and for
  // whose result: bit order of docs/apu-rtl.md ("Scoreboard").
  CorePorts core;
  Vapu_core& top = core.top;
  // 0 LIF F1  1 MUL F3  2 ADD F4 = F1 + F3: raw on A b (read port 3), the
  // multiplier's tag  3 SIN F5  4 ST F9 | MUL F5: the MUL would land with the
  // SIN (latency kMulLatency < kTrigLatency): waw on M d (destination 0), the
  // function unit's tag, until the MUL would land after the SIN; no raw.
  const auto prog = encode({lif(1, 0x3F00), mul(3, 1, 1), addu(AddOp::Add, 4, 1, 3), func(FuncOp::Sin, 5, 1),
                            mem(MemOp::St, 9, 0, 0) | mul(5, 1, 1), halt()});
  for (std::size_t i = 0; i < prog.size(); ++i) core.write_program(static_cast<std::uint16_t>(i), prog[i]);
  top.mpu2apu_hand_over_program = 1;
  core.edge();
  top.mpu2apu_start = top.mpu2apu_start_new_program = 1;
  top.mpu2apu_start_pc = 0;
  top.eval();
  std::vector<int> raw_src, raw_unit, waw_dst, waw_unit, stall;
  for (int c = 0; c < 24 && top.apu2mpu_run_state == static_cast<int>(RunState::Running); ++c) {
    stall.push_back(top.dbg_stall_reason);
    raw_src.push_back(top.dbg_raw_src);
    raw_unit.push_back(top.dbg_raw_unit);
    waw_dst.push_back(top.dbg_waw_dst);
    waw_unit.push_back(top.dbg_waw_unit);
    core.edge();
  }
  const int R = static_cast<int>(Stall::Raw), W = static_cast<int>(Stall::Waw), D = static_cast<int>(Stall::Drain);
  const int F = static_cast<int>(Stall::Fetch);
  // The start's cycles (kStartFetchCycles of `fetch`), then by the first
  // word's cycle: 0 LIF, 1 MUL, 2 raw, 3 ADD, 4 SIN (lands at 13), 5..11 waw
  // (the MUL would land at c + 2 <= 13), 12 ST|MUL, 13 drain, 14 HALT.
  const auto from_start = [](int start, std::vector<int> words) {
    words.insert(words.begin(), kStartFetchCycles, start);
    return words;
  };
  constexpr int kD = 1 << 0, kU = 1 << 2;
  EXPECT_EQ(stall, from_start(F, {0, 0, R, 0, 0, W, W, W, W, W, W, W, 0, D, 0}));
  EXPECT_EQ(raw_src, from_start(0, {0, 0, 1 << 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(raw_unit, from_start(0, {0, 0, 1 << 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(waw_dst, from_start(0, {0, 0, 0, 0, 0, kD, kD, kD, kD, kD, kD, kD, 0, 0, 0}));
  EXPECT_EQ(waw_unit, from_start(0, {0, 0, 0, 0, 0, kU, kU, kU, kU, kU, kU, kU, 0, 0, 0}));
  EXPECT_FALSE(top.dbg_unit_mismatch);
}

TEST(ApuRtl, WaveformHasTheDocumentedSignals) {
  const std::string path = testing::TempDir() + "apu_rtl_test.fst";
  {
    RtlEngine apu(path.c_str());
    EngineProgram r(apu, {lif(1, 0x3F00), func(FuncOp::Sin, 2, 1), func(FuncOp::Cos, 3, 1), mul(4, 2, 3), halt()});
    r.go();
    EXPECT_EQ(apu.state(), RunState::Halted);
    EXPECT_FALSE(apu.unit_mismatch());
  }
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  ASSERT_TRUE(f.good());
  EXPECT_GT(f.tellg(), 1000);
  std::remove(path.c_str());
}

// A benchmark (the suite name *Bench): not in the default run, but in
// `ctest -R apu_rtl_test_bench` (labels bench and long, tests/CMakeLists.txt).
TEST(ApuRtlBench, Throughput) {
  // A two-word loop keeping all three units and the D slot busy every cycle.
  RtlEngine apu;
  EngineProgram r(apu, {li(1, 1) | lif(1, 0x3F00), li(2, 40) | lif(2, 0x4000),
                        mul(3, 1, 2) | addu(AddOp::Add, 4, 1, 2) | func(FuncOp::Sqrt, 5, 2) |
                            mem(MemOp::St, 1, 2, 0) | ialu(IntOp::Addi, 1, 1, 0, 1),
                        mul(6, 1, 2) | addu(AddOp::Sub, 7, 1, 2) | func(FuncOp::Recip, 8, 2) |
                            mem(MemOp::Ld, 9, 2, 0) | seq(SeqOp::Jmp, 0, 2)});
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
  EXPECT_FALSE(apu.unit_mismatch());
}

}  // namespace
}  // namespace mc1::apu
