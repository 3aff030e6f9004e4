// An NC's timeline cut by fig. 3's steps (download, step 1, block lists,
// s1..s4, pixel output), from the firmware's step changes (NcReport::phases):
// what the Gantt chart colours and the statistics sum per NC and step.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mc1_report.hpp"

namespace mc1 {

struct FrameStep {
  const char* key;     // in the statistics: "s1", "block_lists", ...
  const char* label;   // in the chart's legend
  const char* colour;  // in the chart
};
// Download first, then in the paper's order; indices are step ids.
const std::vector<FrameStep>& frame_steps();
constexpr int kNoStep = -1;  // a frame without steps (the diagnostic frame)

// A piece of an NC's activity inside one step.
struct StepSpan {
  Picos begin = 0, end = 0;
  nc::Activity what = nc::Activity::Busy;
  std::uint32_t block = 0xFFFFFFFF;
  int step = kNoStep;
  bool done = false;  // waiting after the NC's last block: idle
};
std::vector<StepSpan> step_spans(const NcReport& n);

struct StepTime {
  Picos busy = 0, waiting = 0;  // waiting: for the RC or the image bus inside the step
};
// By step id; all zero for a frame without steps.
std::vector<StepTime> step_times(const NcReport& n);

// The engines a frame ran on, as the summary and the chart's title say it:
// "iss engine", "rtl engine", "iss engine, RTL core on NCs 1-4,9" (the
// NCs of --rtl-nodes and the traced NC: FrameReport::rtl_nodes).
std::string engine_text(const FrameReport& r);

}  // namespace mc1
