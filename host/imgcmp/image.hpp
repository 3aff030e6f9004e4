// RGB8 images, their PNG files (png.hpp), and the comparisons used to check a rendered
// frame against the reference renderer (PSNR, difference image).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace mc1::imgcmp {

// Rows top first, pixels left to right, 3 bytes (R, G, B) each.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0) {}
  std::uint8_t* at(int x, int y) { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
  const std::uint8_t* at(int x, int y) const {
    return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  }
};

class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Mean squared error over all 3 * width * height samples.
double mse(const Image& a, const Image& b);
// 10 log10(255^2 / MSE) in dB; +infinity for identical images.
double psnr(const Image& a, const Image& b);
int max_abs_diff(const Image& a, const Image& b);
// Per sample min(255, scale * |a - b|).
Image difference(const Image& a, const Image& b, int scale);

// A defect: an 8-connected cluster of pixels where some channel differs by more
// than a threshold. PSNR averages a few wrong pixels away; a cluster of them is
// a visible streak or blotch, not rounding noise.
struct Cluster {
  int pixels = 0;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // bounding box, inclusive
};
struct Defects {
  int wrong_pixels = 0;               // pixels with a channel error > threshold
  std::vector<Cluster> clusters;      // largest first (ties: top-left first)
};
Defects defects(const Image& a, const Image& b, int threshold);

}  // namespace mc1::imgcmp

// The PNG files of an Image (read_png, write_png, ...) come with it.
#include "png.hpp"  // IWYU pragma: export
