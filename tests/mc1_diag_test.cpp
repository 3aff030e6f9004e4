// The machine's self-test frame end to end: the frame memory equals the
// host's FP24-model image bit for bit for 1, 3, 16 and 256 NCs, on both APU
// engines and with HDLC faults; every block is dispatched and completed
// exactly once; per-NC times add up to the simulated time.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "diag.hpp"
#include "mc1_diag.hpp"
#include "mc1_engines.hpp"
#include "mc1_system.hpp"
#include "report_writers.hpp"
#include "sc_test_harness.hpp"

using namespace mc1;

namespace {

SystemConfig config(unsigned nodes, unsigned size, unsigned block) {
  SystemConfig c;
  c.nodes = nodes;
  c.width = size;
  c.height = size;
  c.block_w = block;
  c.block_h = block;
  return c;
}

FrameReport run(const SystemConfig& c) {
  test::fresh_kernel();
  return run_diag(c);
}

// Every block handed out once and reported done once; one Finish per NC.
void expect_dispatch_exact(const FrameReport& r) {
  std::map<std::uint32_t, int> handed, done;
  std::map<unsigned, int> finish;
  for (const rc::Dispatch& d : r.dispatches) {
    if (d.block == rc::kNoBlock)
      ++finish[d.nc];
    else
      ++handed[d.block];
  }
  for (const rc::Completion& c : r.completions) ++done[c.block];
  ASSERT_EQ(handed.size(), r.blocks);
  ASSERT_EQ(done.size(), r.blocks);
  for (const auto& h : handed) EXPECT_EQ(h.second, 1) << "block " << h.first;
  for (const auto& d : done) EXPECT_EQ(d.second, 1) << "block " << d.first;
  EXPECT_EQ(finish.size(), r.nodes);
  for (const auto& f : finish) EXPECT_EQ(f.second, 1) << "NC " << f.first;
  EXPECT_EQ(r.fm_pixels_written, std::uint64_t{r.width} * r.height);
  std::uint64_t blocks = 0, pixels = 0;
  for (const NcReport& n : r.ncs) {
    blocks += n.blocks;
    pixels += n.pixels;
  }
  EXPECT_EQ(blocks, r.blocks);
  EXPECT_EQ(pixels, std::uint64_t{r.width} * r.height);
}

// busy + waiting + idle = the simulated time, for every NC; spans tile it.
void expect_stats_add_up(const FrameReport& r) {
  for (const NcReport& n : r.ncs) {
    EXPECT_EQ(n.busy + n.wait_rc + n.wait_bus + n.idle, r.frame_time) << "NC " << n.id;
    ASSERT_FALSE(n.spans.empty());
    EXPECT_EQ(n.spans.front().begin, 0u);
    EXPECT_EQ(n.spans.back().end, r.frame_time);
    for (std::size_t i = 1; i < n.spans.size(); ++i) ASSERT_EQ(n.spans[i].begin, n.spans[i - 1].end);
    EXPECT_LE(n.apu_busy, n.busy);
    EXPECT_GE(n.apu_busy, n.apu_cycles ? 1u : 0u);
  }
}

}  // namespace

TEST(DiagPattern, KnownPixels) {
  // At the centre u = v = 0: sin 0 = 0, cos 0 = 1, q = 1/sqrt(1) = 1:
  // R = fix(0 * 255) = 0, G = fix(1 * 255) = 255, B = fix((0 + 1) * 1 * 127.5) = 127.
  EXPECT_EQ(diag::expected_pixel(32, 32, 32, 32), (Rgb8{0, 255, 127}));
  // 16 pixels right: u = 1.0, sin 1 = 0.841..., |.| * 255 = 214.6 -> 214.
  EXPECT_EQ(diag::expected_pixel(48, 32, 32, 32).r, 214);
  const auto img = diag::expected_image(64, 64);
  ASSERT_EQ(img.size(), 64u * 64u * 3u);
  EXPECT_EQ(img[3 * (32 * 64 + 32)], 0);
  EXPECT_EQ(img[3 * (32 * 64 + 32) + 1], 255);
}

TEST(DiagFrame, OneNc) {
  const FrameReport r = run(config(1, 64, 8));
  EXPECT_EQ(r.rgb, diag::expected_image(64, 64));
  expect_dispatch_exact(r);
  expect_stats_add_up(r);
}

TEST(DiagFrame, ThreeNcsNonSquareClippedBlocks) {
  SystemConfig c = config(3, 0, 0);
  c.width = 70;
  c.height = 45;
  c.block_w = 16;
  c.block_h = 8;  // the last column (6 wide) and row (5 high) are clipped
  const FrameReport r = run(c);
  EXPECT_EQ(r.rgb, diag::expected_image(70, 45));
  expect_dispatch_exact(r);
  expect_stats_add_up(r);
}

TEST(DiagFrame, SixteenNcs) {
  const FrameReport r = run(config(16, 64, 8));
  EXPECT_EQ(r.rgb, diag::expected_image(64, 64));
  expect_dispatch_exact(r);
  expect_stats_add_up(r);
  for (const NcReport& n : r.ncs) EXPECT_GE(n.blocks, 1u) << "NC " << n.id << " got no block";
}

TEST(DiagFrame, TwoHundredFiftySixNcs) {
  const FrameReport r = run(config(256, 64, 4));
  EXPECT_EQ(r.rgb, diag::expected_image(64, 64));
  EXPECT_EQ(r.hdlc.ports, 2u);  // 254 NCs per HDLC port
  expect_dispatch_exact(r);
  expect_stats_add_up(r);
}

TEST(DiagFrame, SameFrameWhateverTheNodeCount) {
  const auto one = run(config(1, 48, 8)).rgb;
  for (unsigned n : {2u, 5u, 36u}) EXPECT_EQ(run(config(n, 48, 8)).rgb, one) << n << " NCs";
}

TEST(DiagFrame, RtlEngine) {
  SystemConfig c = config(3, 32, 8);
  c.engine = EngineKind::Rtl;
  c.engines = make_engine;
  const FrameReport rtl = run(c);
  EXPECT_EQ(rtl.rgb, diag::expected_image(32, 32));
  c.engine = EngineKind::Iss;
  const FrameReport iss = run(c);
  // Cycle-exact engines: the same timeline, not only the same frame.
  EXPECT_EQ(rtl.frame_time, iss.frame_time);
}

TEST(DiagFrame, WithBitErrorsAndADeadLink) {
  SystemConfig c = config(16, 64, 8);
  c.ber = 1e-4;
  c.dead_links.push_back(DeadLink{5, 500'000'000, 4'000'000'000});  // NC 5: 0.5 to 4 ms
  const FrameReport r = run(c);
  EXPECT_EQ(r.rgb, diag::expected_image(64, 64));
  expect_dispatch_exact(r);
  expect_stats_add_up(r);
  EXPECT_TRUE(r.link_downs.empty());  // 3.5 ms dead and BER 1e-4: no false link-down
  EXPECT_GT(r.hdlc.fcs_errors, 0u);
  EXPECT_GT(r.hdlc.bits_dead, 0u);
  std::uint64_t retx = 0;
  for (const auto& l : r.hdlc.down) retx += l.retransmissions;
  for (const auto& l : r.hdlc.up) retx += l.retransmissions;
  EXPECT_GT(retx, 0u);
  // The faults cost time, not pixels.
  const FrameReport clean = run(config(16, 64, 8));
  EXPECT_GT(r.frame_time, clean.frame_time);
}

// The same link supervision as the rendered frame: a killed NC (silent
// station) and an NC behind a cut line, each rendering a block, are found
// by unanswered polls; their blocks go to the others (who wait for them
// instead of taking Finish); the frame is still exact.
TEST(DiagFrame, KilledNcAndCutLineFoundByLinkSupervision) {
  SystemConfig c = config(16, 64, 8);
  c.kills = {{3, 3'500'000'000}};        // 3.5 ms: inside one of its blocks
  c.cut_lines = {{7, 4'500'000'000}};    // 4.5 ms
  const FrameReport r = run(c);
  EXPECT_EQ(r.rgb, diag::expected_image(64, 64));
  EXPECT_EQ(r.fm_pixels_written, 64u * 64u);
  std::map<std::uint32_t, int> done;
  for (const rc::Completion& x : r.completions) ++done[x.block];
  ASSERT_EQ(done.size(), r.blocks);
  for (const auto& d : done) EXPECT_EQ(d.second, 1) << "block " << d.first;
  EXPECT_TRUE(r.timeouts.empty());
  ASSERT_EQ(r.link_downs.size(), 2u);
  const TimingParams& tp = c.timing;
  const Picos bound = 1000 * tp.hdlc_poll_interval_ns + (tp.hdlc_n2_retries + 1) * (1000 * tp.hdlc_t1_timeout_ns + 1'000'000'000);
  for (const rc::LinkDown& d : r.link_downs) {
    const Picos fault = d.nc == 3 ? c.kills[0].time : c.cut_lines[0].time;
    EXPECT_TRUE(d.nc == 3 || d.nc == 7) << d.nc;
    EXPECT_EQ(d.reason, hdlc::LinkDownReason::PollUnanswered) << "NC " << d.nc;
    EXPECT_EQ(d.requeued, 1u) << "NC " << d.nc;
    EXPECT_GT(d.time, fault);
    EXPECT_LE(d.time, fault + bound) << "NC " << d.nc;
  }
  for (const NcReport& n : r.ncs) {
    EXPECT_EQ(n.busy + n.wait_rc + n.wait_bus + n.idle + n.dead, r.frame_time) << "NC " << n.id;
    EXPECT_EQ(n.link_down != 0, n.id == 3 || n.id == 7) << "NC " << n.id;
  }
}

TEST(DiagFrame, TwoHundredFiftySixNcsWithFaults) {
  SystemConfig c = config(256, 64, 4);
  c.ber = 1e-4;
  c.dead_links.push_back(DeadLink{200, 1'000'000'000, 3'000'000'000});
  const FrameReport r = run(c);
  EXPECT_EQ(r.rgb, diag::expected_image(64, 64));
  expect_dispatch_exact(r);
  expect_stats_add_up(r);
  EXPECT_TRUE(r.link_downs.empty());
}

TEST(DiagFrame, Deterministic) {
  const FrameReport a = run(config(5, 40, 8));
  const FrameReport b = run(config(5, 40, 8));
  EXPECT_EQ(a.frame_time, b.frame_time);
  EXPECT_EQ(stats_json(a).substr(0, 200), stats_json(b).substr(0, 200));
  ASSERT_EQ(a.dispatches.size(), b.dispatches.size());
  for (std::size_t i = 0; i < a.dispatches.size(); ++i) {
    EXPECT_EQ(a.dispatches[i].nc, b.dispatches[i].nc);
    EXPECT_EQ(a.dispatches[i].block, b.dispatches[i].block);
  }
}

TEST(DiagFrame, StatsJsonAndGantt) {
  const FrameReport r = run(config(4, 32, 8));
  const std::string j = stats_json(r);
  for (const char* key : {"\"simulated_time_ps\": ", "\"busy_ps\"", "\"idle_ps\"", "\"waiting_ps\"",
                          "\"apu_utilization\"", "\"retransmissions\"", "\"info_bytes\"", "\"image_bus\"",
                          "\"utilization\""})
    EXPECT_NE(j.find(key), std::string::npos) << key;
  EXPECT_NE(j.find("\"simulated_time_ps\": " + std::to_string(r.frame_time)), std::string::npos);
  const std::string svg = gantt_svg(r);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  for (unsigned k = 1; k <= 4; ++k) EXPECT_NE(svg.find(">NC " + std::to_string(k) + "<"), std::string::npos);
  // 256 rows: thin rows, labels every 16th.
  const std::string big = gantt_svg(run(config(256, 32, 2)));
  EXPECT_NE(big.find(">NC 17<"), std::string::npos);
  EXPECT_EQ(big.find(">NC 18<"), std::string::npos);
}

MC1_SYSTEMC_GTEST_MAIN()
