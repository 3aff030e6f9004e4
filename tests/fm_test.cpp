// Frame memory: TLM access, bounds, write cost; PNG writer round trip decoded
// here with zlib's uncompress (signature, IHDR, chunk CRCs, IEND, pixels).
#include <zlib.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "frame_memory.hpp"
#include "png_writer.hpp"
#include "sc_test_harness.hpp"

using namespace mc1;
using sc_core::sc_time;
using sc_core::SC_NS;

namespace {

using Bytes = std::vector<std::uint8_t>;

std::uint32_t be32(const Bytes& b, std::size_t i) {
  return static_cast<std::uint32_t>(b[i]) << 24 | b[i + 1] << 16 | b[i + 2] << 8 | b[i + 3];
}

struct Chunk {
  std::string type;
  Bytes data;
  bool crc_ok;
};

// A strict reader for the subset encode_png_rgb8 writes.
std::vector<Chunk> chunks(const Bytes& png) {
  std::vector<Chunk> out;
  std::size_t i = 8;
  while (i + 12 <= png.size()) {
    const std::uint32_t len = be32(png, i);
    if (i + 12 + len > png.size()) break;
    Chunk c;
    c.type.assign(png.begin() + i + 4, png.begin() + i + 8);
    c.data.assign(png.begin() + i + 8, png.begin() + i + 8 + len);
    const uLong crc = crc32(0L, png.data() + i + 4, 4 + len);
    c.crc_ok = crc == be32(png, i + 8 + len);
    out.push_back(c);
    i += 12 + len;
  }
  EXPECT_EQ(i, png.size()) << "trailing bytes after the last chunk";
  return out;
}

Rgb8 pattern(unsigned x, unsigned y) {
  return Rgb8{static_cast<std::uint8_t>(x * 40), static_cast<std::uint8_t>(y * 50),
              static_cast<std::uint8_t>(0xFF - x - y)};
}

class FrameMemoryTest : public test::SystemCTest {};

}  // namespace

TEST(Png, SignatureIhdrIdatIendAndPixels) {
  const unsigned w = 7, h = 5;  // odd width: rows are 21 bytes, no padding
  Bytes rgb;
  for (unsigned y = 0; y < h; ++y)
    for (unsigned x = 0; x < w; ++x) {
      const Rgb8 c = pattern(x, y);
      rgb.insert(rgb.end(), {c.r, c.g, c.b});
    }
  const Bytes png = encode_png_rgb8(w, h, rgb.data());
  ASSERT_GE(png.size(), 8u);
  EXPECT_EQ(Bytes(png.begin(), png.begin() + 8),
            (Bytes{0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A}));
  const auto cs = chunks(png);
  ASSERT_EQ(cs.size(), 3u);
  EXPECT_EQ(cs[0].type, "IHDR");
  EXPECT_EQ(cs[0].data, (Bytes{0, 0, 0, 7, 0, 0, 0, 5, 8, 2, 0, 0, 0}));
  EXPECT_EQ(cs[1].type, "IDAT");
  EXPECT_EQ(cs[2].type, "IEND");
  EXPECT_TRUE(cs[2].data.empty());
  for (const Chunk& c : cs) EXPECT_TRUE(c.crc_ok) << c.type;
  // The IEND chunk of every PNG: length 0, "IEND", CRC AE 42 60 82.
  EXPECT_EQ(Bytes(png.end() - 12, png.end()),
            (Bytes{0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82}));

  Bytes raw((1 + 3 * w) * h + 16);
  uLongf n = raw.size();
  ASSERT_EQ(uncompress(raw.data(), &n, cs[1].data.data(), cs[1].data.size()), Z_OK);
  ASSERT_EQ(n, (1 + 3 * w) * h);
  for (unsigned y = 0; y < h; ++y) {
    const std::uint8_t* row = raw.data() + y * (1 + 3 * w);
    EXPECT_EQ(row[0], 0) << "filter byte of row " << y;
    for (unsigned x = 0; x < w; ++x)
      EXPECT_EQ((Rgb8{row[1 + 3 * x], row[2 + 3 * x], row[3 + 3 * x]}), pattern(x, y))
          << x << "," << y;
  }
  EXPECT_THROW(encode_png_rgb8(0, 1, rgb.data()), std::invalid_argument);
}

TEST_F(FrameMemoryTest, TlmWriteReadBoundsAndCost) {
  TimingParams t;  // 300 ns per pixel written
  FrameMemory fm("fm", t, 8, 4, Rgb8{1, 2, 3});
  EXPECT_EQ(fm.pixel(7, 3), (Rgb8{1, 2, 3}));

  Bytes px = {10, 11, 12, 20, 21, 22};  // two pixels at (6, 2)
  tlm::tlm_generic_payload p;
  p.set_command(tlm::TLM_WRITE_COMMAND);
  p.set_address(3 * (2 * 8 + 6));
  p.set_data_ptr(px.data());
  p.set_data_length(6);
  p.set_streaming_width(6);
  sc_time d = sc_core::SC_ZERO_TIME;
  fm.dc2fm.get_base_interface().b_transport(p, d);
  EXPECT_EQ(p.get_response_status(), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(d, sc_time(600, SC_NS));
  EXPECT_EQ(fm.pixel(6, 2), (Rgb8{10, 11, 12}));
  EXPECT_EQ(fm.pixel(7, 2), (Rgb8{20, 21, 22}));
  EXPECT_EQ(fm.pixels_written(), 2u);

  Bytes back(6);
  p.set_command(tlm::TLM_READ_COMMAND);
  p.set_data_ptr(back.data());
  d = sc_core::SC_ZERO_TIME;
  fm.dc2fm.get_base_interface().b_transport(p, d);
  EXPECT_EQ(p.get_response_status(), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(back, px);

  // The last pixel plus one byte is past the end.
  p.set_command(tlm::TLM_WRITE_COMMAND);
  p.set_address(3 * (4 * 8 - 1));
  p.set_data_length(4);
  fm.dc2fm.get_base_interface().b_transport(p, d);
  EXPECT_EQ(p.get_response_status(), tlm::TLM_ADDRESS_ERROR_RESPONSE);
  EXPECT_EQ(fm.pixel(7, 3), (Rgb8{1, 2, 3}));
}

TEST_F(FrameMemoryTest, PngFileRoundTrip) {
  TimingParams t;
  FrameMemory fm("fm", t, 7, 5);
  for (unsigned y = 0; y < 5; ++y)
    for (unsigned x = 0; x < 7; ++x) fm.set_pixel(x, y, pattern(x, y));
  const std::string path =
      ::testing::TempDir() + "fm_test_" + std::to_string(::getpid()) + ".png";
  const Bytes png = encode_png_rgb8(fm.width(), fm.height(), fm.rgb().data());
  write_file(path, png);
  std::ifstream f(path, std::ios::binary);
  const Bytes file((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  std::remove(path.c_str());
  EXPECT_EQ(file, png);
  const auto cs = chunks(file);
  ASSERT_EQ(cs.size(), 3u);
  Bytes raw(6 * 22);
  uLongf n = raw.size();
  ASSERT_EQ(uncompress(raw.data(), &n, cs[1].data.data(), cs[1].data.size()), Z_OK);
  ASSERT_EQ(n, 5u * 22u);
  EXPECT_EQ((Rgb8{raw[4 * 22 + 1 + 18], raw[4 * 22 + 2 + 18], raw[4 * 22 + 3 + 18]}),
            pattern(6, 4));
}

MC1_SYSTEMC_GTEST_MAIN()
