// Fig. 3's steps over an NC's timeline (frame_steps.hpp).
#include "frame_steps.hpp"

#include <algorithm>

namespace mc1 {
namespace {

constexpr Picos kNever = ~Picos{0};

// The firmware's step names (firmware/render step_name) by step id; the
// download has none: it is the time before the first step change.
const char* const kFirmwareNames[] = {nullptr,         "step1 transform", "step2 block lists",
                                      "s1 hidden surface", "s2 shadows",  "s3 shading",
                                      "s4 reflection/transmission", "output"};

int step_of(const std::string& phase) {
  for (int i = 1; i < static_cast<int>(std::size(kFirmwareNames)); ++i)
    if (phase == kFirmwareNames[i]) return i;
  return kNoStep;
}

}  // namespace

const std::vector<FrameStep>& frame_steps() {
  static const std::vector<FrameStep> steps = {
      {"download", "download", "#bcaaa4"},        {"step1", "step 1 (transform)", "#6d4c41"},
      {"block_lists", "block lists", "#00897b"},  {"s1", "s1 hidden surface", "#2e7d32"},
      {"s2", "s2 shadows", "#afb42b"},            {"s3", "s3 shading", "#fdd835"},
      {"s4", "s4 reflection/transmission", "#4fc3f7"}, {"output", "pixel output", "#f06292"}};
  return steps;
}

std::vector<StepSpan> step_spans(const NcReport& n) {
  // After its last block an NC only waits for the Finish: that is idle.
  Picos last_block = kNever;
  for (const nc::Span& s : n.spans)
    if (s.block != 0xFFFFFFFF) last_block = last_block == kNever ? s.end : std::max(last_block, s.end);
  const bool stepped = !n.phases.empty();
  std::vector<StepSpan> out;
  std::size_t k = 0;  // phases[k] is the first change after the current point
  int step = stepped ? 0 : kNoStep;
  for (const nc::Span& s : n.spans) {
    Picos t = s.begin;
    while (t < s.end) {
      while (k < n.phases.size() && n.phases[k].first <= t) step = step_of(n.phases[k++].second);
      const Picos end = k < n.phases.size() ? std::min(s.end, n.phases[k].first) : s.end;
      out.push_back({t, end, s.what, s.block, step, s.what != nc::Activity::Busy && t >= last_block});
      t = end;
    }
  }
  return out;
}

std::vector<StepTime> step_times(const NcReport& n) {
  std::vector<StepTime> t(frame_steps().size());
  for (const StepSpan& s : step_spans(n)) {
    if (s.step == kNoStep || s.done) continue;
    if (s.what == nc::Activity::Busy) t[s.step].busy += s.end - s.begin;
    else if (s.what == nc::Activity::WaitRc || s.what == nc::Activity::WaitBus) t[s.step].waiting += s.end - s.begin;
  }
  return t;
}

std::string engine_text(const FrameReport& r) {
  std::string t = r.engine + " engine";
  const std::vector<unsigned>& k = r.rtl_nodes;  // sorted, each once
  if (k.empty()) return t;
  t += k.size() == 1 ? ", RTL core on NC " : ", RTL core on NCs ";
  for (std::size_t i = 0; i < k.size();) {
    std::size_t j = i;
    while (j + 1 < k.size() && k[j + 1] == k[j] + 1) ++j;
    t += (i ? "," : "") + std::to_string(k[i]) + (j > i ? (j > i + 1 ? "-" : ",") + std::to_string(k[j]) : "");
    i = j + 1;
  }
  return t;
}

}  // namespace mc1
