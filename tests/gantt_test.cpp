// The Gantt chart and the per-step figures on a hand-made timeline
// (host/mc1/gantt_svg.cpp, frame_steps.cpp): step attribution to the
// picosecond, idle after the last block, tooltips, labels that do not overlap.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "frame_steps.hpp"
#include "report_writers.hpp"

namespace mc1 {
namespace {

using nc::Activity;

// NC 1: download (waiting 0-100, busy 100-110), step 1 (110-200), waits for
// the RC (200-250), block 7's s1 (250-300) and pixel output (300-320), then
// waits for the Finish (320-1000) and takes it (1000-1001).
FrameReport hand_made() {
  FrameReport r;
  r.engine = "iss";
  r.nodes = 1;
  r.blocks = 1;
  r.frame_time = 1001;
  NcReport n;
  n.id = 1;
  n.spans = {{0, 100, Activity::WaitRc},         {100, 200, Activity::Busy},
             {200, 250, Activity::WaitRc},       {250, 300, Activity::Busy, 7},
             {300, 320, Activity::WaitBus, 7},   {320, 1000, Activity::WaitRc},
             {1000, 1001, Activity::Busy}};
  n.phases = {{110, "step1 transform"}, {250, "s1 hidden surface"}, {300, "output"}};
  n.milestones = {{"downloaded", 100}, {"step1", 200}};
  r.ncs.push_back(n);
  r.rc.lists_done = 100;  // at the same time as the download: the labels collide
  return r;
}

TEST(FrameSteps, TimeGoesToTheStepUnderWay) {
  const std::vector<StepTime> t = step_times(hand_made().ncs[0]);
  ASSERT_EQ(t.size(), 8u);
  EXPECT_EQ(t[0].busy, 10u);     // download: 100-110
  EXPECT_EQ(t[0].waiting, 100u);
  EXPECT_EQ(t[1].busy, 90u);     // step 1: 110-200
  EXPECT_EQ(t[1].waiting, 50u);  // 200-250, waiting for the RC inside step 1
  EXPECT_EQ(t[3].busy, 50u);     // s1
  EXPECT_EQ(t[7].waiting, 20u);  // pixel output: the image bus
  EXPECT_EQ(t[7].busy, 1u);      // the Finish, booked to the step under way
  // After the last block (320) the waiting is idle: in no step.
  Picos all = 0;
  for (const StepTime& x : t) all += x.busy + x.waiting;
  EXPECT_EQ(all, 1001u - 680u);
}

TEST(FrameSteps, FrameWithoutStepsHasNone) {
  NcReport n = hand_made().ncs[0];
  n.phases.clear();
  for (const StepSpan& s : step_spans(n)) EXPECT_EQ(s.step, kNoStep);
  for (const StepTime& x : step_times(n)) EXPECT_EQ(x.busy + x.waiting, 0u);
}

TEST(Gantt, ColoursTooltipsIdleAndLabels) {
  const std::string g = gantt_svg(hand_made());
  for (const FrameStep& s : frame_steps()) {
    EXPECT_NE(g.find(std::string(">") + s.label + "<"), std::string::npos) << s.label;
    EXPECT_NE(g.find(std::string("fill=\"") + s.colour + "\" stroke"), std::string::npos) << s.label;  // legend
  }
  EXPECT_NE(g.find("<title>NC 1, block 7: 0.000 ms to 0.000 ms (0.000 ms)</title>"), std::string::npos);
  // The wait for the Finish (x from 70 + 1000 * 320/1001) is drawn idle.
  EXPECT_NE(g.find("<rect x=\"389.68\" y=\"72.00\" width=\"679.32\" height=\"21.00\" fill=\"#eeeeee\"/>"),
            std::string::npos)
      << g;
  // The two phase labels start at the same x; they go to different lanes.
  const std::regex label("<text x=\"([0-9.]+)\" y=\"([0-9.]+)\" fill=\"#1e88e5\" font-size=\"9\">([a-z ]+)</text>");
  std::vector<std::string> ys;
  for (std::sregex_iterator i(g.begin(), g.end(), label), end; i != end; ++i) ys.push_back((*i)[2]);
  ASSERT_EQ(ys.size(), 2u);
  EXPECT_NE(ys[0], ys[1]);
}

TEST(Gantt, StatsJsonHasEachNcsSteps) {
  const std::string j = stats_json(hand_made());
  EXPECT_NE(j.find("\"steps\": {\"download\": {\"busy_ps\": 10, \"waiting_ps\": 100}, \"step1\": {\"busy_ps\": 90, "
                   "\"waiting_ps\": 50}, \"block_lists\": {\"busy_ps\": 0, \"waiting_ps\": 0}, \"s1\": {\"busy_ps\": 50"),
            std::string::npos)
      << j;
}

}  // namespace
}  // namespace mc1
