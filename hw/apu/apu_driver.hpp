// The MPU-side API of the APU (issue text: "load program and data into the
// idle bank, swap, start, wait for done, read results; the same calls drive
// either engine, and firmware uses nothing else to reach the APU").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "apu_engine.hpp"
#include "microword.hpp"

namespace mc1::apu {

class Iss;

// A run that did not end in HALT: a fault, the cycle limit, or misuse; or
// an RTL engine's assertion failed (RtlAssertionError, docs/apu-rtl.md
// "Assertions").
class ApuError : public std::runtime_error {
 public:
  enum class Kind { Fault, CycleLimit, NotRunning, Usage, Assertion };
  ApuError(Kind kind, Fault fault, std::uint64_t cycle, std::uint16_t pc, const std::string& what)
      : std::runtime_error(what), kind_(kind), fault_(fault), cycle_(cycle), pc_(pc) {}
  Kind kind() const { return kind_; }
  Fault fault() const { return fault_; }
  std::uint64_t cycle() const { return cycle_; }
  std::uint16_t pc() const { return pc_; }

 private:
  Kind kind_;
  Fault fault_;
  std::uint64_t cycle_;
  std::uint16_t pc_;
};

class ApuDriver {
 public:
  // Cycles run_until_done() keeps clocking a halted APU so that results of
  // the HALT word's own ops land (docs/apu-isa.md, Clarification 7).
  static constexpr int kSettleCycles = 3;

  explicit ApuDriver(ApuEngine& engine);

  // Into the bank the APU does not use (the MPU's).
  void load_program(const std::vector<Encoded>& words, std::uint16_t base = 0);
  void load_data(std::uint16_t addr, const std::uint32_t* values, std::size_t n);
  void load_data(std::uint16_t addr, const std::vector<std::uint32_t>& values) {
    load_data(addr, values.data(), values.size());
  }
  void hand_over_program();
  void hand_over_data() {
    data_pending_ = true;
    if (hand_over_hook_ && hand_over_hook_()) return;  // the caller hands over at the APU's time
    access();
    engine_.hand_over_data();
  }
  bool program_ready() const {
    access();
    return engine_.program_ready();
  }
  bool data_ready() const {
    access();
    return engine_.data_ready();
  }

  // Starts the idle APU at pc; throws ApuError(Usage) if it is running.
  void start(std::uint16_t pc = 0);

  // Clocks until HALT (then kSettleCycles more), returning the cycles from
  // the call to the cycle after the HALT issued. Throws ApuError on a fault
  // or when max_cycles pass first, naming cycle, pc and (on a limit) the
  // stall the APU is stuck in. `mpu`, if set, is called before every cycle
  // whose number is a multiple of mpu_interval: the firmware's polling loop
  // (hand over the next block when data_ready() clears, ...).
  std::uint64_t run_until_done(std::uint64_t max_cycles, const std::function<void()>& mpu = {},
                               std::uint64_t mpu_interval = 1);
  // run_until_done() in pieces, for a caller that clocks the run itself:
  // begin_run() (throws if the APU is not running), run() while it runs and
  // `done` (the cycles so far) < max_cycles, then end_run(done, max_cycles),
  // which returns or throws as run_until_done() would.
  void begin_run();
  std::uint64_t end_run(std::uint64_t done, std::uint64_t max_cycles);

  // Clocks at most `cycles` cycles, stopping early when the APU stops
  // running; returns the cycles clocked. No exception: look at state().
  std::uint64_t run(std::uint64_t cycles);
  // As run(), and it also stops after the cycle in which the APU takes the
  // data bank handed over (data_ready() turns false; 0 cycles if it is not
  // set): the MPU's wait for the swap interrupt, without a call per cycle.
  std::uint64_t run_until_data_taken(std::uint64_t cycles);

  std::vector<std::uint32_t> read_results(std::uint16_t addr, std::size_t n) const;
  // The same n words into out (no allocation).
  void read_results(std::uint16_t addr, std::uint32_t* out, std::size_t n) const;

  // Called with every cycle's record. Having an observer takes the ISS off
  // its fast path (records are built every cycle).
  void set_observer(std::function<void(const CycleRecord&)> observer) { observer_ = std::move(observer); }
  // Called at every program hand-over with the bank handed over and the
  // words the driver loaded there (a profile or a waveform names the kernel).
  void on_hand_over(std::function<void(int bank, const std::vector<Encoded>& words)> f) { on_hand_over_ = std::move(f); }

  ApuEngine& engine() {
    access();
    return engine_;
  }
  RunState state() const {
    access();
    return engine_.state();
  }
  // The word the driver loaded at (bank, addr), as far as it knows (profiles
  // and error messages disassemble it).
  const Encoded& program_word(int bank, std::uint16_t addr) const {
    access();
    return shadow_[bank & 1][addr % kProgramWords];
  }
  int psel() const {
    access();
    return psel_;
  }
  std::uint16_t pc() const {
    access();
    return pc_;
  }

  // Called before every call above reaches the engine: the NC clocks the
  // APU lazily, on other threads (hw/nc/apu_pool.hpp), and brings it up to
  // date here, before the MPU touches it.
  void set_access_hook(std::function<void()> hook) { hook_ = std::move(hook); }
  // Called instead before load_data() and read_results() while no data
  // hand-over is pending: the APU cannot swap the data banks in the cycles
  // the NC owes it, so the MPU's bank is the same whenever they are clocked.
  // Without it, those calls call the access hook.
  void set_bank_hook(std::function<void()> hook) { bank_hook_ = std::move(hook); }
  // Called first by hand_over_data(): true when the caller takes the
  // hand-over on itself (the NC, whose APU is being clocked on another
  // thread, has that thread hand the bank over once the APU is up to the
  // time of the call; any later call through the access hook waits for it).
  // Without it, or when it returns false, hand_over_data() calls the access
  // hook and hands over at once.
  void set_hand_over_hook(std::function<bool()> hook) { hand_over_hook_ = std::move(hook); }

 private:
  void access() const {
    if (hook_) hook_();
  }
  void access_bank() const;  // before a call on the MPU's data bank alone
  // Stops when not running (and, until_data_taken, once data_ready() clears).
  std::uint64_t clock(std::uint64_t cycles, bool until_data_taken = false);
  [[noreturn]] void fail(ApuError::Kind kind, const std::string& why) const;

  ApuEngine& engine_;
  Iss* iss_;  // the ISS when engine_ is one: its bank and pc without records
  std::function<void(const CycleRecord&)> observer_;
  std::function<void()> hook_, bank_hook_;
  std::function<bool()> hand_over_hook_;
  // A data hand-over the APU may not have taken yet (false only once the
  // driver has seen data_ready() clear, the APU up to date; written by the
  // MPU's calls alone, never by a clocking thread).
  mutable bool data_pending_ = true;
  std::function<void(int, const std::vector<Encoded>&)> on_hand_over_;
  CycleRecord rec_;
  int psel_ = 0;  // the APU's program bank as seen by the driver
  std::uint16_t pc_ = 0;
  bool pc_known_ = true;          // pc_ and last_stall_ describe the last cycle clocked
  std::uint64_t probe_cycle_ = 0;  // engine cycle before an error probe step, or 0
  Stall last_stall_ = Stall::None;
  std::array<std::vector<Encoded>, 2> shadow_;
};

// A data file as the tools read it (docs/apu-tools.md): hex words, whitespace-separated, `#` comments, `@hex` moves
// the load address. Returns (address, value) pairs in file order.
std::vector<std::pair<std::uint16_t, std::uint32_t>> read_data_file(const std::string& path);

}  // namespace mc1::apu
