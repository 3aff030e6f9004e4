// Verilated-RTL harness: clocking, issue and the timing checks of
// docs/fp24-rtl.md, shared by the per-unit fast models and the traced
// all-units model.
#include "fp24_rtl.hpp"

#include <array>
#include <cstdio>

#include "Vfp24_add.h"
#include "Vfp24_func.h"
#include "Vfp24_mul.h"
#include "Vfp24_units.h"
#include "rtl_coverage.hpp"
#include "verilated.h"
#include "verilated_context.hpp"
#include "verilated_fst_c.h"

namespace mc1::fp24::tb {
namespace {

constexpr int kUnits = 3;

int unit_index(Unit u) { return static_cast<int>(u); }

// Operands as the vector interface writes them (fp24-run can replay them).
std::string hex(Bits v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%06x", v);
  return buf;
}

// One result port: valid, result, flags.
struct OutPins {
  CData* valid;
  IData* result;
  CData* flags;
};

// Pointers to one unit's ports inside a verilated model. in_op is null for
// units without it; trig (the function unit's SIN/COS result port) has null
// pointers on the other units.
struct Pins {
  CData* in_valid;
  CData* in_op;
  IData* in_a;
  IData* in_b;
  OutPins out;
  OutPins trig;
};

// The function unit returns SIN/COS on a port of their own, with a latency
// of their own: a RECIP/SQRT issued after a SIN/COS finishes before it or in
// the same cycle (docs/fp24-rtl.md).
bool trig_port(Op op) { return op == Op::Sin || op == Op::Cos; }

// One unit's issue port and its in-flight ops, one list per result port
// (each port's results come in its own issue order). The lists are fixed
// rings: a unit can hold at most a few ops, and the hot loop must not
// allocate.
class Lane {
 public:
  // A result collected on one edge; a unit yields at most two per edge.
  struct Done {
    Result r;
    std::size_t tag;
    Timing t;
  };
  static constexpr int kMaxDone = 2;

  Lane(Unit unit, Pins pins) : unit_(unit), pins_(pins) {}

  // May an op be issued on `edge`? The initiation interval of the op table.
  bool ready(std::uint64_t edge) const { return edge >= next_issue_; }

  void drive_idle() { *pins_.in_valid = 0; }

  void drive(const Issue& op, std::size_t tag, std::uint64_t edge) {
    const OpInfo& info = fp24::info(op.op);
    *pins_.in_valid = 1;
    if (pins_.in_op != nullptr) *pins_.in_op = info.rtl_code;
    *pins_.in_a = op.a & 0xFFFFFF;
    *pins_.in_b = op.b & 0xFFFFFF;
    Ring& q = rings_[trig_port(op.op) ? 1 : 0];
    if (q.count == q.slot.size()) throw TimingError("fp24 " + unit_name() + " unit: too many ops in flight");
    q.slot[(q.head + q.count++) % q.slot.size()] = {op, tag, edge, edge + std::uint64_t(info.latency)};
    next_issue_ = edge + std::uint64_t(info.interval);
  }

  // Called after the posedge of `edge`: the outputs now hold what a consumer
  // samples on edge + 1. Fills done[0..n) with the results there, in issue
  // order, and returns n.
  int collect(std::uint64_t edge, Done* done) {
    const std::uint64_t sample = edge + 1;
    bool taken[2] = {false, false};  // out, trig
    int n = 0;
    // Each ring is in issue order, and so (one latency per port) in order of
    // due edge.
    for (int port = 0; port < 2; ++port) {
      Ring& q = rings_[port];
      while (q.count > 0 && q.slot[q.head].due <= sample) {
        const InFlight& f = q.slot[q.head];
        const OutPins& p = port ? pins_.trig : pins_.out;
        if (*p.valid == 0 || taken[port]) throw late(f);
        taken[port] = true;
        done[n++] = {{*p.result, *p.flags}, f.tag, {f.issue_edge, sample}};
        q.head = (q.head + 1) % q.slot.size();
        --q.count;
      }
    }
    check_idle(pins_.out, taken[0], sample, false);
    if (pins_.trig.valid != nullptr) check_idle(pins_.trig, taken[1], sample, true);
    return n;
  }

  bool busy() const { return rings_[0].count > 0 || rings_[1].count > 0; }

 private:
  struct InFlight {
    Issue op;
    std::size_t tag;
    std::uint64_t issue_edge;
    std::uint64_t due;  // edge on which the result must be sampled
  };

  // A port whose valid is up must have delivered a result due now.
  void check_idle(const OutPins& p, bool taken, std::uint64_t sample, bool trig) const {
    if (taken || *p.valid == 0) return;
    const Ring& q = rings_[trig ? 1 : 0];
    if (q.count > 0) throw TimingError(describe(q.slot[q.head]) + " arrived on edge " + std::to_string(sample));
    throw TimingError("fp24 " + unit_name() + " unit: " + (trig ? "out_trig_valid" : "out_valid") + " on edge " +
                      std::to_string(sample) + " with no op in flight");
  }

  std::string unit_name() const {
    static const char* const kNames[] = {"multiplier", "adder", "function"};
    return kNames[unit_index(unit_)];
  }

  std::string describe(const InFlight& f) const {
    return "fp24 " + unit_name() + " unit: " + std::string(info(f.op.op).name) + " " + hex(f.op.a) + " " +
           hex(f.op.b) + " issued on edge " + std::to_string(f.issue_edge) + ", due on edge " + std::to_string(f.due) +
           " (latency " + std::to_string(info(f.op.op).latency) + "),";
  }

  TimingError late(const InFlight& f) const { return TimingError(describe(f) + " did not arrive"); }

  Unit unit_;
  Pins pins_;
  struct Ring {
    std::array<InFlight, 16> slot{};  // > every latency
    std::size_t head = 0;
    std::size_t count = 0;
  };
  std::array<Ring, 2> rings_{};  // out, trig
  std::uint64_t next_issue_ = 0;
};

template <class Model>
Pins unit_pins(Model& m) {
  Pins p{&m.in_valid, nullptr, &m.in_a, &m.in_b, {&m.out_valid, &m.out_result, &m.out_flags}, {}};
  if constexpr (std::is_same_v<Model, Vfp24_add> || std::is_same_v<Model, Vfp24_func>) p.in_op = &m.in_op;
  if constexpr (std::is_same_v<Model, Vfp24_func>) p.trig = {&m.out_trig_valid, &m.out_trig_result, &m.out_trig_flags};
  return p;
}

std::array<Pins, kUnits> units_pins(Vfp24_units& m) {
  return {{
      {&m.mul_in_valid, nullptr, &m.mul_in_a, &m.mul_in_b, {&m.mul_out_valid, &m.mul_out_result, &m.mul_out_flags},
       {}},
      {&m.add_in_valid, &m.add_in_op, &m.add_in_a, &m.add_in_b,
       {&m.add_out_valid, &m.add_out_result, &m.add_out_flags}, {}},
      {&m.func_in_valid, &m.func_in_op, &m.func_in_a, &m.func_in_b,
       {&m.func_out_valid, &m.func_out_result, &m.func_out_flags},
       {&m.func_out_trig_valid, &m.func_out_trig_result, &m.func_out_trig_flags}},
  }};
}

// A verilated model with its own context, clocked one edge pair at a time:
// inputs are set while clk is low, then one eval per clock edge.
template <class Model>
class Clocked {
 public:
  Clocked() : ctx_(mc1::rtl::new_context()), model_(std::make_unique<Model>(ctx_.get(), "TOP")) {
    // A failing assertion ($error) must not abort: posedge() throws.
    ctx_->fatalOnError(false);
  }

  // The calling thread's Verilator context is this model's, so that a
  // failing assertion reports here (once per run, not per edge).
  void bind() { Verilated::threadContextp(ctx_.get()); }

  Model& model() { return *model_; }
  VerilatedContext& context() { return *ctx_; }

  // Holds rst_n low for two edges (it is synchronous) with nothing issued.
  template <class Idle>
  void reset(Idle idle) {
    bind();
    idle();
    model_->rst_n = 0;
    for (int i = 0; i < 2; ++i) posedge_then_negedge();
    model_->rst_n = 1;
  }

  // The rising edge and its eval; outputs then show the new state.
  void posedge() {
    model_->clk = 1;
    model_->eval();
    if (__builtin_expect(ctx_->gotError(), 0)) {
      std::fflush(stdout);  // Verilator's message first
      throw RtlAssertionError("fp24 RTL: an assertion failed at clock edge " + std::to_string(cycles_) +
                              " (reset edges included; the rule: Verilator's \"APU_ASSERT <Name> failed in <instance>\" "
                              "on standard output)");
    }
    dump(kHalfPeriod);
  }

  // The falling edge: nothing is clocked on it, but the model must see clk
  // low to detect the next rising edge.
  void negedge() {
    model_->clk = 0;
    model_->eval();
    dump(2 * kHalfPeriod);
    ++cycles_;
  }

  void posedge_then_negedge() {
    posedge();
    negedge();
  }

  void trace_to(const std::string& path) {
    if constexpr (std::is_same_v<Model, Vfp24_units>) {
      ctx_->traceEverOn(true);
      fst_ = std::make_unique<VerilatedFstC>();
      model_->trace(fst_.get(), 99);
      fst_->open(path.c_str());
      if (!fst_->isOpen()) throw std::runtime_error(path + ": cannot open for writing");
      model_->clk = 0;
      model_->eval();
      fst_->dump(0);
    }
  }

  ~Clocked() {
    // The model's scopes are erased from the thread's current context, which
    // must be this one (~RtlEngine in hw/apu_rtl_engine/apu_rtl_engine.cpp says why).
    Verilated::threadContextp(ctx_.get());
    if (fst_) fst_->close();
    model_->final();
    mc1::rtl_coverage::collect(*ctx_);  // a coverage build's counts (apu_rtl/rtl_coverage.hpp)
  }

 private:
  // 4 MHz APU clock: 250 ns per cycle, in the trace's unit (Verilator's
  // default time precision, 1 ps).
  static constexpr std::uint64_t kHalfPeriod = 125000;

  void dump(std::uint64_t offset) {
    if (fst_) fst_->dump(cycles_ * 2 * kHalfPeriod + offset);
  }

  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<VerilatedFstC> fst_;
  std::uint64_t cycles_ = 0;
};

}  // namespace

// ---- RtlUnit -----------------------------------------------------------------

struct RtlUnit::Impl {
  virtual ~Impl() = default;
  virtual void run(Op op, const Bits* a, const Bits* b, Result* out, std::size_t n) = 0;
  std::uint64_t edge = 0;
};

namespace {

template <class Model>
class UnitImpl final : public RtlUnit::Impl {
 public:
  UnitImpl(Unit unit) : lane_(unit, unit_pins(clk_.model())) {
    clk_.reset([this] { lane_.drive_idle(); });
  }

  // The hot loop: per cycle, set the inputs, one eval per edge, read the
  // outputs. Nothing here allocates.
  void run(Op op, const Bits* a, const Bits* b, Result* out, std::size_t n) override {
    std::size_t issued = 0, done = 0;
    Lane::Done d[Lane::kMaxDone];
    clk_.bind();
    while (done < n) {
      if (issued < n && lane_.ready(edge)) {
        lane_.drive({op, a[issued], b != nullptr ? b[issued] : 0}, issued, edge);
        ++issued;
      } else {
        lane_.drive_idle();
      }
      clk_.posedge();
      const int k = lane_.collect(edge, d);
      for (int i = 0; i < k; ++i) out[d[i].tag] = d[i].r;
      done += std::size_t(k);
      clk_.negedge();
      ++edge;
    }
  }

 private:
  Clocked<Model> clk_;
  Lane lane_;
};

}  // namespace

RtlUnit::RtlUnit(Unit unit) {
  switch (unit) {
    case Unit::Mul: impl_ = std::make_unique<UnitImpl<Vfp24_mul>>(unit); break;
    case Unit::Adder: impl_ = std::make_unique<UnitImpl<Vfp24_add>>(unit); break;
    case Unit::Func: impl_ = std::make_unique<UnitImpl<Vfp24_func>>(unit); break;
  }
}

RtlUnit::~RtlUnit() = default;

void RtlUnit::run(Op op, const Bits* a, const Bits* b, Result* out, std::size_t n) { impl_->run(op, a, b, out, n); }

std::uint64_t RtlUnit::edges() const { return impl_->edge; }

// ---- RtlUnits ----------------------------------------------------------------

struct RtlUnits::Impl {
  Clocked<Vfp24_units> clk;
  std::array<Pins, kUnits> pins = units_pins(clk.model());
  std::array<Lane, kUnits> lanes = {{{Unit::Mul, pins[0]}, {Unit::Adder, pins[1]}, {Unit::Func, pins[2]}}};
  std::uint64_t edge = 0;

  void idle() {
    for (Lane& l : lanes) l.drive_idle();
  }
};

RtlUnits::RtlUnits(const std::string& fst_path) : impl_(std::make_unique<Impl>()) {
  if (!fst_path.empty()) impl_->clk.trace_to(fst_path);
  impl_->clk.reset([this] { impl_->idle(); });
}

RtlUnits::~RtlUnits() = default;

std::uint64_t RtlUnits::edges() const { return impl_->edge; }

std::vector<Result> RtlUnits::run(const std::vector<Issue>& ops, const IssuePattern& pattern,
                                  std::vector<Timing>* timing) {
  // A unit that always idles would never finish.
  if (!(pattern.bubble >= 0.0 && pattern.bubble < 1.0))
    throw std::invalid_argument("IssuePattern::bubble must be in [0, 1), not " + std::to_string(pattern.bubble));
  Impl& m = *impl_;
  // Each unit's queue: indices into ops, in order.
  std::array<std::vector<std::size_t>, kUnits> queue;
  for (std::size_t i = 0; i < ops.size(); ++i) queue[unit_index(info(ops[i].op).unit)].push_back(i);
  std::array<std::size_t, kUnits> next{};
  std::vector<Result> results(ops.size());
  if (timing != nullptr) timing->assign(ops.size(), Timing{});
  std::mt19937 rng(pattern.seed);
  std::bernoulli_distribution bubble(pattern.bubble);

  std::size_t done = 0;
  m.clk.bind();
  while (done < ops.size()) {
    for (int u = 0; u < kUnits; ++u) {
      const bool waiting = next[u] < queue[u].size();
      if (waiting && m.lanes[u].ready(m.edge) && !bubble(rng)) {
        const std::size_t i = queue[u][next[u]++];
        m.lanes[u].drive(ops[i], i, m.edge);
      } else {
        m.lanes[u].drive_idle();
      }
    }
    m.clk.posedge();
    for (Lane& lane : m.lanes) {
      Lane::Done d[Lane::kMaxDone];
      const int k = lane.collect(m.edge, d);
      for (int i = 0; i < k; ++i) {
        results[d[i].tag] = d[i].r;
        if (timing != nullptr) (*timing)[d[i].tag] = d[i].t;
      }
      done += std::size_t(k);
    }
    m.clk.negedge();
    ++m.edge;
  }
  return results;
}

}  // namespace mc1::fp24::tb
