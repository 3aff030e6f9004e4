// The expected diagnostic frame, computed without the APU: the op sequence
// of firmware/kernels/diag.apu, one FP24 model call per APU operation.
#include "diag.hpp"

#include "fp24.hpp"

namespace mc1::diag {
namespace {

// The kernel's LIF constants, as FP24 encodings (s e7 f16, bias 63).
constexpr fp24::Bits kSixteenth = 0x3B0000;  // 0.0625 = 2^-4
constexpr fp24::Bits kOne = 0x3F0000;        // 1.0
constexpr fp24::Bits k255 = 0x46FE00;        // 255.0 = 1.9921875 x 2^7
constexpr fp24::Bits k127_5 = 0x45FE00;      // 127.5 = 1.9921875 x 2^6

fp24::Bits v(fp24::Result r) { return r.value; }

std::uint8_t fix8(fp24::Bits a) { return static_cast<std::uint8_t>(fp24::to_int(a).value & 0xFF); }

}  // namespace

Rgb8 expected_pixel(std::uint16_t x, std::uint16_t y, std::uint16_t cx, std::uint16_t cy) {
  using namespace fp24;
  const Bits u = v(mul(v(from_int(static_cast<std::uint16_t>(x - cx))), kSixteenth));
  const Bits w = v(mul(v(from_int(static_cast<std::uint16_t>(y - cy))), kSixteenth));
  const Bits su = v(sin(u));
  const Bits cv = v(cos(w));
  const Bits r2 = v(add(v(mul(u, u)), v(mul(w, w))));
  const Bits q = v(recip(v(sqrt(v(add(v(mul(r2, kSixteenth)), kOne))))));
  const std::uint8_t red = fix8(v(mul(v(abs(su)), k255)));
  const std::uint8_t green = fix8(v(mul(q, k255)));
  const Bits p1 = v(add(v(mul(su, cv)), kOne));
  const std::uint8_t blue = fix8(v(mul(v(mul(p1, q)), k127_5)));
  return Rgb8{red, green, blue};
}

std::vector<std::uint8_t> expected_image(unsigned width, unsigned height) {
  std::vector<std::uint8_t> rgb;
  rgb.reserve(3u * width * height);
  const auto cx = centre(static_cast<std::uint16_t>(width));
  const auto cy = centre(static_cast<std::uint16_t>(height));
  for (unsigned y = 0; y < height; ++y)
    for (unsigned x = 0; x < width; ++x) {
      const Rgb8 c = expected_pixel(static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), cx, cy);
      rgb.insert(rgb.end(), {c.r, c.g, c.b});
    }
  return rgb;
}

}  // namespace mc1::diag
