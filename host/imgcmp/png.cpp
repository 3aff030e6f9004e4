// PNG (ISO/IEC 15948) for 8-bit RGB: zlib for deflate and CRC.
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include <zlib.h>

#include "image.hpp"

namespace mc1::imgcmp {
namespace {

const std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}

std::uint32_t get32(const std::uint8_t* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}

void chunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& data) {
  put32(out, static_cast<std::uint32_t>(data.size()));
  std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  uLong crc = crc32(0L, out.data() + start, static_cast<uInt>(out.size() - start));
  put32(out, static_cast<std::uint32_t>(crc));
}

int paeth(int a, int b, int c) {
  int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return (pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c);
}

}  // namespace

std::vector<std::uint8_t> encode_png(const Image& img) {
  std::vector<std::uint8_t> raw;
  std::size_t row = static_cast<std::size_t>(img.width) * 3;
  raw.reserve((row + 1) * img.height);
  for (int y = 0; y < img.height; ++y) {
    raw.push_back(0);  // filter: none
    raw.insert(raw.end(), img.rgb.begin() + y * row, img.rgb.begin() + (y + 1) * row);
  }
  uLongf zlen = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> z(zlen);
  if (compress2(z.data(), &zlen, raw.data(), static_cast<uLong>(raw.size()), 6) != Z_OK)
    throw ImageError("png: deflate failed");
  z.resize(zlen);
  std::vector<std::uint8_t> out(kSignature, kSignature + 8), ihdr;
  put32(ihdr, static_cast<std::uint32_t>(img.width));
  put32(ihdr, static_cast<std::uint32_t>(img.height));
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8-bit, RGB, deflate, filter 0, no interlace
  chunk(out, "IHDR", ihdr);
  chunk(out, "IDAT", z);
  chunk(out, "IEND", {});
  return out;
}

void write_png(const std::string& path, const Image& img) {
  std::vector<std::uint8_t> bytes = encode_png(img);
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!f) throw ImageError(path + ": cannot write");
}

Image decode_png(const std::vector<std::uint8_t>& b, const std::string& name) {
  auto bad = [&](const std::string& m) { return ImageError(name + ": " + m); };
  if (b.size() < 8 || std::memcmp(b.data(), kSignature, 8) != 0) throw bad("not a PNG file");
  Image img;
  std::vector<std::uint8_t> z;
  bool seen_ihdr = false, seen_iend = false;
  for (std::size_t p = 8; p + 12 <= b.size() && !seen_iend;) {
    std::uint32_t len = get32(&b[p]);
    if (p + 12 + len > b.size()) throw bad("truncated chunk");
    std::string type(reinterpret_cast<const char*>(&b[p + 4]), 4);
    const std::uint8_t* data = &b[p + 8];
    if (crc32(crc32(0L, Z_NULL, 0), &b[p + 4], len + 4) != get32(&b[p + 8 + len])) throw bad("CRC error in " + type);
    if (type == "IHDR") {
      if (len != 13) throw bad("bad IHDR");
      img.width = static_cast<int>(get32(data));
      img.height = static_cast<int>(get32(data + 4));
      if (data[8] != 8 || data[9] != 2 || data[12] != 0)
        throw bad("only 8-bit RGB non-interlaced PNG is supported");
      if (img.width <= 0 || img.height <= 0 || img.width > 65536 || img.height > 65536) throw bad("bad size");
      seen_ihdr = true;
    } else if (type == "IDAT") {
      z.insert(z.end(), data, data + len);
    } else if (type == "IEND") {
      seen_iend = true;
    }
    p += 12 + len;
  }
  if (!seen_ihdr || !seen_iend) throw bad("missing IHDR or IEND");
  std::size_t row = static_cast<std::size_t>(img.width) * 3;
  std::vector<std::uint8_t> raw((row + 1) * img.height);
  uLongf rawlen = static_cast<uLongf>(raw.size());
  if (uncompress(raw.data(), &rawlen, z.data(), static_cast<uLong>(z.size())) != Z_OK || rawlen != raw.size())
    throw bad("bad image data");
  img.rgb.assign(row * img.height, 0);
  for (int y = 0; y < img.height; ++y) {
    int filter = raw[y * (row + 1)];
    const std::uint8_t* src = &raw[y * (row + 1) + 1];
    std::uint8_t* dst = &img.rgb[y * row];
    const std::uint8_t* up = y > 0 ? &img.rgb[(y - 1) * row] : nullptr;
    for (std::size_t i = 0; i < row; ++i) {
      int a = i >= 3 ? dst[i - 3] : 0, u = up ? up[i] : 0, c = (up && i >= 3) ? up[i - 3] : 0;
      int pred = filter == 0 ? 0 : filter == 1 ? a : filter == 2 ? u : filter == 3 ? (a + u) / 2 : paeth(a, u, c);
      if (filter > 4) throw bad("bad filter type");
      dst[i] = static_cast<std::uint8_t>(src[i] + pred);
    }
  }
  return img;
}

Image read_png(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw ImageError(path + ": cannot open");
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  return decode_png(bytes, path);
}

}  // namespace mc1::imgcmp
