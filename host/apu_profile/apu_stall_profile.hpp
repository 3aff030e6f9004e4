// The stall profile of many kernel runs on many NCs (mc1 render --profile
// FILE.json, apu-run --profile-json): per kernel and word (pc), summed over
// NCs and per NC, the words issued, the stall cycles by reason, the first
// stalled cycle and the worst one (the longest run of stalled cycles in a
// row at that word), each stamped with simulated time and NC; the text
// report, the JSON of schema "apu-profile/2" and a GTKWave marker list of
// the top stall sites of one NC (docs/apu-tools.md "The stall profile").
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "apu_engine.hpp"
#include "microword.hpp"

namespace mc1::apu {

// The kernels a machine ran, by id (1.. in order of first sight; 0 none):
// the named images it was given, and bank contents that match none of them
// (named "unnamed-K").
class KernelTable {
 public:
  unsigned add(const std::string& name, const std::vector<Encoded>& words);
  // The kernel a program bank holds: the longest named image that is a
  // prefix of it; else the bank's content up to its last non-zero word.
  unsigned identify(const std::vector<Encoded>& bank);
  std::size_t size() const { return kernels_.size(); }
  const std::string& name(unsigned id) const { return kernels_.at(id - 1).name; }
  const std::vector<Encoded>& words(unsigned id) const { return kernels_.at(id - 1).words; }
  // GTKWave translate filter: the id (4 hex digits, as GTKWave prints
  // TOP.mc1.kernel_id[15:0]) to the kernel's name.
  std::string id_filter() const;
  // GTKWave translate filter for TOP.mc1.kpc[27:0] (hw/apu_rtl_engine/apu_trace_top.sv):
  // the pair (kernel id, pc) in 7 hex digits, as GTKWave prints it (4 of id,
  // 3 of pc), to the word that kernel holds at pc, disassembled, for every
  // word of every kernel identify() found (all, if none).
  std::string kpc_filter() const;

 private:
  struct Kernel {
    std::string name;
    std::vector<Encoded> words;
    bool seen = false;  // identify() found it
  };
  std::vector<Kernel> kernels_;
  unsigned unnamed_ = 0;
};

// A JSON string: quoted, with quotes, backslashes and control characters escaped.
std::string json_quote(const std::string& text);

class StallProfile {
 public:
  // One clocked cycle of NC `nc` (1..), running kernel `kernel` (0: not
  // known), which starts at simulated time `time_ps`; `mpu` (for a BANK
  // stall) what the MPU did in it, an id set_mpu_names() names (kNoMpu: not
  // known).
  static constexpr unsigned kNoMpu = ~0u;
  void add(unsigned nc, unsigned kernel, const CycleRecord& r, std::uint64_t time_ps, unsigned mpu = kNoMpu) {
    NcState& s = nc_state(nc);
    s.add(kernel, r, time_ps, mpu);
  }
  // The names of the MPU's activities (add()'s `mpu`), for the reports: the
  // time shares by MPU activity of each top bank stall site.
  void set_mpu_names(std::function<std::string(unsigned)> name) { mpu_name_ = std::move(name); }
  // BANK stall cycles by MPU activity (add()'s `mpu`).
  using MpuShares = std::map<unsigned, std::uint64_t>;
  // "copy, s3 shading 71.0%, wait_rc 20.0%, ...": the top `n` shares.
  std::string mpu_text(const MpuShares& shares, int n = 4) const;

  struct Counts {
    std::uint64_t cycles = 0, issued = 0, faulted = 0;  // faulted: running, neither issued nor stalled (a faulting word)
    std::array<std::uint64_t, kStallKinds> stalls{};  // [0] unused
    std::uint64_t stalled() const;
    void operator+=(const Counts& o);
  };
  struct Event {
    bool seen = false;
    std::uint64_t time_ps = 0, cycles = 0;  // cycles: the run's length (worst)
    unsigned nc = 0;
  };
  struct Site {  // one word of one kernel
    Counts counts;
    Event first, worst;
    MpuShares bank_mpu;  // its BANK stalls by MPU activity
  };

  // Makes NC nc's counters before the frame runs (add() then changes no
  // shared state: NCs may run on threads).
  void add_nc(unsigned nc) { nc_state(nc); }
  // Closes the runs of stalled cycles under way (before the reports).
  void finish();

  Counts totals() const;
  Counts nc_totals(unsigned nc) const;
  // Sums over NCs, per kernel id (index id; 0: not known) and pc.
  std::vector<std::vector<Site>> sites() const;

  std::string json(const KernelTable& kernels, const std::string& source, const std::string& extra = "") const;
  std::string text(const KernelTable& kernels, int top_n) const;
  // The traced NC's window (its waveform's [from, to), ps): stalls there are
  // counted apart for the markers.
  void set_window(unsigned nc, std::uint64_t from_ps, std::uint64_t to_ps) {
    nc_state(nc).window = {true, from_ps, to_ps};
  }
  // The top_n (<= 26) stall sites of NC `nc` by stalled cycles in its window
  // (all time without one), each at the start of its worst run there: GTKWave
  // save-file lines, the marker list (markers A..Z) and comments naming them.
  std::string gtkw_markers(const KernelTable& kernels, unsigned nc, int top_n) const;

 private:
  struct NcSite {
    Counts counts;
    Event first, worst;
    std::uint64_t window_stalled = 0;  // stalled cycles in the NC's window
    Event window_worst;
    MpuShares bank_mpu, window_bank_mpu;  // BANK stalls by MPU activity (all, in the window)
  };
  struct NcState {
    unsigned nc = 0;
    Counts counts;
    std::vector<std::vector<NcSite>> kernels;  // [kernel id][pc], grown on use
    struct { bool on = false; std::uint64_t from = 0, to = ~std::uint64_t{0}; } window;
    struct Run {  // the stalled cycles in a row under way (indices: the vectors grow)
      bool on = false;
      unsigned kernel = 0;
      std::size_t pc = 0;
      std::uint64_t time_ps = 0, cycles = 0, next_cycle = 0;
    } run;
    void add(unsigned kernel, const CycleRecord& r, std::uint64_t time_ps, unsigned mpu);
    void end_run();
  };
  NcState& nc_state(unsigned nc) {
    if (nc >= ncs_.size()) ncs_.resize(nc + 1);
    if (!ncs_[nc]) {
      ncs_[nc] = std::make_unique<NcState>();
      ncs_[nc]->nc = nc;
    }
    return *ncs_[nc];
  }
  std::vector<std::unique_ptr<NcState>> ncs_;  // by NC
  std::function<std::string(unsigned)> mpu_name_;
};

}  // namespace mc1::apu
