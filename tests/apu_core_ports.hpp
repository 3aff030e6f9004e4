// The verilated apu_core driven through its own ports only (no RtlEngine):
// reset, clock edges that drop the one-cycle MPU requests, the MPU's bank
// ports, hand-over and start. For port-level tests of the core.
#pragma once

#include <cstdint>
#include <memory>

#include "Vapu_core.h"
#include "apu_engine.hpp"
#include "verilated.h"
#include "verilated_context.hpp"

namespace mc1::apu {

class CorePorts {
 public:
  CorePorts() : top(ctx_.get()) {
    top.rst_n = 0;
    edge();
    top.rst_n = 1;
    top.eval();
  }
  ~CorePorts() { top.final(); }
  CorePorts(const CorePorts&) = delete;
  CorePorts& operator=(const CorePorts&) = delete;

  // One rising edge; the MPU's write enables and requests last one cycle.
  void edge() {
    top.clk = 1;
    top.eval();
    top.mpu2apu_pmem_we = top.mpu2apu_dmem_we = 0;
    top.mpu2apu_hand_over_program = top.mpu2apu_hand_over_data = 0;
    top.mpu2apu_start = top.mpu2apu_start_new_program = 0;
    top.clk = 0;
    top.eval();
  }

  // The banks the MPU owns now.
  int mpu_program_bank() const { return top.apu2mpu_psel ^ 1; }
  int mpu_data_bank() const { return top.apu2mpu_dsel ^ 1; }

  void write_program(std::uint16_t addr, const Encoded& e) {
    top.mpu2apu_pmem_we = 1;
    top.mpu2apu_pmem_addr = addr;
    top.mpu2apu_pmem_wdata[0] = static_cast<std::uint32_t>(e.lo);
    top.mpu2apu_pmem_wdata[1] = static_cast<std::uint32_t>(e.lo >> 32);
    top.mpu2apu_pmem_wdata[2] = static_cast<std::uint32_t>(e.hi);
    top.mpu2apu_pmem_wdata[3] = static_cast<std::uint32_t>(e.hi >> 32);
    edge();
  }
  void write_data(std::uint16_t addr, std::uint32_t v) {
    top.mpu2apu_dmem_we = 1;
    top.mpu2apu_dmem_addr = addr;
    top.mpu2apu_dmem_wdata = v;
    edge();
  }
  // The data memory reads synchronously: the word addressed in one cycle is
  // on apu2mpu_dmem_rdata in the next (one edge).
  std::uint32_t read_data(std::uint16_t addr) {
    top.mpu2apu_dmem_addr = addr;
    edge();
    return top.apu2mpu_dmem_rdata;
  }

  // Hands over the MPU's program bank (and its data bank if asked), starts
  // at pc in the new program and clocks until the APU stops (at most
  // max_cycles); one more edge lands the last word's writes. Returns the
  // cycles it ran, the start's fetch cycle included.
  int run_handed_over(std::uint16_t pc, bool hand_over_data, int max_cycles = 100) {
    top.mpu2apu_hand_over_program = 1;
    top.mpu2apu_hand_over_data = hand_over_data;
    edge();
    top.mpu2apu_start = top.mpu2apu_start_new_program = 1;
    top.mpu2apu_start_pc = pc;
    top.eval();
    int cycles = 0;
    for (; cycles < max_cycles && top.apu2mpu_run_state == static_cast<int>(RunState::Running); ++cycles) edge();
    edge();
    return cycles;
  }

 private:
  // The ISA's power-on state (every register and word 0), one thread.
  std::unique_ptr<VerilatedContext> ctx_ = mc1::rtl::new_context();  // before top: top is built in it

 public:
  Vapu_core top;
};

}  // namespace mc1::apu
