// Step 2 of fig. 3: the object boxes and triangles projected on the screen
// (r_box, fig. 5) once per frame, and per block the list of the objects that
// may appear in it, nearest first.
#include "render_internal.hpp"

namespace mc1::render {

using namespace layout;

static_assert(P_P1 == P_P0 + 3 && P_P2 == P_P0 + 6, "a triangle's v0, v1, v2 are r_box's three points");

bool RenderFirmware::ScreenRect::overlaps(const Block& b) const {
  if (status == kBehind) return false;
  if (status == kWholeScreen) return true;
  return i0 <= b.x0 + b.w - 1 && i1 >= b.x0 && j0 <= b.y0 + b.h - 1 && j1 >= b.y0;
}

// fig. 5: every object box (four points: x / z and y / z are extreme at
// (min, min, zmin), (max, max, zmin), (min, min, zmax), (max, max, zmax)) and
// every triangle (its vertices) projected on the screen by r_box, once per
// frame; the MPU keeps the integer rectangles.
void RenderFirmware::project_boxes() {
  constexpr Step step = Step::BlockLists;
  struct Item {
    std::array<std::uint32_t, B_IN> w{};
    ScreenRect* out = nullptr;
    int triangle = -1;
  };
  object_rect_.assign(view_.objects.size(), ScreenRect{});
  prim_rect_.assign(view_.prims.size(), ScreenRect{});
  prim_box_.assign(view_.prims.size(), {});
  std::vector<Item> items;
  for (std::size_t o = 0; o < view_.objects.size(); ++o) {
    const auto& b = view_.objects[o].box;  // min xyz, max xyz
    Item it;
    it.w[B_KIND] = BK_POINTS;
    const int corner[B_NPTS][3] = {{0, 1, 2}, {3, 4, 2}, {0, 1, 5}, {3, 4, 5}};
    for (int p = 0; p < B_NPTS; ++p)
      for (int c = 0; c < 3; ++c) it.w[B_PTS + 3 * p + c] = b[corner[p][c]];
    it.out = &object_rect_[o];
    items.push_back(it);
  }
  for (std::size_t k = 0; k < view_.prims.size(); ++k) {
    const auto& p = view_.prims[k];
    if (!is_triangle(p[P_TYPE])) continue;
    Item it;
    it.w[B_KIND] = BK_TRI;
    std::copy(p.begin() + P_P0, p.begin() + P_P0 + 9, it.w.begin() + B_PTS);  // v0, v1, v2
    it.out = &prim_rect_[k];
    it.triangle = static_cast<int>(k);
    items.push_back(it);
  }
  ItemStream s{static_cast<int>(items.size()), B_PER_BATCH, B_ITEMS, B_SIZE, true};
  s.put = [&](int i, std::uint16_t addr) { write(addr, items[i].w.data(), B_IN, step); };
  s.get = [&](int i, std::uint16_t addr) {
    const Item& it = items[i];
    const auto& v = read(addr, it.triangle >= 0 ? B_OUT_TRI : B_OUT, step);
    if (it.triangle >= 0)
      for (int c = 0; c < 6; ++c) prim_box_[it.triangle][c] = order_key(v[B_BOX + c]);
    ScreenRect& r = *it.out;
    r.status = static_cast<int>(v[B_STATUS]);
    r.i0 = static_cast<std::int16_t>(v[B_I0]);
    r.i1 = static_cast<std::int16_t>(v[B_I1]);
    r.j0 = static_cast<std::int16_t>(v[B_J0]);
    r.j1 = static_cast<std::int16_t>(v[B_J1]);
  };
  stream_items("r_box", step, s);
}

BlockList RenderFirmware::build_block_list(const Block& block) {
  auto& c = cost(Step::BlockLists);
  BlockList bl;
  bl.block = block;
  // The objects whose projected box (r_box) overlaps the block. Sort key:
  // the nearest distance of the box along the view axis, -max z (the view
  // looks down -z), 0 if the box reaches the eye plane; as a non-negative
  // FP24 number it orders as an integer.
  std::vector<std::pair<std::uint32_t, int>> keyed;
  for (int o = 0; o < static_cast<int>(view_.objects.size()); ++o) {
    c.list_elements += 1;
    if (view_.objects[o].prim_count == 0 || !object_rect_.at(o).overlaps(block)) continue;
    const std::uint32_t zmax = view_.objects[o].box[3 + 2];
    // distance = -zmax, or 0 when the box contains the eye plane
    const std::uint32_t key = (zmax & 0x800000) ? (zmax & 0x7FFFFF) : 0;
    keyed.emplace_back(key, o);
  }
  std::uint64_t compares = 0;  // this list's: c.sort_compares is the step's, over every list so far
  std::stable_sort(keyed.begin(), keyed.end(), [&](const auto& a, const auto& b) {
    ++compares;
    return a.first < b.first;
  });
  c.sort_compares += compares;
  link_.sort_compares(compares);
  for (const auto& [key, o] : keyed) {
    bl.objects.push_back(o);
    bl.load += view_.objects[o].secondary ? 4 : 1;
  }
  return bl;
}

}  // namespace mc1::render
