// s1 of fig. 3, hidden-surface removal for a block's eye rays: r_scan's
// Z-buffer over the block's triangles, r_cast against its ellipsoids and
// quadrics, and r_surf's hit point, normal, material and colour of every
// hit (of every generation of rays).
#include <iterator>

#include "render_internal.hpp"

namespace mc1::render {

using namespace layout;

std::vector<int> RenderFirmware::eye_candidates(const BlockList& list) {
  std::vector<int> prims;
  for (int o : list.objects) {
    const auto& obj = view_.objects.at(o);
    cost(Step::HiddenSurface).list_elements += obj.prim_count;
    // Within an object of the block list, a triangle whose own projection
    // (r_box) misses the block cannot be met by the block's eye rays.
    for (int k = 0; k < obj.prim_count; ++k)
      if (prim_rect_.at(obj.first_prim + k).overlaps(list.block)) prims.push_back(obj.first_prim + k);
  }
  return prims;
}

std::vector<RenderFirmware::Ray> RenderFirmware::hidden_surface(const BlockList& list) {
  const Block& b = list.block;
  lists_.at(0) = eye_candidates(list);  // [1] and the shadow lists are the frame's
  std::vector<int> triangles;
  std::vector<std::vector<int>> regions(1);  // the eye rays' r_cast candidates
  for (int prim : lists_[0]) (is_triangle(view_.prims[prim][P_TYPE]) ? triangles : regions[0]).push_back(prim);
  const std::vector<ZEntry> z = scan_convert(b, triangles);
  std::vector<Ray> gen;
  for (int j = 0; j < b.h; ++j)
    for (int i = 0; i < b.w; ++i) {
      Ray r;
      r.pixel = j * b.w + i;
      r.rec[R_KIND] = RK_EYE_SCAN;
      r.rec[R_ARG] = static_cast<std::uint32_t>(b.x0 + i);
      r.rec[R_ARG2] = static_cast<std::uint32_t>(b.y0 + j);
      r.rec[R_T] = z[r.pixel].w;
      r.rec[R_ID] = z[r.pixel].id;
      r.rec[R_W] = r.rec[R_W + 1] = r.rec[R_W + 2] = kOne;
      r.rec[R_CHILD] = view_.max_depth > 0 ? CHILD_BOTH : 0;
      r.list = 0;
      gen.push_back(r);
    }
  cast(gen, regions, Step::HiddenSurface);
  return gen;
}

// ---------------------------------------------------------------- r_scan

// The triangles of `triangles` whose projected rectangle meets `t`'s tile,
// clipped to it, in chunks of kPrimSlots (Z_LIST's entries).
void RenderFirmware::clip_to_tile(ScanTile& t, const std::vector<int>& triangles) {
  std::vector<ScanEntry> chunk;
  for (int prim : triangles) {
    cost(Step::HiddenSurface).list_elements += 1;
    const ScreenRect& r = prim_rect_.at(prim);
    if (!r.overlaps(t.rect)) continue;
    ScanEntry e{prim, t.rect.x0, t.rect.y0, t.rect.x0 + t.rect.w - 1, t.rect.y0 + t.rect.h - 1};
    if (r.status == ScreenRect::kBounded) {  // clip r_box's rectangle to the tile
      e.i0 = std::max(e.i0, r.i0);
      e.j0 = std::max(e.j0, r.j0);
      e.ncol = std::min(e.ncol, r.i1);
      e.nrow = std::min(e.nrow, r.j1);
    }
    e.ncol = e.ncol - e.i0 + 1;
    e.nrow = e.nrow - e.j0 + 1;
    chunk.push_back(e);
    if (static_cast<int>(chunk.size()) == kPrimSlots) t.chunks.push_back(std::move(chunk)), chunk.clear();
  }
  if (!chunk.empty()) t.chunks.push_back(std::move(chunk));
}

// Chunk c of tile t as r_scan reads it: the entries, the Z-buffer of the
// earlier chunks (none: ZM_CLEAR), the header.
void RenderFirmware::fill_scan(const ScanTile& t, std::size_t c, Step step) {
  const auto& chunk = t.chunks[c];
  ensure_scene(step);
  std::vector<int> prims;
  for (const auto& e : chunk) prims.push_back(e.prim);
  const auto slots = place_prims(prims, step);
  std::vector<std::uint32_t> words;
  for (std::size_t k = 0; k < chunk.size(); ++k) {
    const ScanEntry& e = chunk[k];
    std::array<std::uint32_t, Z_ENTRY> w{};
    w[Z_SLOT] = static_cast<std::uint32_t>(slots[k]);
    w[Z_I0] = static_cast<std::uint32_t>(e.i0);
    w[Z_J0] = static_cast<std::uint32_t>(e.j0);
    w[Z_NCOL] = static_cast<std::uint32_t>(e.ncol);
    w[Z_NROW] = static_cast<std::uint32_t>(e.nrow);
    w[Z_ADDR] = static_cast<std::uint32_t>(ZBUF + ZB_SIZE * ((e.j0 - t.rect.y0) * t.rect.w + (e.i0 - t.rect.x0)));
    words.insert(words.end(), w.begin(), w.end());
  }
  write(Z_LIST, words.data(), words.size(), step);
  if (c > 0) write(ZBUF, t.zbuf.data(), t.zbuf.size(), step);
  static_assert(Z_STRIDE == H_MODE + 1 && Z_NPIX == H_MODE + 2, "r_scan's header words follow H_MODE");
  const std::uint32_t head[Z_NPIX - H_MODE + 1] = {c > 0 ? std::uint32_t{ZM_GIVEN} : std::uint32_t{ZM_CLEAR},
                                 static_cast<std::uint32_t>(ZB_SIZE * t.rect.w),
                                 static_cast<std::uint32_t>(t.rect.w * t.rect.h)};
  write(H_MODE, head, std::size(head), step);
  write_count(static_cast<int>(chunk.size()), step);
}

// The block in tiles of at most Z_PIXELS pixels (whole rows where they fit);
// per tile the triangles whose projected rectangle meets it, clipped, in
// chunks of kPrimSlots. Chunk c + 1 of a tile continues chunk c's Z-buffer,
// so (as in cast) each chunk level is one stream.
std::vector<RenderFirmware::ZEntry> RenderFirmware::scan_convert(const Block& b,
                                                                 const std::vector<int>& triangles) {
  constexpr Step step = Step::HiddenSurface;
  const int tw = std::min(b.w, Z_PIXELS);
  const int th = std::max(1, std::min(b.h, Z_PIXELS / std::max(tw, 1)));
  std::vector<ScanTile> tiles;
  for (int y = b.y0; y < b.y0 + b.h; y += th)
    for (int x = b.x0; x < b.x0 + b.w; x += tw) {
      ScanTile t;
      t.rect = Block{x, y, std::min(tw, b.x0 + b.w - x), std::min(th, b.y0 + b.h - y)};
      clip_to_tile(t, triangles);
      t.zbuf.resize(ZB_SIZE * static_cast<std::size_t>(t.rect.w) * t.rect.h);
      for (std::size_t p = 0; p < t.zbuf.size(); p += ZB_SIZE) t.zbuf[p + ZB_W] = 0, t.zbuf[p + ZB_ID] = kNoHit;
      tiles.push_back(std::move(t));
    }
  const auto levels =
      chunk_levels(static_cast<int>(tiles.size()), [&](int k) { return tiles[k].chunks.size(); });
  for (std::size_t c = 0; c < levels.size(); ++c) {
    const std::vector<int>& items = levels[c];
    stream("r_scan", static_cast<int>(items.size()), step, [&](int item) { fill_scan(tiles[items[item]], c, step); },
           [&](int item) {
             ScanTile& t = tiles[items[item]];
             t.zbuf = read(ZBUF, t.zbuf.size(), step);
           });
  }
  std::vector<ZEntry> z(static_cast<std::size_t>(b.w) * b.h);
  for (const auto& t : tiles)
    for (int j = 0; j < t.rect.h; ++j)
      for (int i = 0; i < t.rect.w; ++i) {
        const std::size_t from = ZB_SIZE * (static_cast<std::size_t>(j) * t.rect.w + i);
        z[static_cast<std::size_t>(t.rect.y0 - b.y0 + j) * b.w + (t.rect.x0 - b.x0 + i)] =
            ZEntry{t.zbuf[from + ZB_W], t.zbuf[from + ZB_ID]};
      }
  return z;
}

// ---------------------------------------------------------------- r_surf

void RenderFirmware::surface(std::vector<Ray>& rays, Step step) {
  std::vector<int> hits;
  for (int i = 0; i < static_cast<int>(rays.size()); ++i)
    if (is_hit(rays[i])) hits.push_back(i);
  std::vector<int> prims, slots;  // the batch's primitives and their slots
  ItemStream s{static_cast<int>(hits.size()), kRaysPerBatch, RAYS, R_SIZE, true};
  s.begin = [&](int first, int n) {
    prims.clear();
    for (int j = 0; j < n; ++j) {
      const int id = static_cast<int>(rays[hits[first + j]].rec[R_ID]);
      if (std::find(prims.begin(), prims.end(), id) == prims.end()) prims.push_back(id);
    }
    slots = place_prims(prims, step);
  };
  s.put = [&](int i, std::uint16_t addr) {
    auto rec = rays[hits[i]].rec;
    const int id = static_cast<int>(rec[R_ID]);
    rec[R_SLOT] = static_cast<std::uint32_t>(slots[std::find(prims.begin(), prims.end(), id) - prims.begin()]);
    write(addr, rec.data(), R_SLOT + 1, step);
  };
  s.get = [&](int i, std::uint16_t addr) {
    auto& rec = rays[hits[i]].rec;
    const auto& back = read(static_cast<std::uint16_t>(addr + R_P), R_INSIDE - R_P + 1, step);
    std::copy(back.begin(), back.end(), rec.begin() + R_P);
    rec[R_SOLID] = read(static_cast<std::uint16_t>(addr + R_SOLID), 1, step)[0];
  };
  stream_items("r_surf", step, s);
}

}  // namespace mc1::render
