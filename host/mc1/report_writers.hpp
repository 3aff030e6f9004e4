// A FrameReport (hw/mc1/mc1_report.hpp) written out: the statistics JSON, the
// Gantt SVG (docs/platform.md gives both formats), and the figures the
// summaries print.
#pragma once

#include <string>

#include "mc1_report.hpp"

namespace mc1 {

std::string stats_json(const FrameReport& r);
std::string gantt_svg(const FrameReport& r);
// The latest time any live NC reached milestone `name` (0: none did).
Picos milestone_time(const FrameReport& r, const std::string& name);
// Mean over NCs of apu_busy / T.
double apu_utilization_mean(const FrameReport& r);

}  // namespace mc1
