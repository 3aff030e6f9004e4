// Verilated-RTL harness for the FP24 units (apu_rtl/, docs/fp24-rtl.md).
//
// RtlUnit drives one unit's fast model with a stream of ops, one issue per
// cycle; RtlUnits drives the three units side by side (apu_rtl/fp24_units.sv),
// optionally writing an FST waveform. Both check the timing contract on every
// op: a result is sampled exactly `latency` edges after its issue edge (so a
// dependent op could be issued on that edge), on the right port (the function
// unit's SIN/COS on out_trig_*), never before the result of an op issued
// earlier on the same port, and no valid rises with nothing due. A violation throws
// TimingError.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "fp24.hpp"

namespace mc1::fp24::tb {

struct Issue {
  Op op;
  Bits a;  // FLOAT: the 16-bit integer in bits 15..0
  Bits b;  // ignored by one-operand ops
};

// When an op entered its unit and when its result was sampled, in clock
// edges counted from the end of reset.
struct Timing {
  std::uint64_t issue_edge;
  std::uint64_t result_edge;
};

class TimingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An assertion of the RTL (`APU_ASSERT, docs/apu-rtl.md "Assertions") failed
// at a rising edge; Verilator has printed the rule's name on standard output.
class RtlAssertionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One unit's own verilated model (no tracing; built for speed).
class RtlUnit {
 public:
  explicit RtlUnit(Unit unit);
  ~RtlUnit();
  RtlUnit(const RtlUnit&) = delete;
  RtlUnit& operator=(const RtlUnit&) = delete;

  // Streams n ops of kind `op` (operands a[i], b[i]; b may be null for
  // one-operand ops) through the unit, issuing whenever it is ready, and
  // stores the results in issue order in out[0..n).
  void run(Op op, const Bits* a, const Bits* b, Result* out, std::size_t n);

  std::uint64_t edges() const;  // clock edges since reset

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Issue pattern for RtlUnits::run: each cycle a unit with an op waiting
// stays idle with probability `bubble`, in [0, 1) (0: back to back).
struct IssuePattern {
  double bubble = 0.0;
  std::uint32_t seed = 1;
};

// The three units in one model (fp24_units), optionally traced.
class RtlUnits {
 public:
  // fst_path empty: no waveform.
  explicit RtlUnits(const std::string& fst_path = "");
  ~RtlUnits();
  RtlUnits(const RtlUnits&) = delete;
  RtlUnits& operator=(const RtlUnits&) = delete;

  // Runs ops on their units: each unit takes its own ops in the order given,
  // the three units concurrently. Returns the results indexed like ops; if
  // timing is non-null it receives each op's issue and result edges.
  std::vector<Result> run(const std::vector<Issue>& ops, const IssuePattern& pattern = {},
                          std::vector<Timing>* timing = nullptr);

  std::uint64_t edges() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace mc1::fp24::tb
