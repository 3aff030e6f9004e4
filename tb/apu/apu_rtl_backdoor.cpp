// RtlBackdoor: every use of Verilator's internal names of apu_core.
#include "apu_rtl_backdoor.hpp"

#include "Vapu_core.h"
#include "Vapu_core___024root.h"

namespace mc1::apu {

namespace {
constexpr std::uint32_t kMask24 = 0xFFFFFF;
}  // namespace

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
