// What the firmware's files (render_*.cpp) share and its users need not see:
// the layout's consistency checks, the order-key boxes, ray predicates.
#pragma once

#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <vector>

#include "microword.hpp"
#include "render_fw.hpp"
#include "render_layout.hpp"

namespace mc1::render {

// The areas of r_layout.inc tile one data bank in order.
static_assert(layout::BANK_WORDS == apu::kDataWords, "r_layout.inc describes the APU's data bank");
static_assert(layout::LIGHTS + layout::L_SLOTS * layout::L_SIZE == layout::MATS, "lights end where materials begin");
static_assert(layout::MATS + layout::M_SLOTS * layout::M_SIZE == layout::PRIMS, "materials end at the primitives");
static_assert(layout::RAYS + layout::R_SLOTS * layout::R_SIZE == layout::BANK_WORDS, "rays end the bank");
static_assert((1 << layout::L_SHIFT) == layout::L_SIZE && (1 << layout::P_SHIFT) == layout::P_SIZE,
              "the kernels address lights and slots by shifts");
static_assert(layout::OUT + layout::PIX_SLOTS * layout::OUT_SIZE <= layout::PIX, "r_sum's output below its input");

// A box of FP24 order keys (min xyz, max xyz); empty, and grown to hold another.
using KeyBox = std::array<std::int32_t, 6>;
constexpr KeyBox kEmptyBox = {INT32_MAX, INT32_MAX, INT32_MAX, INT32_MIN, INT32_MIN, INT32_MIN};
inline void grow_box(KeyBox& b, const KeyBox& p) {
  for (int c = 0; c < 3; ++c) {
    b[c] = std::min(b[c], p[c]);
    b[3 + c] = std::max(b[3 + c], p[3 + c]);
  }
}

constexpr std::uint32_t kOne = 0x3F0000;  // FP24 1.0

// Triangles and pseudo triangles (P_TYPE): what r_scan draws and r_box projects.
inline bool is_triangle(std::uint32_t type) { return type == kTriangle || type == kPseudoTriangle; }

inline bool is_hit(const RenderFirmware::Ray& r) { return r.rec[layout::R_ID] != kNoHit; }
inline bool is_shadow(std::uint32_t kind) { return kind == layout::RK_SHADOW || kind == layout::RK_SHADOW_GIVEN; }
// The kind of a ray cast again (a later chunk of its candidates, or past a
// hidden hit) with the O, D and t limit an earlier r_cast pass wrote back.
inline std::uint32_t as_given(std::uint32_t kind) {
  if (kind == layout::RK_EYE || kind == layout::RK_EYE_SCAN) return layout::RK_EYE_GIVEN;
  return kind == layout::RK_SHADOW ? layout::RK_SHADOW_GIVEN : kind;
}

// Batches of at most `per` of `items` things.
inline int batch_count(int items, int per) { return (items + per - 1) / per; }

// Per chunk level c, the batches (of `batches`) that have a chunk c, of
// chunks(b) chunks each: chunk c + 1 continues chunk c's results, so each
// level is one stream.
template <class Chunks>
std::vector<std::vector<int>> chunk_levels(int batches, Chunks chunks) {
  std::vector<std::vector<int>> levels;
  for (int b = 0; b < batches; ++b) {
    const std::size_t n = chunks(b);
    if (levels.size() < n) levels.resize(n);
    for (std::size_t c = 0; c < n; ++c) levels[c].push_back(b);
  }
  return levels;
}

}  // namespace mc1::render
