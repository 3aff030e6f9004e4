// The solid rule (docs/scene-format.md "Objects") after a cast of eye or
// secondary rays: hits inside another region of their solid (r_inside) are
// not on its boundary, and the ray goes on past them.
#include <stdexcept>

#include "render_internal.hpp"

namespace mc1::render {

using namespace layout;

// Per object, the region primitives (ellipsoids, quadrics) against which a
// hit on one of its primitives must be tested: a solid with at least one
// region and another primitive (docs/scene-format.md: only regions hide).
void RenderFirmware::build_solid_regions() {
  solid_regions_.assign(view_.objects.size(), {});
  prim_combined_.assign(view_.prims.size(), 0);
  any_combined_ = false;
  for (std::size_t o = 0; o < view_.objects.size(); ++o) {
    const auto& obj = view_.objects[o];
    if (obj.combine != kUnion) {
      any_combined_ = true;
      std::fill_n(prim_combined_.begin() + obj.first_prim, obj.prim_count, 1);
    }
    if (!obj.solid || obj.prim_count < 2) continue;
    std::vector<int> regions;
    for (int k = 0; k < obj.prim_count; ++k) {
      const std::uint32_t type = view_.prims.at(obj.first_prim + k)[P_TYPE];
      if (type == kEllipsoid || type == kQuadric) regions.push_back(obj.first_prim + k);
    }
    cost(Step::Transform).list_elements += obj.prim_count;
    solid_regions_[o] = std::move(regions);
  }
}

// A hit that another region of its solid may hold (not a shadow ray).
bool RenderFirmware::may_be_hidden(const Ray& r) const {
  const std::uint32_t id = r.rec[R_ID];
  if (id == kNoHit || is_shadow(r.rec[R_KIND])) return false;
  const auto& regions = solid_regions_.at(view_.prim_object.at(id));
  return regions.size() >= 2 || (regions.size() == 1 && regions[0] != static_cast<int>(id));
}

std::vector<int> RenderFirmware::hidden_hits(std::vector<Ray>& rays, const std::vector<int>& which, Step step) {
  // Batches of at most R_SLOTS rays whose hits lie on at most LIST_SLOTS
  // objects; the objects' regions in chunks of P_SLOTS slots (a later chunk
  // skips rays already found hidden), as in cast(). A batch without regions
  // does not run.
  auto object_of = [&](int k) { return view_.prim_object.at(rays[which[k]].rec[R_ID]); };
  const std::vector<BatchPlan> plans = plan_batches(
      static_cast<int>(which.size()), object_of,
      [&](int o) -> const std::vector<int>& { return solid_regions_[o]; }, false, cost(step));
  std::vector<char> hidden(which.size(), 0);
  auto fill = [&](const BatchPlan& p, std::size_t c, const std::vector<int>& slots) {
    const auto& chunk = p.chunks[c];
    const std::vector<int> list_n = write_lists(
        p.keys.size(),
        [&](std::size_t k, std::vector<std::uint32_t>& out) {
          for (std::size_t s = 0; s < chunk.size(); ++s)
            if (view_.prim_object[chunk[s]] == p.keys[k]) out.push_back(static_cast<std::uint32_t>(slots[s]));
          cost(step).list_elements += chunk.size();
        },
        step);
    for (int j = 0; j < p.n; ++j) {
      auto rec = rays[which[p.first + j]].rec;
      const int k = p.key_index(object_of(p.first + j));
      rec[R_LIST] = list_addr(k);
      rec[R_LISTN] = hidden[p.first + j] ? 0 : static_cast<std::uint32_t>(list_n[k]);
      write(static_cast<std::uint16_t>(RAYS + R_SIZE * j), rec.data(), R_LISTN + 1, step);
    }
    write_count(p.n, step);
  };
  auto drain = [&](const BatchPlan& p) {
    for (int j = 0; j < p.n; ++j) {
      const std::uint32_t tmin = read(static_cast<std::uint16_t>(RAYS + R_SIZE * j + R_TMIN), 1, step)[0];
      if (tmin == 0) continue;
      hidden[p.first + j] = 1;
      rays[which[p.first + j]].rec[R_TMIN] = tmin;
    }
  };
  stream_chunks("r_inside", plans, step, fill, drain);
  std::vector<int> out;
  for (std::size_t k = 0; k < which.size(); ++k)
    if (hidden[k]) out.push_back(which[k]);
  return out;
}

// One round of the solid rule: the rays `hidden` cast again from the same
// origin and direction (an eye ray as a given ray: r_cast wrote its O and D
// back), ignoring t <= R_TMIN; returns those that may still be hidden.
std::vector<int> RenderFirmware::cast_past(std::vector<Ray>& rays, const std::vector<int>& hidden,
                                           const std::vector<std::vector<int>>& lists, Step step) {
  const std::uint32_t big = scene_words_[C_BIG - C_D0];
  std::vector<Ray> again;
  for (int k : hidden) {
    Ray r = rays[k];
    r.rec[R_T] = r.limit != 0 ? r.limit : big;
    r.rec[R_ID] = kNoHit;
    r.rec[R_KIND] = as_given(r.rec[R_KIND]);
    again.push_back(r);
  }
  cast(again, lists, step);
  std::vector<int> pending;
  for (std::size_t k = 0; k < hidden.size(); ++k) {
    auto& rec = rays[hidden[k]].rec;
    for (int w = R_O; w <= R_T; ++w) rec[w] = again[k].rec[w];
    rec[R_ID] = again[k].rec[R_ID];
    rec[R_SLOT] = again[k].rec[R_SLOT];
    if (may_be_hidden(rays[hidden[k]])) pending.push_back(hidden[k]);
  }
  cost(step).list_elements += hidden.size();
  return pending;
}

void RenderFirmware::solid_rule(std::vector<Ray>& rays, const std::vector<std::vector<int>>& lists, Step step) {
  std::vector<int> pending;
  for (int i = 0; i < static_cast<int>(rays.size()); ++i)
    if (may_be_hidden(rays[i])) pending.push_back(i);
  cost(step).list_elements += rays.size();
  // Every round moves each pending ray past one more crossing of its list's
  // primitives (at most two each): a bound that cannot be reached.
  std::size_t rounds = 0, bound = 2;
  for (const auto& l : lists) bound = std::max(bound, 2 * l.size() + 2);
  while (!pending.empty()) {
    if (++rounds > bound) throw std::logic_error("solid_rule: no end");
    const std::vector<int> hidden = hidden_hits(rays, pending, step);
    stats_.hidden_hits += hidden.size();
    if (hidden.empty()) break;
    pending = cast_past(rays, hidden, lists, step);
  }
}

}  // namespace mc1::render
