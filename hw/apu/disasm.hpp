// The APU disassembler: a microword as one line of the assembly language of
// docs/apu-asm.md, so that co-simulation and profiling reports show code the
// way its author wrote it, and the line re-assembles to the same 128 bits.
#pragma once

#include <cstdint>
#include <string>

#include "microword.hpp"

namespace mc1::apu {

// One line of apuasm syntax, slots in the order M | A | F | D | I | S, e.g.
// "mul f1, f2, f3 | ld f4, [a1+4] | dbnz a2, 0x010"; an empty word is "nop".
// A word the assembler would refuse (reserved op, same register written twice)
// or whose unused fields are not zero comes out as
// ".word 0x<hi>_<lo>  ; <best-effort reading>", which re-assembles bit-exact too.
std::string disassemble(const MicroWord& w);
std::string disassemble(const Encoded& e);

// Why disassemble() cannot print `w` as instructions ("" when it can): a
// reserved op, an out-of-range field, a nonzero unused field, or an illegal
// double write (docs/apu-isa.md).
std::string noncanonical_reason(const MicroWord& w);

// The 128-bit encoding as 32 hex digits, bit 127 first, "hhhhhhhhhhhhhhhh_llllllllllllllll".
std::string encoding_hex(const Encoded& e);

// A CC mask as apuasm spells it: "lt", "lt+eq", ..., "0" for none.
std::string cc_mask_text(unsigned mask);

// A LIF immediate (F = imm << 8) as the exact decimal literal the assembler
// accepts ("1.5", "-0.0", "inf"), or as raw hex "0x7f80" when no short exact
// decimal exists (NaN, denormal-looking patterns, very long expansions).
std::string lif_literal_text(std::uint16_t imm);

}  // namespace mc1::apu
