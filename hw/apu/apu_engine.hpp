// One interface to an APU, whichever engine runs it (the C++ ISS or the
// verilated RTL core): the MPU-side port (banks, hand-over, start) and a
// cycle-by-cycle view for lockstep co-simulation and stall profiling.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "microword.hpp"

namespace mc1::apu {

// Stall (why a cycle issued no word, docs/apu-isa.md, in priority order),
// Fault and RunState, with stall_name() and fault_name(), are generated from
// the instruction-set table with the RTL's stall_e, fault_e and run_e
// (apu_isa.hpp, through microword.hpp).

// An architectural state change, stamped with the cycle in which it becomes
// visible (an FP result's completion cycle, a store's issue cycle, ...).
struct Commit {
  enum class Kind : std::uint8_t { FReg, AReg, Mem, Cc, Flags };
  Kind kind;
  std::uint16_t index;  // register number or data address; 0 for CC/FLAGS
  std::uint32_t value;
  bool operator==(const Commit& o) const {
    return kind == o.kind && index == o.index && value == o.value;
  }
};

// What one clock cycle did.
struct CycleRecord {
  std::uint64_t cycle = 0;
  std::uint16_t pc = 0;       // the word issued or stalled this cycle
  bool issued = false;
  Stall stall = Stall::None;  // reason when !issued and running
  std::uint8_t psel = 0, dsel = 0;
  std::vector<Commit> commits;  // in a fixed order: FReg (by index), AReg, Mem, Cc, Flags
};

// What an engine counts from its reset, in step() and run() alike: the same
// figures on every engine (a word issues, or stalls for one reason, in the
// same cycles on the ISS and on the RTL core).
struct ApuCounters {
  std::uint64_t issued = 0;                // words issued
  std::uint64_t unit_ops[3] = {0, 0, 0};   // of those, the ones with a multiplier, adder, function unit op
  std::uint64_t stalls[kStallKinds] = {};  // running cycles that issued nothing, by Stall (None: 0)
};

class ApuEngine {
 public:
  virtual ~ApuEngine() = default;

  // MPU side: always the bank the APU is not using.
  virtual void write_program(std::uint16_t addr, const Encoded& word) = 0;
  virtual void write_data(std::uint16_t addr, std::uint32_t value) = 0;
  virtual std::uint32_t read_data(std::uint16_t addr) const = 0;
  // n words from addr on (addr + n <= kDataWords): one call for a block
  // (engines override them with a loop that is not a call per word).
  virtual void write_data_block(std::uint16_t addr, const std::uint32_t* values, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) write_data(static_cast<std::uint16_t>(addr + i), values[i]);
  }
  virtual void read_data_block(std::uint16_t addr, std::uint32_t* out, std::size_t n) const {
    for (std::size_t i = 0; i < n; ++i) out[i] = read_data(static_cast<std::uint16_t>(addr + i));
  }
  // Whether the *_data calls above may run on one thread while another
  // clocks the engine, no data hand-over pending (the APU cannot swap the
  // banks then, and touches its own bank only): the ISS's banks are plain
  // arrays; a verilated model is one object to a thread.
  virtual bool mpu_bank_while_running() const { return false; }
  virtual void hand_over_program() = 0;
  virtual void hand_over_data() = 0;
  virtual bool program_ready() const = 0;
  virtual bool data_ready() const = 0;
  virtual void start(std::uint16_t pc) = 0;

  // One APU clock; fills `rec` with what happened in that cycle.
  virtual void step(CycleRecord& rec) = 0;

  // Clocks without records until the APU stops running (HALT issued, fault)
  // or max_cycles cycles have passed; returns the cycles clocked. Engines
  // override it with their fast path (Iss::run, RtlEngine::run).
  virtual std::uint64_t run(std::uint64_t max_cycles) {
    CycleRecord rec;
    std::uint64_t n = 0;
    for (; n < max_cycles && state() == RunState::Running; ++n) step(rec);
    return n;
  }
  // As run(), and it also stops after the cycle in which the APU takes the
  // data bank the MPU handed over (data_ready() turns false; 0 cycles if it
  // is not set): the MPU's wait for the swap interrupt.
  virtual std::uint64_t run_until_data_taken(std::uint64_t max_cycles) {
    std::uint64_t n = 0;
    while (n < max_cycles && data_ready() && state() == RunState::Running) n += run(1);
    return n;
  }

  virtual RunState state() const = 0;
  virtual Fault fault() const = 0;
  virtual std::uint64_t cycle() const = 0;
  virtual std::uint32_t freg(int i) const = 0;
  virtual std::uint16_t areg(int i) const = 0;
  virtual std::uint8_t flags() const = 0;
  virtual std::uint8_t cc() const = 0;
  virtual const ApuCounters& counters() const = 0;

  // The platform's time. A machine that clocks the APU in bursts (the NC:
  // idle between kernel runs) says before each burst at which simulated time
  // (ps) the next cycle starts and how long a cycle is (its timing table's
  // APU clock); time_of() stamps a cycle with it (waveforms, stall
  // profiles). Without set_time(), cycle c starts at c x 250 ns.
  void set_time(std::uint64_t ps, std::uint64_t cycle_ps) {
    time_ps_ = ps;
    time_cycle_ = cycle();
    cycle_ps_ = cycle_ps;
  }
  std::uint64_t time_of(std::uint64_t cycle) const { return time_ps_ + (cycle - time_cycle_) * cycle_ps_; }
  std::uint64_t cycle_ps() const { return cycle_ps_; }

  // Waveform annotations, for an engine that writes one (the RTL engine;
  // others ignore them): dump only simulated times in [from_ps, to_ps);
  // the program in `bank` is kernel `id` (a kernel-id signal follows the
  // APU's program bank).
  virtual void trace_window(std::uint64_t from_ps, std::uint64_t to_ps) { (void)from_ps, (void)to_ps; }
  virtual void trace_kernel(int bank, std::uint16_t id) { (void)bank, (void)id; }
  // The MPU's side on the same time axis (TOP.mc1.mpu_*): before each
  // traced cycle the engine asks `source` for the MPU's state at the
  // cycle's start (ps). Numbers only: their names are the trace's filters.
  struct MpuTraceInputs {
    std::uint8_t doing = 0;   // what the MPU does (nc::MpuDoing)
    std::uint16_t code = 0;   // the firmware's activity code
    std::uint32_t detail = 0, block = 0xFFFFFFFF;
    std::uint16_t words_left = 0;  // of a copy into a bank
  };
  virtual void trace_mpu(std::function<MpuTraceInputs(std::uint64_t ps)> source) { (void)source; }

 private:
  std::uint64_t time_ps_ = 0, time_cycle_ = 0, cycle_ps_ = 250000;  // 4 MHz (paper section 2)
};

}  // namespace mc1::apu
