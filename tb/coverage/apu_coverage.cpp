// APU core coverage (apu_coverage.hpp).
#include "apu_coverage.hpp"

namespace mc1::cov {

namespace {

using namespace mc1::apu;

const char* const kFFrom[] = {"mul", "add", "func", "trig", "ld", "movaf-lif"};
const char* const kFTo[] = {"m.a", "m.b", "a.a", "a.b", "f.a", "d.st", "i.movfa"};
const char* const kStates[] = {"idle", "running", "waiting", "halted", "faulted"};

bool conditional(SeqOp op) { return op >= SeqOp::Bcc && op <= SeqOp::Bltz; }
bool two_operand(AddOp op) { return op == AddOp::Add || op == AddOp::Sub || op == AddOp::Cmp; }
bool reads_s(IntOp op) { return op != IntOp::None && op != IntOp::Li && op != IntOp::Movfa && op != IntOp::Lif; }
bool reads_t(IntOp op) { return op == IntOp::Add || op == IntOp::Sub || op == IntOp::Xor; }
bool writes_f(IntOp op) { return op == IntOp::Movaf || op == IntOp::Lif; }
bool reads_areg(SeqOp op) { return op >= SeqOp::Dbnz && op <= SeqOp::Bltz; }

fp24::Op add_op(AddOp op) {
  switch (op) {
    case AddOp::Sub: return fp24::Op::Sub;
    case AddOp::Cmp: return fp24::Op::Cmp;
    case AddOp::Float: return fp24::Op::Float;
    case AddOp::Fix: return fp24::Op::Fix;
    case AddOp::Neg: return fp24::Op::Neg;
    case AddOp::Abs: return fp24::Op::Abs;
    default: return fp24::Op::Add;
  }
}

fp24::Op func_op(FuncOp op) {
  switch (op) {
    case FuncOp::Sqrt: return fp24::Op::Sqrt;
    case FuncOp::Sin: return fp24::Op::Sin;
    case FuncOp::Cos: return fp24::Op::Cos;
    default: return fp24::Op::Recip;
  }
}

std::string slots_name(const MicroWord& w) {
  std::string s = "------";
  if (w.m.en) s[0] = 'M';
  if (w.a.en) s[1] = 'A';
  if (w.f.en) s[2] = 'F';
  if (w.d.op != MemOp::None) s[3] = 'D';
  if (w.i.op != IntOp::None) s[4] = 'I';
  if (w.s.op != SeqOp::Next) s[5] = 'S';
  return "core.slots." + s;
}

}  // namespace

ApuCoverage::ApuCoverage() { declare(); }

void ApuCoverage::declare() {
  bins_.declare("core.op.m.mul");
  for (int k = 0; k < 8; ++k) bins_.declare(std::string("core.op.a.") + mnemonic(static_cast<AddOp>(k)));
  for (int k = 0; k < 4; ++k) bins_.declare(std::string("core.op.f.") + mnemonic(static_cast<FuncOp>(k)));
  for (int k = 1; k < 4; ++k) bins_.declare(std::string("core.op.d.") + mnemonic(static_cast<MemOp>(k)));
  for (int k = 1; k < 16; ++k) bins_.declare(std::string("core.op.i.") + mnemonic(static_cast<IntOp>(k)));
  for (int k = 1; k < 16; ++k) bins_.declare(std::string("core.op.s.") + mnemonic(static_cast<SeqOp>(k)));
  for (int mask = 0; mask < 64; ++mask) {
    std::string s = "------";
    for (int b = 0; b < 6; ++b)
      if (mask >> b & 1) s[b] = "MAFDIS"[b];
    bins_.declare("core.slots." + s);
  }
  for (int k = 1; k < kStallKinds; ++k) bins_.declare(std::string("core.stall.") + stall_name(static_cast<Stall>(k)));
  for (const char* from : kFFrom)
    for (const char* to : kFTo) bins_.declare(std::string("core.bypass.") + from + "." + to);
  for (const char* to : {"d.base", "i.src", "s.reg"}) bins_.declare(std::string("core.bypass.int.") + to);
  for (const char* to : {"bcc", "bncc"}) bins_.declare(std::string("core.bypass.cmp.") + to);
  for (int k = 1; k <= 5; ++k) bins_.declare(std::string("core.fault.") + fault_name(static_cast<Fault>(k)));
  bins_.declare("core.end.halt");
  for (int k = 2; k <= 7; ++k)
    for (const char* way : {"taken", "not-taken"})
      bins_.declare(std::string("core.branch.") + mnemonic(static_cast<SeqOp>(k)) + "." + way);
  for (const char* bank : {"data", "program"}) {
    for (const char* st : kStates) bins_.declare(std::string("core.handover.") + bank + "." + st);
    for (const char* how : {"ready", "waited"}) bins_.declare(std::string("core.swap.") + bank + "." + how);
  }
}

void ApuCoverage::start() {
  for (auto& v : f_vis_) v = 0;
  for (auto& v : a_vis_) v = 0;
  cc_vis_ = 0;
  branch_ = {};
  last_stall_ = Stall::None;
  waited_ = false;
}

void ApuCoverage::before_cycle(const Iss& iss) {
  for (int i = 0; i < kNumFRegs; ++i) f_[i] = iss.freg(i);
}

void ApuCoverage::after_cycle(const Iss& iss, const CycleRecord& rec) {
  if (rec.stall != Stall::None) bins_.hit(std::string("core.stall.") + stall_name(rec.stall));
  if (rec.issued) {
    const MicroWord w = MicroWord::decode(iss.program_word(rec.psel, rec.pc));
    branch_outcome(rec);
    issued(w, rec);
    waited_ = false;
  } else if (rec.stall == Stall::Bank) {
    waited_ = true;
  }
  last_stall_ = rec.stall;
}

// A conditional branch's way: the next word that issues is its target, or
// the word after it (a branch to the word after it goes both ways at once: not counted).
void ApuCoverage::branch_outcome(const CycleRecord& rec) {
  if (!branch_.pending) return;
  branch_.pending = false;
  const auto next = static_cast<std::uint16_t>(branch_.pc + 1);
  if (branch_.target == next) return;
  const std::string p = std::string("core.branch.") + mnemonic(branch_.op);
  if (rec.pc == branch_.target) bins_.hit(p + ".taken");
  else if (rec.pc == next) bins_.hit(p + ".not-taken");
}

void ApuCoverage::issued(const MicroWord& w, const CycleRecord& rec) {
  bins_.hit(slots_name(w));
  if (w.m.en) bins_.hit("core.op.m.mul");
  if (w.a.en) bins_.hit(std::string("core.op.a.") + mnemonic(w.a.op));
  if (w.f.en) bins_.hit(std::string("core.op.f.") + mnemonic(w.f.op));
  if (w.d.op != MemOp::None) bins_.hit(std::string("core.op.d.") + mnemonic(w.d.op));
  if (w.i.op != IntOp::None) bins_.hit(std::string("core.op.i.") + mnemonic(w.i.op));
  if (w.s.op != SeqOp::Next) bins_.hit(std::string("core.op.s.") + mnemonic(w.s.op));
  if (w.s.op == SeqOp::Swapd || w.s.op == SeqOp::Swapp)
    bins_.hit(std::string("core.swap.") + (w.s.op == SeqOp::Swapd ? "data" : "program") +
              (waited_ ? ".waited" : ".ready"));
  if (conditional(w.s.op)) branch_ = {true, w.s.op, rec.pc, w.s.target};
  reads(w, rec.cycle);
  writes(w, rec.cycle);
  units(w);
}

// Sources read in the cycle their result becomes usable: bypassed.
void ApuCoverage::reads(const MicroWord& w, std::uint64_t t) {
  auto f = [&](std::uint8_t r, int to) {
    r &= 63;
    if (f_vis_[r] == t && f_from_[r]) bins_.hit(std::string("core.bypass.") + f_from_[r] + "." + kFTo[to]);
  };
  auto a = [&](std::uint8_t r, const char* to) {
    if (a_vis_[r & 15] == t) bins_.hit(std::string("core.bypass.int.") + to);
  };
  if (w.m.en) f(w.m.a, 0), f(w.m.b, 1);
  if (w.a.en) {
    f(w.a.a, 2);
    if (two_operand(w.a.op)) f(w.a.b, 3);
  }
  if (w.f.en) f(w.f.a, 4);
  if (w.d.op == MemOp::St) f(w.d.f, 5);
  if (w.i.op == IntOp::Movfa) f(static_cast<std::uint8_t>(w.i.imm), 6);
  if (w.d.op != MemOp::None && w.d.base != 0) a(w.d.base, "d.base");
  if (reads_s(w.i.op)) a(w.i.s, "i.src");
  if (reads_t(w.i.op)) a(w.i.t, "i.src");
  if (reads_areg(w.s.op)) a(w.s.r, "s.reg");
  if ((w.s.op == SeqOp::Bcc || w.s.op == SeqOp::Bncc) && cc_vis_ == t)
    bins_.hit(std::string("core.bypass.cmp.") + mnemonic(w.s.op));
}

void ApuCoverage::writes(const MicroWord& w, std::uint64_t t) {
  auto f = [&](std::uint8_t r, int lat, int from) {
    f_vis_[r & 63] = t + static_cast<std::uint64_t>(lat);
    f_from_[r & 63] = kFFrom[from];
  };
  if (w.m.en) f(w.m.d, kMulLatency, 0);
  if (w.a.en && w.a.op == AddOp::Cmp) cc_vis_ = t + kAddLatency;
  else if (w.a.en) f(w.a.d, kAddLatency, 1);
  if (w.f.en) {
    const bool trig = w.f.op == FuncOp::Sin || w.f.op == FuncOp::Cos;
    f(w.f.d, trig ? kTrigLatency : kFuncLatency, trig ? 3 : 2);
  }
  if (w.d.op == MemOp::Ld) f(w.d.f, kLoadLatency, 4);
  if (writes_f(w.i.op)) f(w.i.d, kLoadLatency, 5);
  else if (w.i.op != IntOp::None) a_vis_[w.i.d & 15] = t + kIntLatency;
  if (w.s.op == SeqOp::Dbnz) a_vis_[w.s.r & 15] = t + kIntLatency;
}

// The FP24 ops the word's units executed, with the operands they read.
void ApuCoverage::units(const MicroWord& w) {
  if (w.m.en) fp24_.sample(fp24::Op::Mul, f_[w.m.a & 63], f_[w.m.b & 63]);
  if (w.a.en && !is_reserved(w.a.op))
    fp24_.sample(add_op(w.a.op), f_[w.a.a & 63], two_operand(w.a.op) ? f_[w.a.b & 63] : 0);
  if (w.f.en) fp24_.sample(func_op(w.f.op), f_[w.f.a & 63]);
}

void ApuCoverage::handover(bool program, RunState state, bool waiting) {
  int k = 0;
  switch (state) {
    case RunState::Idle: k = 0; break;
    case RunState::Running: k = waiting ? 2 : 1; break;
    case RunState::Halted: k = 3; break;
    case RunState::Faulted: k = 4; break;
  }
  bins_.hit(std::string("core.handover.") + (program ? "program." : "data.") + kStates[k]);
}

void ApuCoverage::end(const Iss& iss, const CycleRecord& last) {
  if (iss.state() == RunState::Halted) bins_.hit("core.end.halt");
  if (iss.state() != RunState::Faulted) return;
  bins_.hit(std::string("core.fault.") + fault_name(iss.fault()));
  if (iss.fault() != Fault::ReservedOp) return;
  // The reserved codes of the word that faulted (it did not issue).
  const MicroWord w = MicroWord::decode(iss.program_word(iss.psel(), iss.pc()));
  if (w.a.en && is_reserved(w.a.op)) bins_.hit(std::string("core.op.a.") + mnemonic(w.a.op));
  if (is_reserved(w.d.op)) bins_.hit(std::string("core.op.d.") + mnemonic(w.d.op));
  if (is_reserved(w.i.op)) bins_.hit(std::string("core.op.i.") + mnemonic(w.i.op));
  if (is_reserved(w.s.op)) bins_.hit(std::string("core.op.s.") + mnemonic(w.s.op));
  (void)last;
}

}  // namespace mc1::cov
