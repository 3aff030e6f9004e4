// The machine's self-test frame (docs/platform.md "The diagnostic frame"):
// diag.apu and its MPU firmware (firmware/diag) on every NC.
#pragma once

#include <string>

#include "mc1_report.hpp"
#include "mc1_system.hpp"

namespace mc1 {

FrameReport run_diag(const SystemConfig& cfg, const std::string& vcd_path = "");

}  // namespace mc1
