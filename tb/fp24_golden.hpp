// Golden-file checking (fp24-run --check, fp24-regress --vectors): FP24
// values and flags in words a reader can check by hand, the located mismatch
// line, and the summary by op and by flag.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fp24.hpp"
#include "fp24_vectors.hpp"

namespace mc1::fp24::tb {

// Flags by name, most significant first: "NV|NX"; "-" for none.
std::string flag_names(std::uint8_t flags);
// Reads flags by name ("NV|NX", "nv,nx", "-") or as hex ("0x11", "11").
std::optional<std::uint8_t> parse_flags(std::string_view text);

// The value of an FP24 encoding in decimal, shortest that reads back to the
// same encoding ("1.5", "-0", "inf", "nan"); a zero-exponent encoding with a
// fraction reads "0 (DAZ)", since every op reads it as zero.
std::string decimal(Bits a);
// Operand a or b of op decoded: FLOAT's a is a 16-bit two's-complement integer.
std::string describe_operand(Op op, Bits a);
// A result decoded: CMP's condition by name, FIX's 16-bit integer, else FP24.
std::string describe_result(Op op, Bits value);

// `file:line: ENGINE: op A [B] (a [b]): expected R F (value; flags), got R F
// (value; flags)`: one line per mismatch, everything needed to judge it.
std::string mismatch_line(const std::string& source, const Golden& g, const std::string& engine, Result got);

// Mismatch counts by op and by flag for each engine; text() is the summary
// table that follows the mismatch lines.
class GoldenSummary {
 public:
  explicit GoldenSummary(std::vector<std::string> engines);
  void checked(Op op) { ++vectors_[int(op)]; }
  void mismatch(std::size_t engine, const Golden& g, Result got);
  std::uint64_t mismatches() const { return total_; }
  std::string text() const;

 private:
  struct PerEngine {
    std::array<std::uint64_t, kOpCount> by_op{};
    std::array<std::uint64_t, 5> flag_missing{};  // expected set, got clear (bit i)
    std::array<std::uint64_t, 5> flag_extra{};    // got set, expected clear
    std::uint64_t value = 0;                      // result encodings that differ
  };
  std::vector<std::string> engines_;
  std::vector<PerEngine> per_;
  std::array<std::uint64_t, kOpCount> vectors_{};
  std::uint64_t total_ = 0;
};

}  // namespace mc1::fp24::tb
