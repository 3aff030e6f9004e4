// A run of pixels as it travels on the image bus (s2: NCs write finished
// pixels to a dedicated image bus; the DC collects them into the FM).
// Wire format, little-endian: x:16, y:16, count:16, then count x (R, G, B).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace mc1 {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb8& o) const { return r == o.r && g == o.g && b == o.b; }
  bool operator!=(const Rgb8& o) const { return !(*this == o); }
};

struct PixelRun {
  std::uint16_t x = 0, y = 0;  // first pixel; the run goes right along row y
  std::vector<Rgb8> pixels;    // at most 65535
  bool operator==(const PixelRun& o) const { return x == o.x && y == o.y && pixels == o.pixels; }
};

constexpr std::size_t kRunHeaderBytes = 6;
constexpr std::size_t kBytesPerPixel = 3;

std::vector<std::uint8_t> encode_run(const PixelRun& run);
// nullopt if the length does not match the header's count.
std::optional<PixelRun> decode_run(const std::uint8_t* data, std::size_t length);

}  // namespace mc1
