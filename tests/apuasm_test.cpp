// The APU assembler and disassembler (host/apuasm, hw/apu/disasm): encodings,
// diagnostics, round trips, directives, listing and image formats.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <dirent.h>
#include <fstream>
#include <iterator>
#include <random>
#include <set>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "apu_image.hpp"
#include "apuasm.hpp"
#include "apuasm_expr.hpp"
#include "apuasm_macros.hpp"
#include "disasm.hpp"

namespace mc1::apuasm {
namespace {

using apu::AddOp;
using apu::Encoded;
using apu::FuncOp;
using apu::IntOp;
using apu::MemOp;
using apu::MicroWord;
using apu::SeqOp;

Encoded one(const std::string& line) {
  const auto p = assemble(line + "\n", "t.apu");
  EXPECT_EQ(p.words.size(), 1u) << line;
  return p.words.empty() ? Encoded{} : p.words[0];
}

MicroWord decoded(const std::string& line) { return MicroWord::decode(one(line)); }

// The diagnostics of a source that must not assemble.
std::vector<std::string> errors(const std::string& src, const std::string& file = "e.apu") {
  try {
    assemble(src, file);
  } catch (const AsmError& e) {
    std::vector<std::string> out;
    for (const auto& d : e.diagnostics()) out.push_back(d.str());
    return out;
  }
  ADD_FAILURE() << "assembled without error:\n" << src;
  return {};
}

std::string first_error(const std::string& src) {
  const auto e = errors(src);
  return e.empty() ? "" : e[0];
}

// A scratch directory for .include tests, removed at the end.
class TempDir {
 public:
  TempDir() {
    char tmpl[] = "/tmp/apuasm_test_XXXXXX";
    path_ = mkdtemp(tmpl);
  }
  ~TempDir() {
    for (const auto& f : files_) std::remove(f.c_str());
    for (auto it = dirs_.rbegin(); it != dirs_.rend(); ++it) rmdir(it->c_str());
    rmdir(path_.c_str());
  }
  std::string write(const std::string& name, const std::string& text) {
    const std::string p = path_ + "/" + name;
    const auto slash = name.find('/');
    if (slash != std::string::npos) {
      dirs_.push_back(path_ + "/" + name.substr(0, slash));
      mkdir(dirs_.back().c_str(), 0700);
    }
    std::ofstream(p) << text;
    files_.push_back(p);
    return p;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<std::string> files_, dirs_;
};

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

// ---------------------------------------------------------------------------
// Directives: labels, .equ, .org, .include, macros.

TEST(ApuAsmDirectives, LabelsEquOrg) {
  const auto p = assemble(
      ".equ BASE, 0x10\n"
      ".equ OFF, (BASE << 2) - 3 * 2 + (7 >> 1) - (~0 & 1) + 10 % 4 + (6 ^ 3)\n"  // 64-6+3-1+2+5 = 67
      "start: li a1, OFF\n"
      "  jmp end\n"
      ".org BASE\n"
      "end: a: b: jmp start\n",
      "t.apu");
  EXPECT_EQ(p.symbols.at("OFF"), 67);
  EXPECT_EQ(p.symbols.at("end"), 16);
  EXPECT_EQ(p.symbols.at("b"), 16);
  ASSERT_EQ(p.words.size(), 17u);
  EXPECT_EQ(MicroWord::decode(p.words[0]).i.imm, 67);
  EXPECT_EQ(MicroWord::decode(p.words[1]).s.target, 16);
  EXPECT_EQ(p.words[5], Encoded{});  // the gap .org left
  EXPECT_EQ(MicroWord::decode(p.words[16]).s.op, SeqOp::Jmp);
  EXPECT_EQ(MicroWord::decode(p.words[16]).s.target, 0);
}

TEST(ApuAsmDirectives, CommentsBothStyles) {
  const auto p = assemble("halt ; semicolon\n  # hash\nret # hash\n\n", "t.apu");
  ASSERT_EQ(p.words.size(), 2u);
  EXPECT_EQ(MicroWord::decode(p.words[1]).s.op, SeqOp::Ret);
}

TEST(ApuAsmDirectives, RawWord) {
  const auto p = assemble(".word 0x0003000000000000_0000000000000001\n.word 0xff\n", "t.apu");
  EXPECT_EQ(p.words[0], (Encoded{1, 0x0003000000000000}));
  EXPECT_EQ(p.words[1], (Encoded{0xFF, 0}));
}

TEST(ApuAsmDirectives, IncludeRelativeToIncludingFile) {
  TempDir dir;
  dir.write("lib/consts.inc", ".equ SIX, 6\n.include \"more.inc\"\n");
  dir.write("lib/more.inc", ".equ SEVEN, 7\n  frob\n");
  const auto top = dir.write("top.apu", ".include \"lib/consts.inc\"\nli a1, SIX+SEVEN\n");
  try {
    assemble_file(top);
    FAIL();
  } catch (const AsmError& err) {
    ASSERT_EQ(err.diagnostics().size(), 1u);
    EXPECT_EQ(err.diagnostics()[0].str(), dir.path() + "/lib/more.inc:2:3: error: unknown mnemonic 'frob'");
  }
  dir.write("lib/more.inc", ".equ SEVEN, 7\n");
  const auto p = assemble_file(top);
  ASSERT_EQ(p.words.size(), 1u);
  EXPECT_EQ(MicroWord::decode(p.words[0]).i.imm, 13);
  EXPECT_EQ(first_error(".include \"no/such.inc\"\n"),
            "e.apu:1:10: error: cannot read include file 'no/such.inc': No such file or directory");
}

TEST(ApuAsmDirectives, Macros) {
  const auto p = assemble(
      ".macro madd d, a, b, c\n"
      "  mul \\d, \\a, \\b\n"
      "  add \\d, \\d, \\c\n"
      ".endm\n"
      ".macro spin n\n"
      "  li a1, \\n\n"
      "L\\@: dbnz a1, L\\@\n"
      ".endm\n"
      "  madd f1, f2, f3, f4\n"
      "  spin 3\n"
      "  spin 4*2\n",
      "t.apu");
  ASSERT_EQ(p.words.size(), 6u);
  const auto m = MicroWord::decode(p.words[0]);
  EXPECT_EQ(m.m.d, 1);
  EXPECT_EQ(m.m.b, 3);
  EXPECT_EQ(MicroWord::decode(p.words[1]).a.b, 4);
  EXPECT_EQ(MicroWord::decode(p.words[3]).s.target, 3);
  EXPECT_EQ(MicroWord::decode(p.words[4]).i.imm, 8);
  EXPECT_EQ(MicroWord::decode(p.words[5]).s.target, 5);
  EXPECT_EQ(p.symbols.at("L1"), 3);  // expansion 0 is madd
  EXPECT_EQ(p.symbols.at("L2"), 5);

  EXPECT_EQ(first_error(".macro m a\n  li a1, \\a\n.endm\n  m 1, 2\n"),
            "e.apu:4:3: error: macro 'm' takes 1 argument(s), got 2");
  EXPECT_EQ(first_error(".macro m a\n  li a1, \\b\n.endm\n  m 1\n"),
            "e.apu:2:10: error: unknown macro parameter '\\b' (in macro 'm' invoked at e.apu:4:3)");
  EXPECT_EQ(first_error(".macro m a\n  li a1, \\a\n.endm\n  m 70000\n"),
            "e.apu:2:10: error: immediate 70000 out of range -32768..65535 (in macro 'm' invoked at e.apu:4:3)");
  EXPECT_EQ(first_error(".macro m a\n nop\n"), "e.apu:1:8: error: .macro without .endm");
  EXPECT_EQ(first_error(".macro mul a\n.endm\n"), "e.apu:1:8: error: macro name 'mul' is an instruction mnemonic");
}

// ---------------------------------------------------------------------------
// Hostile input: every integer operation checked, expansion bounded,
// directories refused (issue 11).

// A source that must not assemble and its first diagnostic.
struct BadSource {
  const char* src;
  const char* error;
};

TEST(ApuAsmLimits, ExpressionOverflowIsALocatedError) {
  const BadSource cases[] = {
      // INT64_MIN / -1 used to kill the assembler with SIGFPE.
      {".equ X, -(1<<62)*2/-1\n",
       "e.apu:1:19: error: integer overflow: -9223372036854775808 / -1 does not fit in 64 bits"},
      // (1<<62)*4 wrapped to 0, so this loaded 5.
      {"li a1, (1<<62)*4+5\n", "e.apu:1:15: error: integer overflow: 4611686018427387904 * 4 does not fit in 64 bits"},
      {".equ X, 0x7fffffffffffffff + 1\n",
       "e.apu:1:28: error: integer overflow: 9223372036854775807 + 1 does not fit in 64 bits"},
      {".equ X, -0x7fffffffffffffff - 2\n",
       "e.apu:1:29: error: integer overflow: -9223372036854775807 - 2 does not fit in 64 bits"},
      {".equ M, -0x7fffffffffffffff - 1\n.equ X, -M\n",
       "e.apu:2:9: error: integer overflow: -(-9223372036854775808) does not fit in 64 bits"},
      {".equ X, 3 << 62\n", "e.apu:1:11: error: integer overflow: 3 << 62 does not fit in 64 bits"},
      {".equ X, 1 << 63\n", "e.apu:1:11: error: integer overflow: 1 << 63 does not fit in 64 bits"},
      {"ld f1, [a1-(-0x7fffffffffffffff-1)]\n",
       "e.apu:1:11: error: integer overflow: -(-9223372036854775808) does not fit in 64 bits"},
      {".equ X, 9223372036854775808\n", "e.apu:1:9: error: number too large (the largest is 9223372036854775807)"},
      {".equ X, 4 / (2 - 2)\n", "e.apu:1:11: error: division by zero"},
      {".equ X, 4 % 0\n", "e.apu:1:11: error: modulo by zero"},
      {".equ X, 1 << 64\n", "e.apu:1:11: error: shift count 64 out of range 0..63"},
      {".equ X, 8 >> -1\n", "e.apu:1:11: error: shift count -1 out of range 0..63"},
  };
  for (const auto& c : cases) EXPECT_EQ(first_error(c.src), c.error) << c.src;
}

TEST(ApuAsmLimits, ExpressionEdgesAreValues) {
  const auto p = assemble(
      ".equ MIN, -0x7fffffffffffffff - 1\n"
      ".equ MAX, 9223372036854775807\n"
      ".equ A, MIN % -1\n"
      ".equ B, -1 << 63\n"
      ".equ C, MIN >> 63\n"
      ".equ D, MAX / -1\n"
      ".equ E, -7 / 2\n"
      ".equ F, -7 % 2\n",
      "t.apu");
  EXPECT_EQ(p.symbols.at("MIN"), INT64_MIN);
  EXPECT_EQ(p.symbols.at("MAX"), INT64_MAX);
  EXPECT_EQ(p.symbols.at("A"), 0);
  EXPECT_EQ(p.symbols.at("B"), INT64_MIN);
  EXPECT_EQ(p.symbols.at("C"), -1);
  EXPECT_EQ(p.symbols.at("D"), -INT64_MAX);
  EXPECT_EQ(p.symbols.at("E"), -3);  // C: truncation toward zero
  EXPECT_EQ(p.symbols.at("F"), -1);
}

TEST(ApuAsmLimits, SelfInvokingMacroStopsAtTheNestingLimit) {
  // Two self-invocations per level: 2^32 expansions without the limit.
  const auto e = errors(".macro m\n m\n m\n.endm\nm\n");
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].rfind("e.apu:2:2: error: expanding macro 'm' nests macros deeper than 32 (in macro 'm' invoked at", 0),
            0u)
      << e[0];
  TempDir dir;
  const auto self = dir.write("self.apu", ".include \"self.apu\"\n.include \"self.apu\"\n");
  try {
    assemble_file(self);
    FAIL() << "assembled";
  } catch (const AsmError& e) {
    EXPECT_STREQ(e.what(), (self + ":1:10: error: .include nested deeper than 32").c_str());
  }
}

// A macro `a` that expands to 16 + 16*16 + 16*16*16 = 4368 lines, all comments.
std::string wide_macro() {
  std::string s = ".macro c\n";
  for (int k = 0; k < 16; ++k) s += " ; c\n";
  s += ".endm\n.macro b\n";
  for (int k = 0; k < 16; ++k) s += " c\n";
  s += ".endm\n.macro a\n";
  for (int k = 0; k < 16; ++k) s += " b\n";
  return s + ".endm\n";
}

TEST(ApuAsmLimits, TotalExpansionIsBounded) {
  ASSERT_EQ(detail::kMaxExpandedLines, 65536u);
  std::string src = wide_macro();
  for (int k = 0; k < 15; ++k) src += "a\n";  // 15 * 4368 = 65520 lines: within
  EXPECT_EQ(assemble(src + "halt\n", "t.apu").words.size(), 1u);
  const auto e = errors(src + "a\n");  // the 16th goes over
  ASSERT_EQ(e.size(), 1u);
  EXPECT_NE(e[0].find("error: expanding macro '"), std::string::npos) << e[0];
  EXPECT_NE(e[0].find("exceeds the limit of 65536 lines that macro expansions and .include may add"), std::string::npos)
      << e[0];
  EXPECT_NE(e[0].find("(in macro 'a' invoked at e.apu:" + std::to_string(std::count(src.begin(), src.end(), '\n') + 1) +
                      ":1)"),
            std::string::npos)
      << e[0];
}

// A macro expanded thousands of times with an error in its body: the
// assembly stops at kMaxErrors (the fuzzer's input of this kind took 6 s and
// 33 MB of diagnostics in the Release build before the limit).
TEST(ApuAsmLimits, ErrorsStopAtTheLimit) {
  ASSERT_EQ(kMaxErrors, 100u);
  std::string src = ".macro m\n x: .bogus\n.endm\n";
  for (int k = 0; k < 1000; ++k) src += "m\n";
  const auto e = errors(src);
  ASSERT_EQ(e.size(), kMaxErrors + 1);
  EXPECT_EQ(e[0], "e.apu:2:5: error: unknown directive '.bogus' (in macro 'm' invoked at e.apu:4:1)");
  EXPECT_EQ(e[1], "e.apu:2:2: error: duplicate symbol 'x' (first defined at e.apu:2:2) (in macro 'm' invoked at e.apu:5:1)");
  // 1 error in the first expansion, 2 in each after it: the 100th is the
  // duplicate label of the 51st (line 54), where the note says it stopped.
  EXPECT_EQ(e[kMaxErrors - 1],
            "e.apu:2:2: error: duplicate symbol 'x' (first defined at e.apu:2:2) (in macro 'm' invoked at e.apu:54:1)");
  EXPECT_EQ(e[kMaxErrors], "e.apu:2:2: error: too many errors (100), the assembly stops here");
  // Under the limit every error is still reported.
  std::string few = ".macro m\n .bogus\n.endm\n";
  for (int k = 0; k < 99; ++k) few += "m\n";
  EXPECT_EQ(errors(few).size(), 99u);
}

TEST(ApuAsmLimits, DirectoriesAreRefused) {
  TempDir dir;
  dir.write("sub/x.inc", "nop\n");
  try {
    assemble_file(dir.path());
    FAIL() << "a directory assembled";
  } catch (const AsmError& e) {
    EXPECT_STREQ(e.what(), (dir.path() + ": error: cannot read file: is a directory").c_str());
  }
  const auto top = dir.write("top.apu", "nop\n.include \"sub\"\n");
  try {
    assemble_file(top);
    FAIL() << ".include of a directory assembled";
  } catch (const AsmError& e) {
    EXPECT_STREQ(e.what(), (top + ":2:10: error: cannot read include file '" + dir.path() + "/sub': is a directory").c_str());
  }
}

// `parens` parentheses around `minuses` unary minus signs before 1.
std::string nested(int parens, int minuses) {
  return std::string(static_cast<size_t>(parens), '(') + std::string(static_cast<size_t>(minuses), '-') + "1" +
         std::string(static_cast<size_t>(parens), ')');
}

// The parser recursed once per level and overflowed its stack (exit 139) at
// some ten thousand levels: nesting is bounded, an error at the operator that
// goes over, at any depth.
TEST(ApuAsmLimits, DeepExpressionIsAnErrorNotACrash) {
  ASSERT_EQ(detail::kMaxExprNesting, 256);
  EXPECT_EQ(assemble(".equ X, " + nested(256, 0) + "\n").symbols.at("X"), 1);
  EXPECT_EQ(assemble(".equ X, " + nested(128, 128) + "\n").symbols.at("X"), 1);
  EXPECT_EQ(assemble(".equ X, " + nested(200, 0) + " + " + nested(0, 201) + "\n").symbols.at("X"), 0);
  EXPECT_EQ(assemble("li a1, " + nested(0, 256) + "\n").words.size(), 1u);
  const std::string msg = "error: expression nested deeper than 256 levels of parentheses and unary operators";
  using Errors = std::vector<std::string>;
  EXPECT_EQ(errors(".equ X, " + nested(257, 0) + "\n"), Errors{"e.apu:1:265: " + msg});
  EXPECT_EQ(errors(".equ X, " + nested(60000, 0) + "\n"), Errors{"e.apu:1:265: " + msg});
  EXPECT_EQ(errors("li a1, " + nested(0, 50000) + "\n"), Errors{"e.apu:1:264: " + msg});
  EXPECT_EQ(errors(".equ X, " + nested(100, 50000) + "\n"), Errors{"e.apu:1:265: " + msg});
  std::string tilde_paren;
  for (int k = 0; k < 200; ++k) tilde_paren += "~(";
  EXPECT_EQ(errors("li a1, " + tilde_paren + "1" + std::string(200, ')') + "\n"), Errors{"e.apu:1:264: " + msg});
  EXPECT_EQ(errors("ld f1, [a1+" + nested(300, 0) + "]\n"), Errors{"e.apu:1:268: " + msg});
}

// /dev/zero was read until memory ran out; a source is read up to
// kMaxSourceBytes, and has at most kMaxSourceLines lines.
TEST(ApuAsmLimits, SourceSizeIsBounded) {
  ASSERT_EQ(kMaxSourceBytes, std::size_t{16} << 20);
  ASSERT_EQ(kMaxSourceLines, 65536u);
  const auto what = [](const std::string& path) -> std::string {
    try {
      assemble_file(path);
    } catch (const AsmError& e) {
      return e.what();
    }
    return "assembled";
  };
  EXPECT_EQ(what("/dev/zero"), "/dev/zero: error: cannot read file: larger than 16 MiB");
  TempDir dir;
  const auto top = dir.write("top.apu", "nop\n.include \"/dev/zero\"\n");
  EXPECT_EQ(what(top), top + ":2:10: error: cannot read include file '/dev/zero': larger than 16 MiB");
  const auto over = dir.write("over.apu", std::string(kMaxSourceBytes - 4, ' ') + "halt\n");
  EXPECT_EQ(what(over), over + ": error: cannot read file: larger than 16 MiB");
  const auto at = dir.write("at.apu", std::string(kMaxSourceBytes - 5, ' ') + "halt\n");
  EXPECT_EQ(assemble_file(at).words.size(), 1u);
  EXPECT_EQ(assemble(std::string(kMaxSourceLines - 1, '\n') + "halt").words.size(), 1u);
  EXPECT_EQ(errors(std::string(kMaxSourceLines, '\n') + "halt"),
            std::vector<std::string>{"e.apu: error: more than 65536 lines"});
}

// `n` macros m1..mn, each invoking the next; mn's body is an error.
std::string macro_chain(int n) {
  std::string s;
  for (int k = n; k >= 1; --k)
    s += ".macro m" + std::to_string(k) + "\n" + (k == n ? " .bogus" : " m" + std::to_string(k + 1)) + "\n.endm\n";
  return s + "m1\n";
}

// A message names the three innermost invocations and the outermost; the
// chain of 32 repeated one note 32 times.
TEST(ApuAsmLimits, LongMacroChainsAreElided) {
  ASSERT_EQ(detail::kShownInnerExpansions, 3);
  EXPECT_EQ(errors(macro_chain(4)),
            std::vector<std::string>{"e.apu:2:2: error: unknown directive '.bogus' (in macro 'm4' invoked at e.apu:5:2) "
                                     "(in macro 'm3' invoked at e.apu:8:2) (in macro 'm2' invoked at e.apu:11:2) "
                                     "(in macro 'm1' invoked at e.apu:13:1)"});
  EXPECT_EQ(errors(macro_chain(6)),
            std::vector<std::string>{"e.apu:2:2: error: unknown directive '.bogus' (in macro 'm6' invoked at e.apu:5:2) "
                                     "(in macro 'm5' invoked at e.apu:8:2) (in macro 'm4' invoked at e.apu:11:2) "
                                     "(... 2 more macro invocations ...) (in macro 'm1' invoked at e.apu:19:1)"});
  const auto e = errors(".macro m\n m\n.endm\nm\n");
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0], "e.apu:2:2: error: expanding macro 'm' nests macros deeper than 32 (in macro 'm' invoked at e.apu:2:2) "
                  "(in macro 'm' invoked at e.apu:2:2) (in macro 'm' invoked at e.apu:2:2) "
                  "(... 28 more macro invocations ...) (in macro 'm' invoked at e.apu:4:1)");
}

// ---------------------------------------------------------------------------
// The program: exit status 0 / 1 (an output not written, none left) / 2
// (usage or input), the options of docs/apu-asm.md.

// build/bin/apuasm, beside this test program.
std::string apuasm_program() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return "apuasm";
  const std::string self(buf, static_cast<size_t>(n));
  return self.substr(0, self.find_last_of('/')) + "/apuasm";
}

struct Run {
  int status = -1;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Runs apuasm with `args` (shell words), in `dir` for its output files.
Run run_apuasm(const TempDir& dir, const std::string& args) {
  const std::string out = dir.path() + "/.stdout", err = dir.path() + "/.stderr";
  const std::string cmd = "cd '" + dir.path() + "' && '" + apuasm_program() + "' " + args + " >'" + out + "' 2>'" + err + "'";
  const int rc = std::system(cmd.c_str());
  Run r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  std::remove(out.c_str());
  std::remove(err.c_str());
  return r;
}

std::set<std::string> names_in(const std::string& path) {
  std::set<std::string> out;
  DIR* d = opendir(path.c_str());
  if (!d) return out;
  while (const dirent* e = readdir(d))
    if (std::string(e->d_name) != "." && std::string(e->d_name) != "..") out.insert(e->d_name);
  closedir(d);
  return out;
}

bool exists(const std::string& path) {
  struct stat st {};
  return stat(path.c_str(), &st) == 0;
}

TEST(ApuAsmProgram, WritesImageListingAndHex) {
  TempDir dir;
  const std::string src = "start: mul f1, f2, f3\n  halt\n";
  dir.write("k.apu", src);
  const auto r = run_apuasm(dir, "-l k.lst -x k.hex k.apu");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto p = assemble(src, "k.apu");
  EXPECT_EQ(slurp(dir.path() + "/k.bin"), image_bytes(p.words));  // default: the source name with .bin
  EXPECT_EQ(slurp(dir.path() + "/k.lst"), listing_text(p));
  EXPECT_EQ(slurp(dir.path() + "/k.hex"), readmemh_text(p.words));
  const auto d = run_apuasm(dir, "-d k.bin");
  EXPECT_EQ(d.status, 0) << d.err;
  EXPECT_EQ(d.out, disassembly_text(p.words));
  for (const char* f : {"/k.bin", "/k.lst", "/k.hex"}) std::remove((dir.path() + f).c_str());
}

TEST(ApuAsmProgram, FailedWriteExitsOneAndLeavesNoOutput) {
  TempDir dir;
  dir.write("k.apu", "halt\n");
  auto r = run_apuasm(dir, "-o /dev/full k.apu");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "apuasm: /dev/full: cannot write: No space left on device\n");
  struct stat st {};
  ASSERT_EQ(stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device was replaced";
  // The image is written, the listing is not: neither is left.
  r = run_apuasm(dir, "-o k.bin -l /dev/full k.apu");
  EXPECT_EQ(r.status, 1);
  EXPECT_FALSE(exists(dir.path() + "/k.bin"));
  r = run_apuasm(dir, "-o no/such/dir/k.bin k.apu");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("no/such/dir/k.bin: cannot create a temporary file beside it"), std::string::npos) << r.err;
  EXPECT_EQ(names_in(dir.path()), std::set<std::string>{"k.apu"}) << "a temporary file was left";
}

TEST(ApuAsmProgram, UsageAndInputErrorsExitTwo) {
  TempDir dir;
  dir.write("bad.apu", "frob\n");
  dir.write("sub/x.inc", "nop\n");
  auto r = run_apuasm(dir, "bad.apu");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "bad.apu:1:1: error: unknown mnemonic 'frob'\n");
  EXPECT_FALSE(exists(dir.path() + "/bad.bin"));
  r = run_apuasm(dir, "sub");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "sub: error: cannot read file: is a directory\n");
  r = run_apuasm(dir, "missing.apu");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "missing.apu: error: cannot read file: No such file or directory\n");
  r = run_apuasm(dir, "-d bad.apu");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "apuasm: bad.apu: not an APU image (no \"APU1\" header)\n");
  for (const char* args : {"", "--frob bad.apu", "-o", "a.apu b.apu", "-d x.bin bad.apu", "-d x.bin -o y.bin"}) {
    r = run_apuasm(dir, args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(r.err.rfind("apuasm: ", 0), 0u) << args << ": " << r.err;
  }
}

// A nesting that crashed the program (exit 139) and a source without end
// are input errors, exit 2, nothing written.
TEST(ApuAsmProgram, DeepExpressionAndEndlessSourceExitTwo) {
  TempDir dir;
  dir.write("deep.apu", ".equ X, " + nested(60000, 0) + "\n");
  auto r = run_apuasm(dir, "deep.apu");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "deep.apu:1:265: error: expression nested deeper than 256 levels of parentheses and unary operators\n");
  r = run_apuasm(dir, "-o z.bin /dev/zero");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "/dev/zero: error: cannot read file: larger than 16 MiB\n");
  EXPECT_EQ(names_in(dir.path()), std::set<std::string>{"deep.apu"});
}

// An output that is an input (by name, "./", "..", a hard or symbolic link),
// or two outputs that are one file: a usage error before anything is written.
TEST(ApuAsmProgram, OutputsMustNotReplaceInputsOrEachOther) {
  TempDir dir;
  const std::string src = "halt\n";
  dir.write("k.apu", src);
  dir.write("x.bin", src);
  dir.write("sub/x.inc", "nop\n");
  dir.write("top.apu", ".include \"sub/x.inc\"\nhalt\n");
  const std::string hard = dir.path() + "/h.apu", soft = dir.path() + "/s.apu";
  ASSERT_EQ(link((dir.path() + "/k.apu").c_str(), hard.c_str()), 0);
  ASSERT_EQ(symlink("k.apu", soft.c_str()), 0);
  const auto before = names_in(dir.path());
  const std::pair<const char*, const char*> cases[] = {
      {"k.apu -o k.apu", "-o k.apu would replace the source k.apu"},
      {"k.apu -l ./k.apu", "-l ./k.apu would replace the source k.apu"},
      {"k.apu -x sub/../k.apu", "-x sub/../k.apu would replace the source k.apu"},
      {"k.apu -o h.apu", "-o h.apu would replace the source k.apu"},
      {"s.apu -l k.apu", "-l k.apu would replace the source s.apu"},
      {"x.bin", "-o (default) x.bin would replace the source x.bin"},
      {"k.apu -o y.bin -l y.bin", "-o and -l name one file: y.bin"},
      {"k.apu -o y.bin -x ./y.bin", "-o and -x name one file: ./y.bin"},
      {"k.apu -l y.lst -x sub/../y.lst", "-l and -x name one file: sub/../y.lst"},
      {"k.apu -l k.bin", "-l and -o (default) name one file: k.bin"},
      {"top.apu -l sub/x.inc -o t.bin", "-l sub/x.inc would replace the include file sub/x.inc"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = run_apuasm(dir, args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(r.err, "apuasm: " + std::string(message) + "\n") << args;
    EXPECT_EQ(names_in(dir.path()), before) << args;
  }
  EXPECT_EQ(slurp(dir.path() + "/k.apu"), src);
  EXPECT_EQ(slurp(dir.path() + "/sub/x.inc"), "nop\n");
  // A device is written in place: two outputs to /dev/null are no loss.
  EXPECT_EQ(run_apuasm(dir, "k.apu -o /dev/null -l /dev/null").status, 0);
  std::remove(hard.c_str());
  std::remove(soft.c_str());
}

TEST(ApuAsmProgram, HelpAndVersion) {
  TempDir dir;
  auto r = run_apuasm(dir, "--help");
  EXPECT_EQ(r.status, 0);
  for (const char* opt : {"-o FILE", "-l FILE", "-x FILE", "-d FILE", "--version", "SOURCE.apu"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt << " missing from\n" << r.out;
  r = run_apuasm(dir, "--version");
  EXPECT_EQ(r.status, 0);
  const std::string prefix = "apuasm (MC-1 virtual platform) ";  // every program's form
  ASSERT_EQ(r.out.rfind(prefix, 0), 0u) << r.out;
  const std::string version = r.out.substr(prefix.size());  // CMake's project(VERSION), e.g. "0.1.0\n"
  EXPECT_GE(version.size(), 6u) << r.out;
  EXPECT_EQ(version.find_first_not_of("0123456789.\n"), std::string::npos) << r.out;
}

// ---------------------------------------------------------------------------
// Disassembly round trips.

// One line per op of every slot, in the disassembler's own spelling.
const char* const kEveryOp[] = {
    "nop",
    "mul f1, f2, f3",
    "add f4, f5, f6",
    "sub f7, f8, f9",
    "cmp f10, f11",
    "float f12, f13",
    "fix f14, f15",
    "neg f16, f17",
    "abs f18, f19",
    "recip f20, f21",
    "sqrt f22, f23",
    "sin f24, f25",
    "cos f26, f27",
    "ld f28, [a1+4]",
    "st f29, [a2-7]",
    "ld f30, [a3]",
    "li a1, -3",
    "addi a2, a3, 100",
    "add a4, a5, a6",
    "sub a7, a8, a9",
    "muli a10, a11, -1000",
    "shl a12, a13, 3",
    "shr a14, a15, 15",
    "sra a1, a2, 1",
    "andi a3, a4, 0x00ff",
    "ori a5, a6, 0x8000",
    "xor a7, a8, a9",
    "movaf f31, a10",
    "movfa a11, f32",
    "lif f33, 1.5",
    "lif f33, -0.0",
    "lif f33, inf",
    "lif f33, 0x7f80",
    "jmp 0x010",
    "bcc lt+eq, 0x011",
    "bncc gt+un, 0x012",
    "bcc 0, 0x012",
    "dbnz a2, 0x013",
    "bz a3, 0x014",
    "bnz a4, 0x015",
    "bltz a5, 0x016",
    "call 0x3ff",
    "ret",
    "swapd",
    "swapp 0x020",
    "halt",
    "mul f1, f2, f3 | add f4, f5, f6 | sin f7, f8 | ld f9, [a1+4] | addi a1, a1, 8 | dbnz a2, 0x002",
};

TEST(ApuDisasm, EveryOpRoundTripsAsText) {
  for (const char* line : kEveryOp) {
    const auto e = one(line);
    EXPECT_EQ(apu::disassemble(e), line);
    EXPECT_EQ(one(apu::disassemble(e)), e) << line;
  }
}

TEST(ApuDisasm, LifLiteralTextCoversAllImmediates) {
  // Every 16-bit LIF immediate prints as a literal that assembles back to it
  // (64 programs of 1024 words).
  for (unsigned base = 0; base < 0x10000; base += 1024) {
    std::string src;
    for (unsigned imm = base; imm < base + 1024; ++imm)
      src += "lif f1, " + apu::lif_literal_text(static_cast<std::uint16_t>(imm)) + "\n";
    const auto p = assemble(src, "lif.apu");
    ASSERT_EQ(p.words.size(), 1024u);
    for (unsigned k = 0; k < 1024; ++k) ASSERT_EQ(MicroWord::decode(p.words[k]).i.imm, base + k);
  }
}

// Random words whose every field is legal and canonical (unused fields zero,
// no double writes): disassemble -> assemble is bit-exact.
MicroWord random_legal(std::mt19937& rng) {
  auto r = [&](unsigned n) { return static_cast<unsigned>(rng() % n); };
  MicroWord w;
  if (r(2)) w.m = {true, std::uint8_t(r(64)), std::uint8_t(r(64)), std::uint8_t(r(64))};
  if (r(2)) {
    w.a.en = true;
    w.a.op = AddOp(r(7));
    w.a.d = w.a.op == AddOp::Cmp ? 0 : std::uint8_t(r(64));
    w.a.a = std::uint8_t(r(64));
    const bool two = w.a.op == AddOp::Add || w.a.op == AddOp::Sub || w.a.op == AddOp::Cmp;
    w.a.b = two ? std::uint8_t(r(64)) : 0;
  }
  if (r(2)) w.f = {true, FuncOp(r(4)), std::uint8_t(r(64)), std::uint8_t(r(64))};
  w.d.op = MemOp(r(3));
  if (w.d.op != MemOp::None) {
    w.d.f = std::uint8_t(r(64));
    w.d.base = std::uint8_t(r(16));
    w.d.disp = static_cast<std::int8_t>(r(256));
  }
  w.i.op = IntOp(r(15));
  switch (w.i.op) {
    case IntOp::None: break;
    case IntOp::Li: w.i.d = std::uint8_t(r(16)); w.i.imm = std::uint16_t(r(65536)); break;
    case IntOp::Add:
    case IntOp::Sub:
    case IntOp::Xor: w.i.d = std::uint8_t(r(16)); w.i.s = std::uint8_t(r(16)); w.i.t = std::uint8_t(r(16)); break;
    case IntOp::Movaf: w.i.d = std::uint8_t(r(64)); w.i.s = std::uint8_t(r(16)); break;
    case IntOp::Movfa: w.i.d = std::uint8_t(r(16)); w.i.imm = std::uint16_t(r(64)); break;
    case IntOp::Lif: w.i.d = std::uint8_t(r(64)); w.i.imm = std::uint16_t(r(65536)); break;
    case IntOp::Shl:
    case IntOp::Shr:
    case IntOp::Sra: w.i.d = std::uint8_t(r(16)); w.i.s = std::uint8_t(r(16)); w.i.imm = std::uint16_t(r(16)); break;
    default: w.i.d = std::uint8_t(r(16)); w.i.s = std::uint8_t(r(16)); w.i.imm = std::uint16_t(r(65536)); break;
  }
  w.s.op = SeqOp(r(13));
  switch (w.s.op) {
    case SeqOp::Jmp:
    case SeqOp::Call:
    case SeqOp::Swapp: w.s.target = std::uint16_t(r(1024)); break;
    case SeqOp::Bcc:
    case SeqOp::Bncc:
    case SeqOp::Dbnz:
    case SeqOp::Bz:
    case SeqOp::Bnz:
    case SeqOp::Bltz: w.s.r = std::uint8_t(r(16)); w.s.target = std::uint16_t(r(1024)); break;
    default: break;
  }
  return w;
}

TEST(ApuDisasm, RandomLegalWordsRoundTrip) {
  std::mt19937 rng(20240601);
  int legal = 0;
  for (int n = 0; n < 20000; ++n) {
    const MicroWord w = random_legal(rng);
    const Encoded e = w.encode();
    const std::string text = apu::disassemble(w);
    if (!apu::noncanonical_reason(w).empty()) {
      // Only double writes make a random word here illegal.
      EXPECT_NE(apu::noncanonical_reason(w).find("written twice"), std::string::npos) << text;
      EXPECT_EQ(text.rfind(".word 0x", 0), 0u) << text;
    } else {
      ++legal;
      EXPECT_EQ(text.find(".word"), std::string::npos) << text;
    }
    ASSERT_EQ(one(text), e) << text;
  }
  EXPECT_GT(legal, 10000);
}

TEST(ApuDisasm, ArbitraryBitsRoundTripThroughWord) {
  std::mt19937_64 rng(7);
  for (int n = 0; n < 2000; ++n) {
    const Encoded e{rng(), rng()};
    ASSERT_EQ(one(apu::disassemble(e)), e) << apu::disassemble(e);
  }
  // A reserved op is shown, but as a raw word.
  MicroWord w;
  w.i.op = IntOp::Reserved;
  EXPECT_EQ(apu::disassemble(w), ".word 0x000000000000f000_0000000000000000  ; int.op15");
  EXPECT_EQ(apu::noncanonical_reason(w), "reserved I-slot op");
  w = MicroWord{};
  w.a = {true, AddOp::Neg, 1, 2, 3};  // NEG ignores b
  EXPECT_EQ(apu::noncanonical_reason(w), "nonzero unused field");
}

TEST(ApuDisasm, Helpers) {
  EXPECT_EQ(apu::cc_mask_text(0), "0");
  EXPECT_EQ(apu::cc_mask_text(5), "lt+gt");
  EXPECT_EQ(apu::cc_mask_text(15), "lt+eq+gt+un");
  EXPECT_EQ(apu::lif_literal_text(0x3F80), "1.5");
  EXPECT_EQ(apu::lif_literal_text(0x4000), "2.0");
  EXPECT_EQ(apu::lif_literal_text(0xBF00), "-1.0");
  EXPECT_EQ(apu::lif_literal_text(0x0001), "0x0001");  // e = 0: reads as zero, no literal
  EXPECT_EQ(apu::lif_literal_text(0x0100), "0x0100");  // 2^-62: 44 digits, shown raw
  EXPECT_EQ(apu::lif_literal_text(0xFF00), "-inf");
}

// ---------------------------------------------------------------------------
// Listing, image formats.

TEST(ApuAsmOutput, ListingFormat) {
  const auto p = assemble("# top\nstart: mul f1, f2, f3\n  halt\n", "t.apu");
  EXPECT_EQ(listing_text(p),
            "                                         # top\n"
            "0000  0000000000000000_0000000000006103  start: mul f1, f2, f3\n"
            "0001  0003000000000000_0000000000000000    halt\n");
  EXPECT_EQ(disassembly_text(p.words),
            "0000  0000000000000000_0000000000006103  mul f1, f2, f3\n"
            "0001  0003000000000000_0000000000000000  halt\n");
  EXPECT_EQ(readmemh_text(p.words),
            "00000000000000000000000000006103\n"
            "00030000000000000000000000000000\n");
}

TEST(ApuAsmOutput, ImageBytes) {
  const std::vector<Encoded> words = {{0x0123456789ABCDEFull, 0xFEDCBA9876543210ull}, {1, 2}};
  const std::string b = apu::image_bytes(words);
  ASSERT_EQ(b.size(), 8u + 32u);
  EXPECT_EQ(b.substr(0, 4), "APU1");
  EXPECT_EQ(static_cast<unsigned char>(b[4]), 2);
  EXPECT_EQ(static_cast<unsigned char>(b[8]), 0xEF);   // lo, little-endian
  EXPECT_EQ(static_cast<unsigned char>(b[16]), 0x10);  // hi
  EXPECT_EQ(static_cast<unsigned char>(b[24]), 1);
  EXPECT_EQ(static_cast<unsigned char>(b[32]), 2);
  EXPECT_EQ(apu::parse_image(b), words);
  EXPECT_THROW(apu::parse_image("APU0" + b.substr(4)), std::runtime_error);
  EXPECT_THROW(apu::parse_image(b.substr(0, b.size() - 1)), std::runtime_error);

  TempDir dir;
  const std::string path = dir.path() + "/x.bin";
  {
    std::ofstream out(path, std::ios::binary);
    out << b;
  }
  EXPECT_EQ(apu::load_image(path), words);
  std::remove(path.c_str());
}

// A directory or an endless device is refused, naming the path (issue 11).
TEST(ApuImage, LoadRefusesADirectoryAndAnEndlessDevice) {
  TempDir dir;
  try {
    apu::load_image(dir.path());
    FAIL() << "a directory was read as an image";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), dir.path() + ": is a directory (expected an APU image)");
  }
  try {
    apu::load_image("/dev/zero");
    FAIL() << "/dev/zero was read as an image";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "/dev/zero: not an APU image (no \"APU1\" header)");
  }
}

// ---------------------------------------------------------------------------
// The sample kernels assemble, and their loops are where they claim.

std::string kernel_path(const std::string& name) {
  std::string here = __FILE__;
  return here.substr(0, here.find_last_of('/')) + "/../firmware/kernels/" + name;
}

TEST(ApuKernels, Xform4) {
  const auto p = assemble_file(kernel_path("xform4.apu"));
  const int loop = static_cast<int>(p.symbols.at("loop"));
  const int last = static_cast<int>(p.symbols.at("last"));
  EXPECT_EQ(last - loop, 16);  // one vertex per 16 words
  const auto tail = MicroWord::decode(p.words[static_cast<size_t>(last - 1)]);
  EXPECT_EQ(tail.s.op, SeqOp::Dbnz);
  EXPECT_EQ(tail.s.target, loop);
  // The multiplier issues in every word of the loop, the adder in 12 of 16.
  int muls = 0, adds = 0;
  for (int a = loop; a < last; ++a) {
    const auto w = MicroWord::decode(p.words[static_cast<size_t>(a)]);
    muls += w.m.en;
    adds += w.a.en;
  }
  EXPECT_EQ(muls, 16);
  EXPECT_EQ(adds, 12);
  EXPECT_EQ(MicroWord::decode(p.words[0]).s.op, SeqOp::Swapd);
}

TEST(ApuKernels, Shade) {
  const auto p = assemble_file(kernel_path("shade.apu"));
  bool units[3] = {}, cmp = false, call = false;
  for (const auto& e : p.words) {
    const auto w = MicroWord::decode(e);
    units[0] |= w.m.en;
    units[1] |= w.a.en;
    units[2] |= w.f.en;
    cmp |= w.a.en && w.a.op == AddOp::Cmp;
    call |= w.s.op == SeqOp::Call;
  }
  EXPECT_TRUE(units[0] && units[1] && units[2] && cmp && call);
  EXPECT_EQ(MicroWord::decode(p.words[static_cast<size_t>(p.symbols.at("done"))]).s.op, SeqOp::Halt);
}

}  // namespace
}  // namespace mc1::apuasm
