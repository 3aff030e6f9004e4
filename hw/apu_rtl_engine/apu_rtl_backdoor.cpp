// RtlBackdoor: every use of Verilator's internal names of apu_core.
#include "apu_rtl_backdoor.hpp"

#include <algorithm>
#include <cstring>

#include "Vapu_core.h"
#include "Vapu_core___024root.h"
#include "Vapu_fast.h"
#include "Vapu_fast___024root.h"
#include "Vapu_fast_func.h"
#include "Vapu_fast_func___024root.h"

// Verilator 5.006's nba region of each model (generated, not in a header).
void Vapu_core___024root___eval_nba(Vapu_core___024root* vlSelf);
void Vapu_fast___024root___eval_nba(Vapu_fast___024root* vlSelf);

namespace mc1::apu {

namespace {
constexpr std::uint32_t kMask24 = 0xFFFFFF;

// A model's internal names: the core's signals under the model's root, as
// apu_core__DOT__u_pmem__DOT__bank0 (Vapu_core) or
// apu_fast__DOT__apu_core__DOT__u_pmem__DOT__bank0 (Vapu_fast, the core as
// instance apu_core of hw/apu_rtl_engine/apu_fast.sv).
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

// ---- RtlFastFunc --------------------------------------------------------------

namespace {
// The stand-in's signals, fp24_func's instance u_func in the core.
#define MC1_FAST_FUNC(name) apu_fast__DOT__apu_core__DOT__u_func__DOT__##name
constexpr int kFuncW = 24;
// The edge of an op and those until its result has left the longer pipe.
constexpr int kFuncClocks = 1 + std::max(kFuncLatency, kTrigLatency);
}  // namespace

RtlFastFunc::RtlFastFunc(Vapu_fast& top, VerilatedContext* ctx)
    : top_(top), unit_(std::make_unique<Vapu_fast_func>(ctx)) {
  Vapu_fast_func& u = *unit_;
  u.rst_n = 0;
  u.clk = 0;
  u.eval();
  u.clk = 1;
  u.eval();
  u.clk = 0;
  u.rst_n = 1;
  u.eval();
  outputs_to_stand_in();
}

RtlFastFunc::~RtlFastFunc() { unit_->final(); }

void RtlFastFunc::outputs_to_stand_in() {
  const Vapu_fast_func& u = *unit_;
  auto& r = *top_.rootp;
  r.MC1_FAST_FUNC(next_valid) = u.out_valid;
  r.MC1_FAST_FUNC(next_result) = u.out_result;
  r.MC1_FAST_FUNC(next_flags) = u.out_flags;
  r.MC1_FAST_FUNC(next_trig_valid) = u.out_trig_valid;
  r.MC1_FAST_FUNC(next_trig_result) = u.out_trig_result;
  r.MC1_FAST_FUNC(next_trig_flags) = u.out_trig_flags;
  r.MC1_FAST_FUNC(next_next_result) = u.out_next_result;
  r.MC1_FAST_FUNC(next_trig_next_result) = u.out_trig_next_result;
}

void RtlFastFunc::before_rising_edge() {
  const std::uint32_t issue = top_.rootp->MC1_FAST_FUNC(issue);  // {in_valid, in_op, in_a}
  const bool valid = (issue >> (kFuncW + 2)) & 1;
  if (valid)
    clocks_ = kFuncClocks;
  else if (clocks_ == 0)
    return;
  --clocks_;
  Vapu_fast_func& u = *unit_;
  u.in_valid = valid;
  u.in_op = (issue >> kFuncW) & 3;
  u.in_a = issue & ((std::uint32_t{1} << kFuncW) - 1);
  u.clk = 1;
  u.eval();
  outputs_to_stand_in();
  // The falling edge triggers nothing: clk low without an eval(), as
  // BasicRtlBackdoor::clock_low_unchanged (the next eval() sees the rise).
  u.clk = 0;
  u.rootp->__Vtrigrprev__TOP__clk = 0;
}
#undef MC1_FAST_FUNC

}  // namespace mc1::apu
