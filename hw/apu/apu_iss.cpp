// The APU instruction-set simulator (docs/apu-isa.md, "Timing" and
// "Clarifications"): the decode, the MPU's calls and step(), the lockstep
// path; run(), the fast path, is apu_iss_run.cpp. Per-cycle work is a few
// mask tests and, on issue, the FP24 model calls; nothing allocates once a
// CycleRecord has its capacity.
#include "apu_iss.hpp"

#include "apu_iss_inline.hpp"

namespace mc1::apu {

namespace {


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
  // The same word again (a kernel loaded anew) changes nothing: its decode
  // and the bank's bodies stand.
  if (program_[bank][addr] == word) return;
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

// An FP unit op issued and not yet landed (`drain`): a later bucket holds
// its write or CC.
bool Iss::fp_in_flight() const {
  for (int k = 1; k <= kMaxLatency; ++k)
    if (ring_[(cycle_ + k) % kRing].slots & kFpSlots) return true;
  return false;
}

}  // namespace mc1::apu
