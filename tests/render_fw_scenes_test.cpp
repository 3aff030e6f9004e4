// The renderer's firmware and kernels on the ISS (docs/renderer.md): every
// expected value below is computed here in double from the same scene, or
// written out by hand.
// Here: the standard scenes against the reference renderer, CSG, the section
// 7 primitives' cost (RenderScenes, RenderCsg, RenderCost).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "refrender.hpp"

#include "render_fw_test_util.hpp"

namespace {

using namespace mc1;
using namespace mc1::render;
using namespace mc1::render::layout;
using namespace mc1::render::test;

// A standard scene (docs/scene-format.md) at width x height, co-simulated
// block by block on the ISS, against the double-precision reference renderer
// at least `floor_db` of PSNR. Below it (or with MC1_RENDER_DUMP) the frame,
// the reference and their difference (x8) go to the working directory (the
// build tree).
void expect_near_reference(const std::string& name, int width, int height, double floor_db) {
  Rig rig;
  const scene::Scene sc = load_standard_scene(rig, name, width, height);
  const imgcmp::Image img = render_frame(rig.fw, width, height);
  const imgcmp::Image want = refrender::Renderer(sc).render();
  const double db = psnr_db(img, want);
  std::printf("%s %dx%d: PSNR %.2f dB, max diff %d\n", name.c_str(), width, height, db,
              imgcmp::max_abs_diff(img, want));
  const std::string stem = "render_fw_" + name + "_" + std::to_string(width) + "x" + std::to_string(height);
  if (db < floor_db || std::getenv("MC1_RENDER_DUMP")) {
    imgcmp::write_png(stem + "_fw.png", img);
    imgcmp::write_png(stem + "_ref.png", want);
    imgcmp::write_png(stem + "_diff.png", imgcmp::difference(img, want, 8));
    std::printf("  wrote %s_{fw,ref,diff}.png\n", stem.c_str());
  }
  EXPECT_GE(db, floor_db) << name << " " << width << "x" << height << ": PSNR against the reference";
}

// Each scene's floor is its measured PSNR less about 3 dB (issue 40: a
// floor far below what is measured lets a wrong rounding pass; truncating
// the pixels instead of rounding them drops whitted to 50.5 dB and room to
// 51.4). Measured (docs/renderer.md "Tests"), 64x48 unless named: whitted
// 67.40, room 73.97, smooth 50.00, teapot 32x24 75.74, teapot 76.31, csg
// 76.98 (55.41 before the solid rule's band, issue 39), lathe 78.75 dB.
TEST(RenderScenes, WhittedNearTheReference) { expect_near_reference("whitted", 64, 48, 64.0); }
TEST(RenderScenes, RoomNearTheReference) { expect_near_reference("room", 64, 48, 70.0); }
TEST(RenderScenes, SmoothNearTheReference) { expect_near_reference("smooth", 64, 48, 47.0); }
TEST(RenderScenes, TeapotNearTheReference) { expect_near_reference("teapot", 32, 24, 72.0); }
TEST(RenderScenes, TeapotAt64x48NearTheReference) { expect_near_reference("teapot", 64, 48, 73.0); }

// Section 7's scenes (docs/renderer.md "CSG and solids of revolution").
TEST(RenderScenes, CsgNearTheReference) { expect_near_reference("csg", 64, 48, 73.0); }
TEST(RenderScenes, LatheNearTheReference) { expect_near_reference("lathe", 64, 48, 75.0); }

// CSG on eye and shadow rays: csg.json at 64x48 as one block, s1 with the
// solid rule (r_inside's CSG_OUT regions hide hits outside them), then s2
// (the combined regions cast apart, the solid rule on the shadow rays):
// every pixel's object and per-light shadow flags against the reference's
// nearest_hit and shadowed.
TEST(RenderCsg, EyeHitsAndShadowFlagsMatchTheReference) {
  const int w = 64, h = 48;
  Rig rig;
  const scene::Scene sc = load_standard_scene(rig, "csg", w, h);
  const auto& v = rig.fw.view();
  const BlockList list = rig.fw.build_block_list({0, 0, w, h});
  std::vector<RenderFirmware::Ray> rays = rig.fw.hidden_surface(list);
  rig.fw.solid_rule(rays, {rig.fw.eye_candidates(list)}, Step::HiddenSurface);
  const std::uint64_t eye_hidden = rig.fw.stats().hidden_hits;
  rig.fw.surface(rays, Step::HiddenSurface);
  rig.fw.shadows(rays);
  const std::uint64_t shadow_hidden = rig.fw.stats().hidden_hits - eye_hidden;
  const refrender::Renderer ref(sc);
  int other_object = 0, other_flags = 0, combined = 0, shadowed = 0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const auto& rec = rays[j * w + i].rec;
      refrender::Hit hit;
      const bool ref_hit = ref.nearest_hit(refrender::eye_ray(sc.camera, i, j, w, h), hit);
      const int obj = rec[R_ID] == kNoHit ? -1 : v.prim_object[rec[R_ID]];
      if (obj != (ref_hit ? hit.object : -1)) {
        ++other_object;
        continue;
      }
      if (obj < 0) continue;
      combined += sc.objects[obj].combine != scene::Combine::union_;
      int ref_flags = 0;
      for (int l = 0; l < static_cast<int>(sc.lights.size()); ++l) ref_flags |= ref.shadowed(hit.point, sc.lights[l]) << l;
      other_flags += static_cast<int>(rec[R_SHADOW]) != ref_flags;
      shadowed += ref_flags != 0;
    }
  std::printf("csg 64x48: %d pixels on combined solids, %d shadowed; hidden hits eye %llu, shadow %llu; "
              "other object %d, other shadow flags %d\n",
              combined, shadowed, static_cast<unsigned long long>(eye_hidden),
              static_cast<unsigned long long>(shadow_hidden), other_object, other_flags);
  EXPECT_GT(combined, 400);
  EXPECT_GT(eye_hidden, 100u);    // the lens's and the bores' hidden crossings
  EXPECT_GT(shadow_hidden, 10u);  // shadow rays past hidden crossings
  EXPECT_LE(other_object, 3);     // measured 0
  EXPECT_LE(other_flags, 3);      // measured 0
}

TEST(RenderCost, CyclesPerRayOfTheSection7Primitives) {
  Rig lathe;
  const scene::Scene sl = load_standard_scene(lathe, "lathe", 64, 48);
  const int pawn = lathe.fw.view().objects.at(2).first_prim + 3;  // its shaft, (0.3, 0.35) - (0.2, 0.8)
  const std::uint64_t none = cast_cycles(lathe, 25, 16, {});
  std::vector<RenderFirmware::Ray> rays;
  const std::uint64_t frustum = cast_cycles(lathe, 25, 16, {pawn}, &rays) - none;
  int hits = 0;
  for (const auto& r : rays) hits += r.rec[R_ID] == static_cast<std::uint32_t>(pawn);
  Rig csg;
  load_standard_scene(csg, "csg", 64, 48);
  const auto& lens = csg.fw.view().objects.at(1);
  const std::vector<int> both{lens.first_prim, lens.first_prim + 1};
  const std::uint64_t sphere = cast_cycles(csg, 22, 0, {lens.first_prim}) - cast_cycles(csg, 22, 0, {});
  std::vector<RenderFirmware::Ray> eye;
  cast_cycles(csg, 22, 0, both, &eye);
  csg.fw.reset_stats();
  csg.fw.solid_rule(eye, {both}, Step::HiddenSurface);
  const std::uint64_t rule = csg.fw.stats().step[static_cast<int>(Step::HiddenSurface)].apu_cycles;
  int on_lens = 0;
  for (const auto& r : eye) on_lens += r.rec[R_ID] != kNoHit;
  std::printf("per ray: a frustum %.1f cycles (%d of 32 hit it), a sphere %.1f; the lens's solid rule %.1f "
              "(%llu hidden hits, %d rays end on the lens)\n",
              frustum / 32.0, hits, sphere / 32.0, rule / 32.0,
              static_cast<unsigned long long>(csg.fw.stats().hidden_hits), on_lens);
  EXPECT_GT(hits, 0);
  EXPECT_GT(frustum, 32u * 20);  // a quadric's root pair and box test with its error bound: 100-300 cycles
  EXPECT_LT(frustum, 32u * 400);
  EXPECT_GT(on_lens, 0);
  EXPECT_GT(csg.fw.stats().hidden_hits, 0u);
}

}  // namespace
