// Instruction lines to microwords (docs/apu-asm.md, "Instructions" and
// "Legality"). Internal to apuasm_lib.
#pragma once

#include <string>
#include <vector>

#include "apuasm_expr.hpp"
#include "apuasm_lexer.hpp"
#include "microword.hpp"

namespace mc1::apuasm::detail {

// True for every mnemonic of the language (lower case), macro-free.
bool is_mnemonic(const std::string& lower_name);

// The word of one instruction line: slot instructions separated by '|'.
// Every error found on the line is appended to `errors`; the word then holds
// the slots that did encode.
apu::Encoded encode_line(const Piece& body, const Lookup& lookup, std::vector<LineError>& errors);

}  // namespace mc1::apuasm::detail
