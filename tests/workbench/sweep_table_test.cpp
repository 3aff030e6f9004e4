// mc1 sweep's table, frame comparison, summary and plot (host/mc1/sweep_table.hpp,
// sweep_svg.hpp) on rows and frames made here, where every answer is known.
#include <gtest/gtest.h>

#include <sstream>

#include "sweep_svg.hpp"
#include "sweep_table.hpp"

namespace mc1::sweep {
namespace {

Row row(std::uint64_t index, unsigned nodes, const std::string& schedule, Picos frame_ps, const std::string& image = "aa") {
  Row r;
  r.index = index;
  r.scene = "/x/whitted.json";
  r.width = 160;
  r.height = 120;
  r.nodes = nodes;
  r.schedule = schedule;
  r.block = "16x16";
  r.frame_ps = frame_ps;
  r.image = image;
  r.steps = {{"download", 0.25}, {"s1", 0.5}, {"idle", 0.25}};
  return r;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream s(text);
  for (std::string l; std::getline(s, l);) out.push_back(l);
  return out;
}

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream s(line);
  for (std::string f; std::getline(s, f, ',');) out.push_back(f);
  return out;
}

TEST(SweepTable, SpeedupAgainstOneNcOfTheSameScheduleAndEfficiencyIsSpeedupOverNcs) {
  std::vector<Row> rows = {row(0, 1, "lpt", 8000), row(1, 4, "lpt", 2500), row(2, 1, "fifo", 9000),
                           row(3, 4, "fifo", 3000), row(4, 16, "static", 1000)};
  add_speedups(rows);
  EXPECT_DOUBLE_EQ(*rows[0].speedup, 1.0);
  EXPECT_DOUBLE_EQ(*rows[0].efficiency, 1.0);
  EXPECT_DOUBLE_EQ(*rows[1].speedup, 3.2);
  EXPECT_DOUBLE_EQ(*rows[1].efficiency, 0.8);
  EXPECT_DOUBLE_EQ(*rows[3].speedup, 3.0);  // fifo's own 1-NC point, not lpt's
  EXPECT_FALSE(rows[4].speedup.has_value());  // no 1-NC static point: n/a
  const std::vector<std::string> t = lines(csv(rows));
  ASSERT_EQ(t.size(), 6u);
  EXPECT_EQ(t[0], std::string(kCsvHeader) + ",share_download,share_s1,share_idle");
  const std::vector<std::string> head = fields(t[0]), last = fields(t[5]);
  ASSERT_EQ(head.size(), last.size());
  auto column = [&](const std::vector<std::string>& f, const std::string& name) {
    for (std::size_t i = 0; i < head.size(); ++i)
      if (head[i] == name) return f[i];
    return std::string("missing ") + name;
  };
  EXPECT_EQ(column(fields(t[2]), "speedup"), "3.2");
  EXPECT_EQ(column(fields(t[2]), "efficiency"), "0.8");
  EXPECT_EQ(column(fields(t[2]), "frame_ms"), "0.000003");  // 2500 ps
  EXPECT_EQ(column(last, "speedup"), "n/a");
  EXPECT_EQ(column(last, "critical_block"), "n/a");
  EXPECT_EQ(column(last, "share_s1"), "0.5");
}

TEST(SweepTable, ASceneNameWithACommaIsQuoted) {
  std::vector<Row> rows = {row(0, 1, "lpt", 1)};
  rows[0].scene = "a,b \"c\".json";
  EXPECT_NE(csv(rows).find("\"a,b \"\"c\"\".json\""), std::string::npos);
}

TEST(SweepFrames, EqualImagesPassAndADifferentOneIsNamedWithItsPoints) {
  std::vector<Row> rows = {row(0, 1, "lpt", 1, "aa"), row(1, 4, "lpt", 1, "aa"), row(2, 16, "lpt", 1, "aa")};
  EXPECT_TRUE(compare_frames(rows).empty());
  rows[1].image = "bb";
  const std::vector<FrameMismatch> m = compare_frames(rows);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(mismatch_text(m[0]), "frames differ: whitted.json frame 0: points 0, 2 give image aa, point 1 gives image bb");
  // Another camera frame of the orbit is another image: not a mismatch.
  rows[1].frame = 1;
  EXPECT_TRUE(compare_frames(rows).empty());
}

// A frame of 2 NCs and 3 blocks: block b dispatched at dispatch[b], reported at report[b].
FrameReport frame(const std::vector<Picos>& dispatch, const std::vector<Picos>& report, Picos frame_time) {
  FrameReport r;
  r.blocks = static_cast<unsigned>(dispatch.size());
  r.frame_time = frame_time;
  for (std::uint32_t b = 0; b < r.blocks; ++b) {
    r.dispatches.push_back({dispatch[b], b % 2 + 1, b, false});
    r.completions.push_back({report[b], b % 2 + 1, b});
  }
  return r;
}

TEST(SweepCriticalBlock, TheLongestBlockBoundsTheFrameWhenItWentOutFirstAndCameBackLast) {
  // Block 1: out at 10 before any report, back last at 100: the critical path.
  CriticalBlock c = critical_block(frame({0, 10, 30}, {20, 100, 50}, 110));
  EXPECT_EQ(c.block, 1);
  EXPECT_EQ(c.time, 90u);
  EXPECT_TRUE(c.bounds_frame);
  // The longest block went out after the first report: a schedule could have started it earlier.
  c = critical_block(frame({0, 30, 5}, {20, 100, 25}, 110));
  EXPECT_EQ(c.block, 1);
  EXPECT_FALSE(c.bounds_frame);
  // The longest block was not the last one back.
  c = critical_block(frame({0, 5, 10}, {90, 15, 95}, 110));
  EXPECT_EQ(c.block, 0);
  EXPECT_FALSE(c.bounds_frame);
}

TEST(SweepSummary, SaysWhenOneBlockBoundsEverySchedule) {
  std::vector<Row> rows = {row(0, 64, "lpt", 1136832000000), row(1, 64, "fifo", 1136034000000)};
  for (Row& r : rows) {
    r.critical_block = 36;
    r.critical_ps = 1032076000000;
    r.critical_path = true;
  }
  std::vector<std::string> s = summary(rows);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].rfind("at 64 NCs, blocks 16x16: every schedule takes 1136.034 ms to 1136.832 ms: block 36 alone takes "
                       "1032.076 ms (90.8 % of the frame)",
                       0),
            0u)
      << s[0];
  EXPECT_EQ(s[1], "speedup and efficiency n/a: no 1-NC point (add 1 to --nodes)");
  rows[1].critical_path = false;  // only lpt's frame is bound
  s = summary(rows);
  ASSERT_GE(s.size(), 1u);
  EXPECT_EQ(s[0].rfind("at 64 NCs, blocks 16x16: lpt takes 1136.832 ms: block 36", 0), 0u) << s[0];
  rows[0].critical_path = false;
  rows.push_back(row(2, 1, "lpt", 9));
  EXPECT_TRUE(summary(rows).empty());
}

TEST(SweepTable, TheTextTableHasAlignedColumnsAndMarksTheCriticalPath) {
  std::vector<Row> rows = {row(0, 1, "lpt", 8000000000), row(1, 64, "static", 1136089000000)};
  rows[1].critical_block = 36;
  rows[1].critical_ps = 1032462000000;
  rows[1].critical_path = true;
  rows[1].apu_utilization = 0.169;
  add_speedups(rows);
  EXPECT_EQ(text_table(rows),
            "point  NCs  schedule  block  frame ms  speedup  efficiency  APU util  critical block\n"
            "    0    1  lpt       16x16     8.000     1.00       1.000     0.0 %  n/a\n"
            "    1   64  static    16x16  1136.089      n/a         n/a    16.9 %  36 (90.9 %) *\n"
            "*: the block is the frame's critical path\n");
}

TEST(SweepSvg, HasTitleAPolylinePerSeriesInEachPanelAndAStepBarPerPoint) {
  std::vector<Row> rows = {row(0, 1, "lpt", 8000), row(1, 4, "lpt", 2500), row(2, 1, "fifo", 9000),
                           row(3, 4, "fifo", 3000)};
  add_speedups(rows);
  const std::string svg = sweep_svg(rows);
  auto count = [&](const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_NE(svg.find("mc1 sweep: whitted.json, 160x120"), std::string::npos);
  EXPECT_EQ(count("class=\"series\""), 6u);  // 2 series x (frame time, speedup, efficiency)
  EXPECT_EQ(count("data-series=\"fifo, blocks 16x16\""), 3u);
  EXPECT_EQ(count("class=\"ideal\""), 1u);
  EXPECT_EQ(count("class=\"step-bar\""), 4u * 3u);  // 4 points x 3 shares
  EXPECT_EQ(svg.find("n/a: no 1-NC point"), std::string::npos);
  // Without a 1-NC point the speedup and efficiency panels say why they are empty.
  std::vector<Row> no_one = {row(1, 4, "lpt", 2500), row(3, 16, "lpt", 900)};
  add_speedups(no_one);
  const std::string empty = sweep_svg(no_one);
  EXPECT_NE(empty.find("n/a: no 1-NC point"), std::string::npos);
  EXPECT_EQ(empty.find("class=\"ideal\""), std::string::npos);
}

}  // namespace
}  // namespace mc1::sweep
