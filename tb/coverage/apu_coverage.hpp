// Functional coverage of the APU core (docs/fp24-verification.md
// "Coverage"), fed from the ISS of a lockstep run, cycle by cycle (apu-cosim
// --coverage): the ISS and the RTL core agree on every cycle record, so what
// the ISS did is what the RTL core did. Bins:
//   core.op.<slot>.<mnemonic>        every op code of every slot (the reserved
//                                    codes when the word faults on them)
//   core.slots.<MAFDIS>              the slots a word issued with ('-' absent)
//   core.stall.<reason>              every stall reason (docs/apu-isa.md)
//   core.bypass.<from>.<to>          a result read in the cycle it completes:
//                                    F from mul/add/func/trig/ld/movaf-lif into
//                                    m.a/m.b/a.a/a.b/f.a/d.st/i.movfa; A from
//                                    int into d.base/i.src/s.reg; CC into bcc/bncc
//   core.fault.<name>                every fault code
//   core.branch.<op>.<taken|not-taken>  every conditional branch both ways
//   core.handover.<data|program>.<state>  the MPU hands a bank over while the
//                                    APU is idle, running, waiting for it
//                                    (bank stall), halted or faulted
//   core.swap.<data|program>.<ready|waited>  SWAPD/SWAPP found the bank
//                                    handed over, or stalled for it first
// and the FP24 bins (fp24_coverage.hpp) of every op a unit executed.
#pragma once

#include <cstdint>
#include <string>

#include "apu_engine.hpp"
#include "apu_iss.hpp"
#include "coverage_bins.hpp"
#include "fp24_coverage.hpp"
#include "microword.hpp"

namespace mc1::cov {

class ApuCoverage {
 public:
  ApuCoverage();
  Bins& bins() { return bins_; }
  const Bins& bins() const { return bins_; }

  // A new program run on a fresh engine.
  void start();
  // Before each cycle (after the MPU acted): the registers the word issued
  // next reads.
  void before_cycle(const apu::Iss& iss);
  // After it: what the ISS did in that cycle.
  void after_cycle(const apu::Iss& iss, const apu::CycleRecord& rec);
  // The MPU handed a bank over (program or data) while the APU was in
  // `state`; waiting: the last cycle stalled on a bank.
  void handover(bool program, apu::RunState state, bool waiting);
  // The run ended: its state, fault and the last record.
  void end(const apu::Iss& iss, const apu::CycleRecord& last);

 private:
  void declare();
  void issued(const apu::MicroWord& w, const apu::CycleRecord& rec);
  void reads(const apu::MicroWord& w, std::uint64_t t);
  void writes(const apu::MicroWord& w, std::uint64_t t);
  void branch_outcome(const apu::CycleRecord& rec);
  void units(const apu::MicroWord& w);

  Bins bins_;
  Fp24Coverage fp24_{bins_};
  std::uint32_t f_[apu::kNumFRegs] = {};  // the F registers a word issuing next reads
  // The cycle each register's last write becomes visible, and its producer.
  std::uint64_t f_vis_[apu::kNumFRegs] = {}, a_vis_[apu::kNumARegs] = {}, cc_vis_ = 0;
  const char* f_from_[apu::kNumFRegs] = {};
  struct Branch {
    bool pending = false;
    apu::SeqOp op = apu::SeqOp::Next;
    std::uint16_t pc = 0, target = 0;
  } branch_;
  apu::Stall last_stall_ = apu::Stall::None;
  bool waited_ = false;  // the word issuing next stalled on a bank
};

}  // namespace mc1::cov
