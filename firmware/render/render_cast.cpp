// The intersection pass of s1, s2 and s4 (r_cast): rays in batches with
// their candidate lists, the lists' primitives in chunks of the bank's
// slots. r_inside (render_solid.cpp) batches its rays the same way.
#include <algorithm>
#include <stdexcept>

#include "render_internal.hpp"

namespace mc1::render {

using namespace layout;

static_assert(R_TMIN == R_FROM + 1, "R_FROM, R_TMIN are written together");

// Items (rays) in batches of at most kRaysPerBatch, in order, whose keys
// (candidate lists) number at most LIST_SLOTS per batch; per batch the union
// of the keys' primitives in chunks of kPrimSlots. Chunk c + 1 of a batch
// continues chunk c's results, so each chunk level is one stream.
// `always_run`: a batch whose keys name no primitive still gets one (empty)
// chunk.
std::vector<RenderFirmware::BatchPlan> RenderFirmware::plan_batches(
    int items, const std::function<int(int)>& key_of, const std::function<const std::vector<int>&(int)>& prims_of,
    bool always_run, StepCost& cost) {
  std::vector<BatchPlan> plans;
  for (int i = 0; i < items;) {
    BatchPlan p;
    p.first = i;
    while (i < items && p.n < kRaysPerBatch) {
      const int key = key_of(i);
      if (std::find(p.keys.begin(), p.keys.end(), key) == p.keys.end()) {
        if (static_cast<int>(p.keys.size()) == LIST_SLOTS) break;
        p.keys.push_back(key);
      }
      ++p.n;
      ++i;
    }
    // The keys' primitives, ascending and distinct (sorted in one buffer,
    // not a set: a node per primitive was most of a frame's allocations).
    std::vector<int>& sorted = sorted_buf_;
    sorted.clear();
    for (int key : p.keys) {
      const std::vector<int>& prims = prims_of(key);
      sorted.insert(sorted.end(), prims.begin(), prims.end());
      cost.list_elements += prims.size();
    }
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    constexpr auto kSlots = static_cast<std::size_t>(kPrimSlots);
    for (std::size_t at = 0; at < sorted.size(); at += kSlots)
      p.chunks.emplace_back(sorted.begin() + static_cast<std::ptrdiff_t>(at),
                            sorted.begin() + static_cast<std::ptrdiff_t>(std::min(at + kSlots, sorted.size())));
    if (always_run && p.chunks.empty()) p.chunks.emplace_back();
    // Each key's list split by chunk once (its positions in the chunk, in
    // list order), not searched again for every chunk: a list of L
    // primitives cost L log L per chunk, L^2 / kPrimSlots for the batch.
    p.split.resize(p.keys.size());
    for (std::size_t k = 0; k < p.keys.size(); ++k) {
      p.split[k].resize(p.chunks.size());
      for (int prim : prims_of(p.keys[k])) {
        const auto at = static_cast<std::size_t>(std::lower_bound(sorted.begin(), sorted.end(), prim) - sorted.begin());
        p.split[k][at / kPrimSlots].push_back(static_cast<int>(at % kPrimSlots));
      }
      cost.list_elements += p.split[k].empty() ? 0 : prims_of(p.keys[k]).size();
    }
    plans.push_back(std::move(p));
  }
  return plans;
}

int RenderFirmware::BatchPlan::key_index(int key) const {
  return static_cast<int>(std::find(keys.begin(), keys.end(), key) - keys.begin());
}

std::uint16_t RenderFirmware::list_addr(int k) { return static_cast<std::uint16_t>(LISTS + LIST_WORDS * k); }

std::vector<int> RenderFirmware::write_lists(
    std::size_t keys, const std::function<void(std::size_t, std::vector<std::uint32_t>&)>& slots_of, Step step) {
  std::vector<int> n(keys);
  std::vector<std::uint32_t>& slots = list_buf_;
  for (std::size_t k = 0; k < keys; ++k) {
    slots.clear();
    slots_of(k, slots);
    if (slots.size() > static_cast<std::size_t>(LIST_WORDS)) throw std::logic_error("write_lists: too long");
    n[k] = static_cast<int>(slots.size());
    if (!slots.empty()) write(list_addr(static_cast<int>(k)), slots.data(), slots.size(), step);
  }
  return n;
}

// Chunk c of batch p: the keys' lists restricted to the chunk's slots, and
// the rays as r_cast reads them.
void RenderFirmware::fill_cast(const std::vector<Ray>& rays, const BatchPlan& p, std::size_t c, const std::vector<int>& slots, Step step) {
  // p.split[k][c]: list k's primitives in chunk c (ascending, chunk[i] in
  // slots[i]) as positions i, in list order.
  const std::vector<int> list_n = write_lists(
      p.keys.size(),
      [&](std::size_t k, std::vector<std::uint32_t>& out) {
        for (int at : p.split[k][c]) out.push_back(static_cast<std::uint32_t>(slots[static_cast<std::size_t>(at)]));
        cost(step).list_elements += p.split[k][c].size();
      },
      step);
  for (int j = 0; j < p.n; ++j) {
    const Ray& ray = rays[p.first + j];
    auto rec = ray.rec;
    const int k = p.key_index(ray.list);
    rec[R_LIST] = list_addr(k);
    rec[R_LISTN] = static_cast<std::uint32_t>(list_n[k]);
    if (c > 0) {  // a later pass: the ray's data as the earlier pass left it
      if (rec[R_KIND] == RK_SHADOW && rec[R_ID] != kNoHit) rec[R_LISTN] = 0;  // already blocked
      rec[R_KIND] = as_given(rec[R_KIND]);
    }
    const auto at = static_cast<std::uint16_t>(RAYS + R_SIZE * j);
    write(at, rec.data(), R_SLOT + 1, step);
    const std::uint32_t tail[2] = {ray.from < 0 ? kNoHit : static_cast<std::uint32_t>(ray.from), rec[R_TMIN]};
    write(static_cast<std::uint16_t>(at + R_FROM), tail, 2, step);
    write_plane_left(ray, c == 0, at, step);
  }
  write_count(p.n, step);
}

// A ray leaving a triangle gets that triangle's plane (R_FPN, R_FP0) on its
// first pass: r_cast moves its origin off the plane, to the side the ray
// goes, by the bound of the origin's distance error, and writes the origin
// back, so a later pass (R_FOFF = 0) starts from the moved origin.
void RenderFirmware::write_plane_left(const Ray& ray, bool first_pass, std::uint16_t at, Step step) {
  std::uint32_t w[R_FOFF - R_FPN + 1] = {};
  bool plane = false;
  if (first_pass && ray.from >= 0 && ray.from < static_cast<int>(view_.prims.size())) {
    const auto& prim = view_.prims[static_cast<std::size_t>(ray.from)];
    plane = prim[P_TYPE] == PT_TRIANGLE || prim[P_TYPE] == PT_PSEUDO;
    if (plane) {
      std::copy(prim.begin() + P_N, prim.begin() + P_N + 3, w + (R_FPN - R_FPN));
      std::copy(prim.begin() + P_P0, prim.begin() + P_P0 + 3, w + (R_FP0 - R_FPN));
      w[R_FOFF - R_FPN] = 1;
    }
  }
  if (plane) write(static_cast<std::uint16_t>(at + R_FPN), w, R_FOFF - R_FPN + 1, step);
  else write(static_cast<std::uint16_t>(at + R_FOFF), w + (R_FOFF - R_FPN), 1, step);
}

void RenderFirmware::cast(std::vector<Ray>& rays, const std::vector<std::vector<int>>& lists, Step step) {
  // Every batch runs (a ray with no candidates still gets its O, D, t).
  const std::vector<BatchPlan> plans = plan_batches(
      static_cast<int>(rays.size()), [&](int i) { return rays[i].list; },
      [&](int l) -> const std::vector<int>& { return lists[l]; }, true, cost(step));
  auto fill = [&](const BatchPlan& p, std::size_t c, const std::vector<int>& slots) {
    fill_cast(rays, p, c, slots, step);
  };
  auto drain = [&](const BatchPlan& p) {
    for (int j = 0; j < p.n; ++j) {
      const auto& back = read(static_cast<std::uint16_t>(RAYS + R_SIZE * j), R_SLOT + 1, step);
      auto& rec = rays[p.first + j].rec;
      for (int w = R_O; w <= R_T; ++w) rec[w] = back[w];
      rec[R_ID] = back[R_ID];
      rec[R_SLOT] = back[R_SLOT];
    }
  };
  stream_chunks("r_cast", plans, step, fill, drain);
}

}  // namespace mc1::render
