// The APU instruction-set simulator: cycle-accurate to docs/apu-isa.md
// (stall priority, scoreboard, bank hand-over, faults, its Clarifications),
// with results and flags from the bit-accurate FP24 model.
//
// Two ways to clock it: step(CycleRecord&) for lockstep co-simulation and
// profiling, and run(max_cycles), the fast path with no records.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "apu_engine.hpp"
#include "microword.hpp"

namespace mc1::apu {

// The smallest power of two above n: a ring of future cycles that long holds
// every write still in flight.
constexpr int pow2_above(int n) {
  int r = 1;
  while (r <= n) r <<= 1;
  return r;
}

// A program word decoded once, when the MPU writes it: the fields plus what
// the stall logic and the issue ask of every word, resolved then (operand
// masks, each F write with its latency from the instruction-set table, the
// checks the word can need), so that a cycle decodes nothing.
class Iss;

struct alignas(64) DecodedWord {  // one cache line: a shift indexes the bank
  enum : std::uint8_t {
    kSwap = 1,       // SWAPD/SWAPP: subject to `bank`
    kCcBranch = 2,   // BCC/BNCC: subject to `cc`
    kHalt = 4,       // subject to `drain`
    kReserved = 8,   // a reserved op in some slot: faults when it would issue
    kMem = 16,       // LD/ST: the data address is checked
    kStack = 32,     // CALL/RET: the call stack is checked
    kRefetch = 64,   // a conditional branch or SWAPP: the next word may miss the fetch
    kMovF = 128,     // MOVAF/LIF: an I-slot F write
    kMayStall = kSwap | kCcBranch | kHalt,  // a stall beyond raw/waw is possible
  };
  // An F register write and the latency after which it is visible.
  struct FDst {
    std::uint8_t reg = 0, latency = 0;
  };
  MicroWord w;
  // A plain word: no swap, BCC/BNCC, HALT, CALL/RET, conditional branch or
  // reserved op, so that it cannot stall beyond raw/waw nor fault beyond its
  // data address, and the sequencer goes on to `next` (the next address or
  // a JMP's target, in the bank) with no fetch miss: run() clocks its
  // cycles whole (Iss::plain_cycle).
  std::uint16_t next = 0;
  // run()'s body from this address: an index into Iss::BodyBank::bodies, or
  // Iss::kBodyUnknown / kNoBody (found in the line the word is read from).
  std::int16_t body = -1;
  std::uint64_t src = 0;     // F registers read (raw)
  std::uint64_t hazard = 0;  // src | the F registers written: a word touching none in flight cannot stall on raw/waw
  // Each F write (waw): a write with latency L must land after every write
  // already in flight to its register.
  std::array<FDst, 5> dsts{};  // M, A, F, LD, MOVAF/LIF
  std::uint8_t ndst = 0;
  std::uint8_t kind = 0;
  // latency(op) of the A and F slots (LD, MOVAF and LIF: kLoadLatency; the
  // I slot's A writes: kIntLatency).
  std::uint8_t lat_a = 0, lat_f = 0;
  // run()'s issue of this word: Iss::issue specialized for the word's M, A,
  // F and D slots (its shape, an index into Iss's table), so that a cycle
  // tests none of them.
  std::uint8_t shape = 0;
  bool plain = false;

  // The word at program address addr.
  static DecodedWord from(const Encoded& e, std::uint32_t addr);
};
static_assert(sizeof(DecodedWord) == 64, "a decoded word is one cache line");

class Iss final : public ApuEngine {
 public:
  Iss() { reset(); }
  // Power-on state: banks 0, flags clear, every register and word 0, idle.
  void reset();

  // ApuEngine.
  void write_program(std::uint16_t addr, const Encoded& word) override;
  void write_data(std::uint16_t addr, std::uint32_t value) override;
  std::uint32_t read_data(std::uint16_t addr) const override;
  void write_data_block(std::uint16_t addr, const std::uint32_t* values, std::size_t n) override;
  void read_data_block(std::uint16_t addr, std::uint32_t* out, std::size_t n) const override;
  void hand_over_program() override { program_ready_ = true; }
  void hand_over_data() override { data_ready_ = true; }
  bool mpu_bank_while_running() const override { return true; }
  bool program_ready() const override { return program_ready_; }
  bool data_ready() const override { return data_ready_; }
  void start(std::uint16_t pc) override;
  void step(CycleRecord& rec) override;
  RunState state() const override { return state_; }
  Fault fault() const override { return fault_; }
  std::uint64_t cycle() const override { return cycle_; }
  std::uint32_t freg(int i) const override { return f_[i & 63]; }
  std::uint16_t areg(int i) const override { return a_[i & 15]; }
  std::uint8_t flags() const override { return static_cast<std::uint8_t>(flags_); }
  std::uint8_t cc() const override { return static_cast<std::uint8_t>(cc_); }
  const ApuCounters& counters() const override { return counters_; }

  // Fast path: clocks until the APU stops running (HALT issued, fault) or
  // max_cycles cycles have passed; returns the cycles clocked (0 when the
  // APU is not running).
  std::uint64_t run(std::uint64_t max_cycles) override { return run_fast<false>(max_cycles); }
  std::uint64_t run_until_data_taken(std::uint64_t max_cycles) override {
    return data_ready_ ? run_fast<true>(max_cycles) : 0;
  }

  // Observers beyond ApuEngine (tests, profiles, the driver).
  std::uint16_t pc() const { return static_cast<std::uint16_t>(pc_); }
  int psel() const { return psel_; }
  int dsel() const { return dsel_; }
  int call_depth() const { return sp_; }
  const Encoded& program_word(int bank, std::uint16_t addr) const {
    return program_[bank & 1][addr % kProgramWords];
  }

  using Counters = ApuCounters;

 private:
  // 32-bit fields throughout: a byte store could alias any member and make
  // the compiler reload the hot state after it.
  // prev: the register's value before the write, while run() holds the
  // write in the register early (see run_fast).
  struct FWrite { std::uint32_t index, value, prev; };
  struct AWrite { std::uint32_t index, value; };
  // What becomes visible in one future cycle. Each write has a fixed slot:
  // a bucket takes at most one write of each pipe (one word issues a cycle
  // and a pipe has one latency), so a push needs no count and a bucket's
  // writes are a mask of slots.
  enum FSlot : std::uint32_t { kSlotM, kSlotA, kSlotRsq, kSlotTrig, kSlotLd, kSlotMov, kFSlots };
  enum ASlot : std::uint32_t { kSlotI, kSlotDbnz, kASlots };
  static constexpr std::uint32_t kFSlotMask = 0x3F, kASlotShift = 8, kCcSlot = 1u << 16;
  // What an FP unit op writes (drain waits for these; LD, MOVAF, LIF are not).
  static constexpr std::uint32_t kFpSlots = 1u << kSlotM | 1u << kSlotA | 1u << kSlotRsq | 1u << kSlotTrig | kCcSlot;
  struct alignas(128) Bucket {  // a power of two: a shift indexes the ring
    // The F registers whose last write in flight lands here: the
    // scoreboard clears them when the bucket is applied.
    std::uint64_t last = 0;
    std::uint32_t slots = 0;  // the slots holding a write: F at bit FSlot, A at 8 + ASlot, CC at 16
    std::uint32_t flags_commit = 0;
    std::uint32_t cc = 0, flags = 0;  // flags: the OR of the ops', then FLAGS once applied
    FWrite f[kFSlots];
    AWrite a[kASlots];
  };
  static constexpr int kRing = pow2_above(kMaxLatency);

  // One cycle's issue, stall or fault; returns the stall reason (None if it
  // issued or did not run).
  template <bool kRecord>
  Stall execute(CycleRecord* rec);
  template <bool kUntilDataTaken>
  std::uint64_t run_fast(std::uint64_t max_cycles);
  bool writes_landed() const;
  template <bool kKeep, bool kEarly>
  void apply_next();
  template <bool kKeep, bool kEarly>
  void apply_bucket(Bucket& b);
  void writes_early();
  void writes_late();
  template <bool kRecord>
  void take_due(CycleRecord* rec, int& cc, int& flags);
  Stall stall_reason(const DecodedWord& dw) const;
  // The sequencer's next PC (1024 when it would run off the bank) and the
  // fault, if any, that keeps the word from issuing.
  std::uint32_t next_pc(const SeqSlot& s) const;
  // Whether `next` is not the word the sequencer fetched behind this one.
  bool fetch_missed(const SeqSlot& s, std::uint32_t next) const;
  Fault check_fault(const DecodedWord& dw, std::uint32_t next) const;
  // kShape: the word's slots as DecodedWord::shape, or kAnyShape
  // (read from the word). kPlain: the word is plain (DecodedWord::plain):
  // its S slot does nothing but choose `next`, and it refetches nothing.
  static constexpr int kAnyShape = -1, kShapes = 48;
  template <bool kRecord, int kShape, bool kPlain = false>
  void issue(const DecodedWord& dw, std::uint32_t next, CycleRecord* rec);
  using RunIssue = void (*)(Iss&, const DecodedWord&, std::uint32_t);
  using PlainCycle = bool (*)(Iss&, const DecodedWord&);
  template <int kShape>
  static void run_issue(Iss& iss, const DecodedWord& dw, std::uint32_t next);
  // A plain word's cycle in run() that is not the call's last and has no
  // stall: the word issues, unless it faults (then false, nothing done), and
  // the cycle's bucket is applied.
  template <int kShape>
  static bool plain_cycle(Iss& iss, const DecodedWord& dw);
  template <int... kShape>
  static constexpr std::array<RunIssue, sizeof...(kShape)> run_issue_table(std::integer_sequence<int, kShape...>) {
    return {&run_issue<kShape>...};
  }
  template <int... kShape>
  static constexpr std::array<PlainCycle, sizeof...(kShape)> plain_cycle_table(std::integer_sequence<int, kShape...>) {
    return {&plain_cycle<kShape>...};
  }
  static const std::array<RunIssue, kShapes> kRunIssue;
  static const std::array<PlainCycle, kShapes> kPlainCycle;
  friend struct DecodedWord;

  // A body: a straight run of plain words from a program address, clocked
  // by run() as a unit (run_body). Its timing is worked out once, when it is
  // built: each word's issue cycle counted from the body's first (its own
  // raw/waw stalls included, as if nothing were in flight when it starts),
  // and for each F register the latest landing cycle of a write in flight
  // at its start that changes none of that schedule (bound). An entry state
  // that meets the bounds and whose data addresses are all in range takes
  // the body, or a prefix of it; any other goes cycle by cycle. A write
  // that lands within the body goes straight to the state (no bucket, no
  // scoreboard); one that lands after it goes to the ring as on any cycle.
  // A body's hot data is compact and its own: run_body reads one Body (a
  // cache line) and its words, each with a copy of what its issue reads (no
  // DecodedWord); the bounds only when a write they bound is in flight, the
  // per-word counts only for a prefix.
  struct BodyWord {
    MicroWord w;
    std::uint16_t pc;        // in the body's bank
    std::uint16_t t;         // issue cycle, from the body's first
    std::uint16_t land;      // t + the longest latency of its FP writes and CC (t + 1 without)
    std::uint8_t shape, kind, lat_a, lat_f;  // as DecodedWord's
    std::uint8_t islot;      // its I slot: kISlotNone, kISlotA (an A1..A15 write) or kISlotF (MOVAF, LIF)
    // Its entry in body_direct_words: its shape, or for a closing branch
    // that can land within the body (no M, A or F op) kBranchEntry + D slot.
    std::uint8_t entry;
  };
  static constexpr int kBranchEntry = 48;
  enum : std::uint8_t { kISlotNone, kISlotA, kISlotF };
  struct BodyCounts {        // the body's stall cycles by reason and unit ops up to a word (its own included)
    std::uint16_t raw = 0, waw = 0, cc = 0;
    std::uint8_t ops[3] = {0, 0, 0};
  };
  struct MemCheck {  // the LD/ST of a body on one base register: its least and greatest displacement
    std::uint8_t base;
    std::int8_t lo, hi;
  };
  static constexpr int kMaxBodyBases = 4;  // base registers of a body's LD/ST
  static constexpr int kMaxBodyWords = 48;
  // What a body's start reads, in one cache line: the successors too, so
  // that a chain of bodies (run_body) goes from one to the next with no
  // look-up by address once it has run.
  struct alignas(64) Body {
    std::uint64_t early = 0;                 // the registers with a bound below kMaxLatency - 1
    std::uint32_t cc_at = ~0u;               // the issue cycle of its BCC/BNCC (no CMP of before may be in flight)
    std::uint32_t first = 0;                 // its words in BodyBank::words (and counts)
    std::uint16_t cycles = 0;                // its cycles (from its first to its last word's issue)
    std::uint16_t next = 0;                  // the pc after it when its last word is not a branch
    std::uint8_t n = 0;
    std::uint8_t direct = 0;                 // the words before this one land every write within the body
    std::uint8_t nmem = 0;
    std::uint8_t branch = 0;                 // its last word is a conditional branch
    // That branch's test, as body_branch evaluates it with no switch:
    // taken iff ((CC or A[r] less 1 or A[r]) & test_mask) != 0, inverted or not.
    std::uint8_t test = 0;                   // kTest* bits
    std::uint16_t test_mask = 0;
    // The bodies that can follow it (0: a branch's target or next; 1: the
    // branch's next address), kBodyUnknown until a chain has looked them up.
    std::int16_t succ[2] = {-1, -1};
    BodyCounts total;                        // the counts of its last word
    MemCheck mem[kMaxBodyBases] = {};        // its data addresses
  };
  enum : std::uint8_t {
    kTestCc = 1,         // BCC/BNCC: CC
    kTestDec = 2,        // DBNZ: A[r] - 1
    kTestInvert = 4,     // BZ, BNCC
    kTestDbnzWrite = 8,  // DBNZ to A1..A15
    kMissTaken = 16,     // taken, the next word missed the fetch
    kMissFall = 32,      // not taken, the same
  };
  static_assert(sizeof(Body) <= 64, "a body's start reads one cache line");
  static constexpr std::int16_t kBodyUnknown = -1, kNoBody = -2;
  struct BodyBank {
    std::vector<std::uint16_t> heads;  // the addresses whose DecodedWord::body is known
    std::vector<Body> bodies;
    std::vector<std::array<std::uint8_t, kNumFRegs>> bounds;  // by body
    std::vector<BodyWord> words;
    std::vector<BodyCounts> counts;  // by word
    bool stale = true;
  };
  struct BodySchedule;
  std::uint64_t run_body(std::uint64_t avail);
  void renew_bodies(int bank);
  bool body_may_start(const BodyBank& bb, std::size_t index, std::uint64_t e) const;
  int body_branch(const Body& body, const BodyWord& w, std::uint64_t e, std::uint64_t end);
  // A body's closing branch: taken or not, from A[r] (ar) and CC before its
  // word's writes; after them, its own effects. Returns the successor.
  bool branch_taken(const Body& body, const BodyWord& w, std::uint32_t& ar) const;
  int branch_done(const Body& body, const BodyWord& w, bool taken, std::uint32_t ar);
  static void branch_test(Body& body, const DecodedWord& dw, std::uint32_t pc);
  std::int16_t build_body(int bank, std::uint32_t pc);
  static bool add_mem_check(Body& body, const DecodedWord& dw);
  std::int16_t body_at(int bank, std::uint32_t pc);
  struct BodySums;
  std::uint64_t one_body(const Body& body, std::uint64_t avail, BodySums& sum, int& succ);
  using BodyIssue = void (*)(Iss&, const BodyWord&, std::uint64_t);
  template <int kShape, bool kTail>
  static void body_issue(Iss& iss, const BodyWord& dw, std::uint64_t end);
  // fl: FLAGS, which the word's writes that land within the body OR into.
  template <int kShape, bool kTail>
  static void body_word(Iss& iss, const BodyWord& dw, std::uint64_t end, std::uint32_t& fl);
  // body: for a closing branch among the words (taken, ar: branch_taken's).
  void body_direct_words(const BodyWord* w, std::uint32_t count, std::uint64_t end, const Body* body, bool& taken,
                         std::uint32_t& ar);
  template <bool kTail>
  void body_write(FSlot slot, int latency, std::uint32_t index, std::uint32_t value, std::uint32_t flags,
                  std::uint64_t end, std::uint32_t& fl);
  template <int... kShape>
  static constexpr std::array<BodyIssue, sizeof...(kShape)> body_table(std::integer_sequence<int, kShape...>,
                                                                       std::false_type) {
    return {&body_issue<kShape, false>...};
  }
  template <int... kShape>
  static constexpr std::array<BodyIssue, sizeof...(kShape)> body_table(std::integer_sequence<int, kShape...>,
                                                                       std::true_type) {
    return {&body_issue<kShape, true>...};
  }
  static const std::array<BodyIssue, kShapes> kBodyDirect, kBodyTail;

  void int_op(const DecodedWord& dw);
  // The I slot's A register result (its reads see the state before the
  // word's writes); false if it writes no A register.
  bool int_value(const IntSlot& i, std::uint16_t& value) const;
  void seq_op(const DecodedWord& dw);
  // An F write and the flags of the op that makes it; pending: the
  // scoreboard before the word. Returns the register's scoreboard bit.
  template <bool kEarly>
  std::uint64_t push_f(FSlot slot, int latency, std::uint32_t index, std::uint32_t value, std::uint32_t flags,
                       std::uint64_t pending);
  bool fp_in_flight() const;
  void push_a(ASlot slot, int latency, std::uint32_t index, std::uint16_t value);

  // What the MPU's side reads while the engine runs (the bank of its data
  // accesses, dsel_; the hand-over flags; state()) on a cache line of its
  // own, which the engine writes only at a start, a HALT or fault and a
  // swap: on a pool worker the engine runs on another core than the MPU's
  // thread, and a line both the MPU's side reads and every cycle writes
  // (pc_, flags_, the first F registers) went back and forth between the
  // cores at the MPU's data-bank accesses (about 3 M a frame).
  alignas(64) RunState state_ = RunState::Idle;
  int psel_ = 0, dsel_ = 0;
  bool program_ready_ = false, data_ready_ = false;

  // Hot state next: what every cycle reads.
  alignas(64) std::uint64_t cycle_ = 0;
  // The scoreboard: the F registers with a write in flight (visible after
  // the current cycle), and for each the cycle its last write becomes
  // visible (writes to one register land in issue order: waw).
  std::uint64_t pending_ = 0;
  std::uint64_t cmp_done_ = 0;     // first cycle with no CMP in flight
  std::uint64_t ring_last_ = 0;    // no bucket after this cycle's holds anything (the latest write pushed)
  std::uint32_t pc_ = 0;
  // Cycles left with no word to issue (`fetch`): a start's fetch and decode,
  // the bubble after a branch miss or a SWAPP.
  int fetching_ = 0;
  std::uint32_t cc_ = 0, flags_ = 0;
  int sp_ = 0;
  Fault fault_ = Fault::None;
  std::array<std::uint32_t, kNumFRegs> f_{};
  std::array<std::uint16_t, kNumARegs> a_{};
  std::array<std::uint16_t, kCallDepth> stack_{};
  Counters counters_;
  std::array<std::uint64_t, kNumFRegs> land_{};
  // Future writes by cycle.
  std::array<Bucket, kRing> ring_{};
  std::array<std::array<DecodedWord, kProgramWords>, 2> decoded_{};
  std::array<std::array<std::uint32_t, kDataWords>, 2> data_{};
  std::array<std::array<Encoded, kProgramWords>, 2> program_{};
  std::array<BodyBank, 2> body_{};
};

}  // namespace mc1::apu
