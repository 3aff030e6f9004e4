#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

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

namespace {

bool wrong(const Image& a, const Image& b, std::size_t pixel, int threshold) {
  for (std::size_t c = 3 * pixel; c < 3 * pixel + 3; ++c)
    if (std::abs(int(a.rgb[c]) - int(b.rgb[c])) > threshold) return true;
  return false;
}

// The 8-connected cluster of wrong pixels holding `seed`, marked in `seen`
// (flood fill with an explicit stack: a frame-sized cluster must not overflow).
Cluster flood(const std::vector<char>& bad, std::vector<char>& seen, int w, int h, int seed) {
  Cluster c{0, seed % w, seed / w, seed % w, seed / w};
  std::vector<int> stack{seed};
  seen[seed] = 1;
  while (!stack.empty()) {
    int p = stack.back(), x = p % w, y = p / w;
    stack.pop_back();
    ++c.pixels;
    c.x0 = std::min(c.x0, x), c.x1 = std::max(c.x1, x), c.y0 = std::min(c.y0, y), c.y1 = std::max(c.y1, y);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        int nx = x + dx, ny = y + dy, n = ny * w + nx;
        if (nx < 0 || ny < 0 || nx >= w || ny >= h || !bad[n] || seen[n]) continue;
        seen[n] = 1;
        stack.push_back(n);
      }
  }
  return c;
}

}  // namespace

Defects defects(const Image& a, const Image& b, int threshold) {
  same_size(a, b);
  int n = a.width * a.height;
  std::vector<char> bad(n), seen(n);
  Defects d;
  for (int p = 0; p < n; ++p) d.wrong_pixels += bad[p] = wrong(a, b, std::size_t(p), threshold);
  for (int p = 0; p < n; ++p)
    if (bad[p] && !seen[p]) d.clusters.push_back(flood(bad, seen, a.width, a.height, p));
  std::stable_sort(d.clusters.begin(), d.clusters.end(),
                   [](const Cluster& x, const Cluster& y) { return x.pixels > y.pixels; });
  return d;
}

}  // namespace mc1::imgcmp
