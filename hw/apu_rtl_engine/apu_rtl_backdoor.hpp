// The RTL engine's backdoor into the verilated apu_core: the one file that
// names Verilator's internal signals (the root members for the memories and
// register files, marked public in apu_rtl/). RtlEngine fills and reads the
// MPU's banks through it (exact between two clock edges: apu_rtl_engine.hpp)
// and reads the register arrays for the ISA's observers.
//
// Two models are verilated from apu_rtl/ (hw/apu_rtl_engine/CMakeLists.txt): Vapu_core,
// traced, with every port of the core, and Vapu_fast, untraced, the core
// inside hw/apu_rtl_engine/apu_fast.sv without the stall-cause ports (the engine's
// model when it writes no waveform). The backdoor is one template over the
// two; RtlBackdoor is the traced model's.
//
// When an RTL instance or array is renamed, only apu_rtl_backdoor.cpp stops
// compiling, and tests/apu_rtl_backdoor_test.cpp checks every accessor
// against the core's own ports, naming the signal (signal_name) that
// disagrees. docs/apu-rtl.md "RtlEngine" lists the signals.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "microword.hpp"

class Vapu_core;
class Vapu_fast;
class Vapu_fast_func;
class VerilatedContext;

namespace mc1::apu {

// Top: Vapu_core or Vapu_fast (instantiated for these two only).
template <class Top>
class BasicRtlBackdoor {
 public:
  // Every internal signal the backdoor reads or writes.
  enum class Signal { ProgramBank0, ProgramBank1, DataBank0, DataBank1, FRegs, ARegs };
  static constexpr Signal kSignals[] = {Signal::ProgramBank0, Signal::ProgramBank1, Signal::DataBank0,
                                        Signal::DataBank1,    Signal::FRegs,        Signal::ARegs};
  // Its hierarchical name in the RTL, e.g. "apu_core.u_pmem.bank0".
  static const char* signal_name(Signal s);
  static Signal program_bank(int bank) { return bank & 1 ? Signal::ProgramBank1 : Signal::ProgramBank0; }
  static Signal data_bank(int bank) { return bank & 1 ? Signal::DataBank1 : Signal::DataBank0; }

  explicit BasicRtlBackdoor(Top& top);

  // A program or data bank by number (0, 1), whoever owns it now.
  void write_program(int bank, std::uint16_t addr, const Encoded& word);
  Encoded read_program(int bank, std::uint16_t addr) const;
  void write_data(int bank, std::uint16_t addr, std::uint32_t value);
  std::uint32_t read_data(int bank, std::uint16_t addr) const;
  // The register files' arrays as the last clock edge left them (no bypass).
  std::uint32_t freg_array(int i) const;
  std::uint16_t areg_array(int i) const;

  // The two clock edges without eval(), for when no input and no bank word
  // has changed since the last eval() (RtlEngine::clock). Verilator 5's
  // eval() first recomputes the logic that depends on the inputs (its `ico`
  // region; the same values again here), then, on a rising edge of clk
  // against the clk of the eval() before, runs the `nba` region: the
  // flip-flops, then the logic that depends on them. So a rising edge is the
  // nba region alone, and a falling edge only notes clk = 0.
  void rising_edge_unchanged();
  void clock_low_unchanged();

  // Every bit of the model's state except the four bank memories, which only
  // a store that issues or an MPU write changes (the fast path's fixed-point
  // test, RtlEngine::run).
  using Snapshot = std::vector<unsigned char>;
  void snapshot(Snapshot& s) const;
  bool same_state(const Snapshot& s) const;

 private:
  Top& top_;
  std::vector<std::pair<const unsigned char*, std::size_t>> state_;  // the root's bytes but the banks
};

using RtlBackdoor = BasicRtlBackdoor<Vapu_core>;
using RtlFastBackdoor = BasicRtlBackdoor<Vapu_fast>;

// Vapu_fast's function unit: fp24_func verilated on its own
// (Vapu_fast_func), clocked in the place of the stand-in that Vapu_fast has
// for it (hw/apu_rtl_engine/fast/fp24_func.sv) only while it has work: from a cycle
// that issues to it until its last op has left the pipes. Idle, the unit's
// registers hold (every stage loads only with its valid bit), and so do its
// outputs: a clock of an idle unit changes nothing.
class RtlFastFunc {
 public:
  // The unit in the model's context, reset (as the core's synchronous
  // reset does), its outputs on the stand-in's next_* inputs.
  RtlFastFunc(Vapu_fast& top, VerilatedContext* ctx);
  ~RtlFastFunc();
  RtlFastFunc(const RtlFastFunc&) = delete;
  RtlFastFunc& operator=(const RtlFastFunc&) = delete;

  // Before each rising edge of Vapu_fast, on the values the core presents
  // (its last eval()): with work, the unit clocked with this cycle's op and
  // its outputs after the edge on the stand-in's next_*, which the core's
  // edge puts on its ports.
  void before_rising_edge();
  // No op in the unit's pipes: a clock would change nothing.
  bool idle() const { return clocks_ == 0; }

 private:
  void outputs_to_stand_in();

  Vapu_fast& top_;
  std::unique_ptr<Vapu_fast_func> unit_;
  int clocks_ = 0;  // clocks the unit still needs for the ops in its pipes
};

}  // namespace mc1::apu
