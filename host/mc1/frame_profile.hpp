// The stall profile of a whole frame (mc1 render --profile FILE.json) and
// the traced NC's kernel-id signal: attached to every NC's APU driver
// through SystemConfig::attach. Kernels are named by their program: at each
// program hand-over the bank's words are matched against the renderer's
// kernel images (docs/apu-tools.md "The stall profile").
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "apu_stall_profile.hpp"
#include "mc1_system.hpp"

namespace mc1 {

class FrameProfiler {
 public:
  // profile: collect the stall profile (the ISS leaves its fast path on
  // every NC); trace_node: the NC whose waveform gets the kernel-id signal
  // and markers at its top stall sites in [from, to) (0: none).
  FrameProfiler(bool profile, unsigned trace_node, Picos from = 0, Picos to = ~Picos{0});
  // SystemConfig::attach.
  void attach(nc::NodeComputer& n);

  apu::KernelTable& kernels() { return kernels_; }
  apu::StallProfile& profile() { return profile_; }

 private:
  struct NcTrack {
    unsigned bank_kernel[2] = {0, 0};
  };
  bool profile_on_;
  unsigned trace_node_;
  Picos window_from_, window_to_;
  std::mutex mutex_;  // the kernel table, if NCs run on threads
  apu::KernelTable kernels_;
  apu::StallProfile profile_;
  std::vector<std::unique_ptr<NcTrack>> tracks_;
};

// The files beside the trace (apu::trace_side_files: TRACE.kernel.txt,
// TRACE.kpc.txt, TRACE.gtkw), the save file with markers at the traced NC's
// top stall sites in the trace's window. Returns them as (path, text), for
// the caller's outputs.
std::vector<std::pair<std::string, std::string>> trace_side_files(const std::string& trace, FrameProfiler& p,
                                                                  unsigned trace_node);

}  // namespace mc1
