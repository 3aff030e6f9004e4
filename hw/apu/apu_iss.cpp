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

}  // namespace

DecodedWord DecodedWord::from(const Encoded& e) {
  DecodedWord d;
  d.w = MicroWord::decode(e);
  const MicroWord& w = d.w;
  const auto write = [&d](unsigned reg, int latency) {
    d.dst |= bit(reg);
    d.dsts[d.ndst++] = {static_cast<std::uint8_t>(reg & 63), static_cast<std::uint8_t>(latency)};
  };
  const auto fp = [&d](int latency) { d.lat_fp = static_cast<std::uint8_t>(std::max<int>(d.lat_fp, latency)); };
  if (w.m.en) {
    d.src |= bit(w.m.a) | bit(w.m.b);
    write(w.m.d, kMulLatency);
    fp(kMulLatency);
  }
  if (w.a.en) {
    if (is_reserved(w.a.op)) {
      d.kind |= kReserved;
    } else {
      d.lat_a = static_cast<std::uint8_t>(latency(w.a.op));
      d.src |= bit(w.a.a) | (two_operand(w.a.op) ? bit(w.a.b) : 0);
      if (w.a.op != AddOp::Cmp) write(w.a.d, d.lat_a);
      fp(d.lat_a);
    }
  }
  if (w.f.en) {
    d.lat_f = static_cast<std::uint8_t>(latency(w.f.op));
    d.src |= bit(w.f.a);
    write(w.f.d, d.lat_f);
    fp(d.lat_f);
  }
  d.lat_d = static_cast<std::uint8_t>(latency(w.d.op));
  switch (w.d.op) {
    case MemOp::Ld:
      write(w.d.f, d.lat_d);
      d.kind |= kMem;
      break;
    case MemOp::St:
      d.src |= bit(w.d.f);
      d.kind |= kMem;
      break;
    case MemOp::None: break;
    case MemOp::Reserved: d.kind |= kReserved | kMem; break;
  }
  d.lat_i = static_cast<std::uint8_t>(latency(w.i.op));
  switch (w.i.op) {
    case IntOp::Movaf:
    case IntOp::Lif: write(w.i.d, d.lat_i); break;
    case IntOp::Movfa: d.src |= bit(w.i.imm); break;
    case IntOp::Reserved: d.kind |= kReserved; break;
    default: break;
  }
  switch (w.s.op) {
    case SeqOp::Swapd: d.kind |= kSwap; break;
    case SeqOp::Swapp: d.kind |= kSwap | kRefetch; break;
    case SeqOp::Bcc:
    case SeqOp::Bncc: d.kind |= kCcBranch | kRefetch; break;
    case SeqOp::Dbnz:
    case SeqOp::Bz:
    case SeqOp::Bnz:
    case SeqOp::Bltz: d.kind |= kRefetch; break;
    case SeqOp::Halt: d.kind |= kHalt; break;
    case SeqOp::Call:
    case SeqOp::Ret: d.kind |= kStack; break;
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
  pending_ = 0;
  land_.fill(0);
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

MC1_HOT void Iss::push_f(int latency, std::uint32_t index, std::uint32_t value, std::uint32_t flags) {
  const std::uint64_t at = cycle_ + latency;
  Bucket& b = ring_[at % kRing];
  b.f[b.nf++] = {index, value};
  b.flags |= flags;
  pending_ |= bit(index);
  land_[index] = std::max(land_[index], at);
}

MC1_HOT void Iss::push_a(int latency, std::uint32_t index, std::uint16_t value) {
  if (index == 0) return;  // A0 reads 0; writes to it are dropped
  Bucket& b = ring_[(cycle_ + latency) % kRing];
  b.a[b.na++] = {index, value};
}

// End of a cycle: the writes that become visible in the next cycle enter the
// state now, so that between two steps the state is the one the next word
// reads (as in the RTL, where they are written at the clock edge). kKeep:
// the bucket stays for the next step to record (take_due retires it);
// otherwise (run's cycles but its last) it is retired at once.
template <bool kKeep>
MC1_HOT void Iss::apply_next() {
  Bucket& b = ring_[cycle_ % kRing];
  if (b.nf | b.na | b.cc_valid | b.flags) {
    for (std::uint32_t i = 0; i < b.nf; ++i) {
      const std::uint32_t r = b.f[i].index;
      f_[r] = b.f[i].value;
      if (land_[r] == cycle_) pending_ &= ~bit(r);  // its last write in flight
    }
    for (std::uint32_t i = 0; i < b.na; ++i) a_[b.a[i].index] = static_cast<std::uint16_t>(b.a[i].value);
    if (b.cc_valid) cc_ = b.cc;
    const std::uint32_t new_flags = flags_ | b.flags;
    if constexpr (kKeep) {
      b.flags_commit = new_flags != flags_;
      b.flags = new_flags;
    } else {
      b.nf = b.na = 0;
      b.cc_valid = 0;
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
  if (b.nf | b.na | b.cc_valid) {
    if constexpr (kRecord) {
      // Commits in the interface's order: FReg by index, then AReg by index.
      auto& out = rec->commits;
      const std::size_t f0 = out.size();
      for (std::uint32_t i = 0; i < b.nf; ++i) {
        const Commit c{Commit::Kind::FReg, static_cast<std::uint16_t>(b.f[i].index), b.f[i].value};
        std::size_t j = out.size();
        out.push_back(c);
        for (; j > f0 && out[j - 1].index > c.index; --j) out[j] = out[j - 1];
        out[j] = c;
      }
      if (b.na == 2 && b.a[1].index < b.a[0].index) std::swap(b.a[0], b.a[1]);
      for (std::uint32_t i = 0; i < b.na; ++i)
        out.push_back({Commit::Kind::AReg, static_cast<std::uint16_t>(b.a[i].index), b.a[i].value});
      if (b.cc_valid) cc = static_cast<int>(b.cc);
      if (b.flags_commit) flags = static_cast<int>(b.flags);
    }
    b.nf = b.na = 0;
    b.cc_valid = b.flags_commit = 0;
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
  if (dw.dst & pending_) {
    for (int i = 0; i < dw.ndst; ++i)
      if (land_[dw.dsts[i].reg] >= cycle_ + dw.dsts[i].latency) return Stall::Waw;
  }
  if ((k & DecodedWord::kCcBranch) && cmp_done_ > cycle_) return Stall::Cc;
  if ((k & DecodedWord::kHalt) && fp_done_ > cycle_) return Stall::Drain;
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

template <bool kRecord>
MC1_HOT void Iss::issue(const DecodedWord& dw, std::uint32_t next, CycleRecord* rec) {
  namespace fp = mc1::fp24;
  namespace inl = mc1::fp24::inl;  // mul, add, sub, cmp inline: no call per op (F registers hold 24 bits)
  const MicroWord& w = dw.w;
  // Every read below sees the state before this word's writes: FP results
  // and register writes go to future buckets; only the store is immediate.
  if (dw.lat_fp) fp_done_ = std::max(fp_done_, cycle_ + dw.lat_fp);
  if (w.m.en) {
    const fp::Result r = inl::mul24(f_[w.m.a], f_[w.m.b]);
    push_f(kMulLatency, w.m.d, r.value, r.flags);
    ++counters_.unit_ops[0];
  }
  if (w.a.en) {
    const std::uint32_t x = f_[w.a.a], y = f_[w.a.b];
    fp::Result r{};
    switch (w.a.op) {
      case AddOp::Add: r = inl::add24(x, y); break;
      case AddOp::Sub: r = inl::sub24(x, y); break;
      case AddOp::Cmp: r = inl::cmp(x, y); break;
      case AddOp::Float: r = fp::from_int(static_cast<std::uint16_t>(x)); break;
      case AddOp::Fix: r = fp::to_int(x); r.value &= 0xFFFF; break;
      case AddOp::Neg: r = fp::neg(x); break;
      default: r = fp::abs(x); break;
    }
    const int latency_a = dw.lat_a;
    if (w.a.op == AddOp::Cmp) {
      Bucket& b = ring_[(cycle_ + latency_a) % kRing];
      b.cc_valid = 1;
      b.cc = r.value;
      b.flags |= r.flags;
      cmp_done_ = cycle_ + latency_a;
    } else {
      push_f(latency_a, w.a.d, r.value, r.flags);
    }
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
    push_f(dw.lat_f, w.f.d, r.value, r.flags);
    ++counters_.unit_ops[2];
  }

  if (w.d.op != MemOp::None) {
    const std::uint16_t addr = static_cast<std::uint16_t>(a_[w.d.base] + w.d.disp);
    if (w.d.op == MemOp::Ld) {
      push_f(dw.lat_d, w.d.f, data_[dsel_][addr]);
    } else {
      data_[dsel_][addr] = f_[w.d.f];
      if constexpr (kRecord) rec->commits.push_back({Commit::Kind::Mem, addr, f_[w.d.f]});
    }
  }

  if (w.i.op != IntOp::None) int_op(dw);
  if (w.s.op != SeqOp::Next) seq_op(dw);
  if ((dw.kind & DecodedWord::kRefetch) && fetch_missed(dw, next)) fetching_ = kBranchMissCycles;
  pc_ = static_cast<std::uint16_t>(next);
  ++counters_.issued;
}

// The I slot (its reads see the state before the word's writes).
MC1_HOT void Iss::int_op(const DecodedWord& dw) {
  const IntSlot& i = dw.w.i;
  const std::uint8_t ad = i.d & 15;
  const std::uint32_t s = a_[i.s], t = a_[i.t], imm = i.imm;
  const int li = dw.lat_i;
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
}

// The sequencer's effects beyond the next pc.
MC1_HOT void Iss::seq_op(const DecodedWord& dw) {
  const MicroWord& w = dw.w;
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
  const Stall s = stall_reason(dw);
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
    issue<kRecord>(dw, next, rec);
    if constexpr (kRecord) rec->issued = true;
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
  apply_next<true>();
}

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

template <bool kUntilDataTaken>
std::uint64_t Iss::run_fast(std::uint64_t max_cycles) {
  if (max_cycles == 0 || state_ != RunState::Running) return 0;
  int cc = kNoCommit, flags = kNoCommit;
  take_due<false>(nullptr, cc, flags);  // what the last clock applied (nothing records it now)
  for (std::uint64_t n = 1;; ++n) {
    const Stall s = execute<false>(nullptr);
    ++cycle_;
    if (n == max_cycles || state_ != RunState::Running || (kUntilDataTaken && !data_ready_)) {
      apply_next<true>();  // as step() leaves it: a step that follows records these writes
      return n;
    }
    apply_next<false>();
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
