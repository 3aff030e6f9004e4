// Internal to the instruction-set simulator (apu_iss.cpp: decode, the MPU's
// calls, step(); apu_iss_run.cpp: run(), its bodies): the per-cycle pieces
// both clock with, inline, so that each cycle loop has them in line. Not an
// interface: nothing outside those two files includes it.
#pragma once

#include <algorithm>

#include "apu_iss.hpp"
#include "fp24.hpp"
#include "fp24_arith_inline.hpp"

namespace mc1::apu {

namespace {


constexpr std::uint64_t bit(unsigned r) { return std::uint64_t{1} << (r & 63); }
constexpr std::uint32_t kMask24 = 0xFFFFFF;
constexpr int kNoCommit = -1;

#define MC1_HOT inline __attribute__((always_inline))

}  // namespace

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
  apply_bucket<kKeep, kEarly>(ring_[cycle_ % kRing]);
}

// A bucket's writes enter the state (run_body applies those of several
// cycles at once).
template <bool kKeep, bool kEarly>
MC1_HOT void Iss::apply_bucket(Bucket& b) {
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

MC1_HOT std::uint32_t Iss::next_pc(const SeqSlot& s) const {
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
MC1_HOT bool Iss::fetch_missed(const SeqSlot& s, std::uint32_t next) const {
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
  if (!kPlain && (dw.kind & DecodedWord::kRefetch) && fetch_missed(dw.w.s, next)) fetching_ = kBranchMissCycles;
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

MC1_HOT bool Iss::int_value(const IntSlot& i, std::uint16_t& v) const {
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
  if (int_value(dw.w.i, v)) push_a(kSlotI, kIntLatency, dw.w.i.d & 15, v);
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
  const std::uint32_t next = next_pc(dw.w.s);
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

}  // namespace mc1::apu
