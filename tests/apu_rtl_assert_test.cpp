// The RTL's assertions fire (docs/apu-rtl.md "Assertions"): a rule broken on
// purpose in the verilated core (a fault code set by hand while the APU
// runs) makes Verilator print the rule's name, and RtlEngine's check after
// the edge fails with the cycle and the pc. Every other test runs with the
// assertions on and none firing.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "Vapu_core.h"
#include "Vapu_core___024root.h"
#include "apu_rtl_engine.hpp"
#include "apu_test_program.hpp"
#include "verilated.h"
#include "verilated_context.hpp"

namespace mc1::apu {
namespace {

using namespace apu_test;

// The core on its own ports, in a context that does not abort on $error.
struct Core {
  std::unique_ptr<VerilatedContext> ctx = mc1::rtl::new_context();
  Vapu_core top{ctx.get()};

  Core() {
    ctx->fatalOnError(false);
    Verilated::threadContextp(ctx.get());
    top.rst_n = 0;
    edge();
    top.rst_n = 1;
    top.eval();
  }
  ~Core() { top.final(); }

  void edge() {
    top.clk = 1;
    top.eval();
    top.mpu2apu_pmem_we = 0;
    top.mpu2apu_hand_over_program = top.mpu2apu_start = top.mpu2apu_start_new_program = 0;
    top.clk = 0;
    top.eval();
  }
  void write_program(std::uint16_t addr, const Encoded& e) {
    top.mpu2apu_pmem_we = 1;
    top.mpu2apu_pmem_addr = addr;
    top.mpu2apu_pmem_wdata[0] = static_cast<std::uint32_t>(e.lo);
    top.mpu2apu_pmem_wdata[1] = static_cast<std::uint32_t>(e.lo >> 32);
    top.mpu2apu_pmem_wdata[2] = static_cast<std::uint32_t>(e.hi);
    top.mpu2apu_pmem_wdata[3] = static_cast<std::uint32_t>(e.hi >> 32);
    edge();
  }
};

TEST(ApuRtlAssert, ABrokenRuleFailsWithItsNameCycleAndPc) {
  Core core;
  Vapu_core& t = core.top;
  const auto prog = encode({li(1, 5), mul(2, 1, 1), nop(), nop(), nop(), nop(), halt()});
  for (std::size_t i = 0; i < prog.size(); ++i) core.write_program(static_cast<std::uint16_t>(i), prog[i]);
  t.mpu2apu_hand_over_program = 1;
  core.edge();
  t.mpu2apu_start = t.mpu2apu_start_new_program = 1;
  t.mpu2apu_start_pc = 0;
  t.eval();

  // Clocked as RtlEngine clocks: the cycle's pc before its edge, the check
  // after it. Nothing fires on the program as it is.
  std::uint64_t cycle = 0;
  for (; cycle < 4; ++cycle) {
    const std::uint16_t pc = t.dbg_pc;
    core.edge();
    ASSERT_NO_THROW(check_rtl_assertions(*core.ctx, cycle, pc)) << "cycle " << cycle;
  }
  // A fault code while the APU runs: FaultIffFaulted breaks at the next
  // rising edge.
  t.rootp->apu_core__DOT__fault_q = 2;
  const std::uint16_t pc = t.dbg_pc;
  testing::internal::CaptureStdout();
  core.edge();
  const std::string printed = testing::internal::GetCapturedStdout();
  EXPECT_NE(printed.find("APU_ASSERT FaultIffFaulted failed in TOP.apu_core"), std::string::npos)
      << printed;
  try {
    check_rtl_assertions(*core.ctx, cycle, pc);
    FAIL() << "no RtlAssertionError";
  } catch (const RtlAssertionError& e) {
    EXPECT_EQ(e.cycle(), 4u);
    EXPECT_EQ(e.pc(), pc);
    char want[64];
    std::snprintf(want, sizeof want, "RTL assertion failed at cycle 4, pc 0x%03x", pc);
    const std::string what = e.what();
    EXPECT_NE(what.find(want), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace mc1::apu
