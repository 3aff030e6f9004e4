// A rendered frame on the machine (paper section 4, fig. 3): the RC loads a
// scene file, converts it to the FP24 scene image it broadcasts, and runs
// the frame with the renderer firmware on every NC (firmware/render_nc).
// docs/platform.md "The rendered frame".
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "mc1_report.hpp"
#include "mc1_system.hpp"
#include "render_nc.hpp"

namespace mc1 {

struct RenderJob {
  std::string scene;               // JSON scene file (docs/scene-format.md)
  unsigned width = 0, height = 0;  // frame size; 0: the scene's camera size
  // The camera's eye turned about its look-at point around its up vector
  // (a frame of mc1 sweep --orbit), degrees.
  double orbit_deg = 0;
};

struct RenderRun {
  FrameReport report;                       // report.rgb is the frame memory
  std::vector<render_nc::NcResult> ncs;     // per NC, 1..N at index 0..N-1
};

// cfg.width / cfg.height are replaced by the frame's size. Throws
// scene::SceneError for a bad scene, std::runtime_error for a failed frame.
RenderRun run_render(const RenderJob& job, SystemConfig cfg, const std::string& vcd_path = "",
                     std::function<void(const rc::Progress&)> progress = {});

}  // namespace mc1
