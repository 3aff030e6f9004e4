// The verilated APU core (apu_rtl/apu_core.sv) behind the ApuEngine
// interface, so that the same programs, tests and lockstep co-simulation run
// on the RTL as on the ISS (docs/apu-rtl.md).
//
// step() clocks one cycle: it reads the core's debug ports (what the cycle
// issues, stalls on and commits) before the rising edge, then clocks. MPU
// calls act at once, as on the ISS: hand-over and start are core inputs that
// the core forwards into the next cycle; bank reads and writes go straight
// into the memory arrays of the bank the APU does not use, through the
// backdoor (apu_rtl_backdoor.hpp; a write there cannot be seen by the APU
// before a swap, so writing it between two clock edges is exact).
//
// Two verilated models of the same RTL (hw/apu_rtl_engine/CMakeLists.txt): with a
// waveform path, Vapu_core, traced, every port of the core; without,
// Vapu_fast (hw/apu_rtl_engine/apu_fast.sv), untraced and without the ports only
// waveforms read, about a quarter less host time per cycle (docs/platform.md
// "Rendering benchmark"). The engine's code is one template over the two
// (apu_rtl_engine.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "apu_driver.hpp"
#include "apu_engine.hpp"
#include "apu_rtl_backdoor.hpp"

namespace mc1::apu {

// An assertion of the RTL (`APU_ASSERT, apu_rtl/apu_assert.svh; docs/apu-rtl.md
// "Assertions") failed at the rising edge ending `cycle()`, the word at
// `pc()` in I. Verilator has printed the rule's name and instance on
// standard output ("%Error: ...: Assertion failed in TOP...: APU_ASSERT
// <Name> failed in ..."); what() says the cycle and the pc. The model is not
// clocked further. An ApuError of kind Assertion, so that a run fails as a
// failed simulation (exit 1), as on a fault.
class RtlAssertionError : public ApuError {
 public:
  RtlAssertionError(std::uint64_t cycle, std::uint16_t pc, const std::string& what)
      : ApuError(Kind::Assertion, Fault::None, cycle, pc, what) {}
};

// Throws RtlAssertionError for (cycle, pc) if an assertion failed in ctx
// (gotError) since it was made: RtlEngine's check after every rising edge,
// for a model whose context does not abort on $error (fatalOnError(false)).
void check_rtl_assertions(const VerilatedContext& ctx, std::uint64_t cycle, std::uint16_t pc);

class RtlEngine final : public ApuEngine {
 public:
  // With a path, every cycle goes to an FST waveform (docs/apu-core.gtkw).
  explicit RtlEngine(const char* fst_path = nullptr);
  ~RtlEngine() override;
  RtlEngine(const RtlEngine&) = delete;
  RtlEngine& operator=(const RtlEngine&) = delete;

  void write_program(std::uint16_t addr, const Encoded& word) override;
  void write_data(std::uint16_t addr, std::uint32_t value) override;
  std::uint32_t read_data(std::uint16_t addr) const override;
  void write_data_block(std::uint16_t addr, const std::uint32_t* values, std::size_t n) override;
  void read_data_block(std::uint16_t addr, std::uint32_t* out, std::size_t n) const override;
  // True without a waveform (Vapu_fast): the MPU's data-bank calls may run
  // while another thread clocks the model (apu_rtl_engine.cpp, note_banks).
  bool mpu_bank_while_running() const override;
  void hand_over_program() override;
  void hand_over_data() override;
  bool program_ready() const override;
  bool data_ready() const override;
  void start(std::uint16_t pc) override;

  void step(CycleRecord& rec) override;

  RunState state() const override;
  Fault fault() const override;
  std::uint64_t cycle() const override;
  std::uint32_t freg(int i) const override;
  std::uint16_t areg(int i) const override;
  std::uint8_t flags() const override;
  std::uint8_t cc() const override;
  const ApuCounters& counters() const override;

  // Clocks without records until the APU stops running or max_cycles have
  // passed; returns the cycles clocked (the fast path, as Iss::run).
  std::uint64_t run(std::uint64_t max_cycles) override;
  // As run(), and it stops after the cycle in which the APU takes the data
  // bank the MPU handed over (apu2mpu_data_ready falls), in one call.
  std::uint64_t run_until_data_taken(std::uint64_t max_cycles) override;

  // Dumps only simulated times in [from_ps, to_ps) (mc1 render --trace-from/--trace-to).
  void trace_window(std::uint64_t from_ps, std::uint64_t to_ps) override;
  // Bank `bank` holds kernel `id`: input of the trace module
  // (hw/apu_rtl_engine/apu_trace_top.sv), whose TOP.mc1.kernel_id is the id of the
  // bank the core runs from and TOP.mc1.kpc the pair (kernel_id, pc); 0
  // until one is named.
  void trace_kernel(int bank, std::uint16_t id) override;
  // The MPU's side (TOP.mc1.mpu_*, apu_trace_top.sv): asked before each
  // traced cycle for the MPU's state at its start.
  void trace_mpu(std::function<MpuTraceInputs(std::uint64_t ps)> source) override;

  // True if a unit's out_valid / out_trig_valid ever disagreed with the core's
  // interlock mirror of the pipelines (a unit latency other than the doc's).
  bool unit_mismatch() const;

 private:
  class Model;  // the engine on one verilated model (apu_rtl_engine.cpp)
  template <class Top, bool kTraced>
  class ModelOf;
  std::unique_ptr<Model> model_;
};

}  // namespace mc1::apu
