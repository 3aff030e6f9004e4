// The vector interface of docs/fp24.md, shared by every engine's front end:
// input lines `OP A [B]` (hex), output lines `RESULT FLAGS` (hex).
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

// Reads every line of `in` (see parse_vector).
std::vector<Issue> read_vectors(std::istream& in, const std::string& source);

// `op a [b]`, as parse_vector reads it (a: 4 hex digits for float, else 6).
std::string format_vector(const Issue& v);

// `rrrrrr ff`: result as 6 hex digits, flags as 2.
std::string format_result(const Result& r);

}  // namespace mc1::fp24::tb
