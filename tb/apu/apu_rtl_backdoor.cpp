// RtlBackdoor: every use of Verilator's internal names of apu_core.
#include "apu_rtl_backdoor.hpp"

#include <algorithm>
#include <cstring>

#include "Vapu_core.h"
#include "Vapu_core___024root.h"

// Verilator 5.006's nba region of the model (generated, not in a header).
void Vapu_core___024root___eval_nba(Vapu_core___024root* vlSelf);

namespace mc1::apu {

namespace {
constexpr std::uint32_t kMask24 = 0xFFFFFF;
}  // namespace

RtlBackdoor::RtlBackdoor(Vapu_core& top) : top_(top) {
  // The root object minus the bank memories, as (start, length) pieces.
  const auto& root = *top_.rootp;
  const auto* base = reinterpret_cast<const unsigned char*>(&root);
  const auto range = [](const auto& a) {
    const auto* p = reinterpret_cast<const unsigned char*>(&a);
    return std::pair<const unsigned char*, const unsigned char*>(p, p + sizeof a);
  };
  std::vector<std::pair<const unsigned char*, const unsigned char*>> banks = {
      range(root.apu_core__DOT__u_pmem__DOT__bank0), range(root.apu_core__DOT__u_pmem__DOT__bank1),
      range(root.apu_core__DOT__u_dmem__DOT__bank0), range(root.apu_core__DOT__u_dmem__DOT__bank1)};
  std::sort(banks.begin(), banks.end());
  const unsigned char* at = base;
  for (const auto& b : banks) {
    if (b.first > at) state_.emplace_back(at, static_cast<std::size_t>(b.first - at));
    at = std::max(at, b.second);
  }
  const unsigned char* end = base + sizeof root;
  if (end > at) state_.emplace_back(at, static_cast<std::size_t>(end - at));
}

void RtlBackdoor::rising_edge_unchanged() {
  auto& root = *top_.rootp;
  top_.clk = 1;
  root.__Vtrigrprev__TOP__clk = 1;
  root.__VnbaTriggered.at(0) = 1;  // the posedge-clk trigger, apu_core's only one
  Vapu_core___024root___eval_nba(&root);
}

void RtlBackdoor::clock_low_unchanged() {
  top_.clk = 0;
  top_.rootp->__Vtrigrprev__TOP__clk = 0;
}

void RtlBackdoor::snapshot(Snapshot& s) const {
  s.clear();
  for (const auto& r : state_) s.insert(s.end(), r.first, r.first + r.second);
}

bool RtlBackdoor::same_state(const Snapshot& s) const {
  const unsigned char* p = s.data();
  for (const auto& r : state_) {
    if (std::memcmp(p, r.first, r.second) != 0) return false;
    p += r.second;
  }
  return true;
}

const char* RtlBackdoor::signal_name(Signal s) {
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

void RtlBackdoor::write_program(int bank, std::uint16_t addr, const Encoded& word) {
  auto& root = *top_.rootp;
  auto& words = bank & 1 ? root.apu_core__DOT__u_pmem__DOT__bank1 : root.apu_core__DOT__u_pmem__DOT__bank0;
  auto& dst = words[addr % kProgramWords];
  dst[0] = static_cast<std::uint32_t>(word.lo);
  dst[1] = static_cast<std::uint32_t>(word.lo >> 32);
  dst[2] = static_cast<std::uint32_t>(word.hi);
  dst[3] = static_cast<std::uint32_t>(word.hi >> 32);
}

Encoded RtlBackdoor::read_program(int bank, std::uint16_t addr) const {
  const auto& root = *top_.rootp;
  const auto& words = bank & 1 ? root.apu_core__DOT__u_pmem__DOT__bank1 : root.apu_core__DOT__u_pmem__DOT__bank0;
  const auto& src = words[addr % kProgramWords];
  Encoded e;
  e.lo = src[0] | std::uint64_t{src[1]} << 32;
  e.hi = src[2] | std::uint64_t{src[3]} << 32;
  return e;
}

void RtlBackdoor::write_data(int bank, std::uint16_t addr, std::uint32_t value) {
  auto& root = *top_.rootp;
  auto& words = bank & 1 ? root.apu_core__DOT__u_dmem__DOT__bank1 : root.apu_core__DOT__u_dmem__DOT__bank0;
  words[addr % kDataWords] = value & kMask24;
}

std::uint32_t RtlBackdoor::read_data(int bank, std::uint16_t addr) const {
  const auto& root = *top_.rootp;
  const auto& words = bank & 1 ? root.apu_core__DOT__u_dmem__DOT__bank1 : root.apu_core__DOT__u_dmem__DOT__bank0;
  return words[addr % kDataWords];
}

std::uint32_t RtlBackdoor::freg_array(int i) const {
  return top_.rootp->apu_core__DOT__u_fregs__DOT__regs[i & (kNumFRegs - 1)];
}

std::uint16_t RtlBackdoor::areg_array(int i) const {
  return top_.rootp->apu_core__DOT__u_aregs__DOT__regs[i & (kNumARegs - 1)];
}

}  // namespace mc1::apu
