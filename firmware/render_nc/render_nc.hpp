// The rendered frame on the machine (paper section 4, fig. 3): the NC-side
// glue that runs the renderer firmware (firmware/render, RenderFirmware) on
// a node computer, and the frame's messages on both sides.
//
//   RC: broadcasts the kernels and the scene image (Download, real bytes:
//       the 4 Mbps wire time counts), then RenderSetup.
//   NC: step 1, load_scene (view coordinates on its APU); asks for work.
//   RC: step 2, hands out list jobs; the NC builds the block lists
//       (build_block_list) and sends them back (Lists).
//   RC: step 3, hands out the blocks by its schedule with their lists
//       (AssignList); the NC renders (render_block) and sends each row of
//       pixels over the image bus, then asks for the next (Request).
//
// NcApuLink is the renderer's ApuLink on an NcPort: every MPU cost class of
// the firmware becomes MPU time from the timing table, and waiting for the
// APU clocks the NC's APU, as the diagnostic firmware does.
// docs/platform.md "The rendered frame" gives the message layouts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "microword.hpp"
#include "nc_port.hpp"
#include "rc_protocol.hpp"
#include "render_fw.hpp"
#include "root_computer.hpp"
#include "scene_image.hpp"

namespace mc1::render_nc {

class NcApuLink final : public render::ApuLink {
 public:
  explicit NcApuLink(nc::NcPort& port) : port_(port) {}
  apu::ApuDriver& apu() override { return port_.apu(); }
  void wait_swap() override { port_.apu_wait_swap(); }
  void wait_halt() override { port_.apu_wait_halt(); }
  void copy_words(std::uint64_t n) override { port_.copy_words(n); }
  void list_elements(std::uint64_t n) override { port_.mpu_work(n * port_.timing().mpu_cycles_per_list_element); }
  void sort_compares(std::uint64_t n) override { port_.mpu_work(n * port_.timing().mpu_cycles_per_sort_compare); }
  void apu_commands(std::uint64_t n) override { port_.apu_commands(n); }
  void enter_step(const char* name) override { port_.phase(name); }
  void activity(std::uint16_t code, std::uint32_t detail) override { port_.mpu_activity(code, detail); }

 private:
  nc::NcPort& port_;
};

// Download payloads. Scene: every FP24 word as 3 bytes, integers
// little-endian (docs/platform.md). Kernel: name, then 128-bit microwords.
rc::Bytes encode_scene(const render::SceneImage& s);
render::SceneImage decode_scene(const rc::Bytes& b);  // throws rc::ProtocolError
rc::Bytes encode_kernel(const std::string& name, const std::vector<apu::Encoded>& words);
struct KernelDownload {
  std::string name;
  std::vector<apu::Encoded> words;
};
KernelDownload decode_kernel(const rc::Bytes& b);  // throws rc::ProtocolError

// The RC's deadline weight of each object (RootComputer, FramePlan::
// object_work): its primitives, 4x when it reflects or refracts (ks, kt > 0),
// as the paper's load prediction counts such objects heavier.
std::vector<std::uint32_t> object_work(const render::SceneImage& scene);

// What the RC does in a rendered frame of `scene` (its width and height are
// the frame's) cut into blocks of block_w x block_h.
rc::FramePlan frame_plan(const render::SceneImage& scene, unsigned block_w, unsigned block_h);

// What an NC's firmware leaves for the host after the frame (also when the
// NC was killed: what it did until then).
struct NcResult {
  render::RenderStats stats;
  std::uint64_t lists_built = 0, blocks_rendered = 0;
};

// The NC's MPU firmware; `result` may be null.
void nc_main(nc::NcPort& port, NcResult* result);

}  // namespace mc1::render_nc
