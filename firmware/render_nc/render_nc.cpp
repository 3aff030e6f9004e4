// The NC's MPU firmware of the rendered frame (fig. 3): download, step 1,
// list jobs of step 2, blocks of step 3. Protocol: docs/platform.md.
#include "render_nc.hpp"

#include <optional>
#include <stdexcept>
#include <string>


namespace mc1::render_nc {
namespace {

std::string nc_name(const nc::NcPort& port) { return "NC " + std::to_string(port.id()); }

struct Download {
  render::KernelTable kernels;  // the firmware runs these, as broadcast
  render::SceneImage scene;
  rc::RenderSetupMsg setup;
};

// s2: the broadcast, up to RenderSetup.
Download receive_download(nc::NcPort& port) {
  std::optional<render::SceneImage> scene;
  render::KernelTable kernels;
  for (;;) {
    const rc::Bytes m = port.receive_from_rc();
    switch (rc::type_of(m)) {
      case rc::MsgType::Download: {
        const rc::DownloadMsg d = rc::decode_download(m);
        if (d.tag == static_cast<std::uint8_t>(rc::DownloadTag::Kernel)) {
          KernelDownload k = decode_kernel(d.payload);
          if (!kernels.emplace(k.name, std::move(k.words)).second)
            throw rc::ProtocolError(nc_name(port) + ": kernel '" + k.name + "' broadcast twice");
        } else if (d.tag == static_cast<std::uint8_t>(rc::DownloadTag::Scene))
          scene = decode_scene(d.payload);
        else
          throw rc::ProtocolError(nc_name(port) + ": download tag " + std::to_string(d.tag));
        break;
      }
      case rc::MsgType::RenderSetup: {
        const rc::RenderSetupMsg setup = rc::decode_render_setup(m);
        if (!scene) throw rc::ProtocolError(nc_name(port) + ": RenderSetup before the scene");
        if (setup.width != scene->width || setup.height != scene->height)
          throw rc::ProtocolError(nc_name(port) + ": frame " + std::to_string(setup.width) + "x" +
                                  std::to_string(setup.height) + " for a scene of " + std::to_string(scene->width) +
                                  "x" + std::to_string(scene->height));
        return Download{std::move(kernels), std::move(*scene), setup};
      }
      default:
        throw rc::ProtocolError(nc_name(port) + ": message type " + std::to_string(m[0]) + " during the download");
    }
  }
}

render::Block to_render(const rc::Block& b) { return render::Block{b.x, b.y, b.w, b.h}; }

// Step 2: the block lists of a job; the answer is also the next request.
rc::ListsMsg build_lists(render::RenderFirmware& fw, const rc::ListJobMsg& job, const std::vector<rc::Block>& blocks,
                         NcResult& out) {
  rc::ListsMsg lists{job, {}};
  for (std::uint32_t id : rc::job_blocks(job, blocks.size())) {
    const render::BlockList bl = fw.build_block_list(to_render(blocks[id]));
    rc::BlockListMsg m{blocks[id], bl.load, {}};
    for (int o : bl.objects) m.objects.push_back(static_cast<std::uint16_t>(o));
    lists.lists.push_back(std::move(m));
    ++out.lists_built;
  }
  return lists;
}

// Step 3: one block, s1..s4, its rows onto the image bus.
void render_block(nc::NcPort& port, render::RenderFirmware& fw, const rc::BlockListMsg& m, NcResult& out) {
  render::BlockList bl;
  bl.block = to_render(m.block);
  bl.load = m.load;
  for (std::uint16_t o : m.objects) bl.objects.push_back(o);
  const std::vector<render::Rgb8> px = fw.render_block(bl);
  fw.enter_step(render::Step::Output);  // the rows onto the image bus: fig. 3's pixel output
  if (px.size() != std::size_t{m.block.w} * m.block.h)
    throw std::logic_error(nc_name(port) + ": render_block gave " + std::to_string(px.size()) +
                           " pixels for a block of " + std::to_string(m.block.w) + "x" + std::to_string(m.block.h));
  for (unsigned row = 0; row < m.block.h; ++row) {
    PixelRun run{m.block.x, static_cast<std::uint16_t>(m.block.y + row), {}};
    run.pixels.reserve(m.block.w);
    for (unsigned i = 0; i < m.block.w; ++i) {
      const render::Rgb8& c = px[row * m.block.w + i];
      run.pixels.push_back(Rgb8{c.r, c.g, c.b});
    }
    port.send_pixels(run);
  }
  ++out.blocks_rendered;
}

// Leaves the firmware's statistics for the host however the firmware ends
// (Finish, or the NC's processor stopped).
struct ResultGuard {
  const render::RenderFirmware& fw;
  NcResult& local;
  NcResult* result;
  ~ResultGuard() {
    if (!result) return;
    *result = local;
    result->stats = fw.stats();
  }
};

}  // namespace

void nc_main(nc::NcPort& port, NcResult* result) {
  NcApuLink link(port);
  render::RenderFirmware fw(link);
  NcResult local;
  ResultGuard guard{fw, local, result};

  Download d = receive_download(port);
  port.milestone("downloaded");
  fw.use_kernels(std::move(d.kernels));  // the microcode as broadcast, not the library's copy
  fw.load_scene(d.scene);  // step 1: to view coordinates on the APU
  port.milestone("step1");
  const std::vector<rc::Block> blocks = rc::split_screen(d.setup.width, d.setup.height, d.setup.block_w,
                                                         d.setup.block_h);

  port.send_to_rc(rc::encode(rc::RequestMsg{rc::kNoBlock}));
  for (;;) {
    const rc::Bytes m = port.receive_from_rc();
    const rc::MsgType type = rc::type_of(m);
    if (type == rc::MsgType::Finish) break;
    if (type == rc::MsgType::ListJob) {
      port.send_to_rc(rc::encode(build_lists(fw, rc::decode_list_job(m), blocks, local)));
    } else if (type == rc::MsgType::AssignList) {
      const rc::AssignListMsg a = rc::decode_assign_list(m);
      port.block_begin(a.list.block.id);
      render_block(port, fw, a.list, local);
      port.block_end();
      port.send_to_rc(rc::encode(rc::RequestMsg{a.list.block.id}));
    } else {
      throw rc::ProtocolError(nc_name(port) + ": message type " + std::to_string(m[0]) + " where work was expected");
    }
  }
  port.finished();
}

}  // namespace mc1::render_nc
