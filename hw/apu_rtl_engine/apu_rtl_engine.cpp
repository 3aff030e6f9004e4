// RtlEngine: the verilated apu_core behind ApuEngine (docs/apu-rtl.md).
#include "apu_rtl_engine.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <string>

#include "Vapu_core.h"
#include "Vapu_fast.h"
#include "rtl_coverage.hpp"
#include "verilated.h"
#include "verilated_context.hpp"
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

// The engine on one verilated model. Top is Vapu_core (kTraced: the FST
// waveform and the trace module's kernel ids) or Vapu_fast; both have the
// ports this code reads and drives, under the same names. Its own
// set_time() is not used: the waveform's times are RtlEngine's.
class RtlEngine::Model : public ApuEngine {
 public:
  virtual bool unit_mismatch() const = 0;
};

template <class Top, bool kTraced>
class RtlEngine::ModelOf final : public Model {
 public:
  // time: the engine, whose set_time() stamps the waveform's cycles.
  ModelOf(const ApuEngine& time, const char* fst_path);
  ~ModelOf() override;

  void write_program(std::uint16_t addr, const Encoded& word) override;
  void write_data(std::uint16_t addr, std::uint32_t value) override;
  std::uint32_t read_data(std::uint16_t addr) const override;
  void write_data_block(std::uint16_t addr, const std::uint32_t* values, std::size_t n) override;
  void read_data_block(std::uint16_t addr, std::uint32_t* out, std::size_t n) const override;
  // The untraced model: the MPU's data bank is an array the clocking thread
  // does not write (the APU's port never selects it, the MPU's port is tied
  // off), and its calls set nothing the clock reads (note_banks()).
  bool mpu_bank_while_running() const override { return !kTraced; }
  void hand_over_program() override;
  void hand_over_data() override;
  bool program_ready() const override { return top_->apu2mpu_program_ready; }
  bool data_ready() const override { return top_->apu2mpu_data_ready; }
  void start(std::uint16_t pc) override;
  void step(CycleRecord& rec) override;
  std::uint64_t run(std::uint64_t max_cycles) override { return clock_until(max_cycles, false); }
  std::uint64_t run_until_data_taken(std::uint64_t max_cycles) override { return clock_until(max_cycles, true); }
  RunState state() const override { return static_cast<RunState>(top_->apu2mpu_run_state); }
  Fault fault() const override { return static_cast<Fault>(top_->apu2mpu_fault); }
  std::uint64_t cycle() const override { return cycle_; }
  std::uint32_t freg(int i) const override;
  std::uint16_t areg(int i) const override { return backdoor_.areg_array(i); }
  std::uint8_t flags() const override { return top_->apu2mpu_flags; }
  std::uint8_t cc() const override { return top_->apu2mpu_cc; }
  const ApuCounters& counters() const override;
  void trace_window(std::uint64_t from_ps, std::uint64_t to_ps) override;
  void trace_kernel(int bank, std::uint16_t id) override;
  void trace_mpu(std::function<MpuTraceInputs(std::uint64_t ps)> source) override { mpu_source_ = std::move(source); }
  bool unit_mismatch() const override { return top_->dbg_unit_mismatch; }

 private:
  // run(), and with until_data_taken also up to the cycle in which the APU
  // takes the handed-over data bank.
  std::uint64_t clock_until(std::uint64_t max_cycles, bool until_data_taken);
  void clock();        // one rising edge and the falling edge after it
  void count();        // this cycle's issue or stall into cycles_by_ (before its edge)
  void settle();       // re-evaluate after an MPU-side input change
  void dump(std::uint64_t ps);  // at simulated time ps, if in the window (times strictly increase)
  void dump_requests();         // the MPU's requests, before the edge that takes them
  void note_banks();            // mpu_dbank_ after a call that clocks or evaluates
  void mpu_inputs(std::uint64_t ps);  // the trace module's MPU inputs at time ps (trace_mpu)
  int mpu_dbank() const { return mpu_dbank_.load(std::memory_order_relaxed); }
  std::uint64_t time_of(std::uint64_t cycle) const { return time_.time_of(cycle); }

  const ApuEngine& time_;
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Top> top_;
  std::unique_ptr<VerilatedFstC> fst_;  // kTraced only
  BasicRtlBackdoor<Top> backdoor_;      // into *top_
  std::unique_ptr<RtlFastFunc> func_;   // Vapu_fast's function unit (not kTraced)
  typename BasicRtlBackdoor<Top>::Snapshot snapshot_;  // run()'s fixed-point test
  std::uint64_t cycle_ = 0;
  // Cycles by what the core's debug ports said before their edge, at
  // [stall reason << 4 | issue << 3 | units issuing]: one increment a cycle;
  // counters() sums them up.
  std::array<std::uint64_t, 16 << 4> cycles_by_{};
  mutable ApuCounters counters_;
  bool dump_pending_ = false;  // MPU inputs changed since the last waveform dump
  std::uint64_t from_ = 0, to_ = ~std::uint64_t{0};  // the dump window (ps)
  bool dumped_ = false;        // a dump was written; last_dump_ is its time
  std::uint64_t last_dump_ = 0;
  // An MPU call changed an input or a program word since the last eval():
  // the next edge is a full eval() (clock()). Not set by the data-bank
  // calls: nothing in front of the flip-flops reads a data bank
  // (apu_banks.sv reads one at the edge), so an edge after them needs no
  // input logic recomputed. (The traced model evaluates fully at every
  // edge anyway.)
  bool changed_ = true;
  // The MPU's data bank (apu2mpu_dsel ^ 1), kept by the thread that clocks
  // the model: the MPU's calls on its bank may run on another thread
  // meanwhile (mpu_bank_while_running), and read this, not the model's
  // port. It changes only with a swap, which no cycle makes while no data
  // hand-over is pending, and that is when those calls overlap a clock.
  std::atomic<std::uint8_t> mpu_dbank_{1};
  std::function<MpuTraceInputs(std::uint64_t ps)> mpu_source_;  // kTraced only
};

namespace {

// A model with its context: the context first (the model's constructor
// needs it), one thread, all registers and words 0 (verilated_context.hpp).
std::unique_ptr<VerilatedContext> make_context(bool traced) {
  auto ctx = mc1::rtl::new_context();
  // A failing assertion ($error) must not abort the process: the engine sees
  // gotError() after the edge and throws RtlAssertionError (clock()).
  ctx->fatalOnError(false);
  if (traced) ctx->traceEverOn(true);
  return ctx;
}

}  // namespace

template <class Top, bool kTraced>
RtlEngine::ModelOf<Top, kTraced>::ModelOf(const ApuEngine& time, const char* fst_path)
    : time_(time),
      ctx_(make_context(fst_path != nullptr)),
      top_(std::make_unique<Top>(ctx_.get())),
      backdoor_(*top_) {
  Top& t = *top_;
  if constexpr (!kTraced) func_ = std::make_unique<RtlFastFunc>(t, ctx_.get());
  // Synchronous reset: one clock with rst_n low; it is not an APU cycle.
  t.rst_n = 0;
  t.clk = 0;
  t.eval();
  t.clk = 1;
  t.eval();
  t.clk = 0;
  t.rst_n = 1;
  t.eval();
  note_banks();

  if constexpr (kTraced) {
    if (fst_path) {
      fst_ = std::make_unique<VerilatedFstC>();
      t.trace(fst_.get(), 99);
      fst_->open(fst_path);
    }
  }
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::trace_kernel(int bank, std::uint16_t id) {
  if constexpr (kTraced) {
    (bank & 1 ? top_->bank1_kernel : top_->bank0_kernel) = id;
    changed_ = true;
  } else {
    (void)bank, (void)id;  // no waveform, no trace module
  }
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::mpu_inputs(std::uint64_t ps) {
  if constexpr (kTraced) {
    if (!mpu_source_) return;
    const MpuTraceInputs m = mpu_source_(ps);
    Top& t = *top_;
    t.mpu_doing = m.doing;
    t.mpu_step = m.code;
    t.mpu_detail = m.detail;
    t.mpu_block = m.block;
    t.mpu_words_left = m.words_left;
  } else {
    (void)ps;
  }
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::trace_window(std::uint64_t from_ps, std::uint64_t to_ps) {
  from_ = from_ps;
  to_ = to_ps;
}

// The first dump in the window is at its start: the state the APU holds
// there (it is clocked in bursts, and between them nothing changes), without
// the MPU's requests of the burst that follows.
template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::dump(std::uint64_t ps) {
  if constexpr (kTraced) {
    if (ps >= to_ || (ps < from_ && !dumped_)) return;
    if (!dumped_) {
      dumped_ = true;
      last_dump_ = from_;
      Top& t = *top_;
      const auto program = t.mpu2apu_hand_over_program, data = t.mpu2apu_hand_over_data, start = t.mpu2apu_start,
                 fresh = t.mpu2apu_start_new_program;
      t.mpu2apu_hand_over_program = t.mpu2apu_hand_over_data = t.mpu2apu_start = t.mpu2apu_start_new_program = 0;
      mpu_inputs(from_);
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
  } else {
    (void)ps;
  }
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::dump_requests() {
  if (dump_pending_) {
    dump(time_of(cycle_) + time_.cycle_ps() / 4);
    dump_pending_ = false;
  }
}

template <class Top, bool kTraced>
RtlEngine::ModelOf<Top, kTraced>::~ModelOf() {
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
  // A coverage build's counts of the model (and of Vapu_fast_func, in the
  // same context) while they are alive (apu_rtl/rtl_coverage.hpp).
  rtl_coverage::collect(*ctx_);
}

// ---- MPU side -----------------------------------------------------------------

// The MPU owns the bank the APU does not use.
template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::write_program(std::uint16_t addr, const Encoded& word) {
  backdoor_.write_program(top_->apu2mpu_psel ^ 1, addr, word);
  changed_ = true;
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::write_data(std::uint16_t addr, std::uint32_t value) {
  backdoor_.write_data(mpu_dbank(), addr, value);
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::write_data_block(std::uint16_t addr, const std::uint32_t* values,
                                                        std::size_t n) {
  const int bank = mpu_dbank();
  for (std::size_t i = 0; i < n; ++i) backdoor_.write_data(bank, static_cast<std::uint16_t>(addr + i), values[i]);
}

template <class Top, bool kTraced>
std::uint32_t RtlEngine::ModelOf<Top, kTraced>::read_data(std::uint16_t addr) const {
  return backdoor_.read_data(mpu_dbank(), addr);
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::read_data_block(std::uint16_t addr, std::uint32_t* out, std::size_t n) const {
  const int bank = mpu_dbank();
  for (std::size_t i = 0; i < n; ++i) out[i] = backdoor_.read_data(bank, static_cast<std::uint16_t>(addr + i));
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::note_banks() {
  const std::uint8_t bank = top_->apu2mpu_dsel ^ 1;
  if (mpu_dbank_.load(std::memory_order_relaxed) != bank) mpu_dbank_.store(bank, std::memory_order_relaxed);
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::hand_over_program() {
  top_->mpu2apu_hand_over_program = 1;
  settle();
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::hand_over_data() {
  top_->mpu2apu_hand_over_data = 1;
  settle();
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::start(std::uint16_t pc) {
  if (state() == RunState::Running) return;  // only an idle APU starts
  // The start completes a pending program hand-over, one made since the last
  // cycle included; a hand-over after this call sets the flag anew.
  top_->mpu2apu_start_new_program = program_ready();
  top_->mpu2apu_hand_over_program = 0;
  top_->mpu2apu_start = 1;
  top_->mpu2apu_start_pc = pc % kProgramWords;
  settle();
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::settle() {
  top_->eval();
  note_banks();
  changed_ = true;  // the inputs: the next rising edge recomputes their logic
  dump_pending_ = fst_ != nullptr;
}

// ---- clocking -----------------------------------------------------------------

// An assertion failed at the rising edge just clocked (docs/apu-rtl.md
// "Assertions"): Verilator has printed its name; the run fails here.
[[noreturn]] static void assertion_failed(std::uint64_t cycle, std::uint16_t pc);

void check_rtl_assertions(const VerilatedContext& ctx, std::uint64_t cycle, std::uint16_t pc) {
  if (__builtin_expect(ctx.gotError(), 0)) assertion_failed(cycle, pc);
}

[[noreturn]] static void assertion_failed(std::uint64_t cycle, std::uint16_t pc) {
  std::fflush(stdout);  // Verilator's message first
  char where[96];
  std::snprintf(where, sizeof where, "cycle %llu, pc 0x%03x", static_cast<unsigned long long>(cycle), pc);
  throw RtlAssertionError(cycle, pc,
                          std::string("RTL assertion failed at ") + where +
                              " (the rule: Verilator's \"APU_ASSERT <Name> failed in <instance>\" on standard output)");
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::clock() {
  Top& t = *top_;
  const bool traced = kTraced && fst_;
  const std::uint16_t pc = t.dbg_pc;  // the word of the cycle, for an assertion's report
  if constexpr (!kTraced) func_->before_rising_edge();
  // Time in ps (Verilator's default precision): 250 ns cycles, 4 MHz.
  if (traced) mpu_inputs(time_of(cycle_));  // the MPU's side in this cycle
  if (changed_ || traced) {
    t.clk = 1;
    t.eval();
    changed_ = false;
  } else {
    // Nothing the MPU does has reached the model since its last eval(): the
    // edge without recomputing the input logic (a third of the host time).
    backdoor_.rising_edge_unchanged();
  }
  // Assertions run at the rising edge (the core's, and the function unit's
  // in before_rising_edge(): one context).
  check_rtl_assertions(*ctx_, cycle_, pc);
  if (traced) dump(time_of(cycle_) + time_.cycle_ps() / 2);
  // MPU requests last exactly the cycle after the call that made them.
  const bool requests =
      t.mpu2apu_hand_over_program | t.mpu2apu_hand_over_data | t.mpu2apu_start | t.mpu2apu_start_new_program;
  if (requests || traced) {
    t.mpu2apu_hand_over_program = 0;
    t.mpu2apu_hand_over_data = 0;
    t.mpu2apu_start = 0;
    t.mpu2apu_start_new_program = 0;
    if (traced) mpu_inputs(time_of(cycle_ + 1));  // ... and in the next, from its start
    t.clk = 0;
    t.eval();
  } else {
    // No input changed since the rising edge: the falling edge's eval()
    // would compute the same values again.
    backdoor_.clock_low_unchanged();
  }
  ++cycle_;
  if (traced) dump(time_of(cycle_));
}

// The core's debug ports say, before the edge, whether the cycle issues (and
// to which units) or why it stalls: the ISS counts the same cycles.
template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::count() {
  const Top& t = *top_;
  ++cycles_by_[(unsigned{t.dbg_stall_reason} << 4 | unsigned{t.dbg_issue} << 3 | t.dbg_unit_issue) & 0xFF];
}

template <class Top, bool kTraced>
const ApuCounters& RtlEngine::ModelOf<Top, kTraced>::counters() const {
  counters_ = {};
  for (unsigned key = 0; key < cycles_by_.size(); ++key) {
    const std::uint64_t n = cycles_by_[key];
    const unsigned stall = key >> 4, units = key & 7;
    if (key & 8) counters_.issued += n;
    for (int u = 0; u < 3; ++u) counters_.unit_ops[u] += (units >> u & 1) * n;
    if (stall != static_cast<unsigned>(Stall::None) && stall < kStallKinds) counters_.stalls[stall] += n;
  }
  return counters_;
}

template <class Top, bool kTraced>
void RtlEngine::ModelOf<Top, kTraced>::step(CycleRecord& rec) {
  Verilated::threadContextp(ctx_.get());  // a failing assertion reports to the thread's context
  // Show forwarded MPU requests in the waveform before the edge that takes them.
  dump_requests();
  const Top& t = *top_;
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

  count();
  clock();
  note_banks();
}

template <class Top, bool kTraced>
std::uint64_t RtlEngine::ModelOf<Top, kTraced>::clock_until(std::uint64_t max_cycles, bool until_data_taken) {
  Verilated::threadContextp(ctx_.get());  // a failing assertion reports to the thread's context
  dump_requests();
  const Top& t = *top_;
  const bool traced = kTraced && fst_;
  std::uint64_t n = 0;
  while (n < max_cycles && state() == RunState::Running && (!until_data_taken || t.apu2mpu_data_ready)) {
    if (t.dbg_stall_reason == static_cast<std::uint8_t>(Stall::Bank) && !t.dbg_mc_en && !traced) {
      // Waiting for a bank the MPU has not handed over: the MPU acts only
      // between calls, so the inputs stay as they are. Once a clock leaves
      // every bit of the model as it was (the pipelines have drained; the
      // banks change only by a store, and none issues), every further clock
      // would too: the rest of the call's cycles are taken at once.
      backdoor_.snapshot(snapshot_);
      count();
      clock();
      ++n;
      if (n < max_cycles && backdoor_.same_state(snapshot_) && (kTraced || func_->idle())) {
        cycle_ += max_cycles - n;
        cycles_by_[static_cast<unsigned>(Stall::Bank) << 4] += max_cycles - n;
        n = max_cycles;
      }
      continue;
    }
    count();
    clock();
    ++n;
  }
  // Once a call: the MPU's calls that overlap it find no swap in it (none
  // while no hand-over is pending), and the others come after it.
  note_banks();
  return n;
}

// The register as the next word reads it: a result completing in the coming
// cycle is written at its end but already bypassed to that word
// (docs/apu-isa.md, Clarification 2: the state between two steps).
template <class Top, bool kTraced>
std::uint32_t RtlEngine::ModelOf<Top, kTraced>::freg(int i) const {
  const Top& t = *top_;
  i &= 63;
  for (int p = 0; p < kFCompletionPorts; ++p) {
    if (((t.dbg_fc_en >> p) & 1) && static_cast<int>((t.dbg_fc_idx >> (6 * p)) & 63) == i)
      return wide_bits(t.dbg_fc_val, 24 * p, 24);
  }
  return backdoor_.freg_array(i);
}

// ---- RtlEngine: the model its waveform needs ------------------------------------

RtlEngine::RtlEngine(const char* fst_path) {
  if (fst_path)
    model_ = std::make_unique<ModelOf<Vapu_core, true>>(*this, fst_path);
  else
    model_ = std::make_unique<ModelOf<Vapu_fast, false>>(*this, nullptr);
}

RtlEngine::~RtlEngine() = default;

void RtlEngine::write_program(std::uint16_t addr, const Encoded& word) { model_->write_program(addr, word); }
void RtlEngine::write_data(std::uint16_t addr, std::uint32_t value) { model_->write_data(addr, value); }
std::uint32_t RtlEngine::read_data(std::uint16_t addr) const { return model_->read_data(addr); }
void RtlEngine::write_data_block(std::uint16_t addr, const std::uint32_t* values, std::size_t n) {
  model_->write_data_block(addr, values, n);
}
void RtlEngine::read_data_block(std::uint16_t addr, std::uint32_t* out, std::size_t n) const {
  model_->read_data_block(addr, out, n);
}
bool RtlEngine::mpu_bank_while_running() const { return model_->mpu_bank_while_running(); }
void RtlEngine::hand_over_program() { model_->hand_over_program(); }
void RtlEngine::hand_over_data() { model_->hand_over_data(); }
bool RtlEngine::program_ready() const { return model_->program_ready(); }
bool RtlEngine::data_ready() const { return model_->data_ready(); }
void RtlEngine::start(std::uint16_t pc) { model_->start(pc); }
void RtlEngine::step(CycleRecord& rec) { model_->step(rec); }
std::uint64_t RtlEngine::run(std::uint64_t max_cycles) { return model_->run(max_cycles); }
std::uint64_t RtlEngine::run_until_data_taken(std::uint64_t max_cycles) {
  return model_->run_until_data_taken(max_cycles);
}
RunState RtlEngine::state() const { return model_->state(); }
Fault RtlEngine::fault() const { return model_->fault(); }
std::uint64_t RtlEngine::cycle() const { return model_->cycle(); }
std::uint32_t RtlEngine::freg(int i) const { return model_->freg(i); }
std::uint16_t RtlEngine::areg(int i) const { return model_->areg(i); }
std::uint8_t RtlEngine::flags() const { return model_->flags(); }
std::uint8_t RtlEngine::cc() const { return model_->cc(); }
const ApuCounters& RtlEngine::counters() const { return model_->counters(); }
void RtlEngine::trace_window(std::uint64_t from_ps, std::uint64_t to_ps) { model_->trace_window(from_ps, to_ps); }
void RtlEngine::trace_kernel(int bank, std::uint16_t id) { model_->trace_kernel(bank, id); }
void RtlEngine::trace_mpu(std::function<MpuTraceInputs(std::uint64_t ps)> source) {
  model_->trace_mpu(std::move(source));
}
bool RtlEngine::unit_mismatch() const { return model_->unit_mismatch(); }

}  // namespace mc1::apu
