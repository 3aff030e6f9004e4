// The frame's timing evaluation (docs/renderer.md "Timing"): per step of the
// renderer and per APU kernel, APU cycles, words issued, bank stalls and
// utilization, and the MPU cycles of each step, as two Markdown tables.
#include "report_profile.hpp"

#include <string>

#include "report_text.hpp"

namespace mc1 {
namespace {

using apu::report_text::format;

double share(std::uint64_t a, std::uint64_t b) { return b ? 100.0 * static_cast<double>(a) / static_cast<double>(b) : 0.0; }

}  // namespace

std::string profile_tables(const FrameReport& r) {
  std::uint64_t apu = 0, mpu = 0;
  for (const StepReport& s : r.steps) apu += s.apu_cycles, mpu += s.mpu_cycles;
  std::string o = format("Per step, summed over %u NCs (utilization: words issued per APU cycle; bank: cycles waiting "
                      "at SWAPD for the MPU's data bank):\n\n",
                      r.nodes);
  o += "| step | APU cycles | share | issued | utilization | bank stalls | bank share | MPU cycles | share |\n";
  o += "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const StepReport& s : r.steps)
    o += format("| %s | %llu | %.1f %% | %llu | %.1f %% | %llu | %.1f %% | %llu | %.1f %% |\n", s.name.c_str(),
             static_cast<unsigned long long>(s.apu_cycles), share(s.apu_cycles, apu),
             static_cast<unsigned long long>(s.apu_issued), share(s.apu_issued, s.apu_cycles),
             static_cast<unsigned long long>(s.apu_bank_stalls), share(s.apu_bank_stalls, s.apu_cycles),
             static_cast<unsigned long long>(s.mpu_cycles), share(s.mpu_cycles, mpu));
  o += "\nPer kernel (dependence: RAW, WAW, CC and drain stalls; ops: per issued word, multiplier / adder / "
       "function unit):\n\n";
  o += "| kernel | runs | batches | APU cycles | share | utilization | bank stalls | dependence stalls | mul | add | func |\n";
  o += "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const KernelReport& k : r.kernels) {
    const double words = static_cast<double>(k.apu_issued ? k.apu_issued : 1);
    o += format("| %s | %llu | %llu | %llu | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.2f | %.2f | %.2f |\n",
             k.name.c_str(), static_cast<unsigned long long>(k.apu_runs), static_cast<unsigned long long>(k.batches),
             static_cast<unsigned long long>(k.apu_cycles), share(k.apu_cycles, apu), share(k.apu_issued, k.apu_cycles),
             share(k.apu_bank_stalls, k.apu_cycles), share(k.apu_dependence_stalls, k.apu_cycles),
             static_cast<double>(k.unit_ops[0]) / words, static_cast<double>(k.unit_ops[1]) / words,
             static_cast<double>(k.unit_ops[2]) / words);
  }
  return o;
}

}  // namespace mc1
