// The APU disassembler (hw/apu/disasm): every op, random legal words and
// arbitrary bits round trip through text and the assembler.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

#include "apuasm.hpp"
#include "apuasm_test_util.hpp"
#include "disasm.hpp"

namespace mc1::apuasm {
namespace {

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

}  // namespace
}  // namespace mc1::apuasm
