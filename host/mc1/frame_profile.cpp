// The stall profile of a frame and the kernel-id signal (frame_profile.hpp).
#include "frame_profile.hpp"

#include "apu_trace_files.hpp"
#include "render_kernels.hpp"

namespace mc1 {

FrameProfiler::FrameProfiler(bool profile, unsigned trace_node, Picos from, Picos to)
    : profile_on_(profile), trace_node_(trace_node), window_from_(from), window_to_(to) {
  for (const render::KernelImage& k : render::kernel_images()) kernels_.add(k.name, render::kernel_words(k.name));
}

void FrameProfiler::attach(nc::NodeComputer& n) {
  const unsigned id = n.id();
  if (id >= tracks_.size()) tracks_.resize(id + 1);
  tracks_[id] = std::make_unique<NcTrack>();
  NcTrack* t = tracks_[id].get();
  const bool traced = id == trace_node_;
  if (!profile_on_ && !traced) return;
  apu::ApuEngine* engine = &n.engine();
  n.apu().on_hand_over([this, t, traced, engine](int bank, const std::vector<apu::Encoded>& words) {
    unsigned k;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      k = kernels_.identify(words);
    }
    t->bank_kernel[bank & 1] = k;
    if (traced) engine->trace_kernel(bank, static_cast<std::uint16_t>(k));
  });
  // The traced NC is profiled even without --profile FILE.json: its top
  // stall sites become the save file's markers.
  profile_.add_nc(id);
  if (traced) profile_.set_window(id, window_from_, window_to_);
  n.apu().set_observer([this, t, id, engine](const apu::CycleRecord& r) {
    profile_.add(id, t->bank_kernel[r.psel & 1], r, engine->time_of(r.cycle));
  });
}

std::vector<std::pair<std::string, std::string>> trace_side_files(const std::string& trace, FrameProfiler& p,
                                                                  unsigned trace_node) {
  p.profile().finish();
  const std::string markers =
      p.profile().nc_totals(trace_node).cycles ? p.profile().gtkw_markers(p.kernels(), trace_node, 26) : "";
  return apu::trace_side_files(trace, p.kernels(), markers, "mc1 render --trace");
}

}  // namespace mc1
