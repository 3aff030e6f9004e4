// The APU assembler (host/apuasm): directives (labels, .equ, .org, .include,
// macros) and hostile sources (checked integer operations, bounded
// expansion, directories refused; issue 11).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>
#include <sys/stat.h>
#include <unistd.h>

#include "apuasm.hpp"
#include "apuasm_expr.hpp"
#include "apuasm_macros.hpp"
#include "apuasm_test_util.hpp"

namespace mc1::apuasm {
namespace {

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

}  // namespace
}  // namespace mc1::apuasm
