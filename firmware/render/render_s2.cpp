// s2 of fig. 3, shadows: fig. 6's shadow lists (r_slist on the view boxes,
// once per frame), narrowed per group of hits, and the shadow rays toward
// every light cast against them (r_cast), R_SHADOW's bits.
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include "fp24_convert.hpp"
#include "render_internal.hpp"

namespace mc1::render {

using namespace layout;

// fig. 6: for each object A and light L, the objects B whose view box meets
// the box of A's box and L, padded (r_slist); then the primitives of those
// objects as candidate lists. A list is made when a hit on A first needs it
// (ensure_shadow_lists), not for every pair of objects at once: with N
// objects the lists of all pairs hold up to N^2 L entries (issue 39).
void RenderFirmware::build_shadow_lists() {
  const std::size_t nobj = view_.objects.size();
  const std::size_t nlights = view_.lights.size();
  shadow_objects_.assign(nobj * nlights, {});
  shadow_known_.assign(nobj * nlights, 0);
  shadow_holding_.clear();
  for (int o = 0; o < static_cast<int>(nobj); ++o)
    if (view_.objects[o].prim_count != 0) shadow_holding_.push_back(o);
  cost(Step::Shadows).list_elements += nobj;
  link_.list_elements(nobj);
}

namespace {

// The MPU's side of r_slist's test, in doubles: may box(B) meet H = box(A u
// {L}) padded by 16 C_EPS as r_slist computes it in FP24? Conservative: the
// pad is doubled and widened by 2^-10 of the bound (FP24 rounds to 2^-16 of
// it), plus an absolute 1e-30 (DAZ); a NaN bound never excludes.
struct PaddedBox {
  std::array<double, 6> h;  // min xyz, max xyz
  bool may_meet(const std::array<double, 6>& b) const {
    for (int c = 0; c < 3; ++c)
      if (b[c] > h[3 + c] || b[3 + c] < h[c]) return false;
    return true;
  }
};

std::array<double, 6> box_doubles(const std::array<std::uint32_t, 6>& box) {
  std::array<double, 6> d{};
  for (int k = 0; k < 6; ++k) d[k] = fp24_to_double(box[k]);
  return d;
}

PaddedBox padded_box(const std::array<double, 6>& a, const std::array<double, 3>& l, double pad) {
  PaddedBox p;
  const double margin = 2 * std::fabs(pad) + 1e-30;
  for (int c = 0; c < 3; ++c) {
    const double lo = std::min(a[c], l[c]), hi = std::max(a[3 + c], l[c]);
    p.h[c] = lo - margin - std::ldexp(std::fabs(lo), -10);
    p.h[3 + c] = hi + margin + std::ldexp(std::fabs(hi), -10);
    if (std::isnan(a[c]) || std::isnan(l[c])) p.h[c] = -HUGE_VAL;
    if (std::isnan(a[3 + c]) || std::isnan(l[c])) p.h[3 + c] = HUGE_VAL;
  }
  return p;
}

}  // namespace

// r_slist over the items (A, L, B) of the pairs (A, L) not made yet, B every
// object holding a primitive that the MPU's box test (PaddedBox, a superset
// of r_slist's) keeps, in file order: the lists are exactly those of r_slist
// over every B. MPU work: one list element per B looked at.
void RenderFirmware::ensure_shadow_lists(const std::vector<std::pair<int, int>>& pairs) {
  constexpr Step step = Step::Shadows;
  const std::size_t nlights = view_.lights.size();
  const double pad = 16.0 * fp24_to_double(scene_words_.at(C_EPS - C_D0));
  std::vector<std::array<int, 3>> items;  // (A, L, B)
  std::uint64_t looked = 0;
  std::vector<std::array<double, 6>> b_box;  // of shadow_holding_, made on first use
  for (const auto& [a, l] : pairs) {
    const std::size_t at = static_cast<std::size_t>(a) * nlights + l;
    if (shadow_known_.at(at)) continue;
    shadow_known_[at] = 1;
    if (b_box.empty() && !shadow_holding_.empty()) {
      b_box.reserve(shadow_holding_.size());
      for (int b : shadow_holding_) b_box.push_back(box_doubles(view_.objects[b].box));
      looked += shadow_holding_.size();
    }
    std::array<double, 3> lp{};
    for (int c = 0; c < 3; ++c) lp[c] = fp24_to_double(view_.lights[l][L_POS + c]);
    const PaddedBox h = padded_box(box_doubles(view_.objects[a].box), lp, pad);
    for (std::size_t k = 0; k < shadow_holding_.size(); ++k)
      if (h.may_meet(b_box[k])) items.push_back({a, l, shadow_holding_[k]});
    looked += shadow_holding_.size();
  }
  cost(step).list_elements += looked;
  link_.list_elements(looked);
  if (items.empty()) return;
  run_slist(
      static_cast<std::int64_t>(items.size()), [&](int k) { return items[static_cast<std::size_t>(k)]; },
      [&](int a, int l, int b) { shadow_objects_[static_cast<std::size_t>(a) * nlights + l].push_back(b); });
}

// One r_slist stream over `count` items (A, L, B) = pair_of(k): found(A, L,
// B) for each B that may block L for A's points, in item order.
void RenderFirmware::run_slist(std::int64_t count, const std::function<std::array<int, 3>(int)>& pair_of,
                               const std::function<void(int, int, int)>& found) {
  constexpr Step step = Step::Shadows;
  if (count > std::numeric_limits<int>::max())
    throw std::length_error("render: " + std::to_string(count) + " shadow-list pairs: more than one stream takes");
  ItemStream s{static_cast<int>(count), S_PER_BATCH, S_ITEMS, S_SIZE, true};
  s.put = [&](int k, std::uint16_t addr) {
    const auto [a, l, b] = pair_of(k);
    std::array<std::uint32_t, S_IN> w{};
    std::copy(view_.objects[a].box.begin(), view_.objects[a].box.end(), w.begin() + S_A);
    std::copy(view_.lights[l].begin() + L_POS, view_.lights[l].begin() + L_POS + 3, w.begin() + S_L);
    std::copy(view_.objects[b].box.begin(), view_.objects[b].box.end(), w.begin() + S_B);
    write(addr, w.data(), S_IN, step);
  };
  s.get = [&](int k, std::uint16_t addr) {
    if (read(static_cast<std::uint16_t>(addr + S_OUT), 1, step)[0]) {
      const auto [a, l, b] = pair_of(k);
      found(a, l, b);
    }
  };
  stream_items("r_slist", step, s);
}

// The method before issue 39: r_slist over every (A, L, B), made one item at
// a time.
std::vector<std::vector<int>> RenderFirmware::exhaustive_shadow_lists() {
  const int nlights = static_cast<int>(view_.lights.size());
  const std::vector<int>& holding = shadow_holding_;
  const std::int64_t per_l = static_cast<std::int64_t>(holding.size());
  const std::int64_t per_a = per_l * nlights;
  std::vector<std::vector<int>> out(view_.objects.size() * static_cast<std::size_t>(nlights));
  run_slist(
      per_a * per_l,
      [&](int k) {
        return std::array<int, 3>{holding[k / per_a], static_cast<int>(k / per_l % nlights), holding[k % per_l]};
      },
      [&](int a, int l, int b) { out[static_cast<std::size_t>(a) * nlights + l].push_back(b); });
  return out;
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
  std::vector<std::pair<int, int>> needed;  // (object, light): the shadow lists these hits use
  for (const auto& [o, box] : hit_box)
    for (int l = 0; l < lights; ++l) needed.emplace_back(o, l);
  ensure_shadow_lists(needed);
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
