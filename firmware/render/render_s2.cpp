// s2 of fig. 3, shadows: fig. 6's shadow lists (r_slist on the view boxes,
// once per frame), narrowed per group of hits, and the shadow rays toward
// every light cast against them (r_cast), R_SHADOW's bits.
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include "render_internal.hpp"

namespace mc1::render {

using namespace layout;

// fig. 6, once per frame after step 1: for each object A and light L, the
// objects B whose view box meets the box of A's box and L (r_slist); then
// the primitives of those objects as candidate lists.
void RenderFirmware::build_shadow_lists() {
  constexpr Step step = Step::Shadows;
  const int nobj = static_cast<int>(view_.objects.size());
  const int nlights = static_cast<int>(view_.lights.size());
  std::vector<int> holding;  // the objects that hold a primitive, in order
  for (int o = 0; o < nobj; ++o)
    if (view_.objects[o].prim_count != 0) holding.push_back(o);
  // Item k is the pair (A, L, B) = (holding[k / per_a], k / per_l % nlights,
  // holding[k % per_l]): made when r_slist takes it, so that the MPU holds
  // one pair at a time, not all N^2 L of them.
  const std::int64_t per_l = static_cast<std::int64_t>(holding.size());
  const std::int64_t per_a = per_l * nlights;
  const std::int64_t count = per_a * per_l;
  if (count > std::numeric_limits<int>::max())
    throw std::length_error("render: " + std::to_string(count) + " shadow-list pairs (" + std::to_string(per_l) +
                            " objects squared, times " + std::to_string(nlights) + " lights): more than one stream takes");
  auto pair = [&](int k) {
    return std::array<int, 3>{holding[k / per_a], static_cast<int>(k / per_l % nlights), holding[k % per_l]};
  };
  shadow_objects_.assign(static_cast<std::size_t>(nobj) * nlights, {});
  ItemStream s{static_cast<int>(count), S_PER_BATCH, S_ITEMS, S_SIZE, true};
  s.put = [&](int k, std::uint16_t addr) {
    const auto [a, l, b] = pair(k);
    std::array<std::uint32_t, S_IN> w{};
    std::copy(view_.objects[a].box.begin(), view_.objects[a].box.end(), w.begin() + S_A);
    std::copy(view_.lights[l].begin() + L_POS, view_.lights[l].begin() + L_POS + 3, w.begin() + S_L);
    std::copy(view_.objects[b].box.begin(), view_.objects[b].box.end(), w.begin() + S_B);
    write(addr, w.data(), S_IN, step);
  };
  s.get = [&](int k, std::uint16_t addr) {
    if (read(static_cast<std::uint16_t>(addr + S_OUT), 1, step)[0]) {
      const auto [a, l, b] = pair(k);
      shadow_objects_[static_cast<std::size_t>(a) * nlights + l].push_back(b);
    }
  };
  stream_items("r_slist", step, s);
}

// fig. 6's shadow list of (object A, light L), narrowed to these rays: a
// shadow ray from a hit point p of A stays in box(hits on A u {L}) = H, so a
// triangle of `candidates` whose padded view box (r_box) misses H cannot
// block it. MPU work: FP24 order keys compared as integers.
std::vector<int> RenderFirmware::narrow_shadow_list(const std::vector<int>& candidates, int light,
                                                    const Box& hits) {
  Box h = hits;
  for (int c = 0; c < 3; ++c) {
    const std::int32_t l = order_key(view_.lights[light][L_POS + c]);
    h[c] = std::min(h[c], l);
    h[3 + c] = std::max(h[3 + c], l);
  }
  std::vector<int> out;
  for (int q : candidates) {
    if (is_triangle(view_.prims[q][P_TYPE])) {
      const Box& p = prim_box_[q];
      if (p[0] > h[3] || p[1] > h[4] || p[2] > h[5] || p[3] < h[0] || p[4] < h[1] || p[5] < h[2]) continue;
    }
    out.push_back(q);
  }
  cost(Step::Shadows).list_elements += candidates.size();
  return out;
}

std::vector<int> RenderFirmware::shadow_candidates(int object, int light, const Box& hits) {
  std::vector<int> all;
  for (int b : shadow_list(object, light)) {
    const auto& obj = view_.objects[b];
    for (int q = obj.first_prim; q < obj.first_prim + obj.prim_count; ++q) all.push_back(q);
  }
  return narrow_shadow_list(all, light, hits);
}

RenderFirmware::Ray RenderFirmware::shadow_ray(const Ray& hit, int light) {
  Ray s;
  std::copy(hit.rec.begin() + R_P, hit.rec.begin() + R_P + 3, s.rec.begin() + R_O);
  s.rec[R_KIND] = RK_SHADOW;
  s.rec[R_ARG] = static_cast<std::uint32_t>(light);
  s.rec[R_ID] = kNoHit;
  s.from = static_cast<int>(hit.rec[R_ID]);
  return s;
}

// Hits in groups of half an r_cast batch of shadow rays (a group's rays
// toward every light); the box of the hit points (FP24 order keys) on each
// object, per group and for the whole generation. Teapot 64x48 on 4 NCs,
// s2 APU cycles by hits per group: 105 M (16), 91 M (8), 87 M (4), 259 M
// with the generation's box alone; smaller groups cost the MPU more lists.
RenderFirmware::ShadowGroups RenderFirmware::shadow_groups(const std::vector<Ray>& rays) {
  const int lights = static_cast<int>(view_.lights.size());
  const int group_size = std::max(1, kRaysPerBatch / (2 * std::max(lights, 1)));
  std::map<std::pair<int, int>, Box> group_box;  // (group, object)
  std::map<int, Box> hit_box;                    // object
  auto grow = [](auto& boxes, const auto& key, const Box& p) { grow_box(boxes.emplace(key, kEmptyBox).first->second, p); };
  ShadowGroups g;
  g.group_of.assign(rays.size(), -1);
  int hit_count = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray& r = rays[i];
    if (!is_hit(r)) continue;
    const int o = view_.prim_object.at(r.rec[R_ID]);
    Box p;
    for (int c = 0; c < 3; ++c) p[c] = p[3 + c] = order_key(r.rec[R_P + c]);
    g.group_of[i] = hit_count++ / group_size;
    grow(hit_box, o, p);
    grow(group_box, std::make_pair(g.group_of[i], o), p);
  }
  // Two levels: fig. 6's list narrowed to the generation's hits on the
  // object, then to the group's (a subset of the first: the MPU scans the
  // short list once per group).
  std::map<std::pair<int, int>, std::vector<int>> block_list;  // (object, light)
  for (const auto& [o, box] : hit_box)
    for (int l = 0; l < lights; ++l) block_list[{o, l}] = shadow_candidates(o, l, box);
  for (const auto& [key, box] : group_box)
    for (int l = 0; l < lights; ++l) {
      g.list_of[{key.first, key.second * lights + l}] = static_cast<int>(g.lists.size());
      g.lists.push_back(narrow_shadow_list(block_list.at({key.second, l}), l, box));
    }
  return g;
}

void RenderFirmware::shadows(std::vector<Ray>& rays) {
  const int lights = static_cast<int>(view_.lights.size());
  const ShadowGroups g = shadow_groups(rays);
  std::vector<Ray> probes;
  std::vector<std::pair<int, int>> owner;  // (ray, light)
  probes.reserve(rays.size() * static_cast<std::size_t>(lights));  // at most one probe per ray and light
  owner.reserve(probes.capacity());
  for (int i = 0; i < static_cast<int>(rays.size()); ++i) {
    rays[i].rec[R_SHADOW] = 0;
    if (!is_hit(rays[i])) continue;
    for (int l = 0; l < lights; ++l) {
      Ray s = shadow_ray(rays[i], l);
      s.list = g.list_of.at({g.group_of[i], view_.prim_object.at(s.from) * lights + l});
      probes.push_back(s);
      owner.emplace_back(i, l);
    }
  }
  stats_.shadow_rays += probes.size();
  if (!any_combined_) {
    cast(probes, g.lists, Step::Shadows);
  } else {
    // Intersections' and differences' surfaces exist only where the solid
    // rule leaves them: their regions are cast apart, after the others.
    std::vector<std::vector<int>> plain(g.lists.size()), combined(g.lists.size());
    for (std::size_t l = 0; l < g.lists.size(); ++l)
      for (int q : g.lists[l]) (prim_combined_[q] ? combined : plain)[l].push_back(q);
    cost(Step::Shadows).list_elements += probes.size();
    cast(probes, plain, Step::Shadows);
    combined_shadows(probes, combined);
  }
  for (std::size_t k = 0; k < probes.size(); ++k)
    if (is_hit(probes[k])) rays[owner[k].first].rec[R_SHADOW] |= 1u << owner[k].second;
  cost(Step::Shadows).list_elements += probes.size();
}

void RenderFirmware::combined_shadows(std::vector<Ray>& probes, const std::vector<std::vector<int>>& csg_lists) {
  constexpr Step step = Step::Shadows;
  std::vector<Ray> again;
  std::vector<std::size_t> owner;
  for (std::size_t k = 0; k < probes.size(); ++k) {
    const Ray& p = probes[k];
    if (is_hit(p) || csg_lists[p.list].empty()) continue;
    Ray r = p;  // r_cast wrote back O (moved off a triangle's plane), D and the limit |L - O| - eps (R_T)
    r.rec[R_KIND] = RK_GIVEN;
    r.limit = r.rec[R_T];
    // The combined lists hold regions only: a triangle left needs no R_FROM,
    // and its plane offset is in O already (not to be applied twice).
    if (r.from >= 0 && is_triangle(view_.prims[static_cast<std::size_t>(r.from)][P_TYPE])) r.from = -1;
    again.push_back(r);
    owner.push_back(k);
  }
  cost(step).list_elements += probes.size();
  if (again.empty()) return;
  cast(again, csg_lists, step);
  solid_rule(again, csg_lists, step);
  for (std::size_t k = 0; k < again.size(); ++k) probes[owner[k]].rec[R_ID] = again[k].rec[R_ID];
}

}  // namespace mc1::render
