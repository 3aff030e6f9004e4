// The stall profile of a frame and the kernel-id signal (frame_profile.hpp).
#include "frame_profile.hpp"

#include <algorithm>

#include "apu_trace_files.hpp"
#include "mpu_activity.hpp"
#include "render_fw.hpp"
#include "render_kernels.hpp"
#include "report_text.hpp"

namespace mc1 {
namespace {

// The stall profile's MPU activity: what the MPU does (nc::MpuDoing) and the
// firmware's step (its activity code: render::activity_code), as one id.
constexpr unsigned kCodes = 16;
unsigned mpu_id(const nc::MpuState& s) {
  return static_cast<unsigned>(s.doing) * kCodes + (s.code < kCodes ? s.code : 0);
}

// The firmware's name of activity `code` (0: none).
std::string step_text(unsigned code) {
  return code >= 1 && code <= static_cast<unsigned>(render::kSteps) ? render::step_name(static_cast<render::Step>(code - 1))
                                                                      : "";
}

std::string mpu_name(unsigned id) {
  const std::string step = step_text(id % kCodes);
  return std::string(nc::mpu_doing_name(static_cast<nc::MpuDoing>(id / kCodes))) + (step.empty() ? "" : " (" + step + ")");
}

apu::MpuFilters mpu_filters() {
  apu::MpuFilters f;
  f.doing = "# what the MPU does (nc::MpuDoing; GTKWave translate filter for TOP.mc1.mpu_doing)\n";
  for (int d = 0; d < nc::kMpuDoings; ++d)
    f.doing += apu::report_text::format("%X %s\n", d, nc::mpu_doing_name(static_cast<nc::MpuDoing>(d)));
  f.step = "# the firmware's step (render::activity_code; GTKWave translate filter for TOP.mc1.mpu_step)\n0000 -\n";
  for (int s = 0; s < render::kSteps; ++s)
    f.step += apu::report_text::format("%04X %s\n", s + 1, render::step_name(static_cast<render::Step>(s)));
  return f;
}

}  // namespace

FrameProfiler::FrameProfiler(bool profile, unsigned trace_node, Picos from, Picos to)
    : profile_on_(profile), trace_node_(trace_node), window_from_(from), window_to_(to) {
  for (const render::KernelImage& k : render::kernel_images()) kernels_.add(k.name, render::kernel_words(k.name));
  profile_.set_mpu_names(mpu_name);
}

void FrameProfiler::attach(nc::NodeComputer& n) {
  const unsigned id = n.id();
  if (id >= tracks_.size()) tracks_.resize(id + 1);
  tracks_[id] = std::make_unique<NcTrack>();
  NcTrack* t = tracks_[id].get();
  const bool traced = id == trace_node_;
  if (!profile_on_ && !traced) return;
  apu::ApuEngine* engine = &n.engine();
  // The MPU's side: in the waveform, and by BANK stall in the profile.
  n.record_mpu(true);
  nc::MpuTimeline* mpu = &n.mpu_timeline();
  if (traced)
    engine->trace_mpu([mpu](std::uint64_t ps) {
      const nc::MpuState s = mpu->at(ps);
      apu::ApuEngine::MpuTraceInputs in;
      in.doing = static_cast<std::uint8_t>(s.doing);
      in.code = s.code;
      in.detail = s.detail;
      in.block = s.block;
      in.words_left = static_cast<std::uint16_t>(std::min<std::uint32_t>(s.words_left(ps), 0xFFFF));
      return in;
    });
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
  n.apu().set_observer([this, t, id, engine, mpu](const apu::CycleRecord& r) {
    const std::uint64_t ps = engine->time_of(r.cycle);
    const bool bank = !r.issued && r.stall == apu::Stall::Bank;
    profile_.add(id, t->bank_kernel[r.psel & 1], r, ps, bank ? mpu_id(mpu->at(ps)) : apu::StallProfile::kNoMpu);
  });
}

std::vector<std::pair<std::string, std::string>> trace_side_files(const std::string& trace, FrameProfiler& p,
                                                                  unsigned trace_node) {
  p.profile().finish();
  const std::string markers =
      p.profile().nc_totals(trace_node).cycles ? p.profile().gtkw_markers(p.kernels(), trace_node, 26) : "";
  return apu::trace_side_files(trace, p.kernels(), markers, "mc1 render --trace", mpu_filters());
}

}  // namespace mc1
