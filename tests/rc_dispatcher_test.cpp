// The RC's dispatcher without SystemC: a hand-moved clock stands for the
// RC's processor. Every transition of the per-NC state, one by one, first
// as the table allows it, then as the dispatcher makes it; and the pieces of
// work around each (what is sent, what goes back to the queue, when).
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

#include "rc_dispatcher.hpp"

using namespace mc1;
using rc::NcState;

namespace {

constexpr NcState kAll[] = {NcState::Starting, NcState::Working, NcState::Parked,
                            NcState::Finished, NcState::Dead,    NcState::Lost};

// The RC's processor: its clock moves by the work charged and by hand.
struct FakePort : rc::RcPort {
  TimingParams t;
  Picos clock = 0;
  std::vector<std::pair<unsigned, rc::Bytes>> sent;

  Picos now() const override { return clock; }
  void work(std::uint64_t mpu_cycles) override { clock += t.mpu_cycles_ps(mpu_cycles); }
  void send(unsigned nc, const rc::Bytes& msg) override { sent.emplace_back(nc, msg); }
  rc::MsgType last_type(unsigned nc) const {
    for (auto it = sent.rbegin(); it != sent.rend(); ++it)
      if (it->first == nc) return rc::type_of(it->second);
    throw std::logic_error("nothing sent to NC " + std::to_string(nc));
  }
  std::uint32_t last_block(unsigned nc) const {
    for (auto it = sent.rbegin(); it != sent.rend(); ++it)
      if (it->first == nc) return rc::decode_assign(it->second).block.id;
    throw std::logic_error("nothing sent to NC " + std::to_string(nc));
  }
};

// A diagnostic-style plan: `n` blocks of 8x8, equal loads.
rc::FramePlan block_plan(unsigned n, bool fault_tolerant) {
  rc::FramePlan p;
  p.blocks = rc::split_screen(8 * n, 8, 8, 8);
  p.fault_tolerant = fault_tolerant;
  return p;
}

// A rendered-frame plan: step 2 lists, deadlines.
rc::FramePlan list_plan(unsigned blocks, std::uint32_t jobs, rc::Schedule s = rc::Schedule::Lpt) {
  rc::FramePlan p = block_plan(blocks, true);
  p.block_lists = true;
  p.list_jobs = jobs;
  p.schedule = s;
  return p;
}

struct Bench {
  FakePort port;
  rc::FramePlan plan;
  rc::Dispatcher d;

  Bench(unsigned ncs, rc::FramePlan p) : plan(p), d(port.t, ncs, std::move(p), port) {}
  Bench(const Bench&) = delete;  // d holds a reference to port
  NcState state(unsigned nc) const { return d.states()[nc]; }
  void request(unsigned nc, std::uint32_t done = rc::kNoBlock) { d.on_message(nc, rc::encode(rc::RequestMsg{done})); }
  // NC nc sends the lists of the job it was last given; block b's load is `load(b)`.
  template <class Load>
  void send_lists(unsigned nc, Load load) {
    rc::ListJobMsg job;
    for (auto it = port.sent.rbegin(); it != port.sent.rend(); ++it)
      if (it->first == nc) {
        job = rc::decode_list_job(it->second);
        break;
      }
    rc::ListsMsg m{job, {}};
    for (std::uint32_t b : rc::job_blocks(job, plan.blocks.size())) m.lists.push_back({plan.blocks[b], load(b), {}});
    d.on_message(nc, rc::encode(m));
  }
  void link_down(unsigned nc) { d.on_link_down(nc, hdlc::LinkDownReason::PollUnanswered, port.clock); }
  // Moves the clock to the next deadline and lets it pass.
  void pass_deadline() {
    const std::optional<Picos> t = d.next_deadline();
    ASSERT_TRUE(t);
    port.clock = std::max(port.clock, *t);
    d.expire();
    d.serve_parked();
  }
};

// Two NCs, two blocks, deadlines: NC 1 has done block 0 and waits while
// NC 2 holds block 1.
void park_nc1(Bench& b) {
  b.request(1);
  b.request(2);
  b.request(1, 0);
  ASSERT_EQ(b.state(1), NcState::Parked);
}

}  // namespace

// ---------------------------------------------------------------- the table

TEST(NcStateTable, EveryPairAllowedOrRefused) {
  using S = NcState;
  const std::vector<std::pair<S, S>> allowed = {
      {S::Starting, S::Working}, {S::Starting, S::Parked}, {S::Starting, S::Finished}, {S::Starting, S::Dead},
      {S::Starting, S::Lost},    {S::Working, S::Working}, {S::Working, S::Parked},    {S::Working, S::Finished},
      {S::Working, S::Dead},     {S::Working, S::Lost},    {S::Parked, S::Working},    {S::Parked, S::Parked},
      {S::Parked, S::Finished},  {S::Parked, S::Dead},     {S::Parked, S::Lost},       {S::Dead, S::Working},
      {S::Dead, S::Finished},    {S::Dead, S::Lost},       {S::Finished, S::Lost}};
  for (S from : kAll)
    for (S to : kAll) {
      const bool want = std::find(allowed.begin(), allowed.end(), std::make_pair(from, to)) != allowed.end();
      EXPECT_EQ(rc::transition_allowed(from, to), want) << rc::nc_state_name(from) << " -> " << rc::nc_state_name(to);
    }
}

TEST(NcStateTable, ToRefusesAnIllegalTransitionAndKeepsTheState) {
  for (NcState from : kAll)
    for (NcState to : kAll) {
      rc::NcStates s(3);
      if (from != NcState::Starting) s.to(2, from);  // every state is one step from Starting
      ASSERT_EQ(s[2], from);
      if (rc::transition_allowed(from, to)) {
        s.to(2, to);
        EXPECT_EQ(s[2], to);
      } else {
        EXPECT_THROW(s.to(2, to), std::logic_error) << rc::nc_state_name(from) << " -> " << rc::nc_state_name(to);
        EXPECT_EQ(s[2], from);
      }
      EXPECT_EQ(s[1], NcState::Starting);
      EXPECT_EQ(s[3], NcState::Starting);
    }
}

TEST(NcStateTable, CountsAndTakenAsDead) {
  rc::NcStates s(4);
  EXPECT_EQ(s.size(), 4u);
  EXPECT_EQ(s.count(NcState::Starting), 4u);
  s.to(1, NcState::Dead);
  s.to(2, NcState::Lost);
  s.to(3, NcState::Finished);
  EXPECT_TRUE(s.taken_as_dead(1));
  EXPECT_TRUE(s.taken_as_dead(2));
  EXPECT_FALSE(s.taken_as_dead(3));
  EXPECT_FALSE(s.taken_as_dead(4));
  EXPECT_EQ(s.count(NcState::Starting), 1u);
  EXPECT_EQ(s.count(NcState::Finished), 1u);
  EXPECT_THROW(s.to(5, NcState::Working), std::out_of_range);
}

// ---------------------------------------------------------------- from Starting

TEST(RcDispatcher, StartingToWorkingOnTheFirstRequest) {
  Bench b(2, block_plan(3, false));
  EXPECT_EQ(b.state(1), NcState::Starting);
  b.request(1);
  EXPECT_EQ(b.state(1), NcState::Working);
  EXPECT_EQ(b.state(2), NcState::Starting);
  ASSERT_EQ(b.d.dispatches().size(), 1u);
  const rc::Dispatch& x = b.d.dispatches()[0];
  EXPECT_EQ(x.nc, 1u);
  EXPECT_EQ(x.block, 0u);
  EXPECT_FALSE(x.list_job);
  // One list element looked at before the dispatch.
  EXPECT_EQ(x.time, b.port.t.mpu_cycles_ps(b.port.t.mpu_cycles_per_list_element));
  ASSERT_EQ(b.port.sent.size(), 1u);
  EXPECT_EQ(rc::decode_assign(b.port.sent[0].second).block, b.plan.blocks[0]);
  EXPECT_FALSE(b.d.next_deadline());  // no deadlines without fault tolerance
}

TEST(RcDispatcher, StartingToFinishedWhenNothingIsLeft) {
  Bench b(2, block_plan(1, false));
  b.request(1);
  b.request(2);
  EXPECT_EQ(b.state(2), NcState::Finished);
  EXPECT_EQ(b.port.last_type(2), rc::MsgType::Finish);
  EXPECT_EQ(b.d.dispatches().back().block, rc::kNoBlock);
  EXPECT_FALSE(b.d.frame_complete());  // block 0 is out
}

TEST(RcDispatcher, StartingToParkedWhileTheListJobsAreOut) {
  Bench b(2, list_plan(4, 1));  // one list job for two NCs
  b.request(1);
  EXPECT_EQ(b.port.last_type(1), rc::MsgType::ListJob);
  const std::size_t sent = b.port.sent.size();
  b.request(2);
  EXPECT_EQ(b.state(2), NcState::Parked);
  EXPECT_EQ(b.port.sent.size(), sent);  // parked: no answer yet
  EXPECT_EQ(b.d.dispatches().size(), 1u);
}

TEST(RcDispatcher, StartingToDeadWhenItNeverAsks) {
  Bench b(2, block_plan(1, true));
  b.request(1);
  b.request(1, 0);
  EXPECT_EQ(b.state(1), NcState::Finished);
  EXPECT_FALSE(b.d.frame_complete());  // NC 2 never asked
  const Picos last = b.d.completions().back().time;
  ASSERT_TRUE(b.d.next_deadline());
  EXPECT_EQ(*b.d.next_deadline(), last + 1000 * b.port.t.rc_timeout_base_ns);
  b.pass_deadline();
  EXPECT_EQ(b.state(2), NcState::Dead);
  ASSERT_EQ(b.d.timeouts().size(), 1u);
  EXPECT_EQ(b.d.timeouts()[0].nc, 2u);
  EXPECT_EQ(b.d.timeouts()[0].block, rc::kNoBlock);
  EXPECT_TRUE(b.d.frame_complete());
}

TEST(RcDispatcher, StartingToLostOnALinkDown) {
  Bench b(2, block_plan(2, false));
  b.port.clock = 5000;
  b.d.on_link_down(2, hdlc::LinkDownReason::RetryLimit, 4000);
  EXPECT_EQ(b.state(2), NcState::Lost);
  ASSERT_EQ(b.d.link_downs().size(), 1u);
  const rc::LinkDown& x = b.d.link_downs()[0];
  EXPECT_EQ(x.time, 4000u);
  EXPECT_EQ(x.taken, 5000u);
  EXPECT_EQ(x.nc, 2u);
  EXPECT_EQ(x.reason, hdlc::LinkDownReason::RetryLimit);
  EXPECT_EQ(x.requeued, 0u);
}

// ---------------------------------------------------------------- from Working

TEST(RcDispatcher, WorkingToWorkingReportsAndTakesTheNext) {
  Bench b(1, block_plan(2, false));
  b.request(1);
  b.request(1, 0);
  EXPECT_EQ(b.state(1), NcState::Working);
  EXPECT_EQ(b.port.last_block(1), 1u);
  ASSERT_EQ(b.d.completions().size(), 1u);
  EXPECT_EQ(b.d.completions()[0].block, 0u);
  EXPECT_EQ(b.d.completions()[0].nc, 1u);
}

TEST(RcDispatcher, WorkingToParkedWhileBlocksAreOut) {
  Bench b(2, block_plan(2, true));
  b.request(1);
  b.request(2);
  EXPECT_EQ(b.state(1), NcState::Working);
  b.request(1, 0);
  EXPECT_EQ(b.state(1), NcState::Parked);  // block 1 may still come back
  EXPECT_EQ(b.port.last_type(1), rc::MsgType::Assign);
}

TEST(RcDispatcher, WorkingToFinishedCompletesTheFrame) {
  Bench b(1, block_plan(1, false));
  std::vector<rc::Progress> progress;
  b.d.on_progress([&](const rc::Progress& p) { progress.push_back(p); });
  b.request(1);
  b.request(1, 0);
  EXPECT_EQ(b.state(1), NcState::Finished);
  EXPECT_EQ(b.port.last_type(1), rc::MsgType::Finish);
  EXPECT_TRUE(b.d.frame_complete());
  ASSERT_EQ(progress.size(), 1u);
  EXPECT_EQ(progress[0].blocks_done, 1u);
  EXPECT_EQ(progress[0].blocks, 1u);
}

TEST(RcDispatcher, WorkingToDeadAtTheDeadlineAndTheBlockGoesBack) {
  Bench b(2, block_plan(2, true));
  b.request(1);
  const Picos at = b.d.dispatches()[0].time;
  // An 8x8 block of no predicted load: base + 64 x (1 + 0) x per pixel-primitive.
  const Picos expect = at + 1000 * (b.port.t.rc_timeout_base_ns + 64 * b.port.t.rc_timeout_ns_per_pixel_prim);
  ASSERT_TRUE(b.d.next_deadline());
  EXPECT_EQ(*b.d.next_deadline(), expect);
  b.pass_deadline();
  EXPECT_EQ(b.state(1), NcState::Dead);
  ASSERT_EQ(b.d.timeouts().size(), 1u);
  const rc::Timeout& x = b.d.timeouts()[0];
  EXPECT_EQ(x.time, expect);
  EXPECT_EQ(x.nc, 1u);
  EXPECT_EQ(x.block, 0u);
  EXPECT_FALSE(x.list_job);
  EXPECT_EQ(x.requeued, 1u);
  EXPECT_EQ(b.d.stats().reassigned, 1u);
  b.request(2);
  EXPECT_EQ(b.port.last_block(2), 0u);  // back at its place in the schedule: first
}

TEST(RcDispatcher, WorkingToLostRequeuesItsBlock) {
  Bench b(2, block_plan(2, false));
  b.request(1);
  b.request(2);
  b.link_down(1);
  EXPECT_EQ(b.state(1), NcState::Lost);
  EXPECT_EQ(b.d.link_downs()[0].requeued, 1u);
  b.request(2, 1);
  EXPECT_EQ(b.port.last_block(2), 0u);
  b.request(2, 0);
  EXPECT_EQ(b.state(2), NcState::Finished);
  EXPECT_TRUE(b.d.frame_complete());
  b.d.on_message(1, rc::encode(rc::RequestMsg{0}));  // nothing from a lost NC counts
  EXPECT_EQ(b.d.stats().late_reports, 0u);
}

// ---------------------------------------------------------------- from Parked

TEST(RcDispatcher, ParkedToWorkingWhenABlockComesBack) {
  Bench b(2, block_plan(2, true));
  park_nc1(b);
  b.link_down(2);
  b.d.serve_parked();
  EXPECT_EQ(b.state(1), NcState::Working);
  EXPECT_EQ(b.port.last_block(1), 1u);
}

TEST(RcDispatcher, ParkedToWorkingWhenStep3Begins) {
  Bench b(2, list_plan(4, 1));
  b.request(1);
  b.request(2);
  ASSERT_EQ(b.state(2), NcState::Parked);
  b.send_lists(1, [](std::uint32_t blk) { return blk; });  // block 3 heaviest
  b.d.serve_parked();
  EXPECT_EQ(b.port.last_type(1), rc::MsgType::AssignList);
  EXPECT_EQ(b.state(2), NcState::Working);
  EXPECT_EQ(b.port.last_type(2), rc::MsgType::AssignList);
  const auto& order = b.d.order();
  ASSERT_EQ(order.size(), 4u);
  EXPECT_EQ(order[0].id, 3u);
  EXPECT_EQ(order[3].id, 0u);
  EXPECT_GT(b.d.stats().sort_compares, 0u);
  EXPECT_GT(b.d.stats().lists_done, 0u);
}

TEST(RcDispatcher, ParkedToFinishedWhenTheLastBlockIsDone) {
  Bench b(2, block_plan(2, true));
  park_nc1(b);
  b.request(2, 1);
  EXPECT_EQ(b.state(2), NcState::Finished);
  EXPECT_EQ(b.state(1), NcState::Parked);
  b.d.serve_parked();
  EXPECT_EQ(b.state(1), NcState::Finished);
  EXPECT_TRUE(b.d.frame_complete());
}

TEST(RcDispatcher, ParkedToLost) {
  Bench b(2, block_plan(2, true));
  park_nc1(b);
  b.link_down(1);
  EXPECT_EQ(b.state(1), NcState::Lost);
  EXPECT_EQ(b.d.link_downs()[0].requeued, 0u);
}

TEST(RcDispatcher, ParkedToParkedWhenItAsksAgain) {
  Bench b(2, block_plan(2, true));
  park_nc1(b);
  b.request(1);
  EXPECT_EQ(b.state(1), NcState::Parked);
}

TEST(RcDispatcher, ParkedToDeadWhenItHeldAPieceStill) {
  Bench b(1, block_plan(1, true));
  b.request(1);
  b.request(1);  // asks again without reporting block 0
  ASSERT_EQ(b.state(1), NcState::Parked);
  b.pass_deadline();
  EXPECT_EQ(b.state(1), NcState::Dead);
  EXPECT_EQ(b.d.timeouts()[0].block, 0u);
}

// ---------------------------------------------------------------- from Dead

TEST(RcDispatcher, DeadToWorkingWhenItReportsAfterAll) {
  Bench b(2, block_plan(3, true));
  b.request(1);
  b.pass_deadline();
  ASSERT_EQ(b.state(1), NcState::Dead);
  b.request(1, 0);  // only slow: its report counts and it gets work again
  EXPECT_EQ(b.state(1), NcState::Working);
  EXPECT_EQ(b.d.stats().revived, 1u);
  ASSERT_EQ(b.d.completions().size(), 1u);
  EXPECT_EQ(b.d.completions()[0].nc, 1u);
  EXPECT_EQ(b.port.last_block(1), 1u);
  b.request(2);
  EXPECT_EQ(b.port.last_block(2), 2u);  // block 0 was done, not handed out again
}

TEST(RcDispatcher, DeadToWorkingReportIsLateWhenAnotherDidIt) {
  Bench b(3, block_plan(1, true));  // NC 3 never asks: the frame stays open
  b.request(1);
  b.pass_deadline();
  b.request(2);
  b.request(2, 0);
  b.request(1, 0);
  EXPECT_EQ(b.d.stats().late_reports, 1u);
  EXPECT_EQ(b.d.stats().revived, 1u);
  EXPECT_EQ(b.state(1), NcState::Finished);
  EXPECT_EQ(b.d.completions().size(), 1u);
  EXPECT_EQ(b.d.completions()[0].nc, 2u);
  EXPECT_FALSE(b.d.frame_complete());
}

TEST(RcDispatcher, DeadToFinishedAfterTheFrame) {
  Bench b(2, block_plan(1, true));
  b.request(1);
  b.pass_deadline();
  b.request(2);
  b.request(2, 0);
  ASSERT_TRUE(b.d.frame_complete());
  EXPECT_TRUE(b.d.on_message_after_frame(1, rc::encode(rc::RequestMsg{0})));
  EXPECT_EQ(b.state(1), NcState::Finished);
  EXPECT_EQ(b.port.last_type(1), rc::MsgType::Finish);
  EXPECT_EQ(b.d.stats().late_reports, 1u);
  EXPECT_FALSE(b.d.on_message_after_frame(1, rc::encode(rc::RequestMsg{})));  // told once
  EXPECT_FALSE(b.d.on_message_after_frame(2, rc::encode(rc::RequestMsg{})));
}

TEST(RcDispatcher, DeadToLost) {
  Bench b(2, block_plan(2, true));
  b.request(1);
  b.pass_deadline();
  b.link_down(1);
  EXPECT_EQ(b.state(1), NcState::Lost);
  EXPECT_EQ(b.d.link_downs()[0].requeued, 0u);  // given back at the deadline already
  b.request(1, 0);
  EXPECT_EQ(b.d.stats().revived, 0u);  // a lost NC is never revived
}

// ---------------------------------------------------------------- from Finished, Lost

TEST(RcDispatcher, FinishedToLostAndFinishedAsksNoMore) {
  Bench b(2, block_plan(1, false));
  b.request(1);
  b.request(2);
  ASSERT_EQ(b.state(2), NcState::Finished);
  EXPECT_THROW(b.request(2), rc::ProtocolError);
  b.link_down(2);
  EXPECT_EQ(b.state(2), NcState::Lost);
  b.link_down(2);  // reported again: recorded, nothing changes
  EXPECT_EQ(b.d.link_downs().size(), 2u);
  EXPECT_EQ(b.state(2), NcState::Lost);
}

// ---------------------------------------------------------------- the frame

TEST(RcDispatcher, StaticScheduleGivesALostNcsShareToTheOthers) {
  rc::FramePlan p = block_plan(4, false);
  p.schedule = rc::Schedule::Static;
  Bench b(2, p);
  b.request(1);
  EXPECT_EQ(b.port.last_block(1), 0u);
  b.request(1, 0);
  EXPECT_EQ(b.port.last_block(1), 2u);  // its own: blocks 0 and 2
  b.link_down(2);
  b.request(1, 2);
  EXPECT_EQ(b.port.last_block(1), 1u);  // NC 2's share, in schedule order
  b.request(1, 1);
  EXPECT_EQ(b.port.last_block(1), 3u);
  b.request(1, 3);
  EXPECT_TRUE(b.d.frame_complete());
}

TEST(RcDispatcher, ListJobDeadlineAndTakeBack) {
  Bench b(2, list_plan(4, 2));
  b.request(1);
  const rc::Dispatch& x = b.d.dispatches()[0];
  EXPECT_TRUE(x.list_job);
  // Job 0 of 2 over 4 blocks: blocks 0 and 2.
  EXPECT_EQ(*b.d.next_deadline(),
            x.time + 1000 * (b.port.t.rc_timeout_base_ns + 2 * b.port.t.rc_timeout_ns_per_list_block));
  b.pass_deadline();
  EXPECT_EQ(b.state(1), NcState::Dead);
  EXPECT_TRUE(b.d.timeouts()[0].list_job);
  b.request(2);
  EXPECT_EQ(rc::decode_list_job(b.port.sent.back().second).first, 0u);  // job 0 again
}

TEST(RcDispatcher, NoNcLeftIsAnErrorNotAWait) {
  Bench b(2, block_plan(2, false));
  b.request(1);
  b.link_down(1);
  b.link_down(2);
  EXPECT_THROW(b.d.check_progress_possible(), std::runtime_error);
  EXPECT_EQ(b.d.status(), "0 of 2 blocks done, 0 of 2 NCs finished, 2 taken as dead, 0 deadlines missed, 2 links down");
}

TEST(RcDispatcher, MalformedReportsAreProtocolErrors) {
  Bench b(1, block_plan(2, false));
  EXPECT_THROW(b.request(1, 7), rc::ProtocolError);
  EXPECT_THROW(b.d.on_message(1, rc::encode_finish()), rc::ProtocolError);
  Bench l(1, list_plan(2, 1));
  EXPECT_THROW(l.request(1, 0), rc::ProtocolError);  // no block out before step 3
}

TEST(RcDispatcher, APlanThatDoesNotFitIsRefused) {
  FakePort port;
  rc::FramePlan p = block_plan(2, false);
  p.load = {1};
  EXPECT_THROW(rc::Dispatcher(port.t, 1, p, port), std::invalid_argument);
  rc::FramePlan q = list_plan(2, 1);
  q.blocks[1].id = 5;
  EXPECT_THROW(rc::Dispatcher(port.t, 1, q, port), std::invalid_argument);
}

TEST(RcSchedule, NamesRoundTrip) {
  for (rc::Schedule s : {rc::Schedule::Lpt, rc::Schedule::Fifo, rc::Schedule::Static})
    EXPECT_EQ(rc::parse_schedule(rc::schedule_name(s)), s);
  EXPECT_FALSE(rc::parse_schedule("random"));
}
