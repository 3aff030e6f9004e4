// The APU instruction-set simulator: cycle-accurate to docs/apu-isa.md
// (stall priority, scoreboard, bank hand-over, faults, its Clarifications),
// with results and flags from the bit-accurate FP24 model.
//
// Two ways to clock it: step(CycleRecord&) for lockstep co-simulation and
// profiling, and run(max_cycles), the fast path with no records.
#pragma once

#include <array>
#include <cstdint>

#include "apu_engine.hpp"
#include "microword.hpp"

namespace mc1::apu {

// The smallest power of two above n: a ring of future cycles that long holds
// every write still in flight.
constexpr int pow2_above(int n) {
  int r = 1;
  while (r <= n) r <<= 1;
  return r;
}

// A program word decoded once, when the MPU writes it: the fields plus what
// the stall logic and the issue ask of every word, resolved then (operand
// masks, each F write with its latency from the instruction-set table, the
// checks the word can need), so that a cycle decodes nothing.
struct DecodedWord {
  enum : std::uint8_t {
    kSwap = 1,       // SWAPD/SWAPP: subject to `bank`
    kCcBranch = 2,   // BCC/BNCC: subject to `cc`
    kHalt = 4,       // subject to `drain`
    kReserved = 8,   // a reserved op in some slot: faults when it would issue
    kMem = 16,       // LD/ST: the data address is checked
    kStack = 32,     // CALL/RET: the call stack is checked
    kRefetch = 64,   // a conditional branch or SWAPP: the next word may miss the fetch
  };
  // An F register write and the latency after which it is visible.
  struct FDst {
    std::uint8_t reg = 0, latency = 0;
  };
  MicroWord w;
  std::uint64_t src = 0;  // F registers read (raw)
  std::uint64_t dst = 0;  // F registers written, any latency
  // Each F write (waw): a write with latency L must land after every write
  // already in flight to its register.
  std::array<FDst, 5> dsts{};  // M, A, F, LD, MOVAF/LIF
  std::uint8_t ndst = 0;
  std::uint8_t kind = 0;
  // latency(op) of the A, F, D and I slots; the longest FP op's (drain; 0: none).
  std::uint8_t lat_a = 0, lat_f = 0, lat_d = 0, lat_i = 0, lat_fp = 0;

  static DecodedWord from(const Encoded& e);
};

class Iss final : public ApuEngine {
 public:
  Iss() { reset(); }
  // Power-on state: banks 0, flags clear, every register and word 0, idle.
  void reset();

  // ApuEngine.
  void write_program(std::uint16_t addr, const Encoded& word) override;
  void write_data(std::uint16_t addr, std::uint32_t value) override;
  std::uint32_t read_data(std::uint16_t addr) const override;
  void write_data_block(std::uint16_t addr, const std::uint32_t* values, std::size_t n) override;
  void read_data_block(std::uint16_t addr, std::uint32_t* out, std::size_t n) const override;
  void hand_over_program() override { program_ready_ = true; }
  void hand_over_data() override { data_ready_ = true; }
  bool mpu_bank_while_running() const override { return true; }
  bool program_ready() const override { return program_ready_; }
  bool data_ready() const override { return data_ready_; }
  void start(std::uint16_t pc) override;
  void step(CycleRecord& rec) override;
  RunState state() const override { return state_; }
  Fault fault() const override { return fault_; }
  std::uint64_t cycle() const override { return cycle_; }
  std::uint32_t freg(int i) const override { return f_[i & 63]; }
  std::uint16_t areg(int i) const override { return a_[i & 15]; }
  std::uint8_t flags() const override { return static_cast<std::uint8_t>(flags_); }
  std::uint8_t cc() const override { return static_cast<std::uint8_t>(cc_); }

  // Fast path: clocks until the APU stops running (HALT issued, fault) or
  // max_cycles cycles have passed; returns the cycles clocked (0 when the
  // APU is not running).
  std::uint64_t run(std::uint64_t max_cycles) override { return run_fast<false>(max_cycles); }
  std::uint64_t run_until_data_taken(std::uint64_t max_cycles) override {
    return data_ready_ ? run_fast<true>(max_cycles) : 0;
  }

  // Observers beyond ApuEngine (tests, profiles, the driver).
  std::uint16_t pc() const { return static_cast<std::uint16_t>(pc_); }
  int psel() const { return psel_; }
  int dsel() const { return dsel_; }
  int call_depth() const { return sp_; }
  const Encoded& program_word(int bank, std::uint16_t addr) const {
    return program_[bank & 1][addr % kProgramWords];
  }

  // Counters since reset, kept by both step() and run().
  struct Counters {
    std::uint64_t issued = 0;                  // words issued
    std::uint64_t unit_ops[3] = {0, 0, 0};     // multiplier, adder unit, function unit
    std::uint64_t stalls[kStallKinds] = {};    // by Stall
  };
  const Counters& counters() const { return counters_; }

 private:
  // 32-bit fields throughout: a byte store could alias any member and make
  // the compiler reload the hot state after it.
  struct FWrite { std::uint32_t index, value; };
  struct AWrite { std::uint32_t index, value; };
  // What becomes visible in one future cycle. At most one write per slot,
  // except the F slot: a SIN/COS and a RECIP/SQRT issued one cycle later.
  struct alignas(128) Bucket {  // a power of two: a shift indexes the ring
    std::uint32_t nf = 0, na = 0;
    std::uint32_t cc_valid = 0, flags_commit = 0;
    std::uint32_t cc = 0, flags = 0;  // flags: the OR of the ops', then FLAGS once applied
    FWrite f[6];  // M, A, F twice, LD, MOVAF/LIF
    AWrite a[2];  // I slot, DBNZ
  };
  static constexpr int kRing = pow2_above(kMaxLatency);

  // One cycle's issue, stall or fault; returns the stall reason (None if it
  // issued or did not run).
  template <bool kRecord>
  Stall execute(CycleRecord* rec);
  template <bool kUntilDataTaken>
  std::uint64_t run_fast(std::uint64_t max_cycles);
  bool writes_landed() const;
  template <bool kKeep>
  void apply_next();
  template <bool kRecord>
  void take_due(CycleRecord* rec, int& cc, int& flags);
  Stall stall_reason(const DecodedWord& dw) const;
  // The sequencer's next PC (1024 when it would run off the bank) and the
  // fault, if any, that keeps the word from issuing.
  std::uint32_t next_pc(const DecodedWord& dw) const;
  // Whether `next` is not the word the sequencer fetched behind this one.
  bool fetch_missed(const DecodedWord& dw, std::uint32_t next) const;
  Fault check_fault(const DecodedWord& dw, std::uint32_t next) const;
  template <bool kRecord>
  void issue(const DecodedWord& dw, std::uint32_t next, CycleRecord* rec);
  void int_op(const DecodedWord& dw);
  void seq_op(const DecodedWord& dw);
  // An F write and the flags of the op that makes it.
  void push_f(int latency, std::uint32_t index, std::uint32_t value, std::uint32_t flags = 0);
  void push_a(int latency, std::uint32_t index, std::uint16_t value);

  // Hot state first: what every cycle reads.
  std::uint64_t cycle_ = 0;
  // The scoreboard: the F registers with a write in flight (visible after
  // the current cycle), and for each the cycle its last write becomes
  // visible (writes to one register land in issue order: waw).
  std::uint64_t pending_ = 0;
  std::uint64_t fp_done_ = 0;      // first cycle with no FP op in flight
  std::uint64_t cmp_done_ = 0;     // first cycle with no CMP in flight
  std::uint32_t pc_ = 0;
  RunState state_ = RunState::Idle;
  // Cycles left with no word to issue (`fetch`): a start's fetch and decode,
  // the bubble after a branch miss or a SWAPP.
  int fetching_ = 0;
  int psel_ = 0, dsel_ = 0;
  bool program_ready_ = false, data_ready_ = false;
  std::uint32_t cc_ = 0, flags_ = 0;
  int sp_ = 0;
  Fault fault_ = Fault::None;
  std::array<std::uint32_t, kNumFRegs> f_{};
  std::array<std::uint16_t, kNumARegs> a_{};
  std::array<std::uint16_t, kCallDepth> stack_{};
  Counters counters_;
  std::array<std::uint64_t, kNumFRegs> land_{};
  // Future writes by cycle.
  std::array<Bucket, kRing> ring_{};
  std::array<std::array<DecodedWord, kProgramWords>, 2> decoded_{};
  std::array<std::array<std::uint32_t, kDataWords>, 2> data_{};
  std::array<std::array<Encoded, kProgramWords>, 2> program_{};
};

}  // namespace mc1::apu
