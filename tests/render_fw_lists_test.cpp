// The renderer's firmware and kernels on the ISS (docs/renderer.md): every
// expected value below is computed here in double from the same scene, or
// written out by hand.
// Here: block lists, shadow lists and narrowed secondary lists
// (RenderBlockLists, RenderShadows, RenderSecondary).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "refrender.hpp"

#include "render_fw_test_util.hpp"

namespace {

using namespace mc1;
using namespace mc1::render;
using namespace mc1::render::layout;
using namespace mc1::render::test;

// Step 2 (r_box): block lists hold only the objects whose projected box
// meets the block, and s1's candidates only the triangles whose projection
// does; both are conservative: every eye ray's hit (all primitives, one
// pass) is among its block's candidates.
void expect_block_lists_conservative(const scene::Scene& sc, int bs, std::size_t* listed) {
  Rig rig;
  rig.fw.load_scene(make_scene_image(sc));
  const auto& v = rig.fw.view();
  const int w = sc.camera.width, h = sc.camera.height;
  const std::vector<int> all = every_primitive(v);
  std::vector<RenderFirmware::Ray> rays;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      RenderFirmware::Ray r;
      r.rec[R_KIND] = RK_EYE;
      r.rec[R_ARG] = static_cast<Word>(i);
      r.rec[R_ARG2] = static_cast<Word>(j);
      r.rec[R_ID] = kNoHit;
      rays.push_back(r);
    }
  rig.fw.cast(rays, {all}, Step::HiddenSurface);
  *listed = 0;
  for (int y0 = 0; y0 < h; y0 += bs)
    for (int x0 = 0; x0 < w; x0 += bs) {
      const BlockList bl = rig.fw.build_block_list({x0, y0, std::min(bs, w - x0), std::min(bs, h - y0)});
      const auto cand = rig.fw.eye_candidates(bl);
      *listed += cand.size();
      for (int j = y0; j < std::min(h, y0 + bs); ++j)
        for (int i = x0; i < std::min(w, x0 + bs); ++i) {
          const Word id = rays[j * w + i].rec[R_ID];
          if (id == kNoHit) continue;
          EXPECT_NE(std::find(bl.objects.begin(), bl.objects.end(), v.prim_object[id]), bl.objects.end())
              << "pixel " << i << "," << j;
          EXPECT_NE(std::find(cand.begin(), cand.end(), static_cast<int>(id)), cand.end())
              << "pixel " << i << "," << j << " primitive " << id;
        }
    }
}

TEST(RenderBlockLists, ProjectedBoxesCullObjectsAndTriangles) {
  scene::Scene room = scene::load_scene(scene_path("room"));
  room.camera.width = 64;
  room.camera.height = 48;
  Rig rig;
  rig.fw.load_scene(make_scene_image(room));
  // Objects: 0 floor, 1 walls, 2 box, 3 tetrahedron, 4 cylinder, 5 cone,
  // 6 paraboloid (chrome), 7 ellipsoid (chrome); nearest first.
  const BlockList top = rig.fw.build_block_list({0, 0, 16, 16});
  EXPECT_EQ(top.objects, (std::vector<int>{1, 4}));
  EXPECT_EQ(top.load, 2u);
  const BlockList mid = rig.fw.build_block_list({32, 16, 16, 16});
  EXPECT_EQ(mid.objects, (std::vector<int>{1, 0, 6, 2, 5, 3}));
  EXPECT_EQ(mid.load, 1u + 1u + 4u + 1u + 1u + 1u);
  EXPECT_EQ(rig.fw.eye_candidates(mid).size(), 22u);  // of 30 primitives
  std::size_t listed = 0;
  expect_block_lists_conservative(room, 16, &listed);
  EXPECT_EQ(listed, 105u);  // 12 blocks x 30 primitives without step 2
  const scene::Scene small = scene::parse_scene(kWhitted, "whitted-small.json", ".");
  expect_block_lists_conservative(small, 8, &listed);  // 8x8 blocks: triangles and a pseudo quad
  EXPECT_EQ(listed, 129u);  // 30 blocks x 13 primitives without step 2
}

// fig. 6 (r_slist): the objects that may block a light for an object.
TEST(RenderShadows, ShadowListsHoldTheObjectsBetweenAnObjectAndALight) {
  scene::Scene room = scene::load_scene(scene_path("room"));
  Rig rig;
  rig.fw.load_scene(make_scene_image(room));
  // The floor's box touches every object: everything may shadow it.
  EXPECT_EQ(rig.fw.shadow_list(0, 0), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  // The box (right, front) toward light 1 (right, high): floor, walls, itself.
  EXPECT_EQ(rig.fw.shadow_list(2, 1), (std::vector<int>{0, 1, 2}));
  // The cylinder (left, back) toward light 0 (left, front).
  EXPECT_EQ(rig.fw.shadow_list(4, 0), (std::vector<int>{0, 1, 4}));
}

// The cause of the room's old 33 dB: FP24 hit points of quadrics and
// ellipsoids lie up to ~2e-3 off the surface, and shadow rays met their own
// surface just past epsilon. With R_FROM (r_cast: the primitive a ray leaves
// contributes only its other root, -B/A) every eye hit of room.json at 64x48
// has the reference's per-light shadow flags.
TEST(RenderShadows, RoomEyeHitsHaveTheReferenceShadowFlags) {
  const int w = 64, h = 48;
  Rig rig;
  const scene::Scene sc = load_standard_scene(rig, "room", w, h);
  const auto& v = rig.fw.view();
  const std::vector<int> all = every_primitive(v);
  // s1 as the renderer does it (scan conversion, then regions), the frame
  // as one block: rays row-major.
  std::vector<RenderFirmware::Ray> rays = rig.fw.hidden_surface(rig.fw.build_block_list({0, 0, w, h}));
  rig.fw.surface(rays, Step::HiddenSurface);
  const int lights = static_cast<int>(sc.lights.size());
  std::vector<RenderFirmware::Ray> probes;
  for (const auto& r : rays) {
    if (r.rec[R_ID] == kNoHit) continue;
    for (int l = 0; l < lights; ++l) {
      RenderFirmware::Ray s = RenderFirmware::shadow_ray(r, l);
      s.list = 1 + v.prim_object[s.from] * lights + l;  // its shadow list (fig. 6)
      probes.push_back(s);
    }
  }
  std::vector<std::vector<int>> lists{all};
  for (int o = 0; o < static_cast<int>(v.objects.size()); ++o)
    for (int l = 0; l < lights; ++l) {
      lists.emplace_back();
      for (int b : rig.fw.shadow_list(o, l))
        for (int q = 0; q < v.objects[b].prim_count; ++q) lists.back().push_back(v.objects[b].first_prim + q);
    }
  rig.fw.cast(probes, lists, Step::Shadows);
  const refrender::Renderer ref(sc);
  int other_object = 0, other_flags = 0, lit = 0, k = 0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const auto& rec = rays[j * w + i].rec;
      refrender::Hit hit;
      const bool ref_hit = ref.nearest_hit(refrender::eye_ray(sc.camera, i, j, w, h), hit);
      const int obj = rec[R_ID] == kNoHit ? -1 : v.prim_object[rec[R_ID]];
      int flags = 0, ref_flags = 0;
      if (obj >= 0)
        for (int l = 0; l < lights; ++l, ++k) flags |= (probes[k].rec[R_ID] != kNoHit) << l;
      if (obj != (ref_hit ? hit.object : -1)) {
        ++other_object;
        continue;
      }
      if (obj < 0) continue;
      for (int l = 0; l < lights; ++l) ref_flags |= ref.shadowed(hit.point, sc.lights[l]) << l;
      other_flags += flags != ref_flags;
      lit += flags != 3;
    }
  EXPECT_EQ(other_flags, 0);    // was 51 (self-shadowed quadric and ellipsoid pixels)
  EXPECT_LE(other_object, 2);   // silhouette pixels: (21, 27) and (34, 33)
  EXPECT_GT(lit, 2000);
}

// s2's candidates per group of hits (shadows): fig. 6's list of (object,
// light), less the triangles whose padded box misses the box of the group's
// hits on that object and the light. Every shadow flag is the one the whole
// lists give, for at most 1/`gain` of the APU cycles.
void expect_narrowed_shadow_lists_keep_flags(const std::string& name, int w, int h, int bs, double gain) {
  Rig rig;
  const scene::Scene sc = load_standard_scene(rig, name, w, h);
  const auto& v = rig.fw.view();
  const int lights = static_cast<int>(sc.lights.size());
  std::uint64_t narrowed_cycles = 0, whole_cycles = 0;
  int flags_set = 0, hits = 0;
  for (int y0 = 0; y0 < h; y0 += bs)
    for (int x0 = 0; x0 < w; x0 += bs) {
      auto rays = rig.fw.hidden_surface(rig.fw.build_block_list({x0, y0, std::min(bs, w - x0), std::min(bs, h - y0)}));
      rig.fw.surface(rays, Step::HiddenSurface);
      auto& s2 = rig.fw.stats().step[static_cast<int>(Step::Shadows)];
      std::uint64_t c0 = s2.apu_cycles;
      rig.fw.shadows(rays);
      narrowed_cycles += s2.apu_cycles - c0;
      // The same shadow rays against the whole lists.
      std::vector<std::vector<int>> lists;
      std::vector<RenderFirmware::Ray> probes;
      for (const auto& r : rays) {
        if (r.rec[R_ID] == kNoHit) continue;
        for (int l = 0; l < lights; ++l) {
          RenderFirmware::Ray p = RenderFirmware::shadow_ray(r, l);
          lists.emplace_back();
          for (int b : rig.fw.shadow_list(v.prim_object[p.from], l))
            for (int q = 0; q < v.objects[b].prim_count; ++q) lists.back().push_back(v.objects[b].first_prim + q);
          p.list = static_cast<int>(lists.size()) - 1;
          probes.push_back(p);
        }
      }
      c0 = s2.apu_cycles;
      rig.fw.cast(probes, lists, Step::Shadows);
      whole_cycles += s2.apu_cycles - c0;
      std::size_t k = 0;
      for (const auto& r : rays) {
        if (r.rec[R_ID] == kNoHit) continue;
        ++hits;
        Word whole = 0;
        for (int l = 0; l < lights; ++l, ++k) whole |= Word{probes[k].rec[R_ID] != kNoHit} << l;
        EXPECT_EQ(r.rec[R_SHADOW], whole) << name << " block " << x0 << "," << y0;
        flags_set += whole != 0;
      }
    }
  std::printf("%s %dx%d: %d hits, %d shadowed; s2 APU cycles narrowed %.3g M, whole lists %.3g M\n", name.c_str(),
              w, h, hits, flags_set, narrowed_cycles / 1e6, whole_cycles / 1e6);
  EXPECT_GT(flags_set, hits / 20);
  EXPECT_LT(narrowed_cycles * gain, whole_cycles);
}

// s4's candidates per secondary ray (secondary_candidates): every primitive
// less the triangles wholly behind the ray's origin on some axis. The first
// two generations of secondary rays find the same primitive at the same t
// (bits) as against every primitive, for at most 1/`gain` of the APU cycles.
void expect_secondary_lists_keep_hits(const std::string& name, int w, int h, int bs, double gain) {
  Rig rig;
  const scene::Scene sc = load_standard_scene(rig, name, w, h);
  const std::vector<int> every = every_primitive(rig.fw.view());
  std::uint64_t narrowed_cycles = 0, whole_cycles = 0;
  int rays = 0, hits = 0;
  auto& s4 = rig.fw.stats().step[static_cast<int>(Step::Secondary)];
  for (int y0 = 0; y0 < h; y0 += bs)
    for (int x0 = 0; x0 < w; x0 += bs) {
      auto gen = rig.fw.hidden_surface(rig.fw.build_block_list({x0, y0, std::min(bs, w - x0), std::min(bs, h - y0)}));
      for (int depth = 0; depth < 2 && !gen.empty(); ++depth) {
        rig.fw.surface(gen, Step::HiddenSurface);
        rig.fw.shadows(gen);
        rig.fw.shade(gen, Step::Shading);
        auto narrowed = rig.fw.children(gen, depth);
        auto whole = narrowed;
        std::vector<std::vector<int>> lists;
        rig.fw.secondary_candidates(narrowed, lists);
        std::uint64_t c0 = s4.apu_cycles;
        rig.fw.cast(narrowed, lists, Step::Secondary);
        narrowed_cycles += s4.apu_cycles - c0;
        for (auto& r : whole) r.list = 0;
        c0 = s4.apu_cycles;
        rig.fw.cast(whole, {every}, Step::Secondary);
        whole_cycles += s4.apu_cycles - c0;
        for (std::size_t k = 0; k < whole.size(); ++k) {
          ++rays;
          hits += whole[k].rec[R_ID] != kNoHit;
          EXPECT_EQ(narrowed[k].rec[R_ID], whole[k].rec[R_ID]) << name << " block " << x0 << "," << y0 << " ray " << k;
          EXPECT_EQ(narrowed[k].rec[R_T], whole[k].rec[R_T]) << name << " block " << x0 << "," << y0 << " ray " << k;
        }
        gen = std::move(narrowed);
      }
    }
  std::printf("%s %dx%d: %d secondary rays, %d hits; s4 APU cycles narrowed %.3g M, every primitive %.3g M\n",
              name.c_str(), w, h, rays, hits, narrowed_cycles / 1e6, whole_cycles / 1e6);
  EXPECT_GT(hits, rays / 10);
  EXPECT_LT(narrowed_cycles * gain, whole_cycles);
}

// Measured: teapot 0.827 M vs 11.9 M (14x), room 0.0833 M vs 0.139 M (1.7x),
// Whitted 0.488 M vs 0.785 M (1.6x).
TEST(RenderSecondary, NarrowedListsKeepEveryHitOnTheTeapot) { expect_secondary_lists_keep_hits("teapot", 32, 24, 16, 10.0); }
TEST(RenderSecondary, NarrowedListsKeepEveryHitInTheRoom) { expect_secondary_lists_keep_hits("room", 64, 48, 16, 1.4); }
TEST(RenderSecondary, NarrowedListsKeepEveryHitInTheWhittedScene) {
  expect_secondary_lists_keep_hits("whitted", 64, 48, 16, 1.4);
}

// Measured: teapot 9.62 M vs 72.7 M (7.6x), room 3.88 M vs 7.81 M (2.0x).
TEST(RenderShadows, NarrowedListsKeepEveryFlagOnTheTeapot) {
  expect_narrowed_shadow_lists_keep_flags("teapot", 32, 24, 16, 6.0);
}
TEST(RenderShadows, NarrowedListsKeepEveryFlagInTheRoom) {
  expect_narrowed_shadow_lists_keep_flags("room", 64, 48, 16, 1.6);
}

// The MPU work the firmware charges through its link (the platform turns it
// into MPU time: NcApuLink) against the work its statistics count (the
// report's per-step MPU cycles), class by class, over a whole small frame
// of many block lists. Copies, sort compares and APU commands agree: each
// is charged where it is counted (a block list once charged the step's
// running total of compares, every list's before it too). List elements
// are counted everywhere a list is walked but charged only in s2's shadow
// lists (render_s2.cpp): the statistics count more than the MPU is charged.
TEST(RenderBlockLists, ChargedMpuWorkIsTheCountedWork) {
  struct Charges final : ApuLink {
    explicit Charges(apu::ApuDriver& drv) : direct(drv) {}
    apu::ApuDriver& apu() override { return direct.apu(); }
    void wait_swap() override { direct.wait_swap(); }
    void wait_halt() override { direct.wait_halt(); }
    void copy_words(std::uint64_t n) override { cost.word_copies += n; }
    void list_elements(std::uint64_t n) override { cost.list_elements += n; }
    void sort_compares(std::uint64_t n) override { cost.sort_compares += n; }
    void apu_commands(std::uint64_t n) override { cost.apu_commands += n; }
    DirectLink direct;
    StepCost cost;
  };
  const scene::Scene sc = scene::parse_scene(kWhitted, "whitted-small.json", ".");
  apu::Iss iss;
  apu::ApuDriver drv(iss);
  Charges link(drv);
  RenderFirmware fw(link);
  fw.load_scene(make_scene_image(sc));
  int lists = 0;
  for (int y0 = 0; y0 < sc.camera.height; y0 += 8)
    for (int x0 = 0; x0 < sc.camera.width; x0 += 8) {
      const Block b{x0, y0, std::min(8, sc.camera.width - x0), std::min(8, sc.camera.height - y0)};
      fw.render_block(fw.build_block_list(b));
      ++lists;
    }
  StepCost counted;
  for (const StepCost& c : fw.stats().step) counted += c;
  ASSERT_EQ(lists, 30);
  EXPECT_GT(counted.sort_compares, 0u);
  EXPECT_EQ(link.cost.sort_compares, counted.sort_compares);
  EXPECT_EQ(link.cost.word_copies, counted.word_copies);
  EXPECT_EQ(link.cost.apu_commands, counted.apu_commands);
  EXPECT_GT(link.cost.list_elements, 0u);
  EXPECT_LT(link.cost.list_elements, counted.list_elements);
}

}  // namespace
