// The lockstep checker catches a corrupted engine at the exact cycle, and the
// random program generator makes valid, terminating, varied test cases.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <set>

#include "../tb/apu/apu_lockstep.hpp"
#include "apu_driver.hpp"
#include "apu_random.hpp"
#include "disasm.hpp"
#include "apu_rtl_engine.hpp"
#include "apu_test_program.hpp"

namespace mc1::apu {
namespace {

// An ISS whose records are falsified in one cycle, one way.
class CorruptEngine final : public ApuEngine {
 public:
  enum class Mode { FlipCommitBit, DropCommit, ChangeStall, ShiftPc };
  CorruptEngine(std::uint64_t at, Mode mode) : at_(at), mode_(mode) {}

  void write_program(std::uint16_t a, const Encoded& w) override { iss_->write_program(a, w); }
  void write_data(std::uint16_t a, std::uint32_t v) override { iss_->write_data(a, v); }
  std::uint32_t read_data(std::uint16_t a) const override { return iss_->read_data(a); }
  void hand_over_program() override { iss_->hand_over_program(); }
  void hand_over_data() override { iss_->hand_over_data(); }
  bool program_ready() const override { return iss_->program_ready(); }
  bool data_ready() const override { return iss_->data_ready(); }
  void start(std::uint16_t pc) override { iss_->start(pc); }
  RunState state() const override { return iss_->state(); }
  Fault fault() const override { return iss_->fault(); }
  std::uint64_t cycle() const override { return iss_->cycle(); }
  std::uint32_t freg(int i) const override { return iss_->freg(i); }
  std::uint16_t areg(int i) const override { return iss_->areg(i); }
  std::uint8_t flags() const override { return iss_->flags(); }
  std::uint8_t cc() const override { return iss_->cc(); }
  const ApuCounters& counters() const override { return iss_->counters(); }

  void step(CycleRecord& rec) override {
    iss_->step(rec);
    if (rec.cycle != at_) return;
    switch (mode_) {
      case Mode::FlipCommitBit: rec.commits.back().value ^= 0x100; break;
      case Mode::DropCommit: rec.commits.pop_back(); break;
      case Mode::ChangeStall: rec.stall = rec.stall == Stall::Raw ? Stall::Waw : Stall::Raw; break;
      case Mode::ShiftPc: rec.pc ^= 1; break;
    }
  }

 private:
  std::unique_ptr<Iss> iss_ = std::make_unique<Iss>();
  std::uint64_t at_;
  Mode mode_;
};

// Runs a random case on a and b in lockstep; the first divergence, if any.
std::optional<Divergence> lockstep_case(const RandomCase& c, ApuEngine& a, ApuEngine& b, std::uint64_t* cycles = nullptr) {
  ApuEngine* both[2] = {&a, &b};
  RandomMpu mpu(c);
  mpu.boot(both, 2);
  Lockstep ls(a, b);
  std::uint64_t n = 0;
  int settle = ApuDriver::kSettleCycles;  // the HALT word's own results land
  for (; n < c.max_cycles && (ls.running() || settle-- > 0); ++n) {
    mpu.before_cycle(both, 2);
    if (auto d = ls.step()) return d;
  }
  if (cycles) *cycles = n;
  return ls.compare_state();
}

// The cycles of a clean run of case c in which something is committed / stalls.
struct Trace {
  std::vector<std::uint64_t> commit_cycles, stall_cycles;
};
Trace trace_case(const RandomCase& c) {
  Trace t;
  auto iss = std::make_unique<Iss>();
  ApuEngine* one[1] = {iss.get()};
  RandomMpu mpu(c);
  mpu.boot(one, 1);
  CycleRecord r;
  while (iss->state() == RunState::Running) {
    mpu.before_cycle(one, 1);
    iss->step(r);
    if (!r.commits.empty()) t.commit_cycles.push_back(r.cycle);
    if (r.stall != Stall::None) t.stall_cycles.push_back(r.cycle);
  }
  return t;
}

RandomCase busy_case() {
  // The first case of seed 1 with enough commits and stalls to pick from.
  for (std::uint64_t i = 0;; ++i) {
    RandomCase c = make_random_case(case_seed(1, i));
    const Trace t = trace_case(c);
    if (t.commit_cycles.size() > 40 && t.stall_cycles.size() > 10) return c;
  }
}

TEST(ApuCosim, TwoIssAgree) {
  for (std::uint64_t i = 0; i < 50; ++i) {
    const RandomCase c = make_random_case(case_seed(3, i));
    auto a = std::make_unique<Iss>(), b = std::make_unique<Iss>();
    std::uint64_t cycles = 0;
    const auto d = lockstep_case(c, *a, *b, &cycles);
    EXPECT_FALSE(d) << d->report("a", "b");
    EXPECT_GT(cycles, 10u);
  }
}

TEST(ApuCosim, FlippedCommitIsCaughtAtItsCycle) {
  const RandomCase c = busy_case();
  const Trace t = trace_case(c);
  for (std::size_t k : {std::size_t{0}, t.commit_cycles.size() / 2, t.commit_cycles.size() - 1}) {
    const std::uint64_t at = t.commit_cycles[k];
    auto good = std::make_unique<Iss>();
    CorruptEngine bad(at, CorruptEngine::Mode::FlipCommitBit);
    const auto d = lockstep_case(c, *good, bad);
    ASSERT_TRUE(d) << "corruption at cycle " << at << " not caught";
    EXPECT_EQ(d->cycle, at);
    EXPECT_EQ(d->field.rfind("commit ", 0), 0u) << d->field;
    EXPECT_NE(d->a, d->b);
    EXPECT_FALSE(d->word.empty());
    const std::string report = d->report("iss", "bad");
    EXPECT_NE(report.find("divergence at cycle " + std::to_string(at) + ", pc "), std::string::npos) << report;
  }
}

TEST(ApuCosim, DroppedCommitIsCaught) {
  const RandomCase c = busy_case();
  const std::uint64_t at = trace_case(c).commit_cycles[5];
  auto good = std::make_unique<Iss>();
  CorruptEngine bad(at, CorruptEngine::Mode::DropCommit);
  const auto d = lockstep_case(c, *good, bad);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->cycle, at);
  EXPECT_EQ(d->b, "(none)");
}

TEST(ApuCosim, WrongStallReasonAndPcAreCaught) {
  const RandomCase c = busy_case();
  const std::uint64_t at = trace_case(c).stall_cycles[3];
  {
    auto good = std::make_unique<Iss>();
    CorruptEngine bad(at, CorruptEngine::Mode::ChangeStall);
    const auto d = lockstep_case(c, *good, bad);
    ASSERT_TRUE(d);
    EXPECT_EQ(d->cycle, at);
    EXPECT_EQ(d->field, "stall");
  }
  {
    auto good = std::make_unique<Iss>();
    CorruptEngine bad(17, CorruptEngine::Mode::ShiftPc);
    const auto d = lockstep_case(c, *good, bad);
    ASSERT_TRUE(d);
    EXPECT_EQ(d->cycle, 17u);
    EXPECT_EQ(d->field, "pc");
  }
}

TEST(ApuRandom, SameSeedSameCase) {
  const RandomCase a = make_random_case(42), b = make_random_case(42), c = make_random_case(43);
  EXPECT_EQ(a.images, b.images);
  EXPECT_EQ(a.data_blocks, b.data_blocks);
  EXPECT_NE(a.images, c.images);
}

TEST(ApuRandom, ProgramsAreValidVariedAndEndAsPlanned) {
  std::set<int> m_seen, a_ops, f_ops, d_ops, i_ops, s_ops;
  std::array<std::uint64_t, kStallKinds> stalls{};
  std::set<Fault> faults;
  int multi_image = 0;
  for (std::uint64_t i = 0; i < 300; ++i) {
    const RandomCase c = make_random_case(case_seed(9, i));
    multi_image += c.images.size() > 1;
    // A case planned to end in a reserved op has one word with it; the
    // other cases must use only the ISA's ops, in the assembler's form.
    for (std::size_t img = 0; img < c.images.size() && c.planned_fault != Fault::ReservedOp; ++img) {
      const auto& words = c.images[img];
      for (std::size_t at = c.entry[img]; at < words.size(); ++at) {
        const MicroWord w = MicroWord::decode(words[at]);
        if (w.m.en) m_seen.insert(0);
        if (w.a.en) a_ops.insert(static_cast<int>(w.a.op));
        if (w.f.en) f_ops.insert(static_cast<int>(w.f.op));
        d_ops.insert(static_cast<int>(w.d.op));
        i_ops.insert(static_cast<int>(w.i.op));
        s_ops.insert(static_cast<int>(w.s.op));
        EXPECT_EQ(noncanonical_reason(w), "") << c.describe() << " word " << at << ": " << disassemble(w);
      }
    }
    auto iss = std::make_unique<Iss>();
    ApuEngine* one[1] = {iss.get()};
    RandomMpu mpu(c);
    mpu.boot(one, 1);
    CycleRecord r;
    std::uint64_t n = 0;
    for (; n < c.max_cycles && iss->state() == RunState::Running; ++n) {
      mpu.before_cycle(one, 1);
      iss->step(r);
      ++stalls[static_cast<int>(r.stall)];
    }
    if (c.planned_fault == Fault::None) {
      EXPECT_EQ(iss->state(), RunState::Halted) << c.describe();
    } else {
      EXPECT_EQ(iss->fault(), c.planned_fault) << c.describe();
      faults.insert(c.planned_fault);
    }
  }
  EXPECT_EQ(a_ops.size(), 7u);
  EXPECT_EQ(f_ops.size(), 4u);
  EXPECT_EQ(d_ops.size(), 3u);
  EXPECT_EQ(i_ops.size(), 15u);  // none and the 14 ops
  EXPECT_EQ(s_ops, (std::set<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
  for (int k = 1; k < kStallKinds; ++k) EXPECT_GT(stalls[k], 0u) << stall_name(static_cast<Stall>(k));
  EXPECT_GE(faults.size(), 4u);
  EXPECT_GT(multi_image, 30);
}

// The ISS's fast path (run(): word-shape issue, F registers written at
// issue and put back on return) leaves, after every call, the state that
// as many step()s leave. The MPU acts between calls, on both alike.
TEST(ApuCosim, IssRunAgreesWithItsStepsOnRandomPrograms) {
  std::uint64_t compared = 0;
  for (std::uint64_t i = 0; i < 60; ++i) {
    const RandomCase c = make_random_case(case_seed(11, i));
    auto stepped = std::make_unique<Iss>(), fast = std::make_unique<Iss>();
    ApuEngine* both[2] = {stepped.get(), fast.get()};
    RandomMpu mpu(c);
    mpu.boot(both, 2);
    Rng chunks(c.seed);
    CycleRecord r;
    while (stepped->state() == RunState::Running && stepped->cycle() < c.max_cycles) {
      mpu.before_cycle(both, 2);
      const std::uint64_t k = chunks.range(1, 40);
      std::uint64_t n = 0;
      while (n < k && stepped->state() == RunState::Running) stepped->step(r), ++n;
      ASSERT_EQ(fast->run(k), n) << c.describe() << " at cycle " << stepped->cycle();
      ASSERT_EQ(fast->cycle(), stepped->cycle()) << c.describe();
      ASSERT_EQ(fast->state(), stepped->state()) << c.describe() << " at cycle " << stepped->cycle();
      ASSERT_EQ(fast->fault(), stepped->fault()) << c.describe();
      ASSERT_EQ(fast->pc(), stepped->pc()) << c.describe() << " at cycle " << stepped->cycle();
      for (int f = 0; f < kNumFRegs; ++f)
        ASSERT_EQ(fast->freg(f), stepped->freg(f)) << c.describe() << " F" << f << " at cycle " << stepped->cycle();
      for (int a = 0; a < kNumARegs; ++a)
        ASSERT_EQ(fast->areg(a), stepped->areg(a)) << c.describe() << " A" << a << " at cycle " << stepped->cycle();
      ASSERT_EQ(fast->cc(), stepped->cc()) << c.describe() << " at cycle " << stepped->cycle();
      ASSERT_EQ(fast->flags(), stepped->flags()) << c.describe() << " at cycle " << stepped->cycle();
      ++compared;
    }
    std::vector<std::uint32_t> bank_s(kDataWords), bank_f(kDataWords);
    stepped->read_data_block(0, bank_s.data(), kDataWords);
    fast->read_data_block(0, bank_f.data(), kDataWords);
    EXPECT_EQ(bank_f, bank_s) << c.describe();
  }
  EXPECT_GT(compared, 1000u);
}

// The same with the counters too and calls of up to 400 cycles, so that
// run() clocks most words in bodies (Iss::run_body: whole straight runs,
// their prefixes where a call ends, their closing branches), and with
// single cycles between, so that bodies start with writes in flight.
TEST(ApuCosim, IssRunBodiesAgreeWithStepsOnRandomPrograms) {
  std::uint64_t compared = 0;
  for (std::uint64_t i = 0; i < 300; ++i) {
    const RandomCase c = make_random_case(case_seed(13, i));
    auto stepped = std::make_unique<Iss>(), fast = std::make_unique<Iss>();
    ApuEngine* both[2] = {stepped.get(), fast.get()};
    RandomMpu mpu(c);
    mpu.boot(both, 2);
    Rng chunks(c.seed ^ 0x5bd1e995);
    CycleRecord r;
    while (stepped->state() == RunState::Running && stepped->cycle() < c.max_cycles) {
      mpu.before_cycle(both, 2);
      const int kind = chunks.range(0, 3);
      const auto k = static_cast<std::uint64_t>(kind == 0 ? 1 : kind == 1 ? chunks.range(1, 12) : chunks.range(1, 400));
      std::uint64_t n = 0;
      while (n < k && stepped->state() == RunState::Running) stepped->step(r), ++n;
      const std::string at = c.describe() + " at cycle " + std::to_string(stepped->cycle());
      ASSERT_EQ(fast->run(k), n) << at;
      ASSERT_EQ(fast->cycle(), stepped->cycle()) << at;
      ASSERT_EQ(fast->state(), stepped->state()) << at;
      ASSERT_EQ(fast->fault(), stepped->fault()) << at;
      ASSERT_EQ(fast->pc(), stepped->pc()) << at;
      for (int f = 0; f < kNumFRegs; ++f) ASSERT_EQ(fast->freg(f), stepped->freg(f)) << at << " F" << f;
      for (int a = 0; a < kNumARegs; ++a) ASSERT_EQ(fast->areg(a), stepped->areg(a)) << at << " A" << a;
      ASSERT_EQ(fast->cc(), stepped->cc()) << at;
      ASSERT_EQ(fast->flags(), stepped->flags()) << at;
      const Iss::Counters &cf = fast->counters(), &cs = stepped->counters();
      ASSERT_EQ(cf.issued, cs.issued) << at;
      for (int u = 0; u < 3; ++u) ASSERT_EQ(cf.unit_ops[u], cs.unit_ops[u]) << at << " unit " << u;
      for (int k2 = 0; k2 < kStallKinds; ++k2)
        ASSERT_EQ(cf.stalls[k2], cs.stalls[k2]) << at << " " << stall_name(static_cast<Stall>(k2));
      ++compared;
    }
    // A step after the last call records what the fast path left in flight.
    CycleRecord rs, rf;
    for (int k2 = 0; k2 < kMaxLatency + 2; ++k2) {
      stepped->step(rs);
      fast->step(rf);
      ASSERT_EQ(rf.commits.size(), rs.commits.size()) << c.describe();
      for (std::size_t j = 0; j < rs.commits.size(); ++j) {
        ASSERT_EQ(rf.commits[j].kind, rs.commits[j].kind) << c.describe();
        ASSERT_EQ(rf.commits[j].index, rs.commits[j].index) << c.describe();
        ASSERT_EQ(rf.commits[j].value, rs.commits[j].value) << c.describe();
      }
    }
    std::vector<std::uint32_t> bank_s(kDataWords), bank_f(kDataWords);
    stepped->read_data_block(0, bank_s.data(), kDataWords);
    fast->read_data_block(0, bank_f.data(), kDataWords);
    EXPECT_EQ(bank_f, bank_s) << c.describe();
  }
  EXPECT_GT(compared, 5000u);
}

// A program from 0 on two ISSs: `stepped` a cycle at a time up to its end
// or 100 cycles, `fast` by one run() of as many cycles. Returns how many
// more cycles run() clocked than the steps (0 when they agree).
std::int64_t run_and_steps(const std::vector<MicroWord>& prog, Iss& stepped, Iss& fast) {
  for (Iss* iss : {&stepped, &fast}) {
    ApuDriver d(*iss);
    d.load_program(apu_test::encode(prog));
    d.hand_over_program();
    d.start(0);
  }
  CycleRecord r;
  std::uint64_t n = 0;
  while (stepped.state() == RunState::Running && n < 100) stepped.step(r), ++n;
  return static_cast<std::int64_t>(fast.run(100)) - static_cast<std::int64_t>(n);
}

// A body's LD or ST at the data bank's edges: run() starts the body only
// when every data address is in range without a wrap, so that one past
// the bank (4096), or below 0 (a wrap to 0xFFFF), faults at its word as
// step() does, and the last word of the bank (4095) and a wrap that lands
// in range go through. The random programs rarely reach an edge exactly.
TEST(ApuCosim, IssRunBodyAtTheDataBankEdgeFaultsAsItsSteps) {
  using namespace apu_test;
  struct Edge {
    std::uint16_t base;
    int disp;
  };
  int faults = 0;
  for (const Edge e : {Edge{4095, 0}, Edge{4095, 1}, Edge{4000, 95}, Edge{4000, 96}, Edge{3969, 127},
                       Edge{1, -1}, Edge{0, -1}, Edge{0, -128}, Edge{127, -128}}) {
    for (const MemOp op : {MemOp::Ld, MemOp::St}) {
      // LI before the body (a body ends before a LD/ST whose base an earlier
      // word of it writes), then a body of plain words with the access.
      const std::vector<MicroWord> prog = {li(1, e.base), lif(2, 0x4000), mul(3, 2, 2), mem(op, 2, 1, e.disp),
                                           mul(4, 2, 2), nop(), nop(), halt()};
      const std::string what = "base " + std::to_string(e.base) + " disp " + std::to_string(e.disp) +
                               (op == MemOp::Ld ? " LD" : " ST");
      Iss stepped, fast;
      EXPECT_EQ(run_and_steps(prog, stepped, fast), 0) << what;
      EXPECT_EQ(fast.state(), stepped.state()) << what;
      EXPECT_EQ(fast.fault(), stepped.fault()) << what;
      EXPECT_EQ(fast.pc(), stepped.pc()) << what;
      EXPECT_EQ(fast.freg(2), stepped.freg(2)) << what;
      EXPECT_EQ(fast.freg(4), stepped.freg(4)) << what;
      const bool out = e.base + e.disp >= static_cast<int>(kDataWords) || e.base + e.disp < 0;
      EXPECT_EQ(stepped.fault(), out ? Fault::DataAddress : Fault::None) << what;
      faults += out;
    }
  }
  EXPECT_EQ(faults, 12);
}

// A body closed by DBNZ on A0: A0 reads 0 and drops writes, so the branch
// is taken (0 - 1 is not 0) and A0 is still 0 after it, under run() as
// under step(). The random programs avoid DBNZ A0 (it never ends a loop).
TEST(ApuCosim, IssRunBodyClosedByDbnzOnA0LeavesA0Zero) {
  using namespace apu_test;
  const std::vector<MicroWord> prog = {li(1, 5), nop(), seq(SeqOp::Dbnz, 0, 4), li(3, 9),
                                       ialu(IntOp::Addi, 2, 0, 0, 1), ialu(IntOp::Add, 4, 1, 0, 0), halt()};
  Iss stepped, fast;
  EXPECT_EQ(run_and_steps(prog, stepped, fast), 0);
  ASSERT_EQ(stepped.state(), RunState::Halted);
  EXPECT_EQ(fast.state(), RunState::Halted);
  for (int a = 0; a < kNumARegs; ++a) EXPECT_EQ(fast.areg(a), stepped.areg(a)) << "A" << a;
  EXPECT_EQ(stepped.areg(0), 0);
  EXPECT_EQ(stepped.areg(2), 1);  // A0 + 1 after the branch
  EXPECT_EQ(stepped.areg(3), 0);  // the word after the DBNZ was skipped: taken
  EXPECT_EQ(stepped.areg(4), 5);  // A1 + A0
  EXPECT_EQ(fast.counters().issued, stepped.counters().issued);
}

// The RTL engine's counters against the ISS's.
::testing::AssertionResult same_counters(const ApuCounters& iss, const ApuCounters& rtl) {
  if (rtl.issued != iss.issued) return ::testing::AssertionFailure() << "issued " << rtl.issued << ", ISS " << iss.issued;
  for (int u = 0; u < 3; ++u)
    if (rtl.unit_ops[u] != iss.unit_ops[u])
      return ::testing::AssertionFailure() << "unit " << u << " ops " << rtl.unit_ops[u] << ", ISS " << iss.unit_ops[u];
  for (int k = 0; k < kStallKinds; ++k)
    if (rtl.stalls[k] != iss.stalls[k])
      return ::testing::AssertionFailure() << stall_name(static_cast<Stall>(k)) << " stalls " << rtl.stalls[k] << ", ISS "
                                           << iss.stalls[k];
  return ::testing::AssertionSuccess();
}

TEST(ApuCosim, IssAndRtlAgreeOnRandomPrograms) {
  for (std::uint64_t i = 0; i < 30; ++i) {
    const RandomCase c = make_random_case(case_seed(5, i));
    auto iss = std::make_unique<Iss>();
    RtlEngine rtl(nullptr);
    const auto d = lockstep_case(c, *iss, rtl);
    EXPECT_FALSE(d) << c.describe() << "\n" << d->report("iss", "rtl");
    EXPECT_TRUE(same_counters(iss->counters(), rtl.counters())) << c.describe();
  }
}

// The RTL engine counts what the ISS counts (issues, unit ops, stalls by
// reason), on its fast path too: its run() in calls of 1 to 400 cycles
// (a bank stall's cycles taken at once among them) against the ISS's steps.
TEST(ApuCosim, RtlRunCountsAsTheIssSteps) {
  ApuCounters total;
  for (std::uint64_t i = 0; i < 40; ++i) {
    const RandomCase c = make_random_case(case_seed(17, i));
    auto stepped = std::make_unique<Iss>();
    RtlEngine rtl(nullptr);
    ApuEngine* both[2] = {stepped.get(), &rtl};
    RandomMpu mpu(c);
    mpu.boot(both, 2);
    Rng chunks(c.seed ^ 0x9e3779b9);
    CycleRecord r;
    while (stepped->state() == RunState::Running && stepped->cycle() < c.max_cycles) {
      mpu.before_cycle(both, 2);
      const auto k = static_cast<std::uint64_t>(chunks.range(0, 1) ? chunks.range(1, 12) : chunks.range(1, 400));
      std::uint64_t n = 0;
      while (n < k && stepped->state() == RunState::Running) stepped->step(r), ++n;
      const std::string at = c.describe() + " at cycle " + std::to_string(stepped->cycle());
      ASSERT_EQ(rtl.run(k), n) << at;
      ASSERT_EQ(rtl.state(), stepped->state()) << at;
      ASSERT_TRUE(same_counters(stepped->counters(), rtl.counters())) << at;
    }
    const ApuCounters& s = stepped->counters();
    total.issued += s.issued;
    for (int k = 0; k < kStallKinds; ++k) total.stalls[k] += s.stalls[k];
  }
  // The cases issue words and stall for every reason the random programs make.
  EXPECT_GT(total.issued, 10000u);
  for (Stall k : {Stall::Bank, Stall::Raw, Stall::Fetch}) EXPECT_GT(total.stalls[static_cast<int>(k)], 100u) << stall_name(k);
}

}  // namespace
}  // namespace mc1::apu
