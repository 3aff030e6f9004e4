// The ISS's fast path, run() (docs/apu-tools.md "The ISS"): cycles clocked
// with no records, F results written at issue, and bodies, straight runs of
// plain words clocked as a unit.
#include "apu_iss.hpp"

#include "apu_iss_inline.hpp"

namespace mc1::apu {

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

// ---- Bodies (run_body): straight runs of plain words clocked as a unit.

const std::array<Iss::BodyIssue, Iss::kShapes> Iss::kBodyDirect =
    Iss::body_table(std::make_integer_sequence<int, Iss::kShapes>{}, std::false_type{});
const std::array<Iss::BodyIssue, Iss::kShapes> Iss::kBodyTail =
    Iss::body_table(std::make_integer_sequence<int, Iss::kShapes>{}, std::true_type{});

namespace {

// A conditional branch on an A register or CC may end a body: it can stall
// only on raw, waw or cc, and fault only past the bank's end.
bool ends_body(const DecodedWord& dw, std::uint32_t addr) {
  const SeqOp op = dw.w.s.op;
  return (op == SeqOp::Dbnz || op == SeqOp::Bz || op == SeqOp::Bnz || op == SeqOp::Bltz || op == SeqOp::Bcc ||
          op == SeqOp::Bncc) &&
         !(dw.kind & DecodedWord::kReserved) && addr + 1 < static_cast<std::uint32_t>(kProgramWords);
}

}  // namespace

// A body's own timing while it is built, as if nothing were in flight when
// it starts (docs/apu-isa.md "Timing": raw first, then waw, then cc).
struct Iss::BodySchedule {
  std::array<int, kNumFRegs> land;  // the cycle each register's last write of the body lands
  int cc_land = -1;                 // the cycle the body's last CMP lands
  int t = -1;                       // the last word's issue cycle
  std::uint32_t raw = 0, waw = 0, cc = 0;
  BodySchedule() { land.fill(-1); }

  // The word after the last issues: its cycle; bound takes its reads and
  // writes. Returns t + its longest latency (t + 1 with no FP write or CC).
  // The bounds count from the first cycle the word tries to issue (t0): a
  // write of before the body still in flight in one of its stall cycles
  // would change the cycle's reason (raw before waw before cc), not only
  // its length.
  int issue(const DecodedWord& dw, std::array<std::uint8_t, kNumFRegs>& bound) {
    const bool cc_branch = (dw.kind & DecodedWord::kCcBranch) != 0;
    const int t0 = ++t;
    for (;;) {
      bool r = false, ww = false;
      for (std::uint64_t m = dw.src; m != 0; m &= m - 1) r |= land[__builtin_ctzll(m)] > t;
      for (int k = 0; k < dw.ndst; ++k) ww |= land[dw.dsts[k].reg] >= t + dw.dsts[k].latency;
      const bool c = cc_branch && cc_land > t;
      if (!r && !ww && !c) break;
      ++(r ? raw : ww ? waw : cc);
      ++t;
    }
    int longest = 1;
    for (std::uint64_t m = dw.src; m != 0; m &= m - 1) {
      std::uint8_t& b = bound[__builtin_ctzll(m)];
      b = static_cast<std::uint8_t>(std::min<int>(b, t0));
    }
    for (int k = 0; k < dw.ndst; ++k) {
      const DecodedWord::FDst& d = dw.dsts[k];
      std::uint8_t& b = bound[d.reg];
      b = static_cast<std::uint8_t>(std::min<int>(b, t0 + d.latency - 1));
      land[d.reg] = t + d.latency;
      longest = std::max<int>(longest, d.latency);
    }
    if (dw.w.a.en) {
      longest = std::max<int>(longest, dw.lat_a);  // CMP's CC
      if (dw.w.a.op == AddOp::Cmp) cc_land = t + dw.lat_a;
    }
    return t + longest;
  }
};

// The LD/ST of a body on one base register: their displacements' range.
// False if it would be a base beyond kMaxBodyBases (the body ends before it).
bool Iss::add_mem_check(Body& body, const DecodedWord& dw) {
  const std::int8_t d = dw.w.d.disp;
  MemCheck* const end = body.mem + body.nmem;
  MemCheck* const it = std::find_if(body.mem, end, [&dw](const MemCheck& c) { return c.base == dw.w.d.base; });
  if (it != end) {
    it->lo = std::min(it->lo, d);
    it->hi = std::max(it->hi, d);
  } else if (body.nmem == kMaxBodyBases) {
    return false;
  } else {
    *it = {static_cast<std::uint8_t>(dw.w.d.base), d, d};
    ++body.nmem;
  }
  return true;
}

// The body from pc: its words, their schedule and the bounds on the writes
// in flight at its start that keep that schedule. It ends before a word
// that is neither plain nor ends_body() (after one that is), after
// kMaxBodyWords words, or before a LD/ST whose base register an earlier
// word of it writes (so that its data addresses are known, and checked,
// when it starts) or that would be its base beyond kMaxBodyBases.
std::int16_t Iss::build_body(int bank, std::uint32_t pc) {
  BodyBank& bb = body_[bank];
  DecodedWord& head = decoded_[bank][pc];
  bb.heads.push_back(static_cast<std::uint16_t>(pc));
  Body body;
  body.first = static_cast<std::uint32_t>(bb.words.size());
  std::array<std::uint8_t, kNumFRegs> bound;
  bound.fill(255);
  BodySchedule sched;
  std::uint32_t a_written = 0;
  BodyCounts sum;
  std::uint32_t p = pc;
  while (body.n < kMaxBodyWords) {
    const DecodedWord& dw = decoded_[bank][p];
    const bool branch = !dw.plain && ends_body(dw, p);
    if (!dw.plain && !branch) break;
    if (dw.w.d.op != MemOp::None && (((a_written >> dw.w.d.base) & 1) || !add_mem_check(body, dw))) break;
    const int land = sched.issue(dw, bound);
    if (dw.kind & DecodedWord::kCcBranch) body.cc_at = static_cast<std::uint32_t>(sched.t);
    sum.ops[0] = static_cast<std::uint8_t>(sum.ops[0] + dw.w.m.en);
    sum.ops[1] = static_cast<std::uint8_t>(sum.ops[1] + dw.w.a.en);
    sum.ops[2] = static_cast<std::uint8_t>(sum.ops[2] + dw.w.f.en);
    sum.raw = static_cast<std::uint16_t>(sched.raw);
    sum.waw = static_cast<std::uint16_t>(sched.waw);
    sum.cc = static_cast<std::uint16_t>(sched.cc);
    std::uint16_t v;
    const bool a_write = int_value(dw.w.i, v);
    const std::uint8_t islot = (dw.kind & DecodedWord::kMovF) ? kISlotF
                               : a_write && (dw.w.i.d & 15) != 0 ? kISlotA
                                                                  : kISlotNone;  // A0 drops its writes
    const std::uint8_t entry = branch && (dw.shape & 15) == 0 ? static_cast<std::uint8_t>(kBranchEntry + (dw.shape >> 4))
                                                               : dw.shape;
    bb.words.push_back({dw.w, static_cast<std::uint16_t>(p), static_cast<std::uint16_t>(sched.t),
                        static_cast<std::uint16_t>(land), dw.shape, dw.kind, dw.lat_a, dw.lat_f, islot, entry});
    bb.counts.push_back(sum);
    if (a_write) a_written |= 1u << (dw.w.i.d & 15);
    if (dw.w.s.op == SeqOp::Dbnz) a_written |= 1u << (dw.w.s.r & 15);
    ++body.n;
    if (branch) {
      branch_test(body, dw, p);
      break;
    }
    p = body.next = dw.next;
  }
  if (body.n == 0) {
    head.body = kNoBody;
    return kNoBody;
  }
  body.total = sum;
  const BodyWord* words = bb.words.data() + body.first;
  body.cycles = static_cast<std::uint16_t>(words[body.n - 1].t + 1u);
  while (body.direct < body.n && words[body.direct].land <= body.cycles) ++body.direct;
  for (int r = 0; r < kNumFRegs; ++r)
    if (bound[r] < kMaxLatency - 1) body.early |= bit(static_cast<unsigned>(r));
  bb.bodies.push_back(body);
  bb.bounds.push_back(bound);
  head.body = static_cast<std::int16_t>(bb.bodies.size() - 1);
  return head.body;
}

// A body's closing branch at pc, for body_branch: next_pc() and
// fetch_missed() worked out once.
void Iss::branch_test(Body& body, const DecodedWord& dw, std::uint32_t pc) {
  const SeqSlot& s = dw.w.s;
  body.branch = 1;
  const bool cc = s.op == SeqOp::Bcc || s.op == SeqOp::Bncc;
  body.test_mask = cc ? s.r : s.op == SeqOp::Bltz ? 0x8000 : 0xFFFF;
  body.test = static_cast<std::uint8_t>((cc ? kTestCc : 0) | (s.op == SeqOp::Dbnz ? kTestDec : 0) |
                                        (s.op == SeqOp::Bz || s.op == SeqOp::Bncc ? kTestInvert : 0) |
                                        (s.op == SeqOp::Dbnz && (s.r & 15) != 0 ? kTestDbnzWrite : 0));
  const std::uint32_t predicted = s.target <= pc ? s.target : pc + 1u;
  if (s.target != predicted) body.test |= kMissTaken;
  if (pc + 1u != predicted) body.test |= kMissFall;
}

// The body at pc (built when first met), or kNoBody.
std::int16_t Iss::body_at(int bank, std::uint32_t pc) {
  const std::int16_t index = decoded_[bank][pc].body;
  return index == kBodyUnknown ? build_body(bank, pc) : index;
}

// A bank's program changed: its bodies are built anew as run() meets them.
void Iss::renew_bodies(int bank) {
  BodyBank& bb = body_[bank];
  for (const std::uint16_t pc : bb.heads) decoded_[bank][pc].body = kBodyUnknown;
  bb.heads.clear();
  bb.bodies.clear();
  bb.bounds.clear();
  bb.words.clear();
  bb.counts.clear();
  bb.stale = false;
}

// kTail: the write may land after the body's end (then into the ring).
template <bool kTail>
MC1_HOT void Iss::body_write(FSlot slot, int latency, std::uint32_t index, std::uint32_t value, std::uint32_t flags,
                             std::uint64_t end, std::uint32_t& fl) {
  if (kTail && cycle_ + latency > end) {
    pending_ |= push_f<true>(slot, latency, index, value, flags, pending_);
    return;
  }
  f_[index] = value;
  fl |= flags;
}

// A word of a body issues: as issue(), with writes that land within the
// body (all of them unless kTail) made at once. The I slot's A write lands
// in the next cycle, always within the body. kTail: cycle_ is the word's
// issue cycle.
template <int kShape, bool kTail>
MC1_HOT void Iss::body_word(Iss& iss, const BodyWord& dw, std::uint64_t end, std::uint32_t& fl) {
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
  // The I slot's result, read before the word's writes (MOVFA reads F):
  // an A register's value or an F register's.
  std::uint16_t av = 0;
  std::uint32_t mov = 0;
  if (__builtin_expect(dw.islot != kISlotNone, 0)) {
    if (dw.islot == kISlotA) {
      iss.int_value(w.i, av);
    } else {
      mov = w.i.op == IntOp::Movaf ? iss.a_[w.i.s] : (std::uint32_t{w.i.imm} << 8) & kMask24;
    }
  }

  if constexpr (m_en) iss.body_write<kTail>(kSlotM, kMulLatency, w.m.d, rm.value, rm.flags, end, fl);
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
        fl |= ra.flags;
      }
    } else {
      iss.body_write<kTail>(kSlotA, dw.lat_a, w.a.d, ra.value, ra.flags, end, fl);
    }
  }
  if constexpr (f_en) {
    const FSlot slot = w.f.op == FuncOp::Sin || w.f.op == FuncOp::Cos ? kSlotTrig : kSlotRsq;
    iss.body_write<kTail>(slot, dw.lat_f, w.f.d, rf.value, rf.flags, end, fl);
  }
  if constexpr (d_op == MemOp::Ld) iss.f_[w.d.f] = loaded;
  if (__builtin_expect(dw.islot != kISlotNone, 0)) {
    if (dw.islot == kISlotA) {
      iss.a_[w.i.d & 15] = av;
    } else {
      iss.f_[w.i.d] = mov;
    }
  }
}

template <int kShape, bool kTail>
void Iss::body_issue(Iss& iss, const BodyWord& dw, std::uint64_t end) {
  body_word<kShape, kTail>(iss, dw, end, iss.flags_);
}

// The first count words of a body, all landing within it, as threaded code:
// each word's issue is in line and ends with its own jump to the next
// word's, so that the host predicts each from the one before, with no call.
void Iss::body_direct_words(const BodyWord* w, std::uint32_t count, std::uint64_t end, const Body* body, bool& taken,
                            std::uint32_t& ar) {
#define MC1_SHAPES(X)                                                                                  \
  X(0) X(1) X(2) X(3) X(4) X(5) X(6) X(7) X(8) X(9) X(10) X(11) X(12) X(13) X(14) X(15) X(16) X(17)  \
  X(18) X(19) X(20) X(21) X(22) X(23) X(24) X(25) X(26) X(27) X(28) X(29) X(30) X(31) X(32) X(33) \
  X(34) X(35) X(36) X(37) X(38) X(39) X(40) X(41) X(42) X(43) X(44) X(45) X(46) X(47)
#define MC1_LABEL(k) &&shape_##k,
#define MC1_WORD(k)                        \
  shape_##k:                               \
  body_word<k, false>(*this, *w, end, fl); \
  if (++w == stop) goto done;              \
  goto* kWord[w->entry];
  static_assert(kShapes == 48 && kBranchEntry == kShapes, "MC1_SHAPES lists every shape");
  // A closing branch with no M, A or F op: D slot none, LD or ST.
  static const void* const kWord[kShapes + 3] = {MC1_SHAPES(MC1_LABEL) &&branch_0, &&branch_16, &&branch_32};
  const BodyWord* const stop = w + count;
  std::uint32_t fl = flags_;  // in a register across the words
  goto* kWord[w->entry];
  MC1_SHAPES(MC1_WORD)
branch_0:
  taken = branch_taken(*body, *w, ar);
  goto shape_0;
branch_16:
  taken = branch_taken(*body, *w, ar);
  goto shape_16;
branch_32:
  taken = branch_taken(*body, *w, ar);
  goto shape_32;
done:
  flags_ = fl;
#undef MC1_WORD
#undef MC1_LABEL
#undef MC1_SHAPES
}

// Whether the state lets the body start at cycle e: every write in flight
// lands no later than its bound, no CMP is in flight at its BCC/BNCC, and
// every data address is in range without a wrap (else cycle by cycle: a
// fault, or a wrap that lands in range).
MC1_HOT bool Iss::body_may_start(const BodyBank& bb, std::size_t index, std::uint64_t e) const {
  const Body& body = bb.bodies[index];
  if (const std::uint64_t early = pending_ & body.early) {
    const std::array<std::uint8_t, kNumFRegs>& bound = bb.bounds[index];
    for (std::uint64_t m = early; m != 0; m &= m - 1) {
      const int r = __builtin_ctzll(m);
      if (land_[r] - e > bound[r]) return false;
    }
  }
  if (cmp_done_ > e + body.cc_at) return false;
  for (std::uint32_t i = 0; i < body.nmem; ++i) {
    const int a = a_[body.mem[i].base];
    if (a + body.mem[i].lo < 0 || a + body.mem[i].hi >= kDataWords) return false;
  }
  return true;
}

// A body's closing conditional branch issues in cycle e + w.t: its reads
// (A[r], CC) see the state before its own writes.
MC1_HOT bool Iss::branch_taken(const Body& body, const BodyWord& w, std::uint32_t& ar) const {
  const std::uint32_t test = body.test;
  ar = a_[w.w.s.r & 15];
  const std::uint32_t v = (test & kTestCc) ? cc_ : ar - ((test & kTestDec) ? 1u : 0u);
  return ((v & body.test_mask) != 0) != ((test & kTestInvert) != 0);
}

MC1_HOT int Iss::branch_done(const Body& body, const BodyWord& w, bool taken, std::uint32_t ar) {
  const std::uint32_t test = body.test;
  if (test & (taken ? kMissTaken : kMissFall)) fetching_ = kBranchMissCycles;
  if (test & kTestDbnzWrite) a_[w.w.s.r & 15] = static_cast<std::uint16_t>(ar - 1);
  pc_ = taken ? w.w.s.target : w.pc + 1u;
  return taken ? 0 : 1;
}

// The closing branch's word issues in cycle e + w.t. Returns the successor
// it leads to (0 taken, 1 not).
MC1_HOT int Iss::body_branch(const Body& body, const BodyWord& w, std::uint64_t e, std::uint64_t end) {
  std::uint32_t ar;
  const bool taken = branch_taken(body, w, ar);
  cycle_ = e + w.t;
  (e + w.land <= end ? kBodyDirect : kBodyTail)[w.shape](*this, w, end);
  return branch_done(body, w, taken, ar);
}

// What a chain of bodies adds to the counters.
struct Iss::BodySums {
  std::uint64_t issued = 0, raw = 0, waw = 0, cc = 0, fetch = 0, ops[3] = {0, 0, 0};
  void add(const BodyCounts& c, std::uint32_t n) {
    issued += n;
    raw += c.raw;
    waw += c.waw;
    cc += c.cc;
    for (int u = 0; u < 3; ++u) ops[u] += c.ops[u];
  }
};

// The body at pc, or its longest prefix that fits in avail cycles (it may
// start: body_may_start): returns the cycles clocked, 0 if none. As many
// cycles of run() (none of them its last) would leave the state and the
// ring; the counts go to sum, and succ is the successor it leads to (-1
// for a prefix).
MC1_HOT std::uint64_t Iss::one_body(const Body& body, std::uint64_t avail, BodySums& sum, int& succ) {
  const BodyBank& bb = body_[psel_];
  const std::uint64_t e = cycle_;
  const BodyWord* words = bb.words.data() + body.first;
  std::uint32_t n = body.n;
  std::uint64_t cycles = body.cycles;
  std::uint32_t direct = body.direct;  // the words before it land every write within the body
  const BodyCounts* counts = &body.total;
  if (__builtin_expect(cycles > avail, 0)) {  // the call ends first: a prefix
    while (n > 0 && words[n - 1].t + 1u > avail) --n;
    if (n == 0) return 0;
    cycles = words[n - 1].t + 1u;
    direct = 0;
    while (direct < n && words[direct].land <= cycles) ++direct;
    counts = &bb.counts[body.first + n - 1];
  }
  const std::uint64_t end = e + cycles;
  // The writes in flight that land within the body enter the state first
  // (no word of it reads or overwrites them earlier: the bounds).
  if (ring_last_ > e) {
    for (std::uint64_t c = e + 1; c <= std::min(ring_last_, end); ++c) {
      apply_bucket<false, true>(ring_[c % kRing]);
    }
  }
  const bool branch = n == body.n && body.branch;
  const std::uint32_t m = n - branch;
  bool taken = false;
  std::uint32_t ar = 0;
  if (branch && direct == n && words[m].entry >= kBranchEntry) {  // every word lands within the body: one threaded run
    body_direct_words(words, n, end, &body, taken, ar);
    succ = branch_done(body, words[m], taken, ar);
    cycle_ = end;
    sum.add(*counts, n);
    return cycles;
  }
  std::uint32_t i = 0;
  if (direct > 0 && m > 0) {
    i = std::min(direct, m);
    body_direct_words(words, i, end, nullptr, taken, ar);
  }
  for (; i < m; ++i) {
    const BodyWord& w = words[i];
    if (e + w.land <= end) {
      kBodyDirect[w.shape](*this, w, end);
    } else {
      cycle_ = e + w.t;
      kBodyTail[w.shape](*this, w, end);
    }
  }
  if (branch) {
    succ = body_branch(body, words[m], e, end);
  } else if (n == body.n) {
    pc_ = body.next;
    succ = 0;
  } else {
    pc_ = words[n].pc;
    succ = -1;
  }
  cycle_ = end;
  sum.add(*counts, n);
  return cycles;
}

// Bodies one after another from pc, as long as each may start and the call
// has cycles left (avail: none of them its last): a body goes on to the
// next through its successor links, with no return to run_fast's loop. A
// branch that missed the fetch: its cycles with no word to issue
// (Stall::Fetch; each applies its bucket, as any cycle of run). Returns the
// cycles clocked, 0 if none.
std::uint64_t Iss::run_body(std::uint64_t avail) {
  const int bank = psel_;
  BodyBank& bb = body_[bank];
  BodySums sum;
  std::uint64_t done = 0;
  for (std::int16_t index = body_at(bank, pc_); index >= 0;) {
    const auto bi = static_cast<std::size_t>(index);
    if (!body_may_start(bb, bi, cycle_)) break;
    int s = -1;
    const std::uint64_t k = one_body(bb.bodies[bi], avail - done, sum, s);
    if (k == 0) break;
    done += k;
    while (fetching_ > 0 && done < avail) {
      --fetching_;
      ++sum.fetch;
      ++done;
      ++cycle_;
      apply_next<false, true>();
    }
    if (fetching_ > 0 || done == avail) break;
    if (s < 0) {
      index = body_at(bank, pc_);
    } else if ((index = bb.bodies[bi].succ[s]) == kBodyUnknown) {
      index = body_at(bank, pc_);  // may build a body: bodies moves
      bb.bodies[bi].succ[s] = index;
    }
  }
  counters_.issued += sum.issued;
  for (int u = 0; u < 3; ++u) counters_.unit_ops[u] += sum.ops[u];
  counters_.stalls[static_cast<int>(Stall::Raw)] += sum.raw;
  counters_.stalls[static_cast<int>(Stall::Waw)] += sum.waw;
  counters_.stalls[static_cast<int>(Stall::Cc)] += sum.cc;
  counters_.stalls[static_cast<int>(Stall::Fetch)] += sum.fetch;
  return done;
}

template <bool kUntilDataTaken>
std::uint64_t Iss::run_fast(std::uint64_t max_cycles) {
  if (max_cycles == 0 || state_ != RunState::Running) return 0;
  int cc = kNoCommit, flags = kNoCommit;
  take_due<false>(nullptr, cc, flags);  // what the last clock applied (nothing records it now)
  writes_early();
  for (int bank = 0; bank < 2; ++bank)
    if (body_[bank].stale) renew_bodies(bank);
  for (std::uint64_t n = 1;; ++n) {
    if (fetching_ == 0 && n < max_cycles) {
      // After bodies (run_body goes on while one may start), the cycle
      // after them.
      n += run_body(max_cycles - n);
      if (fetching_ == 0 && n < max_cycles) {
        const DecodedWord& dw = decoded_[psel_][pc_];
        if (dw.plain && !(dw.hazard & pending_) && kPlainCycle[dw.shape](*this, dw)) continue;
      }
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
