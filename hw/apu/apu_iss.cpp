// The APU instruction-set simulator (docs/apu-isa.md, "Timing" and
// "Clarifications"). Per-cycle work is a few mask tests and, on issue, the
// FP24 model calls; nothing allocates once a CycleRecord has its capacity.
#include "apu_iss.hpp"

#include <algorithm>

#include "fp24.hpp"
#include "fp24_arith_inline.hpp"

namespace mc1::apu {

namespace {

constexpr std::uint64_t bit(unsigned r) { return std::uint64_t{1} << (r & 63); }
constexpr std::uint32_t kMask24 = 0xFFFFFF;
constexpr int kNoCommit = -1;

#define MC1_HOT inline __attribute__((always_inline))

bool two_operand(AddOp op) { return op == AddOp::Add || op == AddOp::Sub || op == AddOp::Cmp; }

// A word's shape: M enabled (bit 0), the A slot (bits 1-2: none, ADD, SUB,
// another op), F enabled (bit 3), the D slot (bits 4-5: none, LD, ST).
// Reserved ops fault and never issue: their slot counts as empty.
int shape_of(const MicroWord& w) {
  int a = 0;
  if (w.a.en) a = w.a.op == AddOp::Add ? 1 : w.a.op == AddOp::Sub ? 2 : 3;
  const int d = w.d.op == MemOp::Ld ? 1 : w.d.op == MemOp::St ? 2 : 0;
  return (w.m.en ? 1 : 0) | a << 1 | (w.f.en ? 8 : 0) | d << 4;
}

// The checks an S-slot op needs (DecodedWord::kind bits).
std::uint8_t seq_kind(SeqOp op) {
  switch (op) {
    case SeqOp::Swapd: return DecodedWord::kSwap;
    case SeqOp::Swapp: return DecodedWord::kSwap | DecodedWord::kRefetch;
    case SeqOp::Bcc:
    case SeqOp::Bncc: return DecodedWord::kCcBranch | DecodedWord::kRefetch;
    case SeqOp::Dbnz:
    case SeqOp::Bz:
    case SeqOp::Bnz:
    case SeqOp::Bltz: return DecodedWord::kRefetch;
    case SeqOp::Halt: return DecodedWord::kHalt;
    case SeqOp::Call:
    case SeqOp::Ret: return DecodedWord::kStack;
    default: return is_reserved(op) ? DecodedWord::kReserved : 0;
  }
}

}  // namespace

DecodedWord DecodedWord::from(const Encoded& e, std::uint32_t addr) {
  DecodedWord d;
  d.w = MicroWord::decode(e);
  const MicroWord& w = d.w;
  std::uint64_t dst = 0;
  const auto write = [&d, &dst](unsigned reg, int latency) {
    dst |= bit(reg);
    d.dsts[d.ndst++] = {static_cast<std::uint8_t>(reg & 63), static_cast<std::uint8_t>(latency)};
  };
  if (w.m.en) {
    d.src |= bit(w.m.a) | bit(w.m.b);
    write(w.m.d, kMulLatency);
  }
  if (w.a.en) {
    if (is_reserved(w.a.op)) {
      d.kind |= kReserved;
    } else {
      d.lat_a = static_cast<std::uint8_t>(latency(w.a.op));
      d.src |= bit(w.a.a) | (two_operand(w.a.op) ? bit(w.a.b) : 0);
      if (w.a.op != AddOp::Cmp) write(w.a.d, d.lat_a);
    }
  }
  if (w.f.en) {
    d.lat_f = static_cast<std::uint8_t>(latency(w.f.op));
    d.src |= bit(w.f.a);
    write(w.f.d, d.lat_f);
  }
  switch (w.d.op) {
    case MemOp::Ld:
      write(w.d.f, kLoadLatency);
      d.kind |= kMem;
      break;
    case MemOp::St:
      d.src |= bit(w.d.f);
      d.kind |= kMem;
      break;
    case MemOp::None: break;
    case MemOp::Reserved: d.kind |= kReserved | kMem; break;
  }
  switch (w.i.op) {
    case IntOp::Movaf:
    case IntOp::Lif:
      write(w.i.d, kLoadLatency);
      d.kind |= kMovF;
      break;
    case IntOp::Movfa: d.src |= bit(w.i.imm); break;
    case IntOp::Reserved: d.kind |= kReserved; break;
    default: break;
  }
  d.kind |= seq_kind(w.s.op);
  d.hazard = d.src | dst;
  d.shape = static_cast<std::uint8_t>(shape_of(w));
  const std::uint32_t next = w.s.op == SeqOp::Jmp ? w.s.target : addr + 1;
  constexpr std::uint8_t kNotPlain = kMayStall | kReserved | kStack | kRefetch;
  d.plain = (w.s.op == SeqOp::Next || w.s.op == SeqOp::Jmp) && !(d.kind & kNotPlain) && next < kProgramWords;
  d.next = static_cast<std::uint16_t>(next);
  return d;
}

const std::array<Iss::RunIssue, Iss::kShapes> Iss::kRunIssue =
    Iss::run_issue_table(std::make_integer_sequence<int, Iss::kShapes>{});
const std::array<Iss::PlainCycle, Iss::kShapes> Iss::kPlainCycle =
    Iss::plain_cycle_table(std::make_integer_sequence<int, Iss::kShapes>{});

void Iss::reset() {
  f_.fill(0);
  a_.fill(0);
  cc_ = flags_ = 0;
  pc_ = 0;
  stack_.fill(0);
  sp_ = 0;
  psel_ = dsel_ = 0;
  program_ready_ = data_ready_ = false;
  state_ = RunState::Idle;
  fault_ = Fault::None;
  cycle_ = 0;
  fetching_ = 0;
  for (int b = 0; b < 2; ++b) {
    program_[b].fill(Encoded{});
    for (int i = 0; i < kProgramWords; ++i) decoded_[b][i] = DecodedWord::from(Encoded{}, i);
    data_[b].fill(0);
  }
  ring_.fill(Bucket{});
  for (BodyBank& bb : body_) bb.stale = true;
  pending_ = 0;
  land_.fill(0);
  cmp_done_ = 0;
  ring_last_ = 0;
  counters_ = Counters{};
}

void Iss::write_program(std::uint16_t addr, const Encoded& word) {
  const int bank = psel_ ^ 1;
  addr %= kProgramWords;
  program_[bank][addr] = word;
  decoded_[bank][addr] = DecodedWord::from(word, addr);
  body_[bank].stale = true;
}

void Iss::write_data(std::uint16_t addr, std::uint32_t value) {
  data_[dsel_ ^ 1][addr % kDataWords] = value & kMask24;
}

std::uint32_t Iss::read_data(std::uint16_t addr) const { return data_[dsel_ ^ 1][addr % kDataWords]; }

// A block within the bank (the driver's calls always are) is a plain loop
// the compiler vectorizes; one that wraps goes word by word.
void Iss::write_data_block(std::uint16_t addr, const std::uint32_t* values, std::size_t n) {
  auto& bank = data_[dsel_ ^ 1];
  if (addr + n <= static_cast<std::size_t>(kDataWords)) {
    std::uint32_t* out = bank.data() + addr;
    for (std::size_t i = 0; i < n; ++i) out[i] = values[i] & kMask24;
    return;
  }
  for (std::size_t i = 0; i < n; ++i) bank[(addr + i) % kDataWords] = values[i] & kMask24;
}

void Iss::read_data_block(std::uint16_t addr, std::uint32_t* out, std::size_t n) const {
  const auto& bank = data_[dsel_ ^ 1];
  if (addr + n <= static_cast<std::size_t>(kDataWords)) {
    std::copy_n(bank.data() + addr, n, out);
    return;
  }
  for (std::size_t i = 0; i < n; ++i) out[i] = bank[(addr + i) % kDataWords];
}

void Iss::start(std::uint16_t pc) {
  if (state_ == RunState::Running) return;  // only an idle APU starts (Clarification 8)
  if (program_ready_) {
    psel_ ^= 1;
    program_ready_ = false;
  }
  sp_ = 0;
  fault_ = Fault::None;
  pc_ = pc % kProgramWords;
  state_ = RunState::Running;
  fetching_ = kStartFetchCycles;
}

// kEarly (run's cycles): the register takes the value at once, the bucket
// keeps the one it replaces. No word can see it before it lands: a reader
// stalls (raw) while it is in flight, and the word's own reads come first.
template <bool kEarly>
MC1_HOT std::uint64_t Iss::push_f(FSlot slot, int latency, std::uint32_t index, std::uint32_t value,
                                  std::uint32_t flags, std::uint64_t pending) {
  const std::uint64_t at = cycle_ + latency;
  Bucket& b = ring_[at % kRing];
  if constexpr (kEarly) {
    b.f[slot] = {index, value, f_[index]};
    f_[index] = value;
  } else {
    b.f[slot] = {index, value, 0};
  }
  b.slots |= 1u << slot;
  b.flags |= flags;
  ring_last_ = std::max(ring_last_, at);
  // This write lands after any other to its register (waw): the bucket of
  // one still in flight no longer clears the register from the scoreboard.
  const std::uint64_t m = bit(index);
  if (__builtin_expect((pending & m) != 0, 0)) ring_[land_[index] % kRing].last &= ~m;
  b.last |= m;
  land_[index] = at;
  return m;
}

MC1_HOT void Iss::push_a(ASlot slot, int latency, std::uint32_t index, std::uint16_t value) {
  if (index == 0) return;  // A0 reads 0; writes to it are dropped
  Bucket& b = ring_[(cycle_ + latency) % kRing];
  b.a[slot] = {index, value};
  b.slots |= 1u << (kASlotShift + slot);
  ring_last_ = std::max<std::uint64_t>(ring_last_, cycle_ + latency);
}

// End of a cycle: the writes that become visible in the next cycle enter the
// state now, so that between two steps the state is the one the next word
// reads (as in the RTL, where they are written at the clock edge). kKeep:
// the bucket stays for the next step to record (take_due retires it);
// otherwise (run's cycles but its last) it is retired at once. kEarly: the
// F registers have their values already (push_f).
template <bool kKeep, bool kEarly>
MC1_HOT void Iss::apply_next() {
  Bucket& b = ring_[cycle_ % kRing];
  if (b.slots) {
    if constexpr (!kEarly) {
      for (std::uint32_t m = b.slots & kFSlotMask; m != 0; m &= m - 1) {
        const FWrite& w = b.f[__builtin_ctz(m)];
        f_[w.index] = w.value;
      }
    }
    pending_ &= ~b.last;
    b.last = 0;
    for (std::uint32_t m = b.slots >> kASlotShift & 3; m != 0; m &= m - 1) {
      const AWrite& w = b.a[__builtin_ctz(m)];
      a_[w.index] = static_cast<std::uint16_t>(w.value);
    }
    if (b.slots & kCcSlot) cc_ = b.cc;
    const std::uint32_t new_flags = flags_ | b.flags;
    if constexpr (kKeep) {
      b.flags_commit = new_flags != flags_;
      b.flags = new_flags;
    } else {
      b.slots = 0;
      b.flags = 0;
    }
    flags_ = new_flags;
  }
}

// Start of a cycle: records (kRecord) and retires the writes applied at the
// end of the last one. CC and FLAGS come back through cc/flags (recorded
// after any store of this cycle).
template <bool kRecord>
MC1_HOT void Iss::take_due(CycleRecord* rec, int& cc, int& flags) {
  Bucket& b = ring_[cycle_ % kRing];
  if (b.slots) {
    if constexpr (kRecord) {
      // Commits in the interface's order: FReg by index, then AReg by index.
      auto& out = rec->commits;
      const std::size_t f0 = out.size();
      for (std::uint32_t m = b.slots & kFSlotMask; m != 0; m &= m - 1) {
        const FWrite& w = b.f[__builtin_ctz(m)];
        const Commit c{Commit::Kind::FReg, static_cast<std::uint16_t>(w.index), w.value};
        std::size_t j = out.size();
        out.push_back(c);
        for (; j > f0 && out[j - 1].index > c.index; --j) out[j] = out[j - 1];
        out[j] = c;
      }
      const std::size_t a0 = out.size();
      for (std::uint32_t m = b.slots >> kASlotShift & 3; m != 0; m &= m - 1) {
        const AWrite& w = b.a[__builtin_ctz(m)];
        out.push_back({Commit::Kind::AReg, static_cast<std::uint16_t>(w.index), w.value});
      }
      if (out.size() == a0 + 2 && out[a0 + 1].index < out[a0].index) std::swap(out[a0], out[a0 + 1]);
      if (b.slots & kCcSlot) cc = static_cast<int>(b.cc);
      if (b.flags_commit) flags = static_cast<int>(b.flags);
    }
    b.slots = b.flags_commit = 0;
    b.flags = 0;
  }
}

MC1_HOT Stall Iss::stall_reason(const DecodedWord& dw) const {
  const std::uint8_t k = dw.kind;
  if (k & DecodedWord::kSwap) {
    const bool ready = dw.w.s.op == SeqOp::Swapd ? data_ready_ : program_ready_;
    if (!ready) return Stall::Bank;
  }
  // pending_: the registers with a write that becomes visible after this
  // cycle. A write of latency L collides with (or would be overtaken by) one
  // visible at cycle_ + L or later.
  if (dw.src & pending_) return Stall::Raw;
  if (dw.hazard & pending_) {  // src & pending_ is clear: the writes
    for (int i = 0; i < dw.ndst; ++i)
      if (land_[dw.dsts[i].reg] >= cycle_ + dw.dsts[i].latency) return Stall::Waw;
  }
  if ((k & DecodedWord::kCcBranch) && cmp_done_ > cycle_) return Stall::Cc;
  if ((k & DecodedWord::kHalt) && fp_in_flight()) return Stall::Drain;
  return Stall::None;
}

MC1_HOT std::uint32_t Iss::next_pc(const DecodedWord& dw) const {
  const SeqSlot& s = dw.w.s;
  const std::uint32_t fall = pc_ + 1u;
  if (s.op == SeqOp::Next) return fall;
  const std::uint16_t ar = a_[s.r & 15];
  switch (s.op) {
    case SeqOp::Jmp: return s.target;
    case SeqOp::Bcc: return (cc_ & s.r) ? s.target : fall;
    case SeqOp::Bncc: return (cc_ & s.r) ? fall : s.target;
    case SeqOp::Dbnz: return static_cast<std::uint16_t>(ar - 1) != 0 ? s.target : fall;
    case SeqOp::Bz: return ar == 0 ? s.target : fall;
    case SeqOp::Bnz: return ar != 0 ? s.target : fall;
    case SeqOp::Bltz: return (ar & 0x8000) ? s.target : fall;
    case SeqOp::Call: return s.target;
    case SeqOp::Ret: return sp_ > 0 ? stack_[sp_ - 1] : fall;
    case SeqOp::Swapp: return s.target;
    case SeqOp::Halt: return pc_;
    default: return fall;
  }
}

// The sequencer fetches the word after a word while it decodes it
// (docs/apu-isa.md "Timing"): JMP, CALL and RET exactly, a conditional branch
// as taken iff its target is not after it; a SWAPP's next word only once it
// has issued (from the new bank). Any other next word costs kBranchMissCycles.
MC1_HOT bool Iss::fetch_missed(const DecodedWord& dw, std::uint32_t next) const {
  const SeqSlot& s = dw.w.s;
  if (s.op == SeqOp::Swapp) return true;
  const std::uint32_t predicted = s.target <= pc_ ? s.target : pc_ + 1u;
  return next != predicted;
}

MC1_HOT Fault Iss::check_fault(const DecodedWord& dw, std::uint32_t next) const {
  if (dw.kind & DecodedWord::kReserved) return Fault::ReservedOp;
  const MemSlot& d = dw.w.d;
  if (d.op != MemOp::None) {
    const std::uint16_t addr = static_cast<std::uint16_t>(a_[d.base] + d.disp);
    if (addr >= kDataWords) return Fault::DataAddress;
  }
  const SeqOp op = dw.w.s.op;
  if (next >= kProgramWords || (op == SeqOp::Call && pc_ + 1u >= kProgramWords)) return Fault::PcOverflow;
  if (op == SeqOp::Call && sp_ == kCallDepth) return Fault::CallOverflow;
  if (op == SeqOp::Ret && sp_ == 0) return Fault::CallUnderflow;
  return Fault::None;
}

namespace {

// The A slot's result (CMP: its condition in value).
MC1_HOT fp24::Result add_unit(AddOp op, std::uint32_t x, std::uint32_t y) {
  namespace fp = mc1::fp24;
  namespace inl = mc1::fp24::inl;
  switch (op) {
    case AddOp::Add: return inl::add24(x, y);
    case AddOp::Sub: return inl::sub24(x, y);
    case AddOp::Cmp: return inl::cmp(x, y);
    case AddOp::Float: return fp::from_int(static_cast<std::uint16_t>(x));
    case AddOp::Fix: {
      fp::Result r = fp::to_int(x);
      r.value &= 0xFFFF;
      return r;
    }
    case AddOp::Neg: return fp::neg(x);
    default: return fp::abs(x);
  }
}

MC1_HOT fp24::Result func_unit(FuncOp op, std::uint32_t x) {
  namespace fp = mc1::fp24;
  switch (op) {
    case FuncOp::Recip: return fp::recip(x);
    case FuncOp::Sqrt: return fp::sqrt(x);
    case FuncOp::Sin: return fp::sin(x);
    default: return fp::cos(x);
  }
}

}  // namespace

// Every read of the word sees the state before its writes: all operands are
// read, and the store done, before the first F write (which run() makes at
// once, push_f); A registers, CC and FLAGS change only when their bucket is
// applied.
template <bool kRecord, int kShape, bool kPlain>
MC1_HOT void Iss::issue(const DecodedWord& dw, std::uint32_t next, CycleRecord* rec) {
  constexpr bool kEarly = !kRecord;
  constexpr bool kAny = kShape == kAnyShape;
  const MicroWord& w = dw.w;
  const bool m_en = kAny ? w.m.en : (kShape & 1) != 0;
  const bool a_en = kAny ? w.a.en : (kShape & 6) != 0;
  const bool f_en = kAny ? w.f.en : (kShape & 8) != 0;
  const MemOp d_op = kAny ? w.d.op : static_cast<MemOp>(kShape >> 4);
  fp24::Result rm, ra, rf;
  if (m_en) rm = fp24::inl::mul24(f_[w.m.a], f_[w.m.b]);
  if (a_en) {
    if constexpr (kShape >= 0 && (kShape & 6) == 2) {
      ra = fp24::inl::add24(f_[w.a.a], f_[w.a.b]);
    } else if constexpr (kShape >= 0 && (kShape & 6) == 4) {
      ra = fp24::inl::sub24(f_[w.a.a], f_[w.a.b]);
    } else {
      ra = add_unit(w.a.op, f_[w.a.a], f_[w.a.b]);
    }
  }
  if (f_en) rf = func_unit(w.f.op, f_[w.f.a]);
  std::uint32_t loaded = 0;
  if (d_op != MemOp::None) {
    const std::uint16_t addr = static_cast<std::uint16_t>(a_[w.d.base] + w.d.disp);
    if (d_op == MemOp::Ld) {
      loaded = data_[dsel_][addr];
    } else {
      data_[dsel_][addr] = f_[w.d.f];
      if constexpr (kRecord) rec->commits.push_back({Commit::Kind::Mem, addr, f_[w.d.f]});
    }
  }
  if (w.i.op != IntOp::None) int_op(dw);  // MOVFA reads F
  if (!kPlain && w.s.op != SeqOp::Next) seq_op(dw);  // a plain word's S slot is NEXT or JMP

  const std::uint64_t pending = pending_;
  std::uint64_t set = 0;
  if (m_en) set |= push_f<kEarly>(kSlotM, kMulLatency, w.m.d, rm.value, rm.flags, pending);
  if (a_en) {
    if (!(kShape >= 0 && (kShape & 6) != 6) && w.a.op == AddOp::Cmp) {
      Bucket& b = ring_[(cycle_ + dw.lat_a) % kRing];
      b.slots |= kCcSlot;
      b.cc = ra.value;
      b.flags |= ra.flags;
      cmp_done_ = cycle_ + dw.lat_a;
      ring_last_ = std::max(ring_last_, cmp_done_);
    } else {
      set |= push_f<kEarly>(kSlotA, dw.lat_a, w.a.d, ra.value, ra.flags, pending);
    }
  }
  if (f_en) {
    const FSlot slot = w.f.op == FuncOp::Sin || w.f.op == FuncOp::Cos ? kSlotTrig : kSlotRsq;
    set |= push_f<kEarly>(slot, dw.lat_f, w.f.d, rf.value, rf.flags, pending);
  }
  if (d_op == MemOp::Ld) set |= push_f<kEarly>(kSlotLd, kLoadLatency, w.d.f, loaded, 0, pending);
  if (dw.kind & DecodedWord::kMovF) {
    const std::uint32_t v = w.i.op == IntOp::Movaf ? a_[w.i.s] : (std::uint32_t{w.i.imm} << 8) & kMask24;
    set |= push_f<kEarly>(kSlotMov, kLoadLatency, w.i.d, v, 0, pending);
  }
  pending_ = pending | set;
  if (!kPlain && (dw.kind & DecodedWord::kRefetch) && fetch_missed(dw, next)) fetching_ = kBranchMissCycles;
  pc_ = static_cast<std::uint16_t>(next);
  counters_.unit_ops[0] += m_en;
  counters_.unit_ops[1] += a_en;
  counters_.unit_ops[2] += f_en;
  ++counters_.issued;
}

template <int kShape>
void Iss::run_issue(Iss& iss, const DecodedWord& dw, std::uint32_t next) {
  iss.issue<false, kShape>(dw, next, nullptr);
}

template <int kShape>
bool Iss::plain_cycle(Iss& iss, const DecodedWord& dw) {
  // A plain word's D slot is LD, ST or empty (a reserved op is not plain).
  constexpr bool kMem = (kShape >> 4) != 0;
  if (kMem && static_cast<std::uint16_t>(iss.a_[dw.w.d.base] + dw.w.d.disp) >= kDataWords) return false;
  iss.issue<false, kShape, true>(dw, dw.next, nullptr);
  ++iss.cycle_;
  iss.apply_next<false, true>();
  return true;
}

MC1_HOT bool Iss::int_value(const DecodedWord& dw, std::uint16_t& v) const {
  const IntSlot& i = dw.w.i;
  const std::uint32_t s = a_[i.s], t = a_[i.t], imm = i.imm;
  switch (i.op) {
    case IntOp::Li: v = static_cast<std::uint16_t>(imm); return true;
    case IntOp::Addi: v = static_cast<std::uint16_t>(s + imm); return true;
    case IntOp::Add: v = static_cast<std::uint16_t>(s + t); return true;
    case IntOp::Sub: v = static_cast<std::uint16_t>(s - t); return true;
    case IntOp::Muli: v = static_cast<std::uint16_t>(std::uint32_t{s} * imm); return true;
    case IntOp::Shl: v = static_cast<std::uint16_t>(s << (imm & 15)); return true;
    case IntOp::Shr: v = static_cast<std::uint16_t>(s >> (imm & 15)); return true;
    case IntOp::Sra: v = static_cast<std::uint16_t>(static_cast<std::int16_t>(s) >> (imm & 15)); return true;
    case IntOp::Andi: v = static_cast<std::uint16_t>(s & imm); return true;
    case IntOp::Ori: v = static_cast<std::uint16_t>(s | imm); return true;
    case IntOp::Xor: v = static_cast<std::uint16_t>(s ^ t); return true;
    case IntOp::Movfa: v = static_cast<std::uint16_t>(f_[i.imm & 63]); return true;
    default: return false;  // none, MOVAF and LIF (F writes: issue()), reserved
  }
}

// The I slot (its reads see the state before the word's writes).
MC1_HOT void Iss::int_op(const DecodedWord& dw) {
  std::uint16_t v;
  if (int_value(dw, v)) push_a(kSlotI, kIntLatency, dw.w.i.d & 15, v);
}

// The sequencer's effects beyond the next pc.
MC1_HOT void Iss::seq_op(const DecodedWord& dw) {
  const MicroWord& w = dw.w;
  switch (w.s.op) {
    case SeqOp::Dbnz: push_a(kSlotDbnz, latency(SeqOp::Dbnz), w.s.r, static_cast<std::uint16_t>(a_[w.s.r] - 1)); break;
    case SeqOp::Call: stack_[sp_++] = static_cast<std::uint16_t>(pc_ + 1); break;
    case SeqOp::Ret: --sp_; break;
    case SeqOp::Swapd:
      dsel_ ^= 1;
      data_ready_ = false;
      break;
    case SeqOp::Swapp:
      psel_ ^= 1;
      program_ready_ = false;
      break;
    case SeqOp::Halt: state_ = RunState::Halted; break;
    default: break;
  }
}

// A cycle between retiring the last one's writes and applying the next
// one's: the word at pc issues, stalls or faults.
template <bool kRecord>
MC1_HOT Stall Iss::execute(CycleRecord* rec) {
  if (state_ != RunState::Running) return Stall::None;
  if (fetching_ > 0) {
    --fetching_;  // the word at pc is in the program RAM or in decode: nothing issues
    ++counters_.stalls[static_cast<int>(Stall::Fetch)];
    if constexpr (kRecord) rec->stall = Stall::Fetch;
    return Stall::Fetch;
  }
  const DecodedWord& dw = decoded_[psel_][pc_];
  // Most words touch no register in flight and can stall on nothing else.
  Stall s = Stall::None;
  if (__builtin_expect((dw.kind & DecodedWord::kMayStall) || (dw.hazard & pending_), 0)) s = stall_reason(dw);
  if (s != Stall::None) {
    ++counters_.stalls[static_cast<int>(s)];
    if constexpr (kRecord) rec->stall = s;
    return s;
  }
  const std::uint32_t next = next_pc(dw);
  // Most words can fault only on their data address, if at all.
  Fault f = Fault::None;
  if (__builtin_expect((dw.kind & (DecodedWord::kReserved | DecodedWord::kStack)) || next >= kProgramWords, 0))
    f = check_fault(dw, next);
  else if ((dw.kind & DecodedWord::kMem) && static_cast<std::uint16_t>(a_[dw.w.d.base] + dw.w.d.disp) >= kDataWords)
    f = Fault::DataAddress;
  if (f != Fault::None) {
    state_ = RunState::Faulted;
    fault_ = f;
  } else {
    if constexpr (kRecord) {
      issue<true, kAnyShape>(dw, next, rec);
      rec->issued = true;
    } else {
      kRunIssue[dw.shape](*this, dw, next);
    }
  }
  return Stall::None;
}

void Iss::step(CycleRecord& rec) {
  int cc = kNoCommit, flags = kNoCommit;
  rec.cycle = cycle_;
  rec.pc = static_cast<std::uint16_t>(pc_);
  rec.issued = false;
  rec.stall = Stall::None;
  rec.psel = static_cast<std::uint8_t>(psel_);
  rec.dsel = static_cast<std::uint8_t>(dsel_);
  rec.commits.clear();
  take_due<true>(&rec, cc, flags);
  execute<true>(&rec);
  if (cc != kNoCommit) rec.commits.push_back({Commit::Kind::Cc, 0, static_cast<std::uint32_t>(cc)});
  if (flags != kNoCommit) rec.commits.push_back({Commit::Kind::Flags, 0, static_cast<std::uint32_t>(flags)});
  ++cycle_;
  apply_next<true, false>();
}

// No write in flight: every bucket but this cycle's (applied already, taken at
// the start of the next clock) is empty. (Flags and CC arrive only with an F
// write or a CMP's CC.) Every write lands within kMaxLatency cycles, so no
// scan of the ring goes further.
bool Iss::writes_landed() const {
  for (int k = 1; k <= kMaxLatency; ++k) {
    const Bucket& b = ring_[(cycle_ + k) % kRing];
    if (b.slots) return false;
  }
  return true;
}

// run()'s F writes are early (push_f): on the way in the writes in flight
// take their registers too, in the order they land; on the way out the
// registers get back the values of the writes still in flight, last first,
// so that between calls the state is the one step() keeps.
void Iss::writes_early() {
  if (pending_ == 0) return;  // no F write in flight
  for (int k = 1; k <= kMaxLatency; ++k) {
    Bucket& b = ring_[(cycle_ + k) % kRing];
    for (std::uint32_t m = b.slots & kFSlotMask; m != 0; m &= m - 1) {
      FWrite& w = b.f[__builtin_ctz(m)];
      w.prev = f_[w.index];
      f_[w.index] = w.value;
    }
  }
}

void Iss::writes_late() {
  if (pending_ == 0) return;
  for (int k = kMaxLatency; k >= 1; --k) {
    const Bucket& b = ring_[(cycle_ + k) % kRing];
    for (std::uint32_t m = b.slots & kFSlotMask; m != 0; m &= m - 1) {
      const FWrite& w = b.f[__builtin_ctz(m)];
      f_[w.index] = w.prev;
    }
  }
}

// An FP unit op issued and not yet landed (`drain`): a later bucket holds
// its write or CC.
bool Iss::fp_in_flight() const {
  for (int k = 1; k <= kMaxLatency; ++k)
    if (ring_[(cycle_ + k) % kRing].slots & kFpSlots) return true;
  return false;
}

// ---- Bodies (run_body): straight runs of plain words clocked as a unit.

const std::array<Iss::BodyIssue, Iss::kShapes> Iss::kBodyDirect =
    Iss::body_table(std::make_integer_sequence<int, Iss::kShapes>{}, std::false_type{});
const std::array<Iss::BodyIssue, Iss::kShapes> Iss::kBodyTail =
    Iss::body_table(std::make_integer_sequence<int, Iss::kShapes>{}, std::true_type{});

// The body from pc: its words, their schedule with the body's own stalls
// (docs/apu-isa.md "Timing": raw first, then waw) and the bounds on the
// writes in flight at its start that keep that schedule. It ends before a
// word that is not plain, after kMaxBodyWords words, or before a LD/ST whose
// base register an earlier word of it writes (so that its data addresses are
// known, and checked, when it starts).
std::int32_t Iss::build_body(int bank, std::uint32_t pc) {
  BodyBank& bb = body_[bank];
  Body body;
  body.first = static_cast<std::uint32_t>(bb.words.size());
  body.mem_first = static_cast<std::uint32_t>(bb.mem.size());
  body.bound.fill(255);
  std::array<int, kNumFRegs> land{};  // the body's own writes: the cycle each register's last one lands
  land.fill(-1);
  int cc_land = -1;                   // the body's CMPs: the cycle the last one lands
  std::uint32_t a_written = 0;
  int t = -1;
  std::uint32_t raw = 0, waw = 0, ccs = 0, ops[3] = {0, 0, 0};
  std::uint32_t p = pc;
  while (body.n < static_cast<std::uint32_t>(kMaxBodyWords)) {
    const DecodedWord& dw = decoded_[bank][p];
    // A conditional branch on an A register or CC may end a body: it can
    // stall only on raw, waw or cc, and fault only past the bank's end.
    const SeqOp op = dw.w.s.op;
    const bool branch = !dw.plain && (op == SeqOp::Dbnz || op == SeqOp::Bz || op == SeqOp::Bnz ||
                                      op == SeqOp::Bltz || op == SeqOp::Bcc || op == SeqOp::Bncc) &&
                        !(dw.kind & DecodedWord::kReserved) && p + 1 < static_cast<std::uint32_t>(kProgramWords);
    if (!dw.plain && !branch) break;
    const bool mem = dw.w.d.op != MemOp::None;
    if (mem && ((a_written >> dw.w.d.base) & 1)) break;
    const bool cc_branch = (dw.kind & DecodedWord::kCcBranch) != 0;
    int ti = t + 1;
    for (;;) {
      bool r = false, ww = false;
      for (std::uint64_t m = dw.src; m != 0; m &= m - 1) r |= land[__builtin_ctzll(m)] > ti;
      for (int k = 0; k < dw.ndst; ++k) ww |= land[dw.dsts[k].reg] >= ti + dw.dsts[k].latency;
      const bool c = cc_branch && cc_land > ti;
      if (!r && !ww && !c) break;
      ++(r ? raw : ww ? waw : ccs);
      ++ti;
    }
    int longest = 1;
    for (std::uint64_t m = dw.src; m != 0; m &= m - 1) {
      std::uint8_t& b = body.bound[__builtin_ctzll(m)];
      b = static_cast<std::uint8_t>(std::min<int>(b, ti));
    }
    for (int k = 0; k < dw.ndst; ++k) {
      const DecodedWord::FDst& d = dw.dsts[k];
      std::uint8_t& b = body.bound[d.reg];
      b = static_cast<std::uint8_t>(std::min<int>(b, ti + d.latency - 1));
      land[d.reg] = ti + d.latency;
      longest = std::max<int>(longest, d.latency);
    }
    if (dw.w.a.en) {
      longest = std::max<int>(longest, dw.lat_a);  // CMP's CC
      if (dw.w.a.op == AddOp::Cmp) cc_land = ti + dw.lat_a;
    }
    if (cc_branch) body.cc_at = static_cast<std::uint64_t>(ti);
    ops[0] += dw.w.m.en;
    ops[1] += dw.w.a.en;
    ops[2] += dw.w.f.en;
    BodyWord w{};
    w.pc = static_cast<std::uint16_t>(p);
    w.t = static_cast<std::uint16_t>(ti);
    w.land = static_cast<std::uint16_t>(ti + longest);
    w.shape = dw.shape;
    w.branch = branch;
    w.raw = raw;
    w.waw = waw;
    w.cc = ccs;
    for (int u = 0; u < 3; ++u) w.ops[u] = ops[u];
    bb.words.push_back(w);
    if (mem) {
      const std::int8_t d = dw.w.d.disp;
      auto it = std::find_if(bb.mem.begin() + body.mem_first, bb.mem.end(),
                             [&dw](const MemCheck& c) { return c.base == dw.w.d.base; });
      if (it == bb.mem.end()) {
        bb.mem.push_back({static_cast<std::uint8_t>(dw.w.d.base), d, d});
      } else {
        it->lo = std::min(it->lo, d);
        it->hi = std::max(it->hi, d);
      }
    }
    std::uint16_t v;
    if (int_value(dw, v)) a_written |= 1u << (dw.w.i.d & 15);
    if (op == SeqOp::Dbnz) a_written |= 1u << (dw.w.s.r & 15);
    t = ti;
    p = dw.next;
    ++body.n;
    if (branch) break;
  }
  if (body.n == 0) {
    bb.at[pc] = kNoBody;
    return kNoBody;
  }
  body.nmem = static_cast<std::uint32_t>(bb.mem.size()) - body.mem_first;
  const BodyWord* words = bb.words.data() + body.first;
  body.cycles = words[body.n - 1].t + 1u;
  while (body.direct < body.n && words[body.direct].land <= body.cycles) ++body.direct;
  for (int r = 0; r < kNumFRegs; ++r)
    if (body.bound[r] < kMaxLatency - 1) body.early |= bit(static_cast<unsigned>(r));
  bb.bodies.push_back(body);
  const auto index = static_cast<std::int32_t>(bb.bodies.size() - 1);
  bb.at[pc] = index;
  return index;
}

// A bucket's writes enter the state (their F values are there already:
// run's writes are early) and it is retired.
MC1_HOT void Iss::apply_bucket(Bucket& b) {
  pending_ &= ~b.last;
  b.last = 0;
  for (std::uint32_t m = b.slots >> kASlotShift & 3; m != 0; m &= m - 1) {
    const AWrite& w = b.a[__builtin_ctz(m)];
    a_[w.index] = static_cast<std::uint16_t>(w.value);
  }
  if (b.slots & kCcSlot) cc_ = b.cc;
  flags_ |= b.flags;
  b.slots = 0;
  b.flags = 0;
}

// kTail: the write may land after the body's end (then into the ring).
template <bool kTail>
MC1_HOT void Iss::body_write(FSlot slot, int latency, std::uint32_t index, std::uint32_t value, std::uint32_t flags,
                             std::uint64_t end) {
  if (kTail && cycle_ + latency > end) {
    pending_ |= push_f<true>(slot, latency, index, value, flags, pending_);
    return;
  }
  f_[index] = value;
  flags_ |= flags;
}

// A word of a body issues: as issue(), with writes that land within the
// body (all of them unless kTail) made at once. The I slot's A write lands
// in the next cycle, always within the body. kTail: cycle_ is the word's
// issue cycle.
template <int kShape, bool kTail>
void Iss::body_issue(Iss& iss, const DecodedWord& dw, std::uint64_t end) {
  constexpr bool m_en = (kShape & 1) != 0, a_en = (kShape & 6) != 0, f_en = (kShape & 8) != 0;
  constexpr auto d_op = static_cast<MemOp>(kShape >> 4);
  const MicroWord& w = dw.w;
  const auto& f = iss.f_;
  fp24::Result rm{}, ra{}, rf{};
  if constexpr (m_en) rm = fp24::inl::mul24(f[w.m.a], f[w.m.b]);
  if constexpr ((kShape & 6) == 2) {
    ra = fp24::inl::add24(f[w.a.a], f[w.a.b]);
  } else if constexpr ((kShape & 6) == 4) {
    ra = fp24::inl::sub24(f[w.a.a], f[w.a.b]);
  } else if constexpr (a_en) {
    ra = add_unit(w.a.op, f[w.a.a], f[w.a.b]);
  }
  if constexpr (f_en) rf = func_unit(w.f.op, f[w.f.a]);
  std::uint32_t loaded = 0;
  if constexpr (d_op != MemOp::None) {
    const std::uint16_t addr = static_cast<std::uint16_t>(iss.a_[w.d.base] + w.d.disp);
    if constexpr (d_op == MemOp::Ld) {
      loaded = iss.data_[iss.dsel_][addr];
    } else {
      iss.data_[iss.dsel_][addr] = f[w.d.f];
    }
  }
  std::uint16_t av = 0;
  const bool a_write = w.i.op != IntOp::None && iss.int_value(dw, av);  // MOVFA reads F
  std::uint32_t mov = 0;
  if (dw.kind & DecodedWord::kMovF) mov = w.i.op == IntOp::Movaf ? iss.a_[w.i.s] : (std::uint32_t{w.i.imm} << 8) & kMask24;

  if constexpr (m_en) iss.body_write<kTail>(kSlotM, kMulLatency, w.m.d, rm.value, rm.flags, end);
  if constexpr (a_en) {
    if ((kShape & 6) == 6 && w.a.op == AddOp::Cmp) {
      if (kTail && iss.cycle_ + dw.lat_a > end) {
        Bucket& b = iss.ring_[(iss.cycle_ + dw.lat_a) % kRing];
        b.slots |= kCcSlot;
        b.cc = ra.value;
        b.flags |= ra.flags;
        iss.cmp_done_ = iss.cycle_ + dw.lat_a;
        iss.ring_last_ = std::max(iss.ring_last_, iss.cmp_done_);
      } else {
        iss.cc_ = ra.value;  // lands within the body: no CMP in flight after it
        iss.flags_ |= ra.flags;
      }
    } else {
      iss.body_write<kTail>(kSlotA, dw.lat_a, w.a.d, ra.value, ra.flags, end);
    }
  }
  if constexpr (f_en) {
    const FSlot slot = w.f.op == FuncOp::Sin || w.f.op == FuncOp::Cos ? kSlotTrig : kSlotRsq;
    iss.body_write<kTail>(slot, dw.lat_f, w.f.d, rf.value, rf.flags, end);
  }
  if constexpr (d_op == MemOp::Ld) iss.f_[w.d.f] = loaded;
  if (dw.kind & DecodedWord::kMovF) iss.f_[w.i.d] = mov;
  if (a_write && (w.i.d & 15) != 0) iss.a_[w.i.d & 15] = av;
}

// The body at pc, or its longest prefix that fits in avail cycles, when the
// state allows it (the bounds, the data addresses): returns the cycles
// clocked, 0 if none. As many cycles of run() (none of them its last) would
// leave the state, the ring and the counters.
MC1_HOT std::uint64_t Iss::run_body(std::uint64_t avail) {
  const int bank = psel_;
  BodyBank& bb = body_[bank];
  std::int32_t index = bb.at[pc_];
  if (index < 0) {
    if (index == kNoBody) return 0;
    index = build_body(bank, pc_);
    if (index < 0) return 0;
  }
  const Body& body = bb.bodies[static_cast<std::size_t>(index)];
  const std::uint64_t e = cycle_;
  for (std::uint64_t m = pending_ & body.early; m != 0; m &= m - 1) {
    const int r = __builtin_ctzll(m);
    if (land_[r] - e > body.bound[r]) return 0;
  }
  if (cmp_done_ > e + body.cc_at) return 0;
  // Every address in range without a wrap (else cycle by cycle: a fault, or a wrap that lands in range).
  const MemCheck* mc = bb.mem.data() + body.mem_first;
  for (std::uint32_t i = 0; i < body.nmem; ++i) {
    const int a = a_[mc[i].base];
    if (a + mc[i].lo < 0 || a + mc[i].hi >= kDataWords) return 0;
  }
  const BodyWord* words = bb.words.data() + body.first;
  std::uint32_t n = body.n;
  std::uint64_t cycles = body.cycles;
  // The words before `direct` have every write land within the body.
  std::uint32_t direct = body.direct;
  if (__builtin_expect(cycles > avail, 0)) {  // the call ends first: a prefix
    while (n > 0 && words[n - 1].t + 1u > avail) --n;
    if (n == 0) return 0;
    cycles = words[n - 1].t + 1u;
    direct = 0;
    while (direct < n && words[direct].land <= cycles) ++direct;
  }
  const std::uint64_t end = e + cycles;
  // The writes in flight that land within the body enter the state first
  // (no word of it reads or overwrites them earlier: the bounds).
  if (ring_last_ > e) {
    const std::uint64_t ahead = std::min(ring_last_, end);
    for (std::uint64_t c = e + 1; c <= ahead; ++c) {
      Bucket& b = ring_[c % kRing];
      if (b.slots) apply_bucket(b);
    }
  }
  const auto& dec = decoded_[bank];
  const BodyWord& last = words[n - 1];
  const std::uint32_t m = n - last.branch;
  std::uint32_t i = 0;
  for (; i < std::min(direct, m); ++i) kBodyDirect[words[i].shape](*this, dec[words[i].pc], end);
  for (; i < m; ++i) {
    const BodyWord& w = words[i];
    if (__builtin_expect(e + w.land <= end, 1)) {
      kBodyDirect[w.shape](*this, dec[w.pc], end);
    } else {
      cycle_ = e + w.t;
      kBodyTail[w.shape](*this, dec[w.pc], end);
    }
  }
  if (last.branch) {
    // Its reads (A[r], CC) see the state before its own writes.
    const DecodedWord& dw = dec[last.pc];
    pc_ = last.pc;
    const std::uint32_t next = next_pc(dw);
    if (fetch_missed(dw, next)) fetching_ = kBranchMissCycles;
    const std::uint32_t r = dw.w.s.r & 15;
    const auto dec_r = static_cast<std::uint16_t>(a_[r] - 1);
    cycle_ = e + last.t;
    (e + last.land <= end ? kBodyDirect : kBodyTail)[last.shape](*this, dw, end);
    if (dw.w.s.op == SeqOp::Dbnz && r != 0) a_[r] = dec_r;
    pc_ = next;
  } else {
    pc_ = dec[last.pc].next;
  }
  cycle_ = end;
  // A branch that missed the fetch: its cycles with no word to issue
  // (Stall::Fetch; each applies its bucket, as any cycle of run).
  while (fetching_ > 0 && cycles < avail) {
    --fetching_;
    ++counters_.stalls[static_cast<int>(Stall::Fetch)];
    ++cycles;
    ++cycle_;
    Bucket& b = ring_[cycle_ % kRing];
    if (b.slots) apply_bucket(b);
  }
  counters_.issued += n;
  for (int u = 0; u < 3; ++u) counters_.unit_ops[u] += last.ops[u];
  counters_.stalls[static_cast<int>(Stall::Raw)] += last.raw;
  counters_.stalls[static_cast<int>(Stall::Waw)] += last.waw;
  counters_.stalls[static_cast<int>(Stall::Cc)] += last.cc;
  return cycles;
}

template <bool kUntilDataTaken>
std::uint64_t Iss::run_fast(std::uint64_t max_cycles) {
  if (max_cycles == 0 || state_ != RunState::Running) return 0;
  int cc = kNoCommit, flags = kNoCommit;
  take_due<false>(nullptr, cc, flags);  // what the last clock applied (nothing records it now)
  writes_early();
  for (BodyBank& bb : body_) {
    if (!bb.stale) continue;
    bb.at.assign(kProgramWords, kBodyUnknown);
    bb.bodies.clear();
    bb.words.clear();
    bb.mem.clear();
    bb.stale = false;
  }
  for (std::uint64_t n = 1;; ++n) {
    if (fetching_ == 0 && n < max_cycles) {
      if (const std::uint64_t k = run_body(max_cycles - n)) {
        n += k - 1;
        continue;
      }
      const DecodedWord& dw = decoded_[psel_][pc_];
      if (dw.plain && !(dw.hazard & pending_) && kPlainCycle[dw.shape](*this, dw)) continue;
    }
    const Stall s = execute<false>(nullptr);
    ++cycle_;
    if (n == max_cycles || state_ != RunState::Running || (kUntilDataTaken && !data_ready_)) {
      apply_next<true, true>();  // as step() leaves it: a step that follows records these writes
      writes_late();
      return n;
    }
    apply_next<false, true>();
    if (s == Stall::Bank && writes_landed()) {
      // A word waiting for a bank the MPU has not handed over waits every
      // cycle until the call returns (the MPU acts between calls, and `bank`
      // comes first in the stall order); with no write left in flight each of
      // those cycles only counts a bank stall: clock them all at once.
      const std::uint64_t k = max_cycles - n;
      counters_.stalls[static_cast<int>(Stall::Bank)] += k;
      cycle_ += k;
      return max_cycles;
    }
  }
}

template std::uint64_t Iss::run_fast<false>(std::uint64_t);
template std::uint64_t Iss::run_fast<true>(std::uint64_t);

}  // namespace mc1::apu
