#include "mc1_diag.hpp"

#include "diag.hpp"

namespace mc1 {

FrameReport run_diag(const SystemConfig& cfg, const std::string& vcd_path) {
  return run_frame(cfg, diag::kernel(), diag::nc_main, vcd_path);
}

}  // namespace mc1
