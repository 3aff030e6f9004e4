// The two literal operands that are not integer expressions
// (docs/apu-asm.md): the FP24 constant of `lif` and the 128-bit `.word`.
// Internal to apuasm_lib.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "apuasm_lexer.hpp"
#include "microword.hpp"

namespace mc1::apuasm::detail {

// The 16-bit LIF immediate of `p`: an exactly representable decimal, inf,
// -inf, nan, or raw 0xHHHH. Throws LineError naming the nearest constant when
// the decimal is not exact.
std::uint16_t lif_immediate(const Piece& p);

// ".word" operand: 0x and up to 32 hex digits (underscores allowed), bit 127
// first; nullopt when `text` is not one.
std::optional<apu::Encoded> parse_raw_word(const std::string& text);

}  // namespace mc1::apuasm::detail
