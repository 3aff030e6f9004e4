// host/imgcmp/png: the libpng writer against the zlib encoder it replaced
// (kept here as the reference), reading every PNG colour type,
// and the hardening: size limits before allocation, truncated, corrupt and
// directory inputs named, failed writes leaving nothing behind.
#include <sys/resource.h>
#include <unistd.h>

#include <png.h>
#include <zlib.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "png.hpp"

namespace {

namespace fs = std::filesystem;
namespace imgcmp = mc1::imgcmp;
using Bytes = std::vector<std::uint8_t>;

Bytes pattern(std::uint32_t w, std::uint32_t h, unsigned seed) {
  Bytes rgb(3 * std::size_t{w} * h);
  std::uint32_t x = seed;
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    x = x * 1664525u + 1013904223u;
    // Smooth ramps with some noise, as a rendered frame has.
    rgb[i] = static_cast<std::uint8_t>((i / 3 % w) * 3 + (i / 3 / w) * 2 + (x >> 29));
  }
  return rgb;
}

// A fresh empty directory for one test.
fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / ("png_test_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write_bytes(const fs::path& p, const Bytes& b) {
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no error)";
}

void put32(Bytes& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}

void put_chunk(Bytes& out, const char* type, const Bytes& data) {
  put32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t from = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put32(out, static_cast<std::uint32_t>(crc32(0, out.data() + from, static_cast<uInt>(out.size() - from))));
}

// The zlib encoder mc1 wrote its frames with before libpng (hw/fm/png_writer
// until the change to libpng): filter None on every row, compress2 at level
// 6 into one IDAT. The reference for the bytes.
Bytes zlib_encoder(std::uint32_t w, std::uint32_t h, const std::uint8_t* rgb) {
  const std::size_t row = 3 * std::size_t{w};
  Bytes raw;
  for (std::uint32_t y = 0; y < h; ++y) {
    raw.push_back(0);
    raw.insert(raw.end(), rgb + y * row, rgb + (y + 1) * row);
  }
  uLongf zlen = compressBound(static_cast<uLong>(raw.size()));
  Bytes z(zlen);
  EXPECT_EQ(compress2(z.data(), &zlen, raw.data(), static_cast<uLong>(raw.size()), 6), Z_OK);
  z.resize(zlen);
  Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'}, ihdr;
  put32(ihdr, w);
  put32(ihdr, h);
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});
  put_chunk(png, "IHDR", ihdr);
  put_chunk(png, "IDAT", z);
  put_chunk(png, "IEND", {});
  return png;
}

// A well-formed PNG whose header claims w x h, with a few bytes of IDAT.
Bytes claiming(std::uint32_t w, std::uint32_t h) {
  Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'}, ihdr;
  put32(ihdr, w);
  put32(ihdr, h);
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});
  put_chunk(png, "IHDR", ihdr);
  put_chunk(png, "IDAT", {0x78, 0x9C, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01});
  put_chunk(png, "IEND", {});
  return png;
}

// Another PNG writer (libpng's simplified API) for the colour types ours
// never writes: grey, RGBA, palette.
Bytes other_writer(std::uint32_t w, std::uint32_t h, std::uint32_t format, const Bytes& pixels,
                   const Bytes& colormap = {}) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = w;
  image.height = h;
  image.format = format;
  image.colormap_entries = static_cast<png_uint_32>(colormap.size() / 3);
  png_alloc_size_t size = 0;
  const void* cmap = colormap.empty() ? nullptr : colormap.data();
  EXPECT_TRUE(png_image_write_to_memory(&image, nullptr, &size, 0, pixels.data(), 0, cmap)) << image.message;
  Bytes out(size);
  EXPECT_TRUE(png_image_write_to_memory(&image, out.data(), &size, 0, pixels.data(), 0, cmap)) << image.message;
  out.resize(size);
  return out;
}

}  // namespace

// Frames of mc1 (96x64 in tools/frame-check.sh and up) are byte for byte
// what the zlib encoder wrote: filter None, level 6, one IDAT.
TEST(PngWrite, SameBytesAsTheZlibEncoderForFrames) {
  const std::pair<std::uint32_t, std::uint32_t> sizes[] = {{96, 64}, {128, 128}, {320, 240}, {61, 90}};
  for (const auto& [w, h] : sizes)
    for (unsigned seed : {1u, 2u}) {
      const Bytes rgb = pattern(w, h, seed);
      EXPECT_EQ(imgcmp::encode_png_rgb8(w, h, rgb.data()), zlib_encoder(w, h, rgb.data()))
          << w << "x" << h << " seed " << seed;
    }
  const Bytes black(3 * 96 * 64, 0);
  EXPECT_EQ(imgcmp::encode_png_rgb8(96, 64, black.data()), zlib_encoder(96, 64, black.data()));
}

// Up to 16384 bytes of image data libpng writes the smallest zlib window
// that holds it into the zlib header (a compile-time option of Debian's
// libpng, PNG_WRITE_OPTIMIZE_CMF_SUPPORTED): those 2 bytes and the IDAT CRC
// differ from compress2's, the deflate data and the pixels do not.
TEST(PngWrite, SmallImagesDifferOnlyInTheZlibWindowField) {
  const std::pair<std::uint32_t, std::uint32_t> sizes[] = {{1, 1}, {5, 3}, {32, 32}, {60, 90}};
  for (const auto& [w, h] : sizes) {
    const Bytes rgb = pattern(w, h, 3);
    const Bytes ours = imgcmp::encode_png_rgb8(w, h, rgb.data()), old = zlib_encoder(w, h, rgb.data());
    ASSERT_EQ(ours.size(), old.size()) << w << "x" << h;
    const std::size_t zlib_header = 8 + 25 + 8, idat_crc = ours.size() - 12 - 4;
    for (std::size_t i = 0; i < ours.size(); ++i) {
      const bool may_differ = i == zlib_header || i == zlib_header + 1 || (i >= idat_crc && i < idat_crc + 4);
      if (!may_differ) {
        EXPECT_EQ(ours[i], old[i]) << w << "x" << h << " byte " << i;
      }
    }
    EXPECT_EQ(ours[zlib_header] & 0x0F, 8) << "deflate";
    EXPECT_LT(ours[zlib_header] >> 4, 7) << "a window smaller than 32 KiB";
    EXPECT_EQ(imgcmp::decode_png(ours, "ours").rgb, rgb);
    EXPECT_EQ(imgcmp::decode_png(old, "old").rgb, rgb);
  }
}

TEST(PngWrite, RefusesSizesOutsideTheLimits) {
  const Bytes px(3, 0);
  EXPECT_THROW(imgcmp::encode_png_rgb8(0, 1, px.data()), std::invalid_argument);
  EXPECT_THROW(imgcmp::encode_png_rgb8(1, 0, px.data()), std::invalid_argument);
  EXPECT_THROW(imgcmp::encode_png_rgb8(imgcmp::kMaxPngSide + 1, 1, px.data()), std::invalid_argument);
  EXPECT_THROW(imgcmp::encode_png_rgb8(imgcmp::kMaxPngSide, imgcmp::kMaxPngSide, px.data()), std::invalid_argument);
}

TEST(PngRead, RoundTripOfOurOwnFiles) {
  imgcmp::Image img(37, 21);
  img.rgb = pattern(37, 21, 9);
  const fs::path d = temp_dir("roundtrip");
  imgcmp::write_png((d / "a.png").string(), img);
  const imgcmp::Image back = imgcmp::read_png((d / "a.png").string());
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 21);
  EXPECT_EQ(back.rgb, img.rgb);
  EXPECT_EQ(std::vector<fs::path>(fs::directory_iterator(d), {}), std::vector<fs::path>{d / "a.png"})
      << "no temporary file left";
  fs::remove_all(d);
}

TEST(PngRead, GreyRgbaAndPaletteBecomeRgb8) {
  const Bytes grey = {0, 100, 255, 7, 8, 9};
  const imgcmp::Image g = imgcmp::decode_png(other_writer(3, 2, PNG_FORMAT_GRAY, grey), "grey");
  EXPECT_EQ(g.rgb, (Bytes{0, 0, 0, 100, 100, 100, 255, 255, 255, 7, 7, 7, 8, 8, 8, 9, 9, 9}));

  const Bytes rgba = {10, 20, 30, 255, 40, 50, 60, 0};
  const imgcmp::Image a = imgcmp::decode_png(other_writer(2, 1, PNG_FORMAT_RGBA, rgba), "rgba");
  EXPECT_EQ(a.rgb, (Bytes{10, 20, 30, 40, 50, 60})) << "alpha dropped, colours as stored";

  const Bytes colormap = {255, 0, 0, 0, 255, 0, 0, 0, 255}, indices = {2, 0, 1, 1};
  const imgcmp::Image p =
      imgcmp::decode_png(other_writer(2, 2, PNG_FORMAT_RGB_COLORMAP, indices, colormap), "palette");
  EXPECT_EQ(p.rgb, (Bytes{0, 0, 255, 255, 0, 0, 0, 255, 0, 0, 255, 0}));
}

// 69 bytes claiming 65536 x 65536 would need 12.9 GB: refused from the
// header, before any pixel memory is allocated.
TEST(PngRead, RefusesHugeHeadersBeforeAllocating) {
  const Bytes bomb = claiming(65536, 65536);
  EXPECT_LT(bomb.size(), 70u);
  EXPECT_EQ(error_of([&] { imgcmp::decode_png(bomb, "bomb.png"); }),
            "bomb.png: the header says 65536x65536, over the limit of 16384 a side and 67108864 pixels");
  EXPECT_NE(error_of([&] { imgcmp::decode_png(claiming(16385, 1), "wide.png"); }).find("over the limit"),
            std::string::npos);
  EXPECT_NE(error_of([&] { imgcmp::decode_png(claiming(16384, 4097), "big.png"); }).find("over the limit"),
            std::string::npos);
  // At the limit the header is accepted; the missing image data is then the error.
  EXPECT_EQ(error_of([&] { imgcmp::decode_png(claiming(16384, 1), "ok.png"); }), "ok.png: Not enough image data");
}

TEST(PngRead, BadFilesAreNamed) {
  const fs::path d = temp_dir("bad");
  const Bytes rgb = pattern(40, 30, 4);
  const Bytes good = imgcmp::encode_png_rgb8(40, 30, rgb.data());

  write_bytes(d / "cut.png", Bytes(good.begin(), good.end() - 30));
  EXPECT_EQ(error_of([&] { imgcmp::read_png((d / "cut.png").string()); }),
            (d / "cut.png").string() + ": the file ends early (truncated)");

  Bytes corrupt = good;
  corrupt[good.size() - 13] ^= 0x40;  // the last byte of IDAT's CRC
  write_bytes(d / "crc.png", corrupt);
  EXPECT_EQ(error_of([&] { imgcmp::read_png((d / "crc.png").string()); }),
            (d / "crc.png").string() + ": IDAT: CRC error");
  corrupt = good;
  corrupt[60] ^= 0x40;  // inside the deflate data: inflate fails before the CRC is seen
  write_bytes(d / "data.png", corrupt);
  const std::string data_error = error_of([&] { imgcmp::read_png((d / "data.png").string()); });
  EXPECT_EQ(data_error.rfind((d / "data.png").string() + ": IDAT: ", 0), 0u) << data_error;

  write_bytes(d / "text.png", Bytes{'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd', '\n'});
  EXPECT_EQ(error_of([&] { imgcmp::read_png((d / "text.png").string()); }),
            (d / "text.png").string() + ": Not a PNG file");

  write_bytes(d / "empty.png", {});
  EXPECT_EQ(error_of([&] { imgcmp::read_png((d / "empty.png").string()); }),
            (d / "empty.png").string() + ": the file ends early (truncated)");

  EXPECT_EQ(error_of([&] { imgcmp::read_png(d.string()); }), d.string() + ": is a directory, not a PNG file");
  EXPECT_EQ(error_of([&] { imgcmp::read_png((d / "none.png").string()); }),
            (d / "none.png").string() + ": cannot open: No such file or directory");
  fs::remove_all(d);
}

TEST(PngWriteFile, FailedWritesThrowAndLeaveNothing) {
  imgcmp::Image img(16, 16);
  EXPECT_EQ(error_of([&] { imgcmp::write_png("/dev/full", img); }),
            "/dev/full: cannot write: No space left on device");
  imgcmp::write_png("/dev/null", img);  // a device is written in place

  const fs::path d = temp_dir("fail");
  EXPECT_NE(error_of([&] { imgcmp::write_png((d / "no" / "dir.png").string(), img); }).find("cannot create a temporary file"),
            std::string::npos);
  EXPECT_EQ(error_of([&] { imgcmp::write_png(d.string(), img); }), d.string() + ": is a directory");

  // A write cut short by the file-size limit (EFBIG): exception, and
  // neither the PNG nor its temporary file remains.
  imgcmp::Image big(200, 200);
  big.rgb = pattern(200, 200, 5);
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 1000;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string err = error_of([&] { imgcmp::write_png((d / "big.png").string(), big); });
  setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(err, (d / "big.png").string() + ": cannot write: File too large");
  EXPECT_TRUE(fs::is_empty(d)) << "nothing left behind";

  // An existing file is replaced whole.
  imgcmp::write_png((d / "x.png").string(), big);
  imgcmp::write_png((d / "x.png").string(), img);
  EXPECT_EQ(imgcmp::read_png((d / "x.png").string()).width, 16);
  fs::remove_all(d);
}
