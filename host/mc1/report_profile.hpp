// The frame's timing evaluation: per-step and per-kernel tables (Markdown)
// of a rendered frame's FrameReport (docs/renderer.md "Timing").
#pragma once

#include <string>

#include "mc1_report.hpp"

namespace mc1 {

std::string profile_tables(const FrameReport& r);

}  // namespace mc1
