// The APU instruction-set simulator (docs/apu-isa.md, "Timing" and
// "Clarifications"). Per-cycle work is a few mask tests and, on issue, the
// FP24 model calls; nothing allocates once a CycleRecord has its capacity.
#include "apu_iss.hpp"

#include "fp24.hpp"
#include "fp24_arith_inline.hpp"

namespace mc1::apu {

namespace {

constexpr std::uint64_t bit(unsigned r) { return std::uint64_t{1} << (r & 63); }
constexpr std::uint32_t kMask24 = 0xFFFFFF;
constexpr int kNoCommit = -1;

#define MC1_HOT inline __attribute__((always_inline))

bool two_operand(AddOp op) { return op == AddOp::Add || op == AddOp::Sub || op == AddOp::Cmp; }

}  // namespace

DecodedWord DecodedWord::from(const Encoded& e) {
  DecodedWord d;
  d.w = MicroWord::decode(e);
  const MicroWord& w = d.w;
  if (w.m.en) {
    d.src |= bit(w.m.a) | bit(w.m.b);
    d.dst_at[kMulLatency] |= bit(w.m.d);
  }
  if (w.a.en) {
    if (is_reserved(w.a.op)) {
      d.kind |= kReserved;
    } else {
      d.src |= bit(w.a.a) | (two_operand(w.a.op) ? bit(w.a.b) : 0);
      if (w.a.op != AddOp::Cmp) d.dst_at[latency(w.a.op)] |= bit(w.a.d);
    }
  }
  if (w.f.en) {
    d.src |= bit(w.f.a);
    d.dst_at[latency(w.f.op)] |= bit(w.f.d);
  }
  switch (w.d.op) {
    case MemOp::Ld: d.dst_at[latency(w.d.op)] |= bit(w.d.f); break;
    case MemOp::St: d.src |= bit(w.d.f); break;
    case MemOp::None: break;
    case MemOp::Reserved: d.kind |= kReserved; break;
  }
  switch (w.i.op) {
    case IntOp::Movaf:
    case IntOp::Lif: d.dst_at[latency(w.i.op)] |= bit(w.i.d); break;
    case IntOp::Movfa: d.src |= bit(w.i.imm); break;
    case IntOp::Reserved: d.kind |= kReserved; break;
    default: break;
  }
  switch (w.s.op) {
    case SeqOp::Swapd:
    case SeqOp::Swapp: d.kind |= kSwap; break;
    case SeqOp::Bcc:
    case SeqOp::Bncc: d.kind |= kCcBranch; break;
    case SeqOp::Halt: d.kind |= kHalt; break;
    default:
      if (is_reserved(w.s.op)) d.kind |= kReserved;
      break;
  }
  return d;
}

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
  const DecodedWord zero = DecodedWord::from(Encoded{});
  for (int b = 0; b < 2; ++b) {
    program_[b].fill(Encoded{});
    decoded_[b].fill(zero);
    data_[b].fill(0);
  }
  ring_.fill(Bucket{});
  fp_done_ = cmp_done_ = 0;
  counters_ = Counters{};
}

void Iss::write_program(std::uint16_t addr, const Encoded& word) {
  const int bank = psel_ ^ 1;
  addr %= kProgramWords;
  program_[bank][addr] = word;
  decoded_[bank][addr] = DecodedWord::from(word);
}

void Iss::write_data(std::uint16_t addr, std::uint32_t value) {
  data_[dsel_ ^ 1][addr % kDataWords] = value & kMask24;
}

std::uint32_t Iss::read_data(std::uint16_t addr) const { return data_[dsel_ ^ 1][addr % kDataWords]; }

void Iss::write_data_block(std::uint16_t addr, const std::uint32_t* values, std::size_t n) {
  auto& bank = data_[dsel_ ^ 1];
  for (std::size_t i = 0; i < n; ++i) bank[(addr + i) % kDataWords] = values[i] & kMask24;
}

void Iss::read_data_block(std::uint16_t addr, std::uint32_t* out, std::size_t n) const {
  const auto& bank = data_[dsel_ ^ 1];
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

MC1_HOT void Iss::push_f(int latency, std::uint8_t index, std::uint32_t value) {
  Bucket& b = ring_[(cycle_ + latency) % kRing];
  b.f[b.nf++] = {index, value};
  b.fmask |= bit(index);
}

MC1_HOT void Iss::push_a(int latency, std::uint8_t index, std::uint16_t value) {
  if (index == 0) return;  // A0 reads 0; writes to it are dropped
  Bucket& b = ring_[(cycle_ + latency) % kRing];
  b.a[b.na++] = {index, value};
}

MC1_HOT void Iss::push_flags(int latency, std::uint8_t flags) { ring_[(cycle_ + latency) % kRing].flags |= flags; }

MC1_HOT void Iss::note_fp(int latency) {
  if (cycle_ + latency > fp_done_) fp_done_ = cycle_ + latency;
}

// End of a cycle: the writes that become visible in the next cycle enter the
// state now, so that between two steps the state is the one the next word
// reads (as in the RTL, where they are written at the clock edge). The next
// step records them.
MC1_HOT void Iss::apply_next() {
  Bucket& b = ring_[cycle_ % kRing];
  if (b.nf | b.na | b.cc_valid | b.flags) {
    for (int i = 0; i < b.nf; ++i) f_[b.f[i].index] = b.f[i].value;
    for (int i = 0; i < b.na; ++i) a_[b.a[i].index] = b.a[i].value;
    if (b.cc_valid) cc_ = b.cc;
    const std::uint8_t new_flags = flags_ | b.flags;
    b.flags_commit = new_flags != flags_;
    b.flags = new_flags;
    flags_ = new_flags;
    b.fmask = 0;
  }
}

// Start of a cycle: records (kRecord) and retires the writes applied at the
// end of the last one. CC and FLAGS come back through cc/flags (recorded
// after any store of this cycle).
template <bool kRecord>
MC1_HOT void Iss::take_due(CycleRecord* rec, int& cc, int& flags) {
  Bucket& b = ring_[cycle_ % kRing];
  if (b.nf | b.na | b.cc_valid) {
    if constexpr (kRecord) {
      // Commits in the interface's order: FReg by index, then AReg by index.
      auto& out = rec->commits;
      const std::size_t f0 = out.size();
      for (int i = 0; i < b.nf; ++i) {
        const Commit c{Commit::Kind::FReg, b.f[i].index, b.f[i].value};
        std::size_t j = out.size();
        out.push_back(c);
        for (; j > f0 && out[j - 1].index > c.index; --j) out[j] = out[j - 1];
        out[j] = c;
      }
      if (b.na == 2 && b.a[1].index < b.a[0].index) std::swap(b.a[0], b.a[1]);
      for (int i = 0; i < b.na; ++i) out.push_back({Commit::Kind::AReg, b.a[i].index, b.a[i].value});
      if (b.cc_valid) cc = b.cc;
      if (b.flags_commit) flags = b.flags;
    }
    b.nf = b.na = 0;
    b.cc_valid = b.flags_commit = false;
    b.flags = 0;
  }
}

MC1_HOT Stall Iss::stall_reason(const DecodedWord& dw) const {
  const std::uint8_t k = dw.kind;
  if (k & DecodedWord::kSwap) {
    const bool ready = dw.w.s.op == SeqOp::Swapd ? data_ready_ : program_ready_;
    if (!ready) return Stall::Bank;
  }
  // This cycle's bucket is applied and its mask cleared: every mask left
  // belongs to a write that becomes visible after this cycle. late = the
  // registers with a write visible at cycle_ + k or later, k going down: a
  // write of latency k collides with (or would be overtaken by) those.
  std::uint64_t late = 0, waw = 0;
#pragma GCC unroll 16
  for (int k = kRing - 1; k >= 1; --k) {
    late |= ring_[(cycle_ + k) % kRing].fmask;
    if (k <= kMaxLatency) waw |= dw.dst_at[k] & late;
  }
  if (dw.src & late) return Stall::Raw;
  if (waw) return Stall::Waw;
  if ((k & DecodedWord::kCcBranch) && cmp_done_ > cycle_) return Stall::Cc;
  if ((k & DecodedWord::kHalt) && fp_done_ > cycle_) return Stall::Drain;
  return Stall::None;
}

MC1_HOT std::uint32_t Iss::next_pc(const DecodedWord& dw) const {
  const SeqSlot& s = dw.w.s;
  const std::uint32_t fall = pc_ + 1u;
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

template <bool kRecord>
MC1_HOT void Iss::issue(const DecodedWord& dw, std::uint32_t next, CycleRecord* rec) {
  namespace fp = mc1::fp24;
  namespace inl = mc1::fp24::inl;  // mul, add, sub, cmp inline: no call per op
  const MicroWord& w = dw.w;
  // Every read below sees the state before this word's writes: FP results
  // and register writes go to future buckets; only the store is immediate.
  if (w.m.en) {
    const fp::Result r = inl::mul(f_[w.m.a], f_[w.m.b]);
    push_f(kMulLatency, w.m.d, r.value);
    push_flags(kMulLatency, r.flags);
    note_fp(kMulLatency);
    ++counters_.unit_ops[0];
  }
  if (w.a.en) {
    const std::uint32_t x = f_[w.a.a], y = f_[w.a.b];
    fp::Result r{};
    switch (w.a.op) {
      case AddOp::Add: r = inl::add(x, y); break;
      case AddOp::Sub: r = inl::sub(x, y); break;
      case AddOp::Cmp: r = inl::cmp(x, y); break;
      case AddOp::Float: r = fp::from_int(static_cast<std::uint16_t>(x)); break;
      case AddOp::Fix: r = fp::to_int(x); r.value &= 0xFFFF; break;
      case AddOp::Neg: r = fp::neg(x); break;
      default: r = fp::abs(x); break;
    }
    const int latency_a = latency(w.a.op);
    if (w.a.op == AddOp::Cmp) {
      Bucket& b = ring_[(cycle_ + latency_a) % kRing];
      b.cc_valid = true;
      b.cc = static_cast<std::uint8_t>(r.value);
      cmp_done_ = cycle_ + latency_a;
    } else {
      push_f(latency_a, w.a.d, r.value);
    }
    push_flags(latency_a, r.flags);
    note_fp(latency_a);
    ++counters_.unit_ops[1];
  }
  if (w.f.en) {
    const std::uint32_t x = f_[w.f.a];
    fp::Result r{};
    switch (w.f.op) {
      case FuncOp::Recip: r = fp::recip(x); break;
      case FuncOp::Sqrt: r = fp::sqrt(x); break;
      case FuncOp::Sin: r = fp::sin(x); break;
      case FuncOp::Cos: r = fp::cos(x); break;
    }
    const int latency_f = latency(w.f.op);
    push_f(latency_f, w.f.d, r.value);
    push_flags(latency_f, r.flags);
    note_fp(latency_f);
    ++counters_.unit_ops[2];
  }

  if (w.d.op != MemOp::None) {
    const std::uint16_t addr = static_cast<std::uint16_t>(a_[w.d.base] + w.d.disp);
    if (w.d.op == MemOp::Ld) {
      push_f(latency(w.d.op), w.d.f, data_[dsel_][addr]);
    } else {
      data_[dsel_][addr] = f_[w.d.f];
      if constexpr (kRecord) rec->commits.push_back({Commit::Kind::Mem, addr, f_[w.d.f]});
    }
  }

  const IntSlot& i = w.i;
  const std::uint8_t ad = i.d & 15;
  const std::uint16_t s = a_[i.s], t = a_[i.t], imm = i.imm;
  const int li = latency(i.op);
  switch (i.op) {
    case IntOp::None: break;
    case IntOp::Li: push_a(li, ad, imm); break;
    case IntOp::Addi: push_a(li, ad, static_cast<std::uint16_t>(s + imm)); break;
    case IntOp::Add: push_a(li, ad, static_cast<std::uint16_t>(s + t)); break;
    case IntOp::Sub: push_a(li, ad, static_cast<std::uint16_t>(s - t)); break;
    case IntOp::Muli: push_a(li, ad, static_cast<std::uint16_t>(std::uint32_t{s} * imm)); break;
    case IntOp::Shl: push_a(li, ad, static_cast<std::uint16_t>(s << (imm & 15))); break;
    case IntOp::Shr: push_a(li, ad, static_cast<std::uint16_t>(s >> (imm & 15))); break;
    case IntOp::Sra:
      push_a(li, ad, static_cast<std::uint16_t>(static_cast<std::int16_t>(s) >> (imm & 15)));
      break;
    case IntOp::Andi: push_a(li, ad, s & imm); break;
    case IntOp::Ori: push_a(li, ad, s | imm); break;
    case IntOp::Xor: push_a(li, ad, s ^ t); break;
    case IntOp::Movaf: push_f(li, i.d, s); break;
    case IntOp::Movfa: push_a(li, ad, static_cast<std::uint16_t>(f_[i.imm & 63])); break;
    case IntOp::Lif: push_f(li, i.d, (std::uint32_t{imm} << 8) & kMask24); break;
    case IntOp::Reserved: break;
  }

  switch (w.s.op) {
    case SeqOp::Dbnz: push_a(latency(SeqOp::Dbnz), w.s.r, static_cast<std::uint16_t>(a_[w.s.r] - 1)); break;
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
  pc_ = static_cast<std::uint16_t>(next);
  ++counters_.issued;
}

template <bool kRecord>
MC1_HOT Stall Iss::clock(CycleRecord* rec) {
  Stall s = Stall::None;
  int cc = kNoCommit, flags = kNoCommit;
  if constexpr (kRecord) {
    rec->cycle = cycle_;
    rec->pc = pc_;
    rec->issued = false;
    rec->stall = Stall::None;
    rec->psel = static_cast<std::uint8_t>(psel_);
    rec->dsel = static_cast<std::uint8_t>(dsel_);
    rec->commits.clear();
  }
  take_due<kRecord>(rec, cc, flags);
  if (fetching_ > 0) {
    --fetching_;  // the program RAM reads the word at pc: nothing issues
  } else if (state_ == RunState::Running) {
    const DecodedWord& dw = decoded_[psel_][pc_];
    s = stall_reason(dw);
    if (s != Stall::None) {
      ++counters_.stalls[static_cast<int>(s)];
      if constexpr (kRecord) rec->stall = s;
    } else {
      const std::uint32_t next = next_pc(dw);
      const Fault f = check_fault(dw, next);
      if (f != Fault::None) {
        state_ = RunState::Faulted;
        fault_ = f;
      } else {
        issue<kRecord>(dw, next, rec);
        if constexpr (kRecord) rec->issued = true;
      }
    }
  }
  if constexpr (kRecord) {
    if (cc != kNoCommit) rec->commits.push_back({Commit::Kind::Cc, 0, static_cast<std::uint32_t>(cc)});
    if (flags != kNoCommit) rec->commits.push_back({Commit::Kind::Flags, 0, static_cast<std::uint32_t>(flags)});
  }
  ++cycle_;
  apply_next();
  return s;
}

void Iss::step(CycleRecord& rec) { clock<true>(&rec); }

// No write in flight: every bucket but this cycle's (applied already, taken at
// the start of the next clock) is empty. (Flags and CC arrive only with an F
// write or a CMP's CC.)
bool Iss::writes_landed() const {
  for (int k = 1; k < kRing; ++k) {
    const Bucket& b = ring_[(cycle_ + k) % kRing];
    if (b.nf | b.na | b.cc_valid) return false;
  }
  return true;
}

std::uint64_t Iss::run(std::uint64_t max_cycles) {
  std::uint64_t n = 0;
  while (n < max_cycles && state_ == RunState::Running) {
    const Stall s = clock<false>(nullptr);
    ++n;
    if (s == Stall::Bank && n < max_cycles && writes_landed()) {
      // A word waiting for a bank the MPU has not handed over waits every
      // cycle until the call returns (the MPU acts between calls, and `bank`
      // comes first in the stall order); with no write left in flight each of
      // those cycles only counts a bank stall: clock them all at once.
      const std::uint64_t k = max_cycles - n;
      Bucket& b = ring_[cycle_ % kRing];
      b.nf = b.na = 0;
      b.cc_valid = b.flags_commit = false;
      b.flags = 0;
      counters_.stalls[static_cast<int>(Stall::Bank)] += k;
      cycle_ += k;
      n = max_cycles;
    }
  }
  return n;
}

}  // namespace mc1::apu
