// The stall profile of a frame and the kernel-id signal (frame_profile.hpp).
#include "frame_profile.hpp"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "render_kernels.hpp"

#ifndef MC1_SOURCE_DIR
#define MC1_SOURCE_DIR ""
#endif
#ifndef MC1_GTKW_FILTER_DIR
#define MC1_GTKW_FILTER_DIR ""
#endif

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

namespace {

// docs/apu-core.gtkw for this trace: its dump file, the generated filters by
// absolute path, the kernel id and the pc filter of the kernels that ran.
std::string save_file(const std::string& trace, const std::string& pc_filter, const std::string& kernel_filter,
                      const std::string& markers) {
  std::ifstream in(std::string(MC1_SOURCE_DIR) + "/docs/apu-core.gtkw");
  std::ostringstream base;
  base << in.rdbuf();
  std::string text = base.str();
  std::string out = "[*] GTKWave save file written by mc1 render --trace for " + trace + "\n[dumpfile] \"" + trace + "\"\n";
  if (!markers.empty()) out += markers;
  // The view opens at the first marker (the NC's top stall site), 2 us before it.
  long long start = 0;
  if (const auto star = markers.find("\n*-"); star != std::string::npos) {
    std::istringstream f(markers.substr(star + 1));
    std::string zoom;
    f >> zoom >> start;
    start = std::max(0LL, start - 2000000);
  }
  std::istringstream lines(text);
  std::string line;
  const std::string rel = "build/generated/gtkwave/";
  while (std::getline(lines, line)) {
    if (!markers.empty() && line.rfind("*-", 0) == 0) continue;  // the markers' line replaces the zoom line
    if (line.rfind("[timestart]", 0) == 0) line = "[timestart] " + std::to_string(start);
    if (line.size() > 1 && line[0] == '^' && line.find(rel) != std::string::npos)
      line.replace(line.find(rel), rel.size(), std::string(MC1_GTKW_FILTER_DIR) + "/");
    if (line == "TOP.apu_core.pc[9:0]") {
      out += "@2022\n^15 " + pc_filter + "\n" + line + "\n";
      continue;
    }
    out += line + "\n";
    if (line == "-Sequencer" && out.find("kernel_id") == std::string::npos)
      out += "@2022\n^16 " + kernel_filter + "\nTOP.mc1.kernel_id[15:0]\n";
  }
  return out;
}

std::string absolute(const std::string& path) {
  if (!path.empty() && path[0] == '/') return path;
  char buf[4096];
  if (!getcwd(buf, sizeof buf)) return path;
  return std::string(buf) + "/" + path;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> trace_side_files(const std::string& trace, FrameProfiler& p,
                                                                  unsigned trace_node) {
  const std::string abs = absolute(trace);
  std::vector<std::pair<std::string, std::string>> files;
  files.emplace_back(trace + ".kernel.txt", p.kernels().id_filter());
  files.emplace_back(trace + ".pc.txt", p.kernels().pc_filter());
  const std::string markers = p.profile().nc_totals(trace_node).cycles ? p.profile().gtkw_markers(p.kernels(), trace_node, 26) : "";
  files.emplace_back(trace + ".gtkw", save_file(abs, abs + ".pc.txt", abs + ".kernel.txt", markers));
  return files;
}

}  // namespace mc1
