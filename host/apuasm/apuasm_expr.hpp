// Integer expressions of the assembly language (docs/apu-asm.md, "Integer
// expressions"): 64-bit, C precedence, every operation checked. Internal to
// apuasm_lib.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "apuasm_lexer.hpp"

namespace mc1::apuasm::detail {

// Parentheses and unary operators nest at most this deep in one expression,
// together: the parser recurses once per level, and `((((...` of a few ten
// thousand levels would overflow its stack.
constexpr int kMaxExprNesting = 256;

// The value of a symbol, or nullopt when it is not defined.
using Lookup = std::function<std::optional<std::int64_t>(const std::string&)>;

// The value of the expression `p`. Throws LineError at the offending column on
// a syntax error, nesting deeper than kMaxExprNesting, an undefined symbol, a
// result that does not fit in 64 bits, a division by zero or a shift count
// outside 0..63.
std::int64_t eval_expr(const Piece& p, const Lookup& lookup);

// -v; a LineError at `col` when -v does not fit (v is INT64_MIN).
std::int64_t negate(std::int64_t v, int col);

}  // namespace mc1::apuasm::detail
