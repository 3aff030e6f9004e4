// The vector interface of docs/fp24.md, shared by every engine's front end:
// input lines `OP A [B]` (hex), output lines `RESULT FLAGS` (hex); and the
// golden files of `fp24-run --check`: `OP A [B] RESULT FLAGS`.
#pragma once

#include <istream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fp24.hpp"
#include "fp24_rtl.hpp"

namespace mc1::fp24::tb {

// A malformed input line; what() reads `<source>:<line>: <problem>`.
class VectorError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses one line. Returns nullopt for a line that is blank or whose first
// non-blank character is '#' (a comment); throws VectorError naming
// source:line and the offending token for anything else that is not exactly
// `op a [b]` with the op's operand count and in-range hex operands.
std::optional<Issue> parse_vector(std::string_view line, const std::string& source, long line_no);

// Reads every line of `in` (see parse_vector). A line over 4096 bytes, or
// more than 1 GiB in all, is a VectorError naming source:line, read no
// further (a stream that never ends, /dev/zero, is not held whole).
std::vector<Issue> read_vectors(std::istream& in, const std::string& source);

// The five flag bits of docs/fp24.md (NV DZ OF UF NX).
constexpr Bits kFlagMask = 0x1F;

// The largest result encoding of op: CMP a 4-bit condition, FIX a 16-bit
// integer, the rest FP24.
Bits result_max(Op op);

// One line of a golden file, TestFloat style: `op a [b] result flags`.
struct Golden {
  Issue vector;
  Result expected;
  long line;
  bool has_expected;  // false: a bare `op a [b]` (fp24-regress --vectors only)
};

// Parses a golden line: as parse_vector, but the op in any case, every hex
// field with an optional 0x prefix, a `#` token ends the line, and the
// result and flags follow the operands (both range-checked). With
// expected_optional a bare `op a [b]` line is taken too (has_expected false).
std::optional<Golden> parse_golden(std::string_view line, const std::string& source, long line_no,
                                   bool expected_optional = false);

// Reads every line of `in` (see parse_golden), within read_vectors' limits.
std::vector<Golden> read_golden(std::istream& in, const std::string& source, bool expected_optional = false);

// `op a [b]`, as parse_vector reads it (a: 4 hex digits for float, else 6).
std::string format_vector(const Issue& v);

// `rrrrrr ff`: result as 6 hex digits, flags as 2.
std::string format_result(const Result& r);

}  // namespace mc1::fp24::tb
