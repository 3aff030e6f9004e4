// The APU assembler (host/apuasm): each slot's encodings, field by field and
// as hex, and the diagnostics of sources that must not assemble.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "apuasm.hpp"
#include "apuasm_test_util.hpp"
#include "disasm.hpp"

namespace mc1::apuasm {
namespace {

// ---------------------------------------------------------------------------
// Encodings, field by field and as hex.

TEST(ApuAsmEncode, MulField) {
  const auto w = decoded("mul f1, f2, f3");
  EXPECT_TRUE(w.m.en);
  EXPECT_EQ(w.m.d, 1);
  EXPECT_EQ(w.m.a, 2);
  EXPECT_EQ(w.m.b, 3);
  // en | d<<1 | a<<7 | b<<13
  EXPECT_EQ(apu::encoding_hex(one("mul f1, f2, f3")), "0000000000000000_0000000000006103");
}

TEST(ApuAsmEncode, AdderOps) {
  auto w = decoded("sub f63, f0, f62");
  EXPECT_TRUE(w.a.en);
  EXPECT_EQ(w.a.op, AddOp::Sub);
  EXPECT_EQ(w.a.d, 63);
  EXPECT_EQ(w.a.a, 0);
  EXPECT_EQ(w.a.b, 62);
  // bit 19 en, op 1 at 20, d 63 at 23, a 0 at 29, b 62 at 35
  const std::uint64_t lo = (1ull << 19) | (1ull << 20) | (63ull << 23) | (62ull << 35);
  EXPECT_EQ(one("sub f63, f0, f62"), (Encoded{lo, 0}));

  w = decoded("cmp f5, f6");
  EXPECT_EQ(w.a.op, AddOp::Cmp);
  EXPECT_EQ(w.a.d, 0);
  EXPECT_EQ(w.a.a, 5);
  EXPECT_EQ(w.a.b, 6);
  w = decoded("fix f7, f8");
  EXPECT_EQ(w.a.op, AddOp::Fix);
  EXPECT_EQ(w.a.d, 7);
  EXPECT_EQ(w.a.a, 8);
  EXPECT_EQ(w.a.b, 0);
  EXPECT_EQ(decoded("float f1, f2").a.op, AddOp::Float);
  EXPECT_EQ(decoded("neg f1, f2").a.op, AddOp::Neg);
  EXPECT_EQ(decoded("abs f1, f2").a.op, AddOp::Abs);
  EXPECT_EQ(decoded("fadd f1, f2, f3").a.op, AddOp::Add);
}

TEST(ApuAsmEncode, FunctionUnit) {
  const auto w = decoded("cos f10, f33");
  EXPECT_TRUE(w.f.en);
  EXPECT_EQ(w.f.op, FuncOp::Cos);
  EXPECT_EQ(w.f.d, 10);
  EXPECT_EQ(w.f.a, 33);
  // bit 41 en, op 3 at 42, d 10 at 44, a 33 at 50
  const std::uint64_t lo = (1ull << 41) | (3ull << 42) | (10ull << 44) | (33ull << 50);
  EXPECT_EQ(one("cos f10, f33"), (Encoded{lo, 0}));
}

TEST(ApuAsmEncode, DataMoves) {
  auto w = decoded("ld f9, [a1+4]");
  EXPECT_EQ(w.d.op, MemOp::Ld);
  EXPECT_EQ(w.d.f, 9);
  EXPECT_EQ(w.d.base, 1);
  EXPECT_EQ(w.d.disp, 4);
  EXPECT_EQ(apu::encoding_hex(one("ld f9, [a1+4]")), "0000000000000041_2500000000000000");
  w = decoded("st f2, [a15-128]");
  EXPECT_EQ(w.d.op, MemOp::St);
  EXPECT_EQ(w.d.f, 2);
  EXPECT_EQ(w.d.base, 15);
  EXPECT_EQ(w.d.disp, -128);
  EXPECT_EQ(decoded("st f2, [a3]").d.disp, 0);
  EXPECT_EQ(decoded("ld f2, [ a3 + 2*3 ]").d.disp, 6);
  EXPECT_EQ(decoded("ld f2, [a3+127]").d.disp, 127);
}

TEST(ApuAsmEncode, IntegerOps) {
  auto w = decoded("addi a1, a2, -3");
  EXPECT_EQ(w.i.op, IntOp::Addi);
  EXPECT_EQ(w.i.d, 1);
  EXPECT_EQ(w.i.s, 2);
  EXPECT_EQ(w.i.t, 0);
  EXPECT_EQ(w.i.imm, 0xFFFD);
  // op 2 at 76, d 1 at 80, s 2 at 86, imm 0xfffd at 94
  unsigned __int128 all = (static_cast<unsigned __int128>(2) << 76) | (static_cast<unsigned __int128>(1) << 80) |
                          (static_cast<unsigned __int128>(2) << 86) | (static_cast<unsigned __int128>(0xFFFD) << 94);
  EXPECT_EQ(one("addi a1, a2, -3"),
            (Encoded{static_cast<std::uint64_t>(all), static_cast<std::uint64_t>(all >> 64)}));
  EXPECT_EQ(decoded("li a5, 65535").i.imm, 0xFFFF);
  EXPECT_EQ(decoded("li a5, -32768").i.imm, 0x8000);
  w = decoded("xor a3, a4, a5");
  EXPECT_EQ(w.i.op, IntOp::Xor);
  EXPECT_EQ(w.i.t, 5);
  w = decoded("add a3, a4, a5");
  EXPECT_EQ(w.i.op, IntOp::Add);
  EXPECT_FALSE(w.a.en);
  w = decoded("movaf f40, a7");
  EXPECT_EQ(w.i.op, IntOp::Movaf);
  EXPECT_EQ(w.i.d, 40);
  EXPECT_EQ(w.i.s, 7);
  w = decoded("movfa a7, f40");
  EXPECT_EQ(w.i.op, IntOp::Movfa);
  EXPECT_EQ(w.i.d, 7);
  EXPECT_EQ(w.i.imm, 40);
  EXPECT_EQ(decoded("shl a1, a1, 15").i.imm, 15);
  EXPECT_EQ(decoded("andi a1, a1, 0xff00").i.imm, 0xFF00);
}

TEST(ApuAsmEncode, LifConstants) {
  EXPECT_EQ(decoded("lif f1, 1.5").i.imm, 0x3F80);
  EXPECT_EQ(decoded("lif f1, 1.0").i.imm, 0x3F00);
  EXPECT_EQ(decoded("lif f1, -2").i.imm, 0xC000);
  EXPECT_EQ(decoded("lif f1, 0.375").i.imm, 0x3D80);  // 1.5 * 2^-2
  EXPECT_EQ(decoded("lif f1, 256.0").i.imm, 0x4700);
  EXPECT_EQ(decoded("lif f1, 1.99609375").i.imm, 0x3FFF);
  EXPECT_EQ(decoded("lif f1, 0.0").i.imm, 0x0000);
  EXPECT_EQ(decoded("lif f1, -0.0").i.imm, 0x8000);
  EXPECT_EQ(decoded("lif f1, inf").i.imm, 0x7F00);
  EXPECT_EQ(decoded("lif f1, -inf").i.imm, 0xFF00);
  EXPECT_EQ(decoded("lif f1, nan").i.imm, 0x7F80);
  EXPECT_EQ(decoded("lif f1, 0x0123").i.imm, 0x0123);
  EXPECT_EQ(decoded("lif f1, 15e-1").i.imm, 0x3F80);
  EXPECT_EQ(decoded("lif f62, 1.5").i.d, 62);
}

TEST(ApuAsmEncode, Sequencer) {
  auto w = decoded("bcc lt+eq, 5");
  EXPECT_EQ(w.s.op, SeqOp::Bcc);
  EXPECT_EQ(w.s.r, 3);
  EXPECT_EQ(w.s.target, 5);
  // op 2 at 110 (hi bit 46), r 3 at 114, target 5 at 118
  EXPECT_EQ(one("bcc lt+eq, 5"), (Encoded{0, (2ull << 46) | (3ull << 50) | (5ull << 54)}));
  EXPECT_EQ(decoded("bcc un, 1").s.r, 8);
  EXPECT_EQ(decoded("bncc 0xF, 1").s.r, 15);
  w = decoded("ble 9");
  EXPECT_EQ(w.s.op, SeqOp::Bcc);
  EXPECT_EQ(w.s.r, 3);
  w = decoded("bne 9");
  EXPECT_EQ(w.s.op, SeqOp::Bncc);
  EXPECT_EQ(w.s.r, 2);
  EXPECT_EQ(decoded("bge 9").s.r, 6);
  EXPECT_EQ(decoded("bord 9").s.op, SeqOp::Bncc);
  w = decoded("dbnz a2, 1023");
  EXPECT_EQ(w.s.op, SeqOp::Dbnz);
  EXPECT_EQ(w.s.r, 2);
  EXPECT_EQ(w.s.target, 1023);
  EXPECT_EQ(decoded("halt").s.op, SeqOp::Halt);
  EXPECT_EQ(apu::encoding_hex(one("halt")), "0003000000000000_0000000000000000");
  EXPECT_EQ(decoded("swapd").s.op, SeqOp::Swapd);
  EXPECT_EQ(decoded("ret").s.op, SeqOp::Ret);
  EXPECT_EQ(decoded("swapp 7").s.target, 7);
  EXPECT_EQ(one("nop"), Encoded{});
}

TEST(ApuAsmEncode, FullWordAnySlotOrderAndCase) {
  const auto a = one("mul f1, f2, f3 | add f4, f5, f6 | sin f7, f8 | ld f9, [a1+4] | addi a1, a1, 8 | dbnz a2, 0");
  const auto b = one("DBNZ A2, 0 | ADDI a1, a1, 8 | Ld F9, [A1+4] | sin f7, f8 | add f4, f5, f6 | mul f1, f2, f3");
  EXPECT_EQ(a, b);
  const auto w = MicroWord::decode(a);
  EXPECT_TRUE(w.m.en && w.a.en && w.f.en);
  EXPECT_EQ(w.f.op, FuncOp::Sin);
  EXPECT_EQ(w.d.op, MemOp::Ld);
  EXPECT_EQ(w.i.imm, 8);
  EXPECT_EQ(w.s.op, SeqOp::Dbnz);
  EXPECT_EQ(apu::encoding_hex(a), "0009000200412041_25207a30a2086103");
}

// ---------------------------------------------------------------------------
// Diagnostics: every error class at its file:line:col.

TEST(ApuAsmErrors, RegisterWrittenTwice) {
  EXPECT_EQ(first_error("nop\n  mul f1, f2, f3 | add f1, f2, f2\n"),
            "e.apu:2:24: error: f1 is written twice in one word (also at column 7)");
  EXPECT_EQ(first_error("ld f5, [a1] | lif f5, 1.0\n"),
            "e.apu:1:19: error: f5 is written twice in one word (also at column 4)");
  // CMP writes no F register, ST reads its register.
  EXPECT_NO_THROW(assemble("cmp f1, f2 | mul f1, f1, f1 | st f1, [a0]\n"));
}

TEST(ApuAsmErrors, ARegisterWrittenByIAndDbnz) {
  EXPECT_EQ(first_error("addi a2, a2, 1 | dbnz a2, 0\n"),
            "e.apu:1:23: error: a2 is written twice in one word (DBNZ and the I slot at column 6)");
  EXPECT_NO_THROW(assemble("addi a3, a2, 1 | dbnz a2, 0\n"));
  EXPECT_NO_THROW(assemble("movaf f2, a2 | dbnz a2, 0\n"));
}

TEST(ApuAsmErrors, TwoInstructionsForOneSlot) {
  EXPECT_EQ(first_error("li a1, 1 | lif f1, 1.0\n"),
            "e.apu:1:12: error: two instructions for the I (integer) slot in one word (the other at column 1)");
  EXPECT_EQ(first_error("add f1, f2, f3 | cmp f4, f5\n"),
            "e.apu:1:18: error: two instructions for the A (adder) slot in one word (the other at column 1)");
}

TEST(ApuAsmErrors, OutOfRangeFields) {
  EXPECT_EQ(first_error("mul f64, f1, f2"), "e.apu:1:5: error: no such F register 'f64' (f0..f63)");
  EXPECT_EQ(first_error("li a16, 0"), "e.apu:1:4: error: no such A register 'a16' (a0..a15)");
  EXPECT_EQ(first_error("ld f1, [a1+128]"), "e.apu:1:11: error: displacement 128 out of range -128..127");
  EXPECT_EQ(first_error("ld f1, [a1-129]"), "e.apu:1:11: error: displacement -129 out of range -128..127");
  EXPECT_EQ(first_error("li a1, 65536"), "e.apu:1:8: error: immediate 65536 out of range -32768..65535");
  EXPECT_EQ(first_error("li a1, -32769"), "e.apu:1:8: error: immediate -32769 out of range -32768..65535");
  EXPECT_EQ(first_error("jmp 1024"), "e.apu:1:5: error: branch target 1024 out of range 0..1023");
  EXPECT_EQ(first_error("shl a1, a1, 16"), "e.apu:1:13: error: shift amount 16 out of range 0..15");
  EXPECT_EQ(first_error("bcc 16, 0"), "e.apu:1:5: error: CC mask 16 out of range 0..15");
  EXPECT_EQ(first_error("lif f1, 1.3"),
            "e.apu:1:9: error: 1.3 is not exactly representable as an FP24 constant with an 8-bit fraction "
            "(nearest: 1.30078125 = 0x3f4d)");
  EXPECT_EQ(first_error("lif f1, 1e30"),
            "e.apu:1:9: error: 1e30 is not exactly representable as an FP24 constant with an 8-bit fraction "
            "(out of range)");
  // 1 + 2^-9 is exact in binary64 but needs a 9th fraction bit.
  EXPECT_NE(first_error("lif f1, 1.001953125").find("e.apu:1:9: error: 1.001953125 is not exactly"), std::string::npos);
  // Rounds to an FP24 value in binary64 but is not that value.
  EXPECT_NE(first_error("lif f1, 1.50000000000000000000001").find("not exactly representable"), std::string::npos);
  EXPECT_EQ(first_error("lif f1, 0x10000"), "e.apu:1:9: error: raw LIF immediate 0x10000 is wider than 16 bits");
  EXPECT_EQ(first_error(".org 1024"), "e.apu:1:6: error: .org address 1024 out of range 0..1023");
}

TEST(ApuAsmErrors, ProgramTooLarge) {
  std::string src;
  for (int k = 0; k < 1025; ++k) src += "  nop\n";
  EXPECT_EQ(errors(src), std::vector<std::string>{"e.apu:1025:3: error: program larger than 1024 words"});
  EXPECT_EQ(first_error(".org 1023\nnop\nhalt\n"), "e.apu:3:1: error: program larger than 1024 words");
}

TEST(ApuAsmErrors, Labels) {
  EXPECT_EQ(first_error("  jmp nowhere\n"), "e.apu:1:7: error: undefined symbol 'nowhere'");
  EXPECT_EQ(first_error("x: nop\n  x: nop\n"), "e.apu:2:3: error: duplicate symbol 'x' (first defined at e.apu:1:1)");
  EXPECT_EQ(first_error(".equ N, 1\nN: nop\n"), "e.apu:2:1: error: duplicate symbol 'N' (first defined at e.apu:1:6)");
  EXPECT_EQ(first_error("f3: nop\n"), "e.apu:1:1: error: 'f3' is a mnemonic or register name");
  EXPECT_EQ(first_error(".equ A, B\n.equ B, 1\n"), "e.apu:1:9: error: undefined symbol 'B'");
}

TEST(ApuAsmErrors, SyntaxAndOperands) {
  EXPECT_EQ(first_error("frob f1"), "e.apu:1:1: error: unknown mnemonic 'frob'");
  EXPECT_EQ(first_error("mul f1, f2"), "e.apu:1:1: error: 'mul' takes 3 operands: mul fd, fa, fb");
  EXPECT_EQ(first_error("mul f1, a2, f3"), "e.apu:1:9: error: expected an F register (f0..f63), got 'a2'");
  EXPECT_EQ(first_error("ld f1, a2"), "e.apu:1:8: error: expected a data address [aN], [aN+disp] or [aN-disp], got 'a2'");
  EXPECT_EQ(first_error("nop | | halt"), "e.apu:1:7: error: empty slot between '|'");
  EXPECT_EQ(first_error(".bogus 1"), "e.apu:1:1: error: unknown directive '.bogus'");
  EXPECT_EQ(first_error("li a1, 1.5"), "e.apu:1:9: error: malformed number (a float is allowed only in lif)");
  EXPECT_EQ(first_error("li a1, (1+2"), "e.apu:1:12: error: expected ')'");
  EXPECT_EQ(first_error("li a1, 4/0"), "e.apu:1:9: error: division by zero");
  EXPECT_EQ(first_error(".endm"), "e.apu:1:1: error: .endm without .macro");
  EXPECT_EQ(first_error(".org 4\nnop\n.org 4\nhalt\n"),
            "e.apu:4:1: error: address 0x0004 already holds the word of e.apu:2:1");
}

TEST(ApuAsmErrors, AllErrorsReportedInSourceOrder) {
  const auto e = errors("  jmp later\nmul f64, f1, f1\nok: nop\nli a1, 70000\nok: nop\n", "m.apu");
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[0], "m.apu:1:7: error: undefined symbol 'later'");
  EXPECT_EQ(e[1], "m.apu:2:5: error: no such F register 'f64' (f0..f63)");
  EXPECT_EQ(e[2], "m.apu:4:8: error: immediate 70000 out of range -32768..65535");
  EXPECT_EQ(e[3], "m.apu:5:1: error: duplicate symbol 'ok' (first defined at m.apu:3:1)");
  // Every bad slot of one word is reported.
  EXPECT_EQ(errors("mul f99, f1, f1 | ld f1, [a1+999]").size(), 2u);
}

TEST(ApuAsmErrors, ExceptionText) {
  try {
    assemble("nop\nfrob\n", "x.apu");
    FAIL();
  } catch (const AsmError& e) {
    EXPECT_STREQ(e.what(), "x.apu:2:1: error: unknown mnemonic 'frob'");
    EXPECT_EQ(e.diagnostics().at(0).loc.line, 2);
    EXPECT_EQ(e.diagnostics().at(0).loc.col, 1);
  }
}

}  // namespace
}  // namespace mc1::apuasm
