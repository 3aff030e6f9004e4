// The APU cycle profile (apu_profile.hpp).
#include "apu_profile.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <vector>

#include "disasm.hpp"
#include "report_text.hpp"

namespace mc1::apu {
namespace {

std::uint8_t unit_mask(const Encoded& e) {
  const MicroWord w = MicroWord::decode(e);
  return static_cast<std::uint8_t>((w.m.en ? 1 : 0) | (w.a.en ? 2 : 0) | (w.f.en ? 4 : 0));
}

using report_text::format;
using report_text::json_escape;

double percent(std::uint64_t part, std::uint64_t whole) { return whole ? 100.0 * part / whole : 0.0; }

}  // namespace

const char* unit_name(int unit) {
  static const char* const kNames[kFpUnits] = {"multiplier", "adder", "function"};
  return unit >= 0 && unit < kFpUnits ? kNames[unit] : "?";
}

std::uint64_t Profile::PcStats::stalled() const {
  std::uint64_t n = 0;
  for (int s = 1; s < kStallKinds; ++s) n += stalls[s];
  return n;
}

void Profile::add(const CycleRecord& r) {
  if (!r.issued && r.stall == Stall::None) return;  // idle, halted, or a faulting word
  ++cycles_;
  const int bank = r.psel & 1;
  const int pc = r.pc % kProgramWords;
  PcStats& p = pcs_[bank][pc];
  if (!r.issued) {
    if (p.stalled() == 0) p.first_stall_cycle = r.cycle;
    ++stalls_[static_cast<int>(r.stall)];
    ++p.stalls[static_cast<int>(r.stall)];
    if (run_.bank != bank || run_.pc != pc || run_.first + run_.cycles != r.cycle) {
      end_run();
      run_ = {bank, pc, r.cycle, 0};
    }
    ++run_.cycles;
    return;
  }
  end_run();
  ++issued_;
  ++p.issued;
  const Encoded e = word_at_ ? word_at_(bank, static_cast<std::uint16_t>(pc)) : Encoded{};
  if (e != seen_[bank][pc]) {
    seen_[bank][pc] = e;
    units_[bank][pc] = unit_mask(e);
  }
  const std::uint8_t m = units_[bank][pc];
  for (int u = 0; u < kFpUnits; ++u) unit_ops_[u] += (m >> u) & 1;
}

void Profile::end_run() {
  if (run_.bank < 0) return;
  PcStats& p = pcs_[run_.bank][run_.pc];
  if (run_.cycles > p.worst_cycles) {
    p.worst_cycles = run_.cycles;
    p.worst_cycle = run_.first;
  }
  run_.bank = -1;
}

std::string Profile::json(const std::string& program) const {
  Profile closed = *this;  // the run under way counts as it stands
  closed.end_run();
  std::string s = format("{\"schema\": \"apu-profile/1\", \"program\": \"%s\", \"cycles\": %llu, \"issued\": %llu",
                         json_escape(program).c_str(), static_cast<unsigned long long>(cycles_),
                         static_cast<unsigned long long>(issued_));
  s += ", \"unit_ops\": {";
  for (int u = 0; u < kFpUnits; ++u)
    s += format("%s\"%s\": %llu", u ? ", " : "", unit_name(u), static_cast<unsigned long long>(unit_ops_[u]));
  auto stalls = [](const std::array<std::uint64_t, kStallKinds>& a) {
    std::string t = "{";
    for (int k = 1; k < kStallKinds; ++k)
      t += format("%s\"%s\": %llu", k > 1 ? ", " : "", stall_name(static_cast<Stall>(k)),
                  static_cast<unsigned long long>(a[k]));
    return t + "}";
  };
  s += "}, \"stalls\": " + stalls(stalls_) + ", \"words\": [";
  bool first = true;
  for (int b = 0; b < 2; ++b)
    for (int pc = 0; pc < kProgramWords; ++pc) {
      const PcStats& p = closed.pcs_[b][pc];
      if (p.issued == 0 && p.stalled() == 0) continue;
      const Encoded e = word_at_ ? word_at_(b, static_cast<std::uint16_t>(pc)) : Encoded{};
      s += format("%s\n  {\"bank\": %d, \"pc\": %d, \"issued\": %llu, \"stalled\": %llu, \"stalls\": ",
                  first ? "" : ",", b, pc, static_cast<unsigned long long>(p.issued),
                  static_cast<unsigned long long>(p.stalled()));
      s += stalls(p.stalls);
      if (p.stalled())
        s += format(", \"first_stall_cycle\": %llu, \"worst_stall\": {\"cycle\": %llu, \"cycles\": %llu}",
                    static_cast<unsigned long long>(p.first_stall_cycle), static_cast<unsigned long long>(p.worst_cycle),
                    static_cast<unsigned long long>(p.worst_cycles));
      s += ", \"word\": \"" + json_escape(disassemble(e)) + "\"}";
      first = false;
    }
  return s + "\n]}\n";
}

double Profile::utilization(int unit) const {
  return cycles_ ? static_cast<double>(unit_ops_[unit]) / static_cast<double>(cycles_) : 0.0;
}

double Profile::mflops() const {
  const std::uint64_t ops = unit_ops_[0] + unit_ops_[1] + unit_ops_[2];
  return cycles_ ? static_cast<double>(ops) / static_cast<double>(cycles_) * kApuClockHz / 1e6 : 0.0;
}

std::string Profile::report(int top_n) const {
  std::string s;
  s += format("APU profile: %llu cycles (%.3f ms at 4 MHz), %llu words issued (%.1f%%)\n",
              static_cast<unsigned long long>(cycles_), cycles_ / kApuClockHz * 1e3,
              static_cast<unsigned long long>(issued_), percent(issued_, cycles_));
  s += "unit          ops        util    MFLOPS\n";
  std::uint64_t ops = 0;
  for (int u = 0; u < kFpUnits; ++u) {
    ops += unit_ops_[u];
    s += format("%-12s %-10llu %5.1f%%  %6.2f\n", unit_name(u), static_cast<unsigned long long>(unit_ops_[u]),
                100.0 * utilization(u), utilization(u) * kApuClockHz / 1e6);
  }
  s += format("%-12s %-10llu %5.1f%%  %6.2f of %.0f peak\n", "all", static_cast<unsigned long long>(ops),
              cycles_ ? 100.0 * ops / (3.0 * cycles_) : 0.0, mflops(), kFpUnits * kApuClockHz / 1e6);
  std::uint64_t stalled = 0;
  for (int k = 1; k < kStallKinds; ++k) stalled += stalls_[k];
  s += format("stall         cycles     share\n");
  for (int k = 1; k < kStallKinds; ++k)
    s += format("%-12s %-10llu %5.1f%%\n", stall_name(static_cast<Stall>(k)),
                static_cast<unsigned long long>(stalls_[k]), percent(stalls_[k], cycles_));
  s += format("%-12s %-10llu %5.1f%%\n", "all", static_cast<unsigned long long>(stalled), percent(stalled, cycles_));

  struct Hot { int bank, pc; std::uint64_t n; };
  std::vector<Hot> hot;
  for (int b = 0; b < 2; ++b)
    for (int pc = 0; pc < kProgramWords; ++pc)
      if (const std::uint64_t n = pcs_[b][pc].stalled()) hot.push_back({b, pc, n});
  std::stable_sort(hot.begin(), hot.end(), [](const Hot& x, const Hot& y) { return x.n > y.n; });
  if (static_cast<int>(hot.size()) > top_n) hot.resize(static_cast<std::size_t>(top_n));
  if (!hot.empty()) {
    s += "top stalling words\n";
    s += "bank pc     stalled  share   issued";
    for (int k = 1; k < kStallKinds; ++k) s += format(" %6s", stall_name(static_cast<Stall>(k)));
    s += "  word\n";
    for (const Hot& h : hot) {
      const PcStats& p = pcs_[h.bank][h.pc];
      s += format("%-4d 0x%03x %-8llu %5.1f%% %-8llu", h.bank, h.pc, static_cast<unsigned long long>(h.n),
                  percent(h.n, stalled), static_cast<unsigned long long>(p.issued));
      for (int k = 1; k < kStallKinds; ++k) s += format(" %6llu", static_cast<unsigned long long>(p.stalls[k]));
      const Encoded e = word_at_ ? word_at_(h.bank, static_cast<std::uint16_t>(h.pc)) : Encoded{};
      s += "  " + disassemble(e) + "\n";
    }
  }
  return s;
}

}  // namespace mc1::apu
