#include "mc1_render.hpp"

#include <cmath>
#include <map>
#include <memory>

#include "scene.hpp"
#include "scene_image.hpp"

namespace mc1 {
namespace {

// The renderer's per-step costs (fig. 3) and per-kernel APU work, summed
// over the NCs; MPU cycles at the timing table's cost per class.
void add_steps(FrameReport& r, const std::vector<render_nc::NcResult>& ncs, const TimingParams& t) {
  for (int i = 0; i < render::kSteps; ++i) {
    render::StepCost c;
    for (const render_nc::NcResult& n : ncs) c += n.stats.step[static_cast<std::size_t>(i)];
    StepReport s;
    s.name = render::step_name(static_cast<render::Step>(i));
    s.apu_cycles = c.apu_cycles;
    s.apu_runs = c.apu_runs;
    s.batches = c.batches;
    s.word_copies = c.word_copies;
    s.list_elements = c.list_elements;
    s.sort_compares = c.sort_compares;
    s.apu_commands = c.apu_commands;
    s.apu_issued = c.apu_issued;
    s.apu_bank_stalls = c.apu_bank_stalls;
    s.mpu_cycles = s.word_copies * t.mpu_cycles_per_word_copy + s.list_elements * t.mpu_cycles_per_list_element +
                   s.sort_compares * t.mpu_cycles_per_sort_compare + s.apu_commands * t.mpu_cycles_per_apu_command;
    r.steps.push_back(s);
  }
  std::map<std::string, render::KernelCost> kernels;
  for (const render_nc::NcResult& n : ncs)
    for (const auto& [name, c] : n.stats.kernels) kernels[name] += c;
  for (const auto& [name, c] : kernels) {
    KernelReport k;
    k.name = name;
    k.apu_cycles = c.apu_cycles;
    k.apu_runs = c.apu_runs;
    k.batches = c.batches;
    k.apu_issued = c.apu_issued;
    k.apu_bank_stalls = c.apu_bank_stalls;
    k.apu_dependence_stalls = c.apu_dependence_stalls;
    k.unit_ops = c.unit_ops;
    r.kernels.push_back(k);
  }
  for (const render_nc::NcResult& n : ncs) {
    r.rays += n.stats.rays;
    r.shadow_rays += n.stats.shadow_rays;
    r.secondary_rays += n.stats.secondary_rays;
  }
}

}  // namespace

RenderRun run_render(const RenderJob& job, SystemConfig cfg, const std::string& vcd_path,
                     std::function<void(const rc::Progress&)> progress) {
  scene::Scene s = scene::load_scene(job.scene);
  if (job.width) s.camera.width = static_cast<int>(job.width);
  if (job.height) s.camera.height = static_cast<int>(job.height);
  if (job.orbit_deg != 0) {  // Rodrigues' rotation of eye - look_at about up
    const double a = job.orbit_deg * 3.14159265358979323846 / 180.0;
    const glm::dvec3 k = glm::normalize(s.camera.up), v = s.camera.eye - s.camera.look_at;
    s.camera.eye = s.camera.look_at + v * std::cos(a) + glm::cross(k, v) * std::sin(a) +
                   k * glm::dot(k, v) * (1 - std::cos(a));
  }
  const render::SceneImage image = render::make_scene_image(s);
  cfg.width = static_cast<unsigned>(image.width);
  cfg.height = static_cast<unsigned>(image.height);

  auto results = std::make_shared<std::vector<render_nc::NcResult>>(cfg.nodes);
  const nc::Firmware firmware = [results](nc::NcPort& port) {
    render_nc::nc_main(port, &(*results)[port.id() - 1]);
  };
  RenderRun out;
  out.report = run_plan(cfg, render_nc::frame_plan(image, cfg.block_w, cfg.block_h), firmware, vcd_path,
                        std::move(progress));
  out.report.scene = job.scene;
  out.ncs = *results;
  add_steps(out.report, out.ncs, cfg.timing);
  return out;
}

}  // namespace mc1
