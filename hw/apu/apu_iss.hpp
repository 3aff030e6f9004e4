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
// the stall logic asks of every word, precomputed.
struct DecodedWord {
  enum : std::uint8_t {
    kSwap = 1,       // SWAPD/SWAPP: subject to `bank`
    kCcBranch = 2,   // BCC/BNCC: subject to `cc`
    kHalt = 4,       // subject to `drain`
    kReserved = 8,   // a reserved op in some slot: faults when it would issue
  };
  MicroWord w;
  std::uint64_t src = 0;  // F registers read (raw)
  // F registers written, by the latency of the write (waw): a write with
  // latency L must land after every write already in flight to its register.
  std::array<std::uint64_t, kMaxLatency + 1> dst_at{};
  std::uint8_t kind = 0;

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
  bool program_ready() const override { return program_ready_; }
  bool data_ready() const override { return data_ready_; }
  void start(std::uint16_t pc) override;
  void step(CycleRecord& rec) override;
  RunState state() const override { return state_; }
  Fault fault() const override { return fault_; }
  std::uint64_t cycle() const override { return cycle_; }
  std::uint32_t freg(int i) const override { return f_[i & 63]; }
  std::uint16_t areg(int i) const override { return a_[i & 15]; }
  std::uint8_t flags() const override { return flags_; }
  std::uint8_t cc() const override { return cc_; }

  // Fast path: clocks until the APU stops running (HALT issued, fault) or
  // max_cycles cycles have passed; returns the cycles clocked (0 when the
  // APU is not running).
  std::uint64_t run(std::uint64_t max_cycles) override;

  // Observers beyond ApuEngine (tests, profiles, the driver).
  std::uint16_t pc() const { return pc_; }
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
  struct FWrite { std::uint8_t index; std::uint32_t value; };
  struct AWrite { std::uint8_t index; std::uint16_t value; };
  // What becomes visible in one future cycle. At most one write per slot,
  // except the F slot: a SIN/COS and a RECIP/SQRT issued one cycle later.
  struct Bucket {
    std::uint64_t fmask = 0;
    std::uint8_t nf = 0, na = 0;
    bool cc_valid = false, flags_commit = false;
    std::uint8_t cc = 0, flags = 0;  // flags: the OR of the ops', then FLAGS once applied
    FWrite f[6];  // M, A, F twice, LD, MOVAF/LIF
    AWrite a[2];  // I slot, DBNZ
  };
  static constexpr int kRing = pow2_above(kMaxLatency);

  // One cycle; returns the stall reason (None if it issued or did not run).
  template <bool kRecord>
  Stall clock(CycleRecord* rec);
  bool writes_landed() const;
  void apply_next();
  template <bool kRecord>
  void take_due(CycleRecord* rec, int& cc, int& flags);
  Stall stall_reason(const DecodedWord& dw) const;
  // The sequencer's next PC (1024 when it would run off the bank) and the
  // fault, if any, that keeps the word from issuing.
  std::uint32_t next_pc(const DecodedWord& dw) const;
  Fault check_fault(const DecodedWord& dw, std::uint32_t next) const;
  template <bool kRecord>
  void issue(const DecodedWord& dw, std::uint32_t next, CycleRecord* rec);
  void push_f(int latency, std::uint8_t index, std::uint32_t value);
  void push_a(int latency, std::uint8_t index, std::uint16_t value);
  void push_flags(int latency, std::uint8_t flags);
  void note_fp(int latency);  // an FP op in flight until cycle_ + latency (drain)

  // Architectural state.
  std::array<std::uint32_t, kNumFRegs> f_{};
  std::array<std::uint16_t, kNumARegs> a_{};
  std::uint8_t cc_ = 0, flags_ = 0;
  std::uint16_t pc_ = 0;
  std::array<std::uint16_t, kCallDepth> stack_{};
  int sp_ = 0;
  int psel_ = 0, dsel_ = 0;
  bool program_ready_ = false, data_ready_ = false;
  RunState state_ = RunState::Idle;
  Fault fault_ = Fault::None;
  std::uint64_t cycle_ = 0;
  int fetching_ = 0;  // cycles left in which a start fetches its first word
  std::array<std::array<Encoded, kProgramWords>, 2> program_{};
  std::array<std::array<DecodedWord, kProgramWords>, 2> decoded_{};
  std::array<std::array<std::uint32_t, kDataWords>, 2> data_{};

  // Pipeline state: future writes by cycle, and the scoreboard's summaries.
  std::array<Bucket, kRing> ring_{};
  std::uint64_t fp_done_ = 0;      // first cycle with no FP op in flight
  std::uint64_t cmp_done_ = 0;     // first cycle with no CMP in flight
  Counters counters_;
};

}  // namespace mc1::apu
