// The APU as a SystemC module for a user's own test bench (docs/library.md):
// the MPU's view of it, its banks, control and status, behind one TLM-2.0
// target socket, on either engine (the ISS, apu::Iss, or the verilated RTL
// core through the factory mc1::make_engine of host/mc1/mc1_engines.hpp).
//
// Loosely timed, as the NC runs its APU (hw/nc/node_computer.hpp): the
// engine is clocked in bulk at the APU clock of the timing table, never by a
// SystemC event per cycle. Every transaction first clocks the APU up to the
// transaction's time (sc_time_stamp() + delay), then acts; so a poll of
// STATUS sees what the MPU would see at that time, and a bank written then is
// the one the APU is not using. A transaction dated before the APU's own time
// (an initiator behind by its quantum) acts at the APU's time: the APU cannot
// be un-run. While the APU runs, a thread also clocks it every `quantum`;
// the first of the two to find the stop raises apu2mpu_irq and notifies
// halted(), so both come within one quantum of the stop; the cycle it
// stopped in is exact (HALT_CYCLE).
//
// After HALT (or a fault) the APU is clocked ApuDriver::kSettleCycles more,
// so that results of the HALT word's own ops land (docs/apu-isa.md,
// Clarification 7), as ApuDriver::run_until_done and the NC do.
#pragma once

#include <cstdint>
#include <memory>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_target_socket.h>

#include "apu_driver.hpp"
#include "apu_engine.hpp"
#include "timing_params.hpp"

namespace mc1::apu {

// Byte addresses of the target socket. Every access is whole 32-bit words,
// little endian, 4-aligned; a burst (length a multiple of 4) walks the words.
namespace tlm_map {
constexpr std::uint64_t kData = 0x00000;     // R/W: the MPU's data bank, kDataWords words, FP24 in bits 23..0
constexpr std::uint64_t kProgram = 0x10000;  // W: the MPU's program bank, 16 bytes a microword: lo, hi
                                             // (u64 LE each); the word is written with its last 4 bytes
constexpr std::uint64_t kCtrl = 0x20000;     // W: kCtrl* bits, acted on from bit 0 up
constexpr std::uint64_t kStartPc = 0x20004;  // R/W: the pc kCtrlStart starts at
constexpr std::uint64_t kStatus = 0x20008;   // R: kStatus* fields
constexpr std::uint64_t kCycleLo = 0x2000C;  // R: engine cycles clocked, bits 31..0
constexpr std::uint64_t kCycleHi = 0x20010;  // R: bits 63..32
constexpr std::uint64_t kHaltCycle = 0x20014;  // R: the engine cycle after the last stop (low 32 bits)
constexpr std::uint64_t kFlags = 0x20018;    // R: the FLAGS register
constexpr std::uint64_t kCc = 0x2001C;       // R: the condition code
constexpr std::uint64_t kFreg = 0x20100;     // R: F0 .. F(kNumFRegs-1)
constexpr std::uint64_t kAreg = 0x20200;     // R: A0 .. A(kNumARegs-1), in bits 15..0
constexpr std::uint64_t kSize = 0x20240;     // the window the socket decodes

constexpr std::uint32_t kCtrlHandOverProgram = 1u << 0;
constexpr std::uint32_t kCtrlHandOverData = 1u << 1;
constexpr std::uint32_t kCtrlStart = 1u << 2;  // refused (TLM_GENERIC_ERROR_RESPONSE) while running
constexpr std::uint32_t kCtrlIrqAck = 1u << 3;  // lowers apu2mpu_irq

// STATUS: bits 1..0 RunState, bit 2 program_ready, bit 3 data_ready, bits 15..8 Fault.
constexpr std::uint32_t kStatusStateMask = 0x3;
constexpr std::uint32_t kStatusProgramReady = 1u << 2;
constexpr std::uint32_t kStatusDataReady = 1u << 3;
constexpr int kStatusFaultShift = 8;
}  // namespace tlm_map

class ApuTlm : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<ApuTlm> mpu2apu;
  // High from the APU's stop (HALT or fault) until kCtrlIrqAck or the next start.
  sc_core::sc_signal<bool> apu2mpu_irq;

  ApuTlm(sc_core::sc_module_name name, const TimingParams& t, std::unique_ptr<ApuEngine> engine,
         const sc_core::sc_time& quantum = sc_core::sc_time(1, sc_core::SC_US));

  const sc_core::sc_event& halted() const { return halted_; }
  ApuEngine& engine() { return *engine_; }
  // The driver the module runs the engine through (an observer set on it sees
  // every cycle, e.g. for an apu::Profile).
  ApuDriver& driver() { return driver_; }

 private:
  void b_transport(tlm::tlm_generic_payload& p, sc_core::sc_time& delay);
  unsigned transport_dbg(tlm::tlm_generic_payload& p);
  // One word at byte address `addr`; false: the address or command is refused.
  bool access(bool write, std::uint64_t addr, std::uint32_t& value);
  bool write_ctrl(std::uint32_t value);
  std::uint32_t status() const;
  void catch_up(Picos t);  // clock the APU up to simulated time t
  void watch();            // SC_THREAD: the stop, within a quantum
  // apu2mpu_irq has one driver, drive_irq (an SC_METHOD); the accesses and
  // the watch set the level it drives.
  void set_irq(bool level);
  void drive_irq();

  std::unique_ptr<ApuEngine> engine_;
  ApuDriver driver_;
  Picos cycle_ps_;
  sc_core::sc_time quantum_;
  Picos apu_time_ = 0;  // the APU is clocked up to here
  std::uint16_t start_pc_ = 0;
  std::uint64_t halt_cycle_ = 0;
  Encoded pending_;        // the microword being written, piece by piece
  std::uint16_t pending_addr_ = 0;
  bool irq_level_ = false;
  sc_core::sc_event started_, halted_, irq_changed_;
};

}  // namespace mc1::apu
