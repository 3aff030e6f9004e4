// The output of step 3 (r_sum): each pixel's contributions summed in the
// order they were traced and quantised to RGB8 (docs/scene-format.md
// "Output").
#include <stdexcept>

#include "render_internal.hpp"

namespace mc1::render {

using namespace layout;

namespace {

// Pixels in batches of at most PIX_SLOTS whose contributions fit the pool
// (a pixel with more than the pool holds is an error).
struct SumBatch {
  int first = 0, n = 0;
};
constexpr int kPool = (BANK_WORDS - POOL) / POOL_SIZE;

std::vector<SumBatch> sum_batches(const std::vector<std::vector<std::array<std::uint32_t, 3>>>& contrib) {
  std::vector<SumBatch> batches;
  for (int p = 0; p < static_cast<int>(contrib.size());) {
    SumBatch b{p, 0};
    int pool = 0;
    while (p < static_cast<int>(contrib.size()) && b.n < PIX_SLOTS &&
           (b.n == 0 || pool + static_cast<int>(contrib[p].size()) <= kPool)) {
      if (static_cast<int>(contrib[p].size()) > kPool) throw std::runtime_error("r_sum: too many rays for a pixel");
      pool += static_cast<int>(contrib[p].size());
      ++b.n;
      ++p;
    }
    batches.push_back(b);
  }
  return batches;
}

}  // namespace

std::vector<Rgb8> RenderFirmware::sum(const std::vector<std::vector<std::array<std::uint32_t, 3>>>& contrib) {
  constexpr Step step = Step::Output;
  static_assert(POOL_SIZE == 3 && OUT_SIZE == 3, "a contribution and a pixel's output are rgb");
  const std::vector<SumBatch> batches = sum_batches(contrib);
  std::vector<Rgb8> out(contrib.size());
  auto fill = [&](int item) {
    const SumBatch& b = batches[item];
    std::vector<std::uint32_t> pix(PIX_SIZE * b.n), pool;
    for (int k = 0; k < b.n; ++k) {
      pix[PIX_SIZE * k + PIX_POOL] = static_cast<std::uint32_t>(POOL + pool.size());
      pix[PIX_SIZE * k + PIX_N] = static_cast<std::uint32_t>(contrib[b.first + k].size());
      for (const auto& c : contrib[b.first + k]) pool.insert(pool.end(), c.begin(), c.end());
    }
    write(PIX, pix.data(), pix.size(), step);
    if (!pool.empty()) write(POOL, pool.data(), pool.size(), step);
    write_count(b.n, step);
  };
  auto drain = [&](int item) {
    const SumBatch& b = batches[item];
    const auto& v = read(OUT, OUT_SIZE * b.n, step);
    for (int k = 0; k < b.n; ++k) {
      const auto* rgb = &v[OUT_SIZE * k];
      out[b.first + k] = Rgb8{static_cast<std::uint8_t>(rgb[0]), static_cast<std::uint8_t>(rgb[1]),
                              static_cast<std::uint8_t>(rgb[2])};
    }
  };
  stream("r_sum", static_cast<int>(batches.size()), step, fill, drain);
  return out;
}

}  // namespace mc1::render
