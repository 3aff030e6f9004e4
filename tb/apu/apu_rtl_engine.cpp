// RtlEngine: the verilated apu_core behind ApuEngine (docs/apu-rtl.md).
#include "apu_rtl_engine.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "Vapu_core.h"
#include "verilated.h"
#include "verilated_fst_c.h"

namespace mc1::apu {

namespace {

constexpr int kFCompletionPorts = 5;  // mul, add, func RECIP/SQRT, func SIN/COS, LD (from the RAM)
constexpr int kFCommitPorts = 6;      // the completions; MOVAF/LIF of t - 1

// Bits [pos + width - 1 : pos] of a wide Verilator port.
template <typename Wide>
std::uint32_t wide_bits(const Wide& w, int pos, int width) {
  const int word = pos / 32, off = pos % 32;
  std::uint64_t v = w[word];
  if (off + width > 32) v |= std::uint64_t{w[word + 1]} << 32;
  return static_cast<std::uint32_t>(v >> off) & ((std::uint32_t{1} << width) - 1);
}

}  // namespace

RtlEngine::RtlEngine(const char* fst_path) : ctx_(std::make_unique<VerilatedContext>()) {
  ctx_->randReset(0);  // the ISA's power-on state: every register and word is 0
  if (fst_path) ctx_->traceEverOn(true);
  top_ = std::make_unique<Vapu_core>(ctx_.get());
  backdoor_ = std::make_unique<RtlBackdoor>(*top_);
  Vapu_core& t = *top_;

  // Synchronous reset: one clock with rst_n low; it is not an APU cycle.
  t.rst_n = 0;
  t.clk = 0;
  t.eval();
  t.clk = 1;
  t.eval();
  t.clk = 0;
  t.rst_n = 1;
  t.eval();

  if (fst_path) {
    fst_ = std::make_unique<VerilatedFstC>();
    t.trace(fst_.get(), 99);
    fst_->open(fst_path);
  }
}

void RtlEngine::trace_kernel(int bank, std::uint16_t id) {
  (bank & 1 ? top_->bank1_kernel : top_->bank0_kernel) = id;
  changed_ = true;
}

void RtlEngine::trace_window(std::uint64_t from_ps, std::uint64_t to_ps) {
  from_ = from_ps;
  to_ = to_ps;
}

// The first dump in the window is at its start: the state the APU holds
// there (it is clocked in bursts, and between them nothing changes), without
// the MPU's requests of the burst that follows.
void RtlEngine::dump(std::uint64_t ps) {
  if (ps >= to_ || (ps < from_ && !dumped_)) return;
  if (!dumped_) {
    dumped_ = true;
    last_dump_ = from_;
    Vapu_core& t = *top_;
    const auto program = t.mpu2apu_hand_over_program, data = t.mpu2apu_hand_over_data, start = t.mpu2apu_start,
               fresh = t.mpu2apu_start_new_program;
    t.mpu2apu_hand_over_program = t.mpu2apu_hand_over_data = t.mpu2apu_start = t.mpu2apu_start_new_program = 0;
    t.eval();
    fst_->dump(from_);
    t.mpu2apu_hand_over_program = program;
    t.mpu2apu_hand_over_data = data;
    t.mpu2apu_start = start;
    t.mpu2apu_start_new_program = fresh;
    t.eval();
    if (ps == from_) return;
  }
  if (ps <= last_dump_) ps = last_dump_ + 1;  // a burst that starts inside the last one's settle cycles
  last_dump_ = ps;
  fst_->dump(ps);
}

RtlEngine::~RtlEngine() {
  // Verilator 5.006 erases the model's scopes from the thread's current
  // context (Verilated::threadContextp()), not the model's own: with several
  // engines, that may be one already destroyed (a hang on its freed mutex,
  // seen in examples/apu_tb.cpp). Make it ours while top_ goes.
  Verilated::threadContextp(ctx_.get());
  if (fst_) {
    const std::uint64_t end = std::min(time_of(cycle_), to_ - 1);  // the idle tail, up to the last set_time()
    if (!dumped_ || end > last_dump_) dump(end);
    fst_->close();
  }
  top_->final();
}

// ---- MPU side -----------------------------------------------------------------

// The MPU owns the bank the APU does not use.
void RtlEngine::write_program(std::uint16_t addr, const Encoded& word) {
  backdoor_->write_program(top_->apu2mpu_psel ^ 1, addr, word);
  changed_ = true;
}

void RtlEngine::write_data(std::uint16_t addr, std::uint32_t value) {
  backdoor_->write_data(top_->apu2mpu_dsel ^ 1, addr, value);
  changed_ = true;
}

void RtlEngine::write_data_block(std::uint16_t addr, const std::uint32_t* values, std::size_t n) {
  const int bank = top_->apu2mpu_dsel ^ 1;
  for (std::size_t i = 0; i < n; ++i) backdoor_->write_data(bank, static_cast<std::uint16_t>(addr + i), values[i]);
  changed_ = true;
}

std::uint32_t RtlEngine::read_data(std::uint16_t addr) const {
  return backdoor_->read_data(top_->apu2mpu_dsel ^ 1, addr);
}

void RtlEngine::hand_over_program() {
  top_->mpu2apu_hand_over_program = 1;
  settle();
}

void RtlEngine::hand_over_data() {
  top_->mpu2apu_hand_over_data = 1;
  settle();
}

bool RtlEngine::program_ready() const { return top_->apu2mpu_program_ready; }
bool RtlEngine::data_ready() const { return top_->apu2mpu_data_ready; }

void RtlEngine::start(std::uint16_t pc) {
  if (state() == RunState::Running) return;  // only an idle APU starts
  // The start completes a pending program hand-over, one made since the last
  // cycle included; a hand-over after this call sets the flag anew.
  top_->mpu2apu_start_new_program = program_ready();
  top_->mpu2apu_hand_over_program = 0;
  top_->mpu2apu_start = 1;
  top_->mpu2apu_start_pc = pc % kProgramWords;
  settle();
}

void RtlEngine::settle() {
  top_->eval();
  changed_ = true;  // the inputs: the next rising edge recomputes their logic
  dump_pending_ = fst_ != nullptr;
}

// ---- clocking -----------------------------------------------------------------

void RtlEngine::clock() {
  Vapu_core& t = *top_;
  // Time in ps (Verilator's default precision): 250 ns cycles, 4 MHz.
  if (changed_ || fst_) {
    t.clk = 1;
    t.eval();
    changed_ = false;
  } else {
    // Nothing the MPU does has reached the model since its last eval(): the
    // edge without recomputing the input logic (a third of the host time).
    backdoor_->rising_edge_unchanged();
  }
  if (fst_) dump(time_of(cycle_) + cycle_ps() / 2);
  // MPU requests last exactly the cycle after the call that made them.
  const bool requests =
      t.mpu2apu_hand_over_program | t.mpu2apu_hand_over_data | t.mpu2apu_start | t.mpu2apu_start_new_program;
  if (requests || fst_) {
    t.mpu2apu_hand_over_program = 0;
    t.mpu2apu_hand_over_data = 0;
    t.mpu2apu_start = 0;
    t.mpu2apu_start_new_program = 0;
    t.clk = 0;
    t.eval();
  } else {
    // No input changed since the rising edge: the falling edge's eval()
    // would compute the same values again.
    backdoor_->clock_low_unchanged();
  }
  ++cycle_;
  if (fst_) dump(time_of(cycle_));
}

void RtlEngine::step(CycleRecord& rec) {
  // Show forwarded MPU requests in the waveform before the edge that takes them.
  if (dump_pending_) {
    dump(time_of(cycle_) + cycle_ps() / 4);
    dump_pending_ = false;
  }
  const Vapu_core& t = *top_;
  rec.cycle = cycle_;
  rec.pc = t.dbg_pc;
  rec.issued = t.dbg_issue;
  rec.stall = static_cast<Stall>(t.dbg_stall_reason);
  rec.psel = t.apu2mpu_psel;
  rec.dsel = t.apu2mpu_dsel;
  rec.commits.clear();

  // F: by index (no two ports write one register in a cycle).
  std::array<Commit, kFCommitPorts> f;
  int nf = 0;
  for (int p = 0; p < kFCommitPorts; ++p) {
    if (!((t.dbg_fc_en >> p) & 1)) continue;
    const Commit c{Commit::Kind::FReg, static_cast<std::uint16_t>((t.dbg_fc_idx >> (6 * p)) & 63),
                   wide_bits(t.dbg_fc_val, 24 * p, 24)};
    int j = nf++;
    for (; j > 0 && f[j - 1].index > c.index; --j) f[j] = f[j - 1];
    f[j] = c;
  }
  for (int i = 0; i < nf; ++i) rec.commits.push_back(f[i]);

  // A: by index.
  std::array<Commit, 2> a;
  int na = 0;
  for (int p = 0; p < 2; ++p) {
    if (!((t.dbg_ac_en >> p) & 1)) continue;
    a[na++] = {Commit::Kind::AReg, static_cast<std::uint16_t>((t.dbg_ac_idx >> (4 * p)) & 15),
               (t.dbg_ac_val >> (16 * p)) & 0xFFFFu};
  }
  if (na == 2 && a[1].index < a[0].index) std::swap(a[0], a[1]);
  for (int i = 0; i < na; ++i) rec.commits.push_back(a[i]);

  if (t.dbg_mc_en) rec.commits.push_back({Commit::Kind::Mem, t.dbg_mc_addr, t.dbg_mc_val});
  if (t.dbg_cc_en) rec.commits.push_back({Commit::Kind::Cc, 0, t.dbg_cc_val});
  if (t.dbg_flags_en) rec.commits.push_back({Commit::Kind::Flags, 0, t.dbg_flags_val});

  clock();
}

std::uint64_t RtlEngine::run(std::uint64_t max_cycles) {
  if (dump_pending_) {
    dump(time_of(cycle_) + cycle_ps() / 4);
    dump_pending_ = false;
  }
  const Vapu_core& t = *top_;
  std::uint64_t n = 0;
  while (n < max_cycles && state() == RunState::Running) {
    if (t.dbg_stall_reason == static_cast<std::uint8_t>(Stall::Bank) && !t.dbg_mc_en && !fst_) {
      // Waiting for a bank the MPU has not handed over: the MPU acts only
      // between calls, so the inputs stay as they are. Once a clock leaves
      // every bit of the model as it was (the pipelines have drained; the
      // banks change only by a store, and none issues), every further clock
      // would too: the rest of the call's cycles are taken at once.
      backdoor_->snapshot(snapshot_);
      clock();
      ++n;
      if (n < max_cycles && backdoor_->same_state(snapshot_)) {
        cycle_ += max_cycles - n;
        n = max_cycles;
      }
      continue;
    }
    clock();
    ++n;
  }
  return n;
}

// ---- observers ----------------------------------------------------------------

RunState RtlEngine::state() const { return static_cast<RunState>(top_->apu2mpu_run_state); }
Fault RtlEngine::fault() const { return static_cast<Fault>(top_->apu2mpu_fault); }
std::uint8_t RtlEngine::flags() const { return top_->apu2mpu_flags; }
std::uint8_t RtlEngine::cc() const { return top_->apu2mpu_cc; }
bool RtlEngine::unit_mismatch() const { return top_->dbg_unit_mismatch; }

// The register as the next word reads it: a result completing in the coming
// cycle is written at its end but already bypassed to that word
// (docs/apu-isa.md, Clarification 2: the state between two steps).
std::uint32_t RtlEngine::freg(int i) const {
  const Vapu_core& t = *top_;
  i &= 63;
  for (int p = 0; p < kFCompletionPorts; ++p) {
    if (((t.dbg_fc_en >> p) & 1) && static_cast<int>((t.dbg_fc_idx >> (6 * p)) & 63) == i)
      return wide_bits(t.dbg_fc_val, 24 * p, 24);
  }
  return backdoor_->freg_array(i);
}
std::uint16_t RtlEngine::areg(int i) const { return backdoor_->areg_array(i); }

}  // namespace mc1::apu
