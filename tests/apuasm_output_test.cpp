// The APU assembler's outputs (host/apuasm): the listing and image formats,
// loading an image (hw/apu/apu_image), and the sample kernels assembled.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "apu_image.hpp"
#include "apuasm.hpp"
#include "apuasm_test_util.hpp"

namespace mc1::apuasm {
namespace {

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
