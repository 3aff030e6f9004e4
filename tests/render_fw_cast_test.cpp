// The renderer's firmware and kernels on the ISS (docs/renderer.md): every
// expected value below is computed here in double from the same scene, or
// written out by hand.
// Here: eye rays cast, FP24 conversion, whole frames (RenderCast,
// RenderFp24, RenderFrame).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "refrender.hpp"

#include "render_fw_test_util.hpp"

namespace {

using namespace mc1;
using namespace mc1::render;
using namespace mc1::render::layout;
using namespace mc1::render::test;

TEST(RenderCast, EyeRaysFindTheNearestSphereOrTriangle) {
  TestScene s;
  s.add_sphere({0, 0, 6}, 1.5, 0, 0);
  s.add_sphere({1.5, 1, 9}, 2, 0, 1);
  s.add_triangle({-4, -2, 4}, {4, -2, 4}, {-4, -2, 14}, 0, 2);
  Rig rig;
  rig.fw.load_view_scene(s.view());
  std::vector<RenderFirmware::Ray> rays;
  for (int j = 0; j < s.height; ++j)
    for (int i = 0; i < s.width; ++i) {
      RenderFirmware::Ray r;
      r.rec[R_KIND] = RK_EYE;
      r.rec[R_ARG] = static_cast<Word>(i);
      r.rec[R_ARG2] = static_cast<Word>(j);
      r.rec[R_ID] = kNoHit;
      r.list = 0;
      rays.push_back(r);
    }
  rig.fw.cast(rays, {{0, 1, 2}}, Step::HiddenSurface);
  int hits[3] = {0, 0, 0}, misses = 0;
  for (int j = 0; j < s.height; ++j)
    for (int i = 0; i < s.width; ++i) {
      const auto& rec = rays[j * s.width + i].rec;
      const V3 d = s.eye_dir(i, j);
      EXPECT_NEAR(fp24_to_double(rec[R_D + 0]), d.x, 1e-4) << i << "," << j;
      EXPECT_NEAR(fp24_to_double(rec[R_D + 2]), d.z, 1e-4) << i << "," << j;
      const auto [t, id] = s.hit({0, 0, 0}, d, 0, 1e18);
      if (id < 0) {
        EXPECT_EQ(rec[R_ID], kNoHit) << i << "," << j;
        ++misses;
        continue;
      }
      ASSERT_EQ(static_cast<int>(rec[R_ID]), id) << i << "," << j;
      EXPECT_NEAR(fp24_to_double(rec[R_T]), t, 1e-3 * t) << i << "," << j;  // grazing hits lose most
      ++hits[id];
    }
  // The picture has all three primitives and some background.
  EXPECT_GT(hits[0], 20);
  EXPECT_GT(hits[1], 10);
  EXPECT_GT(hits[2], 20);
  EXPECT_GT(misses, 5);
  EXPECT_EQ(rig.fw.stats().step[static_cast<int>(Step::HiddenSurface)].batches, 8u);  // 256 rays / 32
  EXPECT_GT(rig.fw.stats().step[static_cast<int>(Step::HiddenSurface)].apu_cycles, 256u * 3 * 50);
}

TEST(RenderFp24, ConversionRoundsToNearestEven) {
  EXPECT_EQ(fp24_from_double(1.0), 0x3F0000u);
  EXPECT_EQ(fp24_from_double(-2.5), 0xC04000u);
  EXPECT_EQ(fp24_from_double(1.0 + std::ldexp(1.0, -17)), 0x3F0000u);   // tie, to even
  EXPECT_EQ(fp24_from_double(1.0 + 3 * std::ldexp(1.0, -17)), 0x3F0002u);  // tie, to even (up)
  EXPECT_EQ(fp24_from_double(1e30), 0x7F0000u);
  EXPECT_EQ(fp24_from_double(1e-30), 0x000000u);
  EXPECT_EQ(fp24_from_double(M_PI / 360), 0x381DF4u);  // r_xform's degree constant
  EXPECT_EQ(fp24_from_double(1e18), 0x7ABC17u);       // C_BIG
  EXPECT_EQ(fp24_to_double(0x3F8000), 1.5);
}

TEST(RenderFrame, WhittedSceneMatchesTheReferenceRenderer) {
  const scene::Scene sc = scene::parse_scene(kWhitted, "whitted-small.json", ".");
  Rig rig;
  rig.fw.load_scene(make_scene_image(sc));
  const auto& v = rig.fw.view();
  ASSERT_EQ(v.prims.size(), 13u);  // 5 quads as 10 triangles, 1 triangle, 2 ellipsoids
  imgcmp::Image img(sc.camera.width, sc.camera.height);
  for (int y0 = 0; y0 < img.height; y0 += 16)
    for (int x0 = 0; x0 < img.width; x0 += 16) {
      Block b{x0, y0, std::min(16, img.width - x0), std::min(16, img.height - y0)};
      const BlockList bl = rig.fw.build_block_list(b);
      const auto px = rig.fw.render_block(bl);
      ASSERT_EQ(px.size(), static_cast<std::size_t>(b.w * b.h));
      for (int j = 0; j < b.h; ++j)
        for (int i = 0; i < b.w; ++i) {
          auto* p = img.at(x0 + i, y0 + j);
          p[0] = px[j * b.w + i].r, p[1] = px[j * b.w + i].g, p[2] = px[j * b.w + i].b;
        }
    }
  const refrender::Renderer ref(sc);
  const imgcmp::Image want = ref.render();
  const double db = psnr_db(img, want);
  if (const char* dir = std::getenv("MC1_RENDER_DUMP")) {  // for a look: both frames as PNG
    imgcmp::write_png(std::string(dir) + "/whitted_fw.png", img);
    imgcmp::write_png(std::string(dir) + "/whitted_ref.png", want);
  }
  int far = 0;
  for (std::size_t k = 0; k < img.rgb.size(); ++k) far += std::abs(int(img.rgb[k]) - int(want.rgb[k])) > 24;
  std::printf("whitted 48x36: PSNR %.2f dB, %d samples off by more than 24\n", db, far);
  EXPECT_GE(db, 77.0);  // measured 80.51 dB, less about 3 (issue 40)
  const auto& st = rig.fw.stats();
  for (int k = 0; k < kSteps; ++k)
    std::printf("  %-28s APU %10llu cycles  %4llu runs  %5llu batches  %8llu words\n",
                step_name(static_cast<Step>(k)), (unsigned long long)st.step[k].apu_cycles,
                (unsigned long long)st.step[k].apu_runs, (unsigned long long)st.step[k].batches,
                (unsigned long long)st.step[k].word_copies);
  EXPECT_EQ(st.rays, 48u * 36u);
  EXPECT_GT(st.secondary_rays, 100u);  // mirror and glass spheres spawn rays
}

// Determinism: a block's pixels depend only on the scene and the block, not
// on what the NC rendered before (bank caches, kernels left loaded).
TEST(RenderFrame, ABlockIsTheSameAloneOrAfterOthers) {
  const scene::Scene sc = scene::parse_scene(kWhitted, "whitted-small.json", ".");
  Rig alone, busy;
  alone.fw.load_scene(make_scene_image(sc));
  busy.fw.load_scene(make_scene_image(sc));
  render_frame(busy.fw, 48, 36);
  const Block b{16, 16, 16, 16};
  const auto a = alone.fw.render_block(alone.fw.build_block_list(b));
  const auto c = busy.fw.render_block(busy.fw.build_block_list(b));
  ASSERT_EQ(a.size(), 256u);
  EXPECT_TRUE(a == c);
  // Step 2: every object is in front of the eye; the floor (box reaching
  // nearest) comes first, the glass sphere (z 0.9) before the mirror (-0.8).
  const auto bl = alone.fw.build_block_list(b);
  EXPECT_EQ(bl.objects, (std::vector<int>{0, 2, 1, 3}));
  EXPECT_EQ(bl.load, 1u + 4u + 4u + 1u);
}

}  // namespace
