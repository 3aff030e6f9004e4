// A cycle profile of an APU run, built from the CycleRecords of either
// engine: cycles, words issued, ops per unit and their utilization against
// the 12 MFLOPS peak (3 units at 4 MHz), stall cycles by reason, and the
// words that stall most, disassembled, like a profiler's hot list.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>

#include "apu_engine.hpp"
#include "microword.hpp"

namespace mc1::apu {

constexpr double kApuClockHz = 4.0e6;  // paper section 2: 250 ns cycle
constexpr int kFpUnits = 3;            // multiplier, adder unit, function unit
const char* unit_name(int unit);

class Profile {
 public:
  // word_at(bank, pc) returns the word the engine runs there (the driver's
  // program_word, or the ISS's).
  explicit Profile(std::function<Encoded(int, std::uint16_t)> word_at) : word_at_(std::move(word_at)) {}

  void add(const CycleRecord& r);

  struct PcStats {
    std::uint64_t issued = 0;
    std::array<std::uint64_t, kStallKinds> stalls{};
    std::uint64_t stalled() const;
    // The first stalled cycle at this word, and the longest run of stalled
    // cycles in a row there (its first cycle, its length); engine cycles.
    std::uint64_t first_stall_cycle = 0, worst_cycle = 0, worst_cycles = 0;
  };
  std::uint64_t cycles() const { return cycles_; }            // cycles the APU was running
  std::uint64_t issued() const { return issued_; }
  std::uint64_t unit_ops(int unit) const { return unit_ops_[unit]; }
  std::uint64_t stalls(Stall s) const { return stalls_[static_cast<int>(s)]; }
  const PcStats& at(int bank, std::uint16_t pc) const { return pcs_[bank & 1][pc % kProgramWords]; }
  // Fraction of the cycles in which the unit started an op.
  double utilization(int unit) const;
  // Sustained MFLOPS at 4 MHz (every unit op counts as one).
  double mflops() const;

  // The text report of docs/apu-tools.md, with the top_n stalling words.
  std::string report(int top_n = 10) const;
  // The same as JSON, schema "apu-profile/1" (docs/apu-tools.md), every
  // word that issued or stalled listed; `program` names the run.
  std::string json(const std::string& program) const;

 private:
  std::function<Encoded(int, std::uint16_t)> word_at_;
  std::uint64_t cycles_ = 0, issued_ = 0;
  std::array<std::uint64_t, kFpUnits> unit_ops_{};
  std::array<std::uint64_t, kStallKinds> stalls_{};
  std::array<std::array<PcStats, kProgramWords>, 2> pcs_{};
  void end_run();  // closes the run of stalled cycles under way
  struct Run { int bank = -1, pc = 0; std::uint64_t first = 0, cycles = 0; } run_;
  // The unit mask of the word last seen at each pc (recomputed when the word changes).
  std::array<std::array<Encoded, kProgramWords>, 2> seen_{};
  std::array<std::array<std::uint8_t, kProgramWords>, 2> units_{};
};

}  // namespace mc1::apu
