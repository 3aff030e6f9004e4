// The APU core under Icarus Verilog behind ApuEngine (docs/apu-rtl.md
// "Second simulator"): a vvp child process running the bench
// tb/apu/apu_icarus_lockstep_tb.sv, driven over pipes, so that apu-cosim,
// apu-run and the tests run it as they run the ISS and the verilated core
// (apu-cosim --engines iss,icarus: every cycle compared).
//
// The vvp file is the bench compiled by iverilog with an apu_core: the RTL
// (the build's apu_icarus_core.vvp, target apu_icarus_vvp) or any other
// module of apu_core's name and ports, e.g. a flattened Yosys netlist
// (iverilog ... -DAPU_NETLIST; see the docs for the command line). Which
// file: IcarusEngine::Options::vvp_file, else $MC1_ICARUS_VVP, else the
// build's.
//
// MPU calls without a result (program and data words, hand-over, start) are
// queued on the bench's input and sent with the next call that needs an
// answer; step() is one round trip: the bench prints the cycle's debug
// ports, clocks, and prints the state after the edge. Bank and register
// reads are answered from a copy fetched once (4096 words in one line) and
// kept until the next call that may change them.
//
// A bench whose engine ends healthy is reset and kept for the next engine
// on the same file (a vvp start costs ~100 cycles; MC1_ICARUS_FRESH=1: not).
//
// A failure is an IcarusError naming what and where: the vvp file or the
// vvp program missing, the bench ending (its exit status and last lines),
// an X on a port the cycle uses, dbg_unit_mismatch set, or a line of the
// simulation's own output that says ERROR or ASSERT (an assertion of the
// RTL: its text, the cycle and the pc).
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "apu_engine.hpp"

namespace mc1::apu {

// What failed, and where when it happened in a cycle: the cycle and the pc
// (and program bank) of the word in I then, for a report with the word's
// disassembly (apu-cosim).
class IcarusError : public std::runtime_error {
 public:
  explicit IcarusError(const std::string& what) : std::runtime_error(what) {}
  IcarusError(const std::string& what, std::uint64_t at_cycle, std::uint16_t at_pc, std::uint8_t at_psel)
      : std::runtime_error(what), in_cycle(true), cycle(at_cycle), pc(at_pc), psel(at_psel) {}
  bool in_cycle = false;
  std::uint64_t cycle = 0;
  std::uint16_t pc = 0;
  std::uint8_t psel = 0;
};

class IcarusEngine final : public ApuEngine {
 public:
  struct Options {
    std::string vvp_file;  // empty: default_vvp_file()
    std::string vvp;       // the vvp program; empty: the one the build found, else "vvp" on PATH
  };
  // $MC1_ICARUS_VVP if set, else the vvp file the build makes (empty if the
  // build found no iverilog).
  static std::string default_vvp_file();

  IcarusEngine() : IcarusEngine(Options{}) {}
  explicit IcarusEngine(const Options& o);
  ~IcarusEngine() override;
  IcarusEngine(const IcarusEngine&) = delete;
  IcarusEngine& operator=(const IcarusEngine&) = delete;

  void write_program(std::uint16_t addr, const Encoded& word) override;
  void write_data(std::uint16_t addr, std::uint32_t value) override;
  std::uint32_t read_data(std::uint16_t addr) const override;
  void read_data_block(std::uint16_t addr, std::uint32_t* out, std::size_t n) const override;
  void hand_over_program() override;
  void hand_over_data() override;
  bool program_ready() const override;
  bool data_ready() const override;
  void start(std::uint16_t pc) override;

  void step(CycleRecord& rec) override;
  std::uint64_t run(std::uint64_t max_cycles) override;
  std::uint64_t run_until_data_taken(std::uint64_t max_cycles) override;

  RunState state() const override;
  Fault fault() const override;
  std::uint64_t cycle() const override;
  std::uint32_t freg(int i) const override;
  std::uint16_t areg(int i) const override;
  std::uint8_t flags() const override;
  std::uint8_t cc() const override;
  const ApuCounters& counters() const override;

  // The bench's dbg_unit_mismatch (as RtlEngine::unit_mismatch).
  bool unit_mismatch() const;
  // The vvp file this engine runs.
  const std::string& vvp_file() const;

 private:
  std::uint64_t run_bursts(char op, std::uint64_t max_cycles);  // run() and run_until_data_taken()
  class Impl;  // the vvp child, its pipes and what the engine knows of it (apu_icarus_engine.cpp)
  std::unique_ptr<Impl> impl_;
};

}  // namespace mc1::apu
