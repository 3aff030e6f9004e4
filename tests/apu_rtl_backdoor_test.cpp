// The RTL engine's backdoor (hw/apu_rtl_engine/apu_rtl_backdoor.hpp) against the core's
// own ports: every internal signal it names is written or read through the
// backdoor and checked through the normal path (the MPU ports, a program
// run), so a renamed or re-shaped RTL instance fails here, naming the signal.
#include <gtest/gtest.h>

#include <cstdint>

#include "apu_core_ports.hpp"
#include "apu_rtl_backdoor.hpp"

namespace mc1::apu {
namespace {

using Signal = RtlBackdoor::Signal;

MicroWord halt() {
  MicroWord w;
  w.s.op = SeqOp::Halt;
  return w;
}

MicroWord int_op(IntOp op, std::uint8_t d, std::uint16_t imm) {
  MicroWord w;
  w.i = {op, d, 0, 0, imm};
  return w;
}

// The core through its ports, and the backdoor beside it.
struct Core : CorePorts {
  RtlBackdoor backdoor{top};
};

TEST(ApuRtlBackdoor, EverySignalHasAName) {
  for (Signal s : RtlBackdoor::kSignals) EXPECT_STRNE(RtlBackdoor::signal_name(s), "?");
  EXPECT_STREQ(RtlBackdoor::signal_name(RtlBackdoor::program_bank(0)), "apu_core.u_pmem.bank0");
  EXPECT_STREQ(RtlBackdoor::signal_name(RtlBackdoor::data_bank(1)), "apu_core.u_dmem.bank1");
}

TEST(ApuRtlBackdoor, ProgramBanksMatchTheMpuPortAndTheFetch) {
  Core core;
  // Bank 1 is the MPU's after reset, bank 0 after the first start.
  for (const int bank : {1, 0}) {
    ASSERT_EQ(core.mpu_program_bank(), bank);
    const char* name = RtlBackdoor::signal_name(RtlBackdoor::program_bank(bank));
    // Port write, backdoor read.
    const Encoded marker = int_op(IntOp::Li, 5, static_cast<std::uint16_t>(0x1230 + bank)).encode();
    core.write_program(700, marker);
    EXPECT_EQ(core.backdoor.read_program(bank, 700), marker) << name << ": the MPU port's word is not there";
    // Backdoor writes, fetched by the sequencer: JMP 679 at 40, HALT at 679.
    // (Had they missed the bank, the run would go through empty words.)
    MicroWord jmp;
    jmp.s = {SeqOp::Jmp, 0, 679};
    core.backdoor.write_program(bank, 40, jmp.encode());
    core.backdoor.write_program(bank, 679, halt().encode());
    // the start's fetch and decode, JMP, HALT
    EXPECT_EQ(core.run_handed_over(40, false), kStartFetchCycles + 2) << name << ": the backdoor's words did not run";
    EXPECT_EQ(core.top.apu2mpu_run_state, static_cast<int>(RunState::Halted)) << name;
    EXPECT_EQ(core.top.dbg_pc, 679) << name;
  }
}

TEST(ApuRtlBackdoor, DataBanksMatchTheMpuPort) {
  Core core;
  // A program that hands the data banks over: SWAPD | HALT.
  MicroWord swap = halt();
  swap.s.op = SeqOp::Swapd;
  core.write_program(0, swap.encode());
  core.write_program(1, halt().encode());
  for (const int bank : {1, 0}) {
    ASSERT_EQ(core.mpu_data_bank(), bank);
    const char* name = RtlBackdoor::signal_name(RtlBackdoor::data_bank(bank));
    const std::uint32_t a = 0x345600 + bank, b = 0xabcd00 + bank;
    core.write_data(4095, a);
    EXPECT_EQ(core.backdoor.read_data(bank, 4095), a) << name << ": the MPU port's word is not there";
    core.backdoor.write_data(bank, 17, b);
    EXPECT_EQ(core.read_data(17), b) << name << ": the MPU port does not read the backdoor's word";
    core.backdoor.write_data(bank, 18, 0xff123456);
    EXPECT_EQ(core.read_data(18), 0x123456u) << name << ": a data word is 24 bits";
    // Swap the data banks (the program bank too: the next run starts in the
    // other one, so the program is written there first).
    core.run_handed_over(0, true);
    core.write_program(0, swap.encode());
    core.write_program(1, halt().encode());
  }
}

TEST(ApuRtlBackdoor, RegisterArraysHoldWhatTheProgramWrote) {
  Core core;
  // LIF f1 | LIF f62 | LI a1 | LI a15 | HALT: the first and last of each file.
  const MicroWord words[] = {int_op(IntOp::Lif, 1, 0x3fc0), int_op(IntOp::Lif, 62, 0xc123),
                             int_op(IntOp::Li, 1, 0x0101), int_op(IntOp::Li, 15, 0xfedc), halt()};
  for (std::uint16_t i = 0; i < 5; ++i) core.write_program(i, words[i].encode());
  EXPECT_EQ(core.run_handed_over(0, false), kStartFetchCycles + 5);  // the start's cycles, 5 words
  const char* f = RtlBackdoor::signal_name(Signal::FRegs);
  const char* a = RtlBackdoor::signal_name(Signal::ARegs);
  EXPECT_EQ(core.backdoor.freg_array(1), 0x3fc000u) << f;
  EXPECT_EQ(core.backdoor.freg_array(62), 0xc12300u) << f;
  EXPECT_EQ(core.backdoor.freg_array(0), 0u) << f;
  EXPECT_EQ(core.backdoor.freg_array(63), 0u) << f;
  EXPECT_EQ(core.backdoor.areg_array(1), 0x0101) << a;
  EXPECT_EQ(core.backdoor.areg_array(15), 0xfedc) << a;
  EXPECT_EQ(core.backdoor.areg_array(14), 0) << a;
}

}  // namespace
}  // namespace mc1::apu
