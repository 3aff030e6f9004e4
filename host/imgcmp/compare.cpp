#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "image.hpp"

namespace mc1::imgcmp {
namespace {

void same_size(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw ImageError("images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                     " and " + std::to_string(b.width) + "x" + std::to_string(b.height));
}

}  // namespace

double mse(const Image& a, const Image& b) {
  same_size(a, b);
  double sum = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    double d = double(a.rgb[i]) - double(b.rgb[i]);
    sum += d * d;
  }
  return a.rgb.empty() ? 0.0 : sum / double(a.rgb.size());
}

double psnr(const Image& a, const Image& b) {
  double e = mse(a, b);
  if (e == 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(255.0 * 255.0 / e);
}

int max_abs_diff(const Image& a, const Image& b) {
  same_size(a, b);
  int m = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) m = std::max(m, std::abs(int(a.rgb[i]) - int(b.rgb[i])));
  return m;
}

Image difference(const Image& a, const Image& b, int scale) {
  same_size(a, b);
  Image d(a.width, a.height);
  for (std::size_t i = 0; i < a.rgb.size(); ++i)
    d.rgb[i] = static_cast<std::uint8_t>(std::min(255, scale * std::abs(int(a.rgb[i]) - int(b.rgb[i]))));
  return d;
}

}  // namespace mc1::imgcmp
