// The stall profile of many kernel runs (apu_stall_profile.hpp).
#include "apu_stall_profile.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>

#include "disasm.hpp"
#include "report_text.hpp"

namespace mc1::apu {
namespace {

using report_text::format;
using report_text::json_escape;

using ull = unsigned long long;

std::string stalls_json(const std::array<std::uint64_t, kStallKinds>& a) {
  std::string t = "{";
  for (int k = 1; k < kStallKinds; ++k)
    t += format("%s\"%s\": %llu", k > 1 ? ", " : "", stall_name(static_cast<Stall>(k)), static_cast<ull>(a[k]));
  return t + "}";
}

std::string counts_json(const StallProfile::Counts& c) {
  return format("\"cycles\": %llu, \"issued\": %llu, \"faulted\": %llu, \"stalled\": %llu, \"stalls\": ",
                static_cast<ull>(c.cycles), static_cast<ull>(c.issued), static_cast<ull>(c.faulted),
                static_cast<ull>(c.stalled())) +
         stalls_json(c.stalls);
}

std::string us(std::uint64_t ps) { return format("%.3f us", static_cast<double>(ps) * 1e-6); }

void note_stall(StallProfile::Event& first, unsigned nc, std::uint64_t time_ps) {
  if (first.seen && first.time_ps <= time_ps) return;
  first = {true, time_ps, 0, nc};
}

void note_worst(StallProfile::Event& worst, const StallProfile::Event& run) {
  if (!run.seen) return;
  if (!worst.seen || run.cycles > worst.cycles || (run.cycles == worst.cycles && run.time_ps < worst.time_ps))
    worst = run;
}

}  // namespace

std::string json_quote(const std::string& text) { return "\"" + json_escape(text) + "\""; }

// ---- kernels ----------------------------------------------------------------

unsigned KernelTable::add(const std::string& name, const std::vector<Encoded>& words) {
  kernels_.push_back({name, words, false});
  return static_cast<unsigned>(kernels_.size());
}

unsigned KernelTable::identify(const std::vector<Encoded>& bank) {
  unsigned best = 0;
  std::size_t best_len = 0;
  for (std::size_t i = 0; i < kernels_.size(); ++i) {
    const std::vector<Encoded>& w = kernels_[i].words;
    if (w.size() > bank.size() || (best && w.size() <= best_len)) continue;
    if (std::equal(w.begin(), w.end(), bank.begin()) && kernels_[i].name.rfind("unnamed-", 0) != 0) {
      best = static_cast<unsigned>(i + 1);
      best_len = w.size();
    }
  }
  if (best) {
    kernels_[best - 1].seen = true;
    return best;
  }
  std::size_t n = bank.size();
  while (n > 0 && bank[n - 1] == Encoded{}) --n;
  const std::vector<Encoded> content(bank.begin(), bank.begin() + static_cast<std::ptrdiff_t>(n));
  for (std::size_t i = 0; i < kernels_.size(); ++i)
    if (kernels_[i].name.rfind("unnamed-", 0) == 0 && kernels_[i].words == content)
      return static_cast<unsigned>(i + 1);
  const unsigned id = add("unnamed-" + std::to_string(++unnamed_), content);
  kernels_[id - 1].seen = true;
  return id;
}

std::string KernelTable::id_filter() const {
  std::string s = "# kernel id -> kernel name (GTKWave translate filter for TOP.mc1.kernel_id)\n0000 -\n";
  for (std::size_t i = 0; i < kernels_.size(); ++i) s += format("%04X %s\n", static_cast<unsigned>(i + 1), kernels_[i].name.c_str());
  return s;
}

std::string KernelTable::kpc_filter() const {
  std::string s = "# (kernel id, pc) -> the kernel's word there (GTKWave translate filter for TOP.mc1.kpc[27:0])\n";
  const bool any_seen = std::any_of(kernels_.begin(), kernels_.end(), [](const Kernel& k) { return k.seen; });
  for (std::size_t i = 0; i < kernels_.size(); ++i) {
    const Kernel& k = kernels_[i];
    if (!k.seen && any_seen) continue;
    for (std::size_t pc = 0; pc < k.words.size(); ++pc)
      s += format("%04X%03X ", static_cast<unsigned>(i + 1), static_cast<unsigned>(pc)) + disassemble(k.words[pc]) + "\n";
  }
  return s;
}

// ---- collection -------------------------------------------------------------

std::uint64_t StallProfile::Counts::stalled() const {
  std::uint64_t n = 0;
  for (int k = 1; k < kStallKinds; ++k) n += stalls[k];
  return n;
}

void StallProfile::Counts::operator+=(const Counts& o) {
  cycles += o.cycles;
  issued += o.issued;
  faulted += o.faulted;
  for (int k = 0; k < kStallKinds; ++k) stalls[k] += o.stalls[k];
}

void StallProfile::NcState::add(unsigned kernel, const CycleRecord& r, std::uint64_t time_ps, unsigned mpu) {
  ++counts.cycles;
  if (kernel >= kernels.size()) kernels.resize(kernel + 1);
  std::vector<NcSite>& k = kernels[kernel];
  const std::size_t pc = r.pc % kProgramWords;
  if (pc >= k.size()) k.resize(pc + 1);
  NcSite& site = k[pc];
  ++site.counts.cycles;
  if (r.issued) {
    ++counts.issued;
    ++site.counts.issued;
    end_run();
    return;
  }
  if (r.stall == Stall::None) {  // a faulting word (a start's cycles are `fetch` stalls)
    ++counts.faulted;
    ++site.counts.faulted;
    end_run();
    return;
  }
  ++counts.stalls[static_cast<int>(r.stall)];
  ++site.counts.stalls[static_cast<int>(r.stall)];
  note_stall(site.first, nc, time_ps);
  const bool in_window = !window.on || (time_ps >= window.from && time_ps < window.to);
  if (in_window) ++site.window_stalled;
  if (r.stall == Stall::Bank && mpu != kNoMpu) {
    ++site.bank_mpu[mpu];
    if (in_window) ++site.window_bank_mpu[mpu];
  }
  if (!run.on || run.kernel != kernel || run.pc != pc || run.next_cycle != r.cycle) {
    end_run();
    run = Run{true, kernel, pc, time_ps, 0, 0};
  }
  ++run.cycles;
  run.next_cycle = r.cycle + 1;
}

void StallProfile::NcState::end_run() {
  if (!run.on) return;
  NcSite& site = kernels[run.kernel][run.pc];
  const Event e{true, run.time_ps, run.cycles, nc};
  note_worst(site.worst, e);
  if (!window.on || (run.time_ps >= window.from && run.time_ps < window.to)) note_worst(site.window_worst, e);
  run = Run{};
}

void StallProfile::finish() {
  for (auto& s : ncs_)
    if (s) s->end_run();
}

// ---- sums -------------------------------------------------------------------

StallProfile::Counts StallProfile::totals() const {
  Counts c;
  for (const auto& s : ncs_)
    if (s) c += s->counts;
  return c;
}

StallProfile::Counts StallProfile::nc_totals(unsigned nc) const {
  return nc < ncs_.size() && ncs_[nc] ? ncs_[nc]->counts : Counts{};
}

std::vector<std::vector<StallProfile::Site>> StallProfile::sites() const {
  std::vector<std::vector<Site>> out;
  for (const auto& s : ncs_) {
    if (!s) continue;
    if (s->kernels.size() > out.size()) out.resize(s->kernels.size());
    for (std::size_t k = 0; k < s->kernels.size(); ++k) {
      const std::vector<NcSite>& v = s->kernels[k];
      if (v.size() > out[k].size()) out[k].resize(v.size());
      for (std::size_t pc = 0; pc < v.size(); ++pc) {
        Site& t = out[k][pc];
        t.counts += v[pc].counts;
        if (v[pc].first.seen) note_stall(t.first, s->nc, v[pc].first.time_ps);
        for (const auto& [mpu, n] : v[pc].bank_mpu) t.bank_mpu[mpu] += n;
        note_worst(t.worst, v[pc].worst);
      }
    }
  }
  return out;
}

// ---- reports ----------------------------------------------------------------

namespace {

std::string kernel_name(const KernelTable& kernels, std::size_t id) {
  return id && id <= kernels.size() ? kernels.name(static_cast<unsigned>(id)) : std::string("-");
}

std::string word_text(const KernelTable& kernels, std::size_t id, std::size_t pc) {
  if (!id || id > kernels.size()) return "";
  const std::vector<Encoded>& w = kernels.words(static_cast<unsigned>(id));
  return pc < w.size() ? disassemble(w[pc]) : disassemble(Encoded{});
}

// The reason with the most stall cycles.
Stall most_stalls(const StallProfile::Counts& c) {
  int most = 1;
  for (int k = 2; k < kStallKinds; ++k)
    if (c.stalls[k] > c.stalls[most]) most = k;
  return static_cast<Stall>(most);
}

// Shares by count, the largest first.
std::vector<std::pair<unsigned, std::uint64_t>> by_share(const StallProfile::MpuShares& shares) {
  std::vector<std::pair<unsigned, std::uint64_t>> v(shares.begin(), shares.end());
  std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  return v;
}

}  // namespace

std::string StallProfile::mpu_text(const MpuShares& shares, int n) const {
  std::uint64_t total = 0;
  for (const auto& [mpu, c] : shares) total += c;
  if (total == 0) return "";
  std::string s;
  std::uint64_t rest = total;
  int shown = 0;
  for (const auto& [mpu, c] : by_share(shares)) {
    if (shown == n) break;
    const std::string name = mpu_name_ ? mpu_name_(mpu) : "mpu " + std::to_string(mpu);
    s += format("%s%s %.0f%%", shown ? ", " : "", name.c_str(), 100.0 * static_cast<double>(c) / static_cast<double>(total));
    rest -= c;
    ++shown;
  }
  if (rest) s += format(", other %.0f%%", 100.0 * static_cast<double>(rest) / static_cast<double>(total));
  return s;
}

std::string StallProfile::json(const KernelTable& kernels, const std::string& source, const std::string& extra) const {
  const std::vector<std::vector<Site>> all = sites();
  std::string s = "{\"schema\": \"apu-profile/2\", \"source\": \"" + json_escape(source) + "\"" + extra;
  s += ",\n \"totals\": {" + counts_json(totals()) + "},\n \"ncs\": [";
  bool first = true;
  for (const auto& n : ncs_) {
    if (!n) continue;
    s += format("%s\n  {\"nc\": %u, ", first ? "" : ",", n->nc) + counts_json(n->counts) + "}";
    first = false;
  }
  s += "],\n \"kernels\": [";
  bool first_kernel = true;
  for (std::size_t k = 0; k < all.size(); ++k) {
    Counts kc;
    for (const Site& site : all[k]) kc += site.counts;
    if (kc.cycles == 0) continue;
    const std::size_t words = k && k <= kernels.size() ? kernels.words(static_cast<unsigned>(k)).size() : 0;
    s += format("%s\n  {\"id\": %u, \"name\": \"%s\", \"words\": %zu, ", first_kernel ? "" : ",",
                static_cast<unsigned>(k), json_escape(kernel_name(kernels, k)).c_str(), words) +
         counts_json(kc) + ", \"sites\": [";
    first_kernel = false;
    bool first_site = true;
    for (std::size_t pc = 0; pc < all[k].size(); ++pc) {
      const Site& site = all[k][pc];
      if (site.counts.cycles == 0) continue;
      s += format("%s\n   {\"pc\": %zu, \"word\": \"%s\", ", first_site ? "" : ",", pc,
                  json_escape(word_text(kernels, k, pc)).c_str()) +
           counts_json(site.counts);
      first_site = false;
      if (!site.bank_mpu.empty()) {  // its BANK stalls by MPU activity, the largest first
        s += ", \"bank_mpu\": [";
        bool first_mpu = true;
        for (const auto& [mpu, c] : by_share(site.bank_mpu)) {
          const std::string name = mpu_name_ ? mpu_name_(mpu) : "mpu " + std::to_string(mpu);
          s += format("%s{\"activity\": %s, \"cycles\": %llu}", first_mpu ? "" : ", ", json_quote(name).c_str(),
                      static_cast<ull>(c));
          first_mpu = false;
        }
        s += "]";
      }
      if (site.first.seen)
        s += format(", \"first\": {\"time_ps\": %llu, \"nc\": %u}, \"worst\": {\"time_ps\": %llu, \"nc\": %u, \"cycles\": %llu}",
                    static_cast<ull>(site.first.time_ps), site.first.nc, static_cast<ull>(site.worst.time_ps),
                    site.worst.nc, static_cast<ull>(site.worst.cycles));
      s += ", \"by_nc\": [";
      bool first_nc = true;
      for (const auto& n : ncs_) {
        if (!n || k >= n->kernels.size() || pc >= n->kernels[k].size()) continue;
        const NcSite& ns = n->kernels[k][pc];
        if (ns.counts.cycles == 0) continue;
        s += format("%s{\"nc\": %u, ", first_nc ? "" : ", ", n->nc) + counts_json(ns.counts);
        if (ns.first.seen)
          s += format(", \"first_ps\": %llu, \"worst\": {\"time_ps\": %llu, \"cycles\": %llu}",
                      static_cast<ull>(ns.first.time_ps), static_cast<ull>(ns.worst.time_ps),
                      static_cast<ull>(ns.worst.cycles));
        s += "}";
        first_nc = false;
      }
      s += "]}";
    }
    s += "]}";
  }
  return s + "]}\n";
}

std::string StallProfile::text(const KernelTable& kernels, int top_n) const {
  const Counts t = totals();
  const std::vector<std::vector<Site>> all = sites();
  auto pct = [](std::uint64_t a, std::uint64_t b) { return b ? 100.0 * static_cast<double>(a) / static_cast<double>(b) : 0.0; };
  std::string s = format("stall profile: %llu APU cycles on %zu NCs, %llu issued (%.1f%%), %llu stalled (%.1f%%), "
                         "%llu faulted\n",
                         static_cast<ull>(t.cycles), static_cast<std::size_t>(std::count_if(ncs_.begin(), ncs_.end(), [](const auto& n) { return n != nullptr; })),
                         static_cast<ull>(t.issued), pct(t.issued, t.cycles), static_cast<ull>(t.stalled()),
                         pct(t.stalled(), t.cycles), static_cast<ull>(t.faulted));
  s += format("%-12s %11s %11s %11s", "kernel", "cycles", "issued", "stalled");
  for (int k = 1; k < kStallKinds; ++k) s += format(" %9s", stall_name(static_cast<Stall>(k)));
  s += "\n";
  struct Hot { std::size_t kernel, pc; std::uint64_t n; };
  std::vector<Hot> hot;
  for (std::size_t k = 0; k < all.size(); ++k) {
    Counts kc;
    for (std::size_t pc = 0; pc < all[k].size(); ++pc) {
      kc += all[k][pc].counts;
      if (all[k][pc].counts.stalled()) hot.push_back({k, pc, all[k][pc].counts.stalled()});
    }
    if (kc.cycles == 0) continue;
    s += format("%-12s %11llu %11llu %11llu", kernel_name(kernels, k).c_str(), static_cast<ull>(kc.cycles),
                static_cast<ull>(kc.issued), static_cast<ull>(kc.stalled()));
    for (int j = 1; j < kStallKinds; ++j) s += format(" %9llu", static_cast<ull>(kc.stalls[j]));
    s += "\n";
  }
  std::stable_sort(hot.begin(), hot.end(), [](const Hot& a, const Hot& b) { return a.n > b.n; });
  if (static_cast<int>(hot.size()) > top_n) hot.resize(static_cast<std::size_t>(top_n));
  if (hot.empty()) return s;
  s += format("top %zu stall sites (summed over NCs; first and worst: simulated time, NC)\n", hot.size());
  s += format("%-12s %-5s %9s %6s %-6s %-22s %-30s  %s\n", "kernel", "pc", "stalled", "share", "most", "first",
              "worst (cycles in a row)", "word");
  for (const Hot& h : hot) {
    const Site& site = all[h.kernel][h.pc];
    const int most = static_cast<int>(most_stalls(site.counts));
    s += format("%-12s 0x%03zx %9llu %5.1f%% %-6s %-22s %-30s  %s\n", kernel_name(kernels, h.kernel).c_str(), h.pc,
                static_cast<ull>(h.n), pct(h.n, t.stalled()), stall_name(static_cast<Stall>(most)),
                (us(site.first.time_ps) + " NC " + std::to_string(site.first.nc)).c_str(),
                (us(site.worst.time_ps) + " NC " + std::to_string(site.worst.nc) + " x" +
                 std::to_string(site.worst.cycles)).c_str(),
                word_text(kernels, h.kernel, h.pc).c_str());
    if (!site.bank_mpu.empty())
      s += format("%-12s   the MPU in its %llu BANK stall cycles: ", "",
                  static_cast<ull>(site.counts.stalls[static_cast<int>(Stall::Bank)])) +
           mpu_text(site.bank_mpu) + "\n";
  }
  return s;
}

std::string StallProfile::gtkw_markers(const KernelTable& kernels, unsigned nc, int top_n) const {
  top_n = std::min(top_n, 26);
  struct Hot { std::size_t kernel, pc; std::uint64_t n; Event worst; const NcSite* site; };
  std::vector<Hot> hot;
  if (nc < ncs_.size() && ncs_[nc])
    for (std::size_t k = 0; k < ncs_[nc]->kernels.size(); ++k)
      for (std::size_t pc = 0; pc < ncs_[nc]->kernels[k].size(); ++pc) {
        const NcSite& site = ncs_[nc]->kernels[k][pc];
        if (site.window_stalled && site.window_worst.seen)
          hot.push_back({k, pc, site.window_stalled, site.window_worst, &site});
      }
  std::stable_sort(hot.begin(), hot.end(), [](const Hot& a, const Hot& b) { return a.n > b.n; });
  if (static_cast<int>(hot.size()) > top_n) hot.resize(static_cast<std::size_t>(top_n));
  std::string s = format("[*] Markers A.. : the top %zu stall sites of NC %u in the trace, each at the start of its worst run there\n",
                         hot.size(), nc);
  // Zoom -19: one 250 ns cycle is about 100 pixels, wide enough for a word's disassembly (TOP.mc1.kpc).
  std::string line = "*-19.000000 " + (hot.empty() ? std::string("-1") : std::to_string(hot[0].worst.time_ps));
  std::string names;  // [markername] lines: the viewer shows them at the markers
  for (int i = 0; i < 26; ++i) {
    if (i < static_cast<int>(hot.size())) {
      const Hot& h = hot[static_cast<std::size_t>(i)];
      const std::string mpu = mpu_text(h.site->window_bank_mpu, 3);
      s += format("[*] %c %llu ps (%s): %s pc 0x%03zx, %llu stalled cycles, %llu in a row: %s\n", 'A' + i,
                  static_cast<ull>(h.worst.time_ps), us(h.worst.time_ps).c_str(), kernel_name(kernels, h.kernel).c_str(),
                  h.pc, static_cast<ull>(h.n), static_cast<ull>(h.worst.cycles),
                  word_text(kernels, h.kernel, h.pc).c_str());
      if (!mpu.empty()) s += "[*]   the MPU in its BANK stalls there: " + mpu + "\n";
      std::string word = word_text(kernels, h.kernel, h.pc);
      word = word.substr(0, word.find(' ', word.find_first_not_of(' ')));  // the first op
      names += format("[markername] %c%s 0x%03zx %s %s", 'A' + i, kernel_name(kernels, h.kernel).c_str(), h.pc,
                      word.c_str(), stall_name(most_stalls(h.site->counts))) +
               (mpu.empty() ? "" : ": MPU " + mpu) + "\n";
      line += " " + std::to_string(h.worst.time_ps);
    } else {
      line += " -1";
    }
  }
  return s + line + "\n" + names;
}

}  // namespace mc1::apu
