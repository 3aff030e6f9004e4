// The frame's steps together (paper section 4, fig. 3): step 3's per-block
// order of s1..s4 and the output, and the cost bookkeeping. Each step is in
// its own file: render_stream.cpp (bank streaming), render_step1.cpp,
// render_blocklist.cpp (step 2), render_s1.cpp, render_cast.cpp (the
// intersection pass of s1, s2, s4), render_solid.cpp (the solid rule),
// render_s2.cpp, render_s34.cpp, render_output.cpp.
#include "render_internal.hpp"

namespace mc1::render {

using namespace layout;

// An FP24 number as an integer of the same order (sign and magnitude to two's
// complement; both zeros are 0): how the MPU compares FP24 values.
std::int32_t order_key(std::uint32_t fp24) {
  const auto magnitude = static_cast<std::int32_t>(fp24 & 0x7FFFFF);
  return (fp24 & 0x800000) ? -magnitude : magnitude;
}

StepCost& StepCost::operator+=(const StepCost& o) {
  apu_cycles += o.apu_cycles;
  apu_runs += o.apu_runs;
  batches += o.batches;
  word_copies += o.word_copies;
  list_elements += o.list_elements;
  sort_compares += o.sort_compares;
  apu_commands += o.apu_commands;
  apu_issued += o.apu_issued;
  apu_bank_stalls += o.apu_bank_stalls;
  return *this;
}

KernelCost& KernelCost::operator+=(const KernelCost& o) {
  apu_cycles += o.apu_cycles;
  apu_runs += o.apu_runs;
  batches += o.batches;
  apu_issued += o.apu_issued;
  apu_bank_stalls += o.apu_bank_stalls;
  apu_dependence_stalls += o.apu_dependence_stalls;
  for (std::size_t u = 0; u < unit_ops.size(); ++u) unit_ops[u] += o.unit_ops[u];
  return *this;
}

const char* step_name(Step s) {
  static const char* names[kSteps] = {"step1 transform", "step2 block lists", "s1 hidden surface",
                                      "s2 shadows", "s3 shading", "s4 reflection/transmission",
                                      "output"};
  return names[static_cast<int>(s)];
}

StepCost RenderStats::total() const {
  StepCost t;
  for (const auto& s : step) t += s;
  return t;
}

// Step 3 for one block: s1 for the eye rays, then per generation of rays
// the solid rule, the surfaces, s2's shadows and s3's shading, whose
// children are the next generation (s4); the pixels' sums last.
std::vector<Rgb8> RenderFirmware::render_block(const BlockList& list) {
  std::vector<Ray> gen = hidden_surface(list);
  std::vector<std::vector<std::array<std::uint32_t, 3>>> contrib(gen.size());
  stats_.rays += gen.size();
  for (int depth = 0; !gen.empty(); ++depth) {
    const Step s1 = depth == 0 ? Step::HiddenSurface : Step::Secondary;
    const Step s3 = depth == 0 ? Step::Shading : Step::Secondary;
    std::vector<std::vector<int>> own;  // secondary rays: one list each
    if (depth > 0) {                     // depth 0: hidden_surface did s1
      secondary_candidates(gen, own);
      cast(gen, own, s1);
    }
    solid_rule(gen, depth == 0 ? lists_ : own, s1);  // eye rays: list 0
    surface(gen, s1);
    shadows(gen);
    shade(gen, s3);
    for (const auto& r : gen) contrib[r.pixel].push_back({r.rec[R_OUT], r.rec[R_OUT + 1], r.rec[R_OUT + 2]});
    std::vector<Ray> next = children(gen, depth);
    stats_.secondary_rays += next.size();
    cost(s3).list_elements += gen.size();
    gen = std::move(next);
  }
  return sum(contrib);
}

}  // namespace mc1::render
