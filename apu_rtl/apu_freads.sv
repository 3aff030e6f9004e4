// The F register-file read ports a microword's slots use, for apu_core: one
// function of a word, instantiated for the word in I (the interlock's
// sources, the bypass of a word held) and for the word in D (the register
// file's reads, the bypass of a word moving in). docs/apu-rtl.md
// "Register files and the bypass".
//
// Ports by apu_core's RD_* index: 0 M a, 1 M b, 2 A a, 3 A b, 4 F a,
// 5 ST f, 6 MOVFA; addr is flat, port i at [i*FREG_AW +: FREG_AW] (the port
// convention of apu_regfile and apu_interlock). FLOAT, FIX, NEG and ABS read
// `a` only (Clarification 4); a reserved A slot reads nothing (Clarification
// 6). Each output is one concatenation: a simulator computes the vector
// once, not one field after another.
module apu_freads
(
    input  logic [apu_pkg::WORD_W-1:0]    word,
    output logic [6:0]                    en,
    output logic [7*apu_pkg::FREG_AW-1:0] addr
);
`include "apu_microword.svh"

  /* verilator lint_off UNUSEDSIGNAL */
  microword_t x;  // the fields that name F sources
  /* verilator lint_on UNUSEDSIGNAL */
  assign x = word;  // same width; Yosys 0.23 takes no cast to a package's type

  logic add_ok;
  assign add_ok = x.a_en && (x.a_op != apu_pkg::A_RSVD);
  assign en     = {x.i_op == apu_pkg::I_MOVFA, x.d_op == apu_pkg::D_ST, x.f_en,
                   add_ok && ((x.a_op == apu_pkg::A_ADD) || (x.a_op == apu_pkg::A_SUB) || (x.a_op == apu_pkg::A_CMP)),
                   add_ok, x.m_en, x.m_en};
  assign addr   = {x.i_imm[5:0], x.d_f, x.f_a, x.a_b, x.a_a, x.m_b, x.m_a};
endmodule
