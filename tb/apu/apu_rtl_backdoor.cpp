// RtlBackdoor: every use of Verilator's internal names of apu_core.
#include "apu_rtl_backdoor.hpp"

#include <algorithm>
#include <cstring>

#include "Vapu_core.h"
#include "Vapu_core___024root.h"
#include "Vapu_fast.h"
#include "Vapu_fast___024root.h"

// Verilator 5.006's nba region of each model (generated, not in a header).
void Vapu_core___024root___eval_nba(Vapu_core___024root* vlSelf);
void Vapu_fast___024root___eval_nba(Vapu_fast___024root* vlSelf);

namespace mc1::apu {

namespace {
constexpr std::uint32_t kMask24 = 0xFFFFFF;

// A model's internal names: the core's signals under the model's root, as
// apu_core__DOT__u_pmem__DOT__bank0 (Vapu_core) or
// apu_fast__DOT__apu_core__DOT__u_pmem__DOT__bank0 (Vapu_fast, the core as
// instance apu_core of tb/apu/apu_fast.sv).
template <class Top>
struct Names;

#define MC1_RTL_NAMES(TOP, CORE)                                                    \
  template <>                                                                        \
  struct Names<TOP> {                                                                \
    using Root = TOP##___024root;                                                    \
    static void eval_nba(Root* r) { TOP##___024root___eval_nba(r); }                 \
    static auto& pmem(Root& r, int b) { return b ? r.CORE##u_pmem__DOT__bank1 : r.CORE##u_pmem__DOT__bank0; } \
    static auto& dmem(Root& r, int b) { return b ? r.CORE##u_dmem__DOT__bank1 : r.CORE##u_dmem__DOT__bank0; } \
    static auto& fregs(Root& r) { return r.CORE##u_fregs__DOT__regs; }               \
    static auto& aregs(Root& r) { return r.CORE##u_aregs__DOT__regs; }               \
  };
MC1_RTL_NAMES(Vapu_core, apu_core__DOT__)
MC1_RTL_NAMES(Vapu_fast, apu_fast__DOT__apu_core__DOT__)
#undef MC1_RTL_NAMES

}  // namespace

template <class Top>
BasicRtlBackdoor<Top>::BasicRtlBackdoor(Top& top) : top_(top) {
  // The root object minus the bank memories, as (start, length) pieces.
  using N = Names<Top>;
  auto& root = *top_.rootp;
  const auto* base = reinterpret_cast<const unsigned char*>(&root);
  const auto range = [](const auto& a) {
    const auto* p = reinterpret_cast<const unsigned char*>(&a);
    return std::pair<const unsigned char*, const unsigned char*>(p, p + sizeof a);
  };
  std::vector<std::pair<const unsigned char*, const unsigned char*>> banks = {
      range(N::pmem(root, 0)), range(N::pmem(root, 1)), range(N::dmem(root, 0)), range(N::dmem(root, 1))};
  std::sort(banks.begin(), banks.end());
  const unsigned char* at = base;
  for (const auto& b : banks) {
    if (b.first > at) state_.emplace_back(at, static_cast<std::size_t>(b.first - at));
    at = std::max(at, b.second);
  }
  const unsigned char* end = base + sizeof root;
  if (end > at) state_.emplace_back(at, static_cast<std::size_t>(end - at));
}

template <class Top>
void BasicRtlBackdoor<Top>::rising_edge_unchanged() {
  auto& root = *top_.rootp;
  top_.clk = 1;
  root.__Vtrigrprev__TOP__clk = 1;
  root.__VnbaTriggered.at(0) = 1;  // the posedge-clk trigger, apu_core's only one
  Names<Top>::eval_nba(&root);
}

template <class Top>
void BasicRtlBackdoor<Top>::clock_low_unchanged() {
  top_.clk = 0;
  top_.rootp->__Vtrigrprev__TOP__clk = 0;
}

template <class Top>
void BasicRtlBackdoor<Top>::snapshot(Snapshot& s) const {
  s.clear();
  for (const auto& r : state_) s.insert(s.end(), r.first, r.first + r.second);
}

template <class Top>
bool BasicRtlBackdoor<Top>::same_state(const Snapshot& s) const {
  const unsigned char* p = s.data();
  for (const auto& r : state_) {
    if (std::memcmp(p, r.first, r.second) != 0) return false;
    p += r.second;
  }
  return true;
}

template <class Top>
const char* BasicRtlBackdoor<Top>::signal_name(Signal s) {
  switch (s) {
    case Signal::ProgramBank0: return "apu_core.u_pmem.bank0";
    case Signal::ProgramBank1: return "apu_core.u_pmem.bank1";
    case Signal::DataBank0: return "apu_core.u_dmem.bank0";
    case Signal::DataBank1: return "apu_core.u_dmem.bank1";
    case Signal::FRegs: return "apu_core.u_fregs.regs";
    case Signal::ARegs: return "apu_core.u_aregs.regs";
  }
  return "?";
}

template <class Top>
void BasicRtlBackdoor<Top>::write_program(int bank, std::uint16_t addr, const Encoded& word) {
  auto& dst = Names<Top>::pmem(*top_.rootp, bank & 1)[addr % kProgramWords];
  dst[0] = static_cast<std::uint32_t>(word.lo);
  dst[1] = static_cast<std::uint32_t>(word.lo >> 32);
  dst[2] = static_cast<std::uint32_t>(word.hi);
  dst[3] = static_cast<std::uint32_t>(word.hi >> 32);
}

template <class Top>
Encoded BasicRtlBackdoor<Top>::read_program(int bank, std::uint16_t addr) const {
  const auto& src = Names<Top>::pmem(*top_.rootp, bank & 1)[addr % kProgramWords];
  Encoded e;
  e.lo = src[0] | std::uint64_t{src[1]} << 32;
  e.hi = src[2] | std::uint64_t{src[3]} << 32;
  return e;
}

template <class Top>
void BasicRtlBackdoor<Top>::write_data(int bank, std::uint16_t addr, std::uint32_t value) {
  Names<Top>::dmem(*top_.rootp, bank & 1)[addr % kDataWords] = value & kMask24;
}

template <class Top>
std::uint32_t BasicRtlBackdoor<Top>::read_data(int bank, std::uint16_t addr) const {
  return Names<Top>::dmem(*top_.rootp, bank & 1)[addr % kDataWords];
}

template <class Top>
std::uint32_t BasicRtlBackdoor<Top>::freg_array(int i) const {
  return Names<Top>::fregs(*top_.rootp)[i & (kNumFRegs - 1)];
}

template <class Top>
std::uint16_t BasicRtlBackdoor<Top>::areg_array(int i) const {
  return Names<Top>::aregs(*top_.rootp)[i & (kNumARegs - 1)];
}

template class BasicRtlBackdoor<Vapu_core>;
template class BasicRtlBackdoor<Vapu_fast>;

}  // namespace mc1::apu
