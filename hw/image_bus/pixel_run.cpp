#include "pixel_run.hpp"

#include <stdexcept>

namespace mc1 {

std::vector<std::uint8_t> encode_run(const PixelRun& run) {
  if (run.pixels.size() > 0xFFFF) throw std::length_error("encode_run: more than 65535 pixels");
  const auto n = static_cast<std::uint16_t>(run.pixels.size());
  std::vector<std::uint8_t> b;
  b.reserve(kRunHeaderBytes + kBytesPerPixel * n);
  for (std::uint16_t v : {run.x, run.y, n}) {
    b.push_back(static_cast<std::uint8_t>(v & 0xFF));
    b.push_back(static_cast<std::uint8_t>(v >> 8));
  }
  for (const Rgb8& p : run.pixels) {
    b.push_back(p.r);
    b.push_back(p.g);
    b.push_back(p.b);
  }
  return b;
}

std::optional<PixelRun> decode_run(const std::uint8_t* d, std::size_t length) {
  if (length < kRunHeaderBytes) return std::nullopt;
  auto u16 = [d](std::size_t i) { return static_cast<std::uint16_t>(d[i] | d[i + 1] << 8); };
  PixelRun run;
  run.x = u16(0);
  run.y = u16(2);
  const std::size_t n = u16(4);
  if (length != kRunHeaderBytes + kBytesPerPixel * n) return std::nullopt;
  run.pixels.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* p = d + kRunHeaderBytes + kBytesPerPixel * i;
    run.pixels[i] = Rgb8{p[0], p[1], p[2]};
  }
  return run;
}

}  // namespace mc1
