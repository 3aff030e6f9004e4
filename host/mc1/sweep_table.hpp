// mc1 sweep's answers (docs/platform.md "Sweeps"): per point the figures an
// architect reads (simulated frame time, speedup and parallel efficiency
// against 1 NC, APU utilization, the critical block, the steps' shares of
// the NCs' time), as a CSV table and as summary lines; the check that every
// point of one scene and camera frame made the same image. The plots of the
// same rows are sweep_svg.hpp's.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mc1_report.hpp"

namespace mc1::sweep {

// The block that took longest from its dispatch to its report (the RC
// learned it was done). `bounds_frame`: it went out before any block was
// reported (in the first wave) and its report was the frame's last, so the
// frame's step 3 cannot end before it whatever the schedule or the NC count:
// it is the critical path.
struct CriticalBlock {
  std::int64_t block = -1;  // -1: no block was reported
  Picos time = 0;           // its dispatch to its report
  bool bounds_frame = false;
};
CriticalBlock critical_block(const FrameReport& r);

// Each of fig. 3's steps (frame_steps() keys) and "idle": its share of the
// NCs' time, sum over NCs of the step's busy and waiting time / (NCs x frame
// time). The shares add up to 1.
std::vector<std::pair<std::string, double>> step_shares(const FrameReport& r);

// One point of a sweep, as its report gives it.
struct Row {
  std::uint64_t index = 0;
  std::string scene;
  unsigned frame = 0;  // of the camera orbit
  unsigned width = 0, height = 0, nodes = 0;
  std::string schedule, block;  // "lpt", "16x16"
  Picos frame_ps = 0;
  double apu_utilization = 0;
  std::int64_t critical_block = -1;  // -1: not known (no block reported, or an old report)
  Picos critical_ps = 0;
  bool critical_path = false;
  double host_seconds = 0;
  std::string image;  // the frame's hash (FNV-1a of its RGB bytes)
  bool complete = true;
  std::vector<std::pair<std::string, double>> steps;  // step_shares
  // Set by add_speedups: against the 1-NC point of the same scene, camera
  // frame, size, schedule and block size, when the rows have one.
  std::optional<double> speedup, efficiency;
};

// speedup = T(1 NC) / T, efficiency = speedup / NCs, for every row whose
// 1-NC point is among `rows`; the others keep none ("n/a").
void add_speedups(std::vector<Row>& rows);

// The table, one line a row, with a header line; a figure not known is "n/a".
std::string csv(const std::vector<Row>& rows);
extern const char* const kCsvHeader;

// The table for a person, aligned columns: scene and camera frame (when the
// rows have more than one), NCs, schedule, block, frame ms, speedup,
// efficiency, APU utilization, the critical block and its share ("*": the
// critical path).
std::string text_table(const std::vector<Row>& rows);

// Points of one scene and camera frame whose images differ: the points of
// each distinct image, in order of first appearance.
struct FrameMismatch {
  std::string scene;
  unsigned frame = 0;
  std::vector<std::pair<std::string, std::vector<std::uint64_t>>> images;  // hash, point indices
};
std::vector<FrameMismatch> compare_frames(const std::vector<Row>& rows);
// "frames differ: whitted.json frame 0: points 0, 1 give image 1f..., point 2 gives image 9a..."
std::string mismatch_text(const FrameMismatch& m);

// The summary's lines: one per scene, camera frame, NC count and block size
// whose frame one block bounds ("at 64 NCs, blocks 16x16: every schedule
// takes 1136.034 ms: block 36 alone takes ..."), and, when the rows lack a
// 1-NC point, a line saying the speedups are not known.
std::vector<std::string> summary(const std::vector<Row>& rows);

}  // namespace mc1::sweep
