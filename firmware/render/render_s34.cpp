// s3 and s4 of fig. 3: r_shade's weighted local colour of every ray and the
// data of its reflected and transmitted rays; those rays as the next
// generation, with their candidate lists.
#include "render_internal.hpp"

namespace mc1::render {

using namespace layout;

static_assert(R_CHILD == R_OUT + 3 && R_RW == R_RD + 3 && R_TW == R_TD + 3, "r_shade's results, read in runs");

// Only the words r_shade reads go in (R_D .. R_ID, R_P .. R_SHADOW, R_CHILD,
// R_SOLID: 22 of 48), and only the words it wrote come back (R_OUT, R_CHILD,
// and a child's direction and weight where its bit is set): the MPU's copies
// were most of s3's time, the APU waiting at SWAPD (docs/renderer.md "Timing").
void RenderFirmware::shade(std::vector<Ray>& rays, Step step) {
  ItemStream s{static_cast<int>(rays.size()), kRaysPerBatch, RAYS, R_SIZE, true};
  auto put = [&](const Ray& r, std::uint16_t addr, int first, int last) {
    write(static_cast<std::uint16_t>(addr + first), r.rec.data() + first, static_cast<std::size_t>(last - first + 1),
          step);
  };
  s.put = [&](int i, std::uint16_t addr) {
    put(rays[i], addr, R_D, R_ID);
    put(rays[i], addr, R_P, R_SHADOW);
    put(rays[i], addr, R_CHILD, R_CHILD);
    put(rays[i], addr, R_SOLID, R_SOLID);
  };
  s.get = [&](int i, std::uint16_t addr) {
    auto& rec = rays[i].rec;
    auto get = [&](int first, int words) {
      const auto& back = read(static_cast<std::uint16_t>(addr + first), static_cast<std::size_t>(words), step);
      std::copy(back.begin(), back.end(), rec.begin() + first);
    };
    get(R_OUT, R_CHILD + 1 - R_OUT);
    if (rec[R_CHILD] & CHILD_RD) get(R_RD, R_RW + 3 - R_RD);
    if (rec[R_CHILD] & CHILD_TD) get(R_TD, R_TW + 3 - R_TD);
  };
  stream_items("r_shade", step, s);
}

// s4's candidates, one list per ray: every primitive in file order, as the
// paper's s4 has no lists, less the triangles that lie wholly behind the
// ray. A ray with d_c >= 0 (sign bit clear) never reaches a point with x_c
// below its origin's, so a triangle whose padded view box (r_box, 16
// epsilon) ends below it cannot be hit; the same for d_c < 0 and a box that
// begins above it. An object whose triangles' box is behind is passed over
// whole. Regions are kept. MPU work: order keys and sign bits compared as
// integers. Teapot 64x48 on 4 NCs, s4 APU cycles: 98 M with no culling,
// 11 M with a list per ray (an r_cast batch then holds 8 rays, not 32);
// lists shared by groups of 2 or 4 consecutive rays (culling on the axes
// where all agree) gave 19 M and 30 M.
void RenderFirmware::secondary_candidates(std::vector<Ray>& rays, std::vector<std::vector<int>>& lists) {
  auto& c = cost(Step::Secondary);
  lists.reserve(lists.size() + rays.size());
  std::vector<int> list;  // built here, kept at its size: one allocation a ray
  for (Ray& r : rays) {
    std::array<std::int32_t, 3> origin;
    unsigned negative = 0;  // bit a: d_a's sign bit
    for (int a = 0; a < 3; ++a) {
      origin[a] = order_key(r.rec[R_O + a]);
      negative |= ((r.rec[R_D + a] >> 23) & 1u) << a;
    }
    auto behind = [&](const Box& b) {
      for (int a = 0; a < 3; ++a)
        if ((negative >> a) & 1 ? b[a] > origin[a] : b[3 + a] < origin[a]) return true;
      return false;
    };
    list.clear();
    for (std::size_t o = 0; o < view_.objects.size(); ++o) {
      const auto& obj = view_.objects[o];
      const bool skip_triangles = behind(object_tri_box_[o]);
      c.list_elements += skip_triangles ? 1 : obj.prim_count;
      for (int q = obj.first_prim; q < obj.first_prim + obj.prim_count; ++q) {
        if (is_triangle(view_.prims[q][P_TYPE]) && (skip_triangles || behind(prim_box_[q]))) continue;
        list.push_back(q);
      }
    }
    r.list = static_cast<int>(lists.size());
    lists.emplace_back(list.begin(), list.end());
  }
}

std::vector<RenderFirmware::Ray> RenderFirmware::children(const std::vector<Ray>& gen, int depth) const {
  struct Child {
    std::uint32_t bit;
    int dir, weight;
  };
  constexpr Child kChildren[2] = {{CHILD_RD, R_RD, R_RW}, {CHILD_TD, R_TD, R_TW}};  // reflected first
  const std::uint32_t big = scene_words_[C_BIG - C_D0];
  std::vector<Ray> next;
  for (const auto& r : gen)
    for (const Child& c : kChildren) {
      if (!(r.rec[R_CHILD] & c.bit)) continue;
      Ray k;
      std::copy(r.rec.begin() + R_P, r.rec.begin() + R_P + 3, k.rec.begin() + R_O);
      std::copy(r.rec.begin() + c.dir, r.rec.begin() + c.dir + 3, k.rec.begin() + R_D);
      std::copy(r.rec.begin() + c.weight, r.rec.begin() + c.weight + 3, k.rec.begin() + R_W);
      k.rec[R_T] = big;
      k.rec[R_ID] = kNoHit;
      k.rec[R_KIND] = RK_GIVEN;
      k.rec[R_CHILD] = depth + 1 < view_.max_depth ? CHILD_BOTH : 0;
      k.pixel = r.pixel;
      k.depth = depth + 1;
      k.from = static_cast<int>(r.rec[R_ID]);
      k.list = 1;
      next.push_back(k);
    }
  return next;
}

}  // namespace mc1::render
