// ApuTlm (hw/apu_tlm): the APU behind a TLM-2.0 target socket, on the ISS
// and the RTL core. Exact timing of HALT against the driver's cycle count,
// the irq within a quantum, results against the FP24 model, and the
// responses to every kind of malformed access.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <memory>
#include <tlm_utils/simple_initiator_socket.h>

#include "apu_iss.hpp"
#include "apu_tlm.hpp"
#include "apuasm.hpp"
#include "fp24.hpp"
#include "mc1_engines.hpp"
#include "sc_test_harness.hpp"

namespace mc1::apu {
namespace {

using namespace sc_core;
namespace map = tlm_map;

// A test's MPU: `body` runs in a thread with word accesses on the socket.
struct Mpu : sc_module {
  tlm_utils::simple_initiator_socket<Mpu> mpu2apu{"mpu2apu"};
  std::function<void(Mpu&)> body;
  Mpu(sc_module_name n, std::function<void(Mpu&)> b) : sc_module(n), body(std::move(b)) {
    SC_HAS_PROCESS(Mpu);
    SC_THREAD(run);
  }
  void run() { body(*this); }

  tlm::tlm_response_status access(tlm::tlm_command cmd, std::uint64_t addr, std::uint32_t* words, unsigned n,
                                  unsigned char* byte_enables = nullptr) {
    tlm::tlm_generic_payload p;
    p.set_command(cmd);
    p.set_address(addr);
    p.set_data_ptr(reinterpret_cast<unsigned char*>(words));
    p.set_data_length(4 * n);
    p.set_streaming_width(4 * n);
    if (byte_enables) {
      p.set_byte_enable_ptr(byte_enables);
      p.set_byte_enable_length(4);
    }
    sc_time delay = SC_ZERO_TIME;
    mpu2apu->b_transport(p, delay);
    return p.get_response_status();
  }
  void write(std::uint64_t addr, std::uint32_t v) {
    ASSERT_EQ(access(tlm::TLM_WRITE_COMMAND, addr, &v, 1), tlm::TLM_OK_RESPONSE) << std::hex << addr;
  }
  std::uint32_t read(std::uint64_t addr) {
    std::uint32_t v = 0xDEADBEEF;
    EXPECT_EQ(access(tlm::TLM_READ_COMMAND, addr, &v, 1), tlm::TLM_OK_RESPONSE) << std::hex << addr;
    return v;
  }
  void load(const std::vector<Encoded>& words) {
    for (std::size_t i = 0; i < words.size(); ++i) {
      std::uint32_t piece[4] = {static_cast<std::uint32_t>(words[i].lo), static_cast<std::uint32_t>(words[i].lo >> 32),
                                static_cast<std::uint32_t>(words[i].hi), static_cast<std::uint32_t>(words[i].hi >> 32)};
      ASSERT_EQ(access(tlm::TLM_WRITE_COMMAND, map::kProgram + 16 * i, piece, 4), tlm::TLM_OK_RESPONSE);
    }
  }
  RunState state() { return static_cast<RunState>(read(map::kStatus) & map::kStatusStateMask); }
};

const char* kSquare = "lif f1, 3.0\nmul f2, f1, f1\nhalt\n";

// The cycles ApuDriver::run_until_done counts for `source` on a fresh ISS.
std::uint64_t driver_cycles(const std::string& source) {
  Iss iss;
  ApuDriver drv(iss);
  drv.load_program(apuasm::assemble(source).words);
  drv.hand_over_program();
  drv.start(0);
  return drv.run_until_done(1000);
}

class ApuTlmTest : public test::SystemCTest, public ::testing::WithParamInterface<EngineKind> {};

TEST_P(ApuTlmTest, HaltsInTheDriversCycleAndRaisesTheIrqWithinAQuantum) {
  const TimingParams t;
  const std::uint64_t n = driver_cycles(kSquare);
  ASSERT_GT(n, 2u);
  ApuTlm apu("apu", t, make_engine(GetParam()), sc_time(1, SC_US));
  sc_time irq_at = SC_ZERO_TIME;
  Mpu mpu("mpu", [&](Mpu& m) {
    m.load(apuasm::assemble(kSquare).words);
    m.write(map::kCtrl, map::kCtrlHandOverProgram | map::kCtrlStart);
    EXPECT_EQ(m.state(), RunState::Running);
    EXPECT_FALSE(apu.apu2mpu_irq.read());
    wait(t.apu_cycle_ps() * (n - 1), SC_PS);
    EXPECT_EQ(m.state(), RunState::Running) << "one cycle before HALT";
    wait(t.apu_cycle_ps(), SC_PS);
    EXPECT_EQ(m.state(), RunState::Halted);
    EXPECT_EQ(m.read(map::kHaltCycle), n);
    EXPECT_EQ(m.read(map::kFreg + 4 * 2), fp24::mul(0x408000, 0x408000).value);
    EXPECT_EQ(m.read(map::kStatus) >> map::kStatusFaultShift, 0u);
    wait(apu.halted());
    irq_at = sc_time_stamp();
    EXPECT_TRUE(apu.apu2mpu_irq.read());
    m.write(map::kCtrl, map::kCtrlIrqAck);
    wait(apu.apu2mpu_irq.negedge_event());
    EXPECT_EQ(sc_time_stamp(), irq_at) << "the ack lowers the irq at once";
  });
  mpu.mpu2apu.bind(apu.mpu2apu);
  mc1::sc_run(1, SC_MS);
  const double halt_us = n * t.apu_cycle_ps() * 1e-6;
  EXPECT_GE(irq_at.to_seconds() * 1e6, halt_us);
  EXPECT_LE(irq_at.to_seconds() * 1e6, halt_us + 1.0);
}

TEST_P(ApuTlmTest, StreamsABlockAndReturnsTheModelsResults) {
  const TimingParams t;
  ApuTlm apu("apu", t, make_engine(GetParam()));
  const std::vector<std::uint32_t> in = {0x3F0000, 0x408000, 0x7EFFFF, 0x7EFFFF, 0x810000, 0x3E0000};
  Mpu mpu("mpu", [&](Mpu& m) {
    m.load(apuasm::assemble(R"(
        swapd
        li a1, 0
        li a2, 3
loop:   ld f1, [a1+0]
        ld f2, [a1+1]
        add f3, f1, f2
        mul f4, f1, f2
        st f3, [a1+8]
        st f4, [a1+9]
        addi a1, a1, 2 | dbnz a2, loop
        swapd
        halt
)").words);
    std::vector<std::uint32_t> block = in;
    ASSERT_EQ(m.access(tlm::TLM_WRITE_COMMAND, map::kData, block.data(), 6), tlm::TLM_OK_RESPONSE);  // a burst
    m.write(map::kCtrl, map::kCtrlHandOverProgram | map::kCtrlHandOverData | map::kCtrlStart);
    EXPECT_NE(m.read(map::kStatus) & map::kStatusDataReady, 0u);
    while (m.read(map::kStatus) & map::kStatusDataReady) wait(1, SC_US);
    m.write(map::kCtrl, map::kCtrlHandOverData);
    wait(apu.halted());
    std::uint32_t out[6] = {};
    ASSERT_EQ(m.access(tlm::TLM_READ_COMMAND, map::kData + 4 * 8, out, 6), tlm::TLM_OK_RESPONSE);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(out[2 * i], fp24::add(in[2 * i], in[2 * i + 1]).value) << i;
      EXPECT_EQ(out[2 * i + 1], fp24::mul(in[2 * i], in[2 * i + 1]).value) << i;
    }
    EXPECT_EQ(m.read(map::kAreg + 4 * 1), 6u);
  });
  mpu.mpu2apu.bind(apu.mpu2apu);
  mc1::sc_run(1, SC_MS);
  EXPECT_EQ(apu.engine().state(), RunState::Halted);
}

TEST_P(ApuTlmTest, RefusesMalformedAccesses) {
  const TimingParams t;
  ApuTlm apu("apu", t, make_engine(GetParam()));
  Mpu mpu("mpu", [&](Mpu& m) {
    std::uint32_t v = 0;
    EXPECT_EQ(m.access(tlm::TLM_READ_COMMAND, map::kProgram, &v, 1), tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(m.access(tlm::TLM_WRITE_COMMAND, map::kStatus, &v, 1), tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(m.access(tlm::TLM_WRITE_COMMAND, map::kFreg, &v, 1), tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(m.access(tlm::TLM_READ_COMMAND, map::kSize, &v, 1), tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(m.access(tlm::TLM_READ_COMMAND, map::kData + 4 * kDataWords, &v, 1), tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(m.access(tlm::TLM_READ_COMMAND, map::kData + 2, &v, 1), tlm::TLM_BURST_ERROR_RESPONSE);
    unsigned char be[4] = {0xFF, 0, 0, 0};
    EXPECT_EQ(m.access(tlm::TLM_READ_COMMAND, map::kData, &v, 1, be), tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
    v = kProgramWords;
    EXPECT_EQ(m.access(tlm::TLM_WRITE_COMMAND, map::kStartPc, &v, 1), tlm::TLM_ADDRESS_ERROR_RESPONSE);
    m.load(apuasm::assemble("loop: jmp loop\n").words);
    m.write(map::kCtrl, map::kCtrlHandOverProgram | map::kCtrlStart);
    v = map::kCtrlStart;
    EXPECT_EQ(m.access(tlm::TLM_WRITE_COMMAND, map::kCtrl, &v, 1), tlm::TLM_ADDRESS_ERROR_RESPONSE) << "running";
    wait(10, SC_US);
    EXPECT_EQ(m.state(), RunState::Running);
    EXPECT_EQ(m.read(map::kCycleLo), 40u);  // 10 us at 4 MHz
    EXPECT_EQ(m.read(map::kCycleHi), 0u);
    // A word whose 32-bit data is wider than 24 bits keeps its low 24 (docs/apu-isa.md 9).
    m.write(map::kData + 4 * 5, 0xFF123456);
    EXPECT_EQ(m.read(map::kData + 4 * 5), 0x123456u);
  });
  mpu.mpu2apu.bind(apu.mpu2apu);
  mc1::sc_run(20, SC_US);
}

// Benches hold several RTL engines (an ApuTlm and NCs): destroyed newest
// first, the older one's scopes once went to the newer's freed Verilator
// context (a hang at the end of examples/apu_tb.cpp).
TEST(RtlEngineLifetime, SeveralEnginesAreDestroyedInAnyOrder) {
  for (bool newest_first : {true, false}) {
    auto older = make_engine(EngineKind::Rtl);
    auto newer = make_engine(EngineKind::Rtl);
    older->write_data(3, 0x3F0000);
    newer->write_data(3, 0x400000);
    (newest_first ? newer : older).reset();
    auto& kept = newest_first ? older : newer;
    EXPECT_EQ(kept->read_data(3), newest_first ? 0x3F0000u : 0x400000u);
    kept.reset();
  }
}

INSTANTIATE_TEST_SUITE_P(Engines, ApuTlmTest, ::testing::Values(EngineKind::Iss, EngineKind::Rtl),
                         [](const auto& info) { return std::string(engine_name(info.param)); });

}  // namespace
}  // namespace mc1::apu

MC1_SYSTEMC_GTEST_MAIN()
