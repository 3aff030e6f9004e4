// The renderer's firmware and kernels on the ISS (docs/renderer.md): every
// expected value below is computed here in double from the same scene, or
// written out by hand.
// Here: s1's scan conversion against ray casting (RenderScan).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "render_fw_test_util.hpp"

namespace {

using namespace mc1;
using namespace mc1::render;
using namespace mc1::render::layout;
using namespace mc1::render::test;

// s1's scan conversion (r_scan: edge and depth plane equations per pixel of
// each triangle's projected rectangle, then r_cast for the regions) finds the
// same nearest primitive as casting every eye ray against every primitive,
// up to pixels whose centre lies within FP24 rounding of a triangle edge,
// and the same distance.
struct ScanAgreement {
  int pixels = 0, triangle_hits = 0, region_hits = 0, id_differs = 0;
  double max_rel_t = 0;
};

ScanAgreement scan_against_casting(const std::string& name, int w, int h, int bs) {
  Rig rig;
  const scene::Scene sc = load_standard_scene(rig, name, w, h);
  const auto& v = rig.fw.view();
  const std::vector<int> all = every_primitive(v);
  ScanAgreement a;
  for (int y0 = 0; y0 < h; y0 += bs)
    for (int x0 = 0; x0 < w; x0 += bs) {
      const BlockList bl = rig.fw.build_block_list({x0, y0, std::min(bs, w - x0), std::min(bs, h - y0)});
      const auto scanned = rig.fw.hidden_surface(bl);
      std::vector<RenderFirmware::Ray> cast;
      for (int j = 0; j < bl.block.h; ++j)
        for (int i = 0; i < bl.block.w; ++i) {
          RenderFirmware::Ray r;
          r.rec[R_KIND] = RK_EYE;
          r.rec[R_ARG] = static_cast<Word>(x0 + i);
          r.rec[R_ARG2] = static_cast<Word>(y0 + j);
          r.rec[R_ID] = kNoHit;
          cast.push_back(r);
        }
      rig.fw.cast(cast, {all}, Step::HiddenSurface);
      for (std::size_t p = 0; p < cast.size(); ++p) {
        ++a.pixels;
        const Word id = scanned[p].rec[R_ID];
        if (id != kNoHit) {
          const Word type = v.prims[id][P_TYPE];
          ++(type == kTriangle || type == kPseudoTriangle ? a.triangle_hits : a.region_hits);
        }
        for (int c = 0; c < 3; ++c) EXPECT_EQ(scanned[p].rec[R_D + c], cast[p].rec[R_D + c]);
        if (id != cast[p].rec[R_ID]) {
          ++a.id_differs;
          continue;
        }
        if (id == kNoHit) continue;
        const double ts = fp24_to_double(scanned[p].rec[R_T]), tc = fp24_to_double(cast[p].rec[R_T]);
        a.max_rel_t = std::max(a.max_rel_t, std::fabs(ts - tc) / tc);
      }
    }
  std::printf("%s %dx%d blocks %d: %d pixels, %d triangle hits, %d region hits, %d ids differ, max |dt|/t %.2e\n",
              name.c_str(), w, h, bs, a.pixels, a.triangle_hits, a.region_hits, a.id_differs, a.max_rel_t);
  return a;
}

TEST(RenderScan, TrianglesScanConvertedLikeRayCastingInTheRoom) {
  const ScanAgreement a = scan_against_casting("room", 64, 48, 16);
  EXPECT_EQ(a.pixels, 64 * 48);
  EXPECT_GT(a.triangle_hits, 2000);
  EXPECT_GT(a.region_hits, 100);
  EXPECT_LE(a.id_differs, a.pixels / 100);  // measured 0
  EXPECT_LT(a.max_rel_t, 2e-4);             // measured 4.6e-5
}

TEST(RenderScan, PseudoPolygonsInTilesOfAWholeFrameBlock) {
  // 64x48 in one block: 3072 pixels, tiles of Z_PIXELS, many chunks of 48.
  const ScanAgreement a = scan_against_casting("smooth", 64, 48, 64);
  EXPECT_EQ(a.pixels, 64 * 48);
  EXPECT_GT(a.triangle_hits, 1000);
  EXPECT_LE(a.id_differs, a.pixels / 100);
  // Measured 4.9e-4 (0 ids differ): the teapot-like model's grazing facets,
  // where both the plane equation w and r_cast's N.D lose bits.
  EXPECT_LT(a.max_rel_t, 1e-3);
}

// Watertight edges (docs/renderer.md "Predicates"): a curved mesh whose
// vertices lie on the eye rays of pixel centres 4 pixels apart, so that its
// row, column and diagonal edges pass through pixel centres (within the FP24
// rounding of the vertices: rounding decides which side), each shared by two
// triangles. No pixel centre inside the mesh may fall between them (the
// former edge functions, of each triangle's own v0, E1, E2, 1 / V and
// stepped along the row: 94 of the 633 on-edge pixels did).
TEST(RenderScan, SharedEdgesThroughPixelCentresLeaveNoCrack) {
  TestScene s;
  s.width = 48;
  s.height = 32;
  const int cols = 10, rows = 7, step = 4, first = 2;
  auto vertex = [&](int a, int b) {
    const int i = first + step * a, j = first + step * b;
    const double h = std::tan(s.fov_deg * M_PI / 360.0), px = 2 * h / s.height;
    const double depth = 6 + 0.7 * std::sin(0.9 * a) + 0.5 * std::cos(1.3 * b);  // not planar
    return V3{(i + 0.5 - s.width / 2.0) * px * depth, (s.height / 2.0 - j - 0.5) * px * depth, depth};
  };
  for (int b = 0; b < rows; ++b)
    for (int a = 0; a < cols; ++a) {
      s.add_triangle(vertex(a, b), vertex(a + 1, b), vertex(a + 1, b + 1), 0, 0);
      s.add_triangle(vertex(a, b), vertex(a + 1, b + 1), vertex(a, b + 1), 0, 0);
    }
  Rig rig;
  rig.fw.load_view_scene(s.view());
  const auto z = rig.fw.scan_convert({0, 0, s.width, s.height}, every_primitive(rig.fw.view()));
  int inside = 0, on_edges = 0, cracks = 0;
  for (int j = first + 1; j < first + step * rows; ++j)
    for (int i = first + 1; i < first + step * cols; ++i) {
      ++inside;
      const int di = (i - first) % step, dj = (j - first) % step;
      on_edges += di == 0 || dj == 0 || di == dj;
      if (z[j * s.width + i].id == kNoHit) ++cracks, ADD_FAILURE() << "crack at (" << i << ", " << j << ")";
    }
  std::printf("mesh of %d triangles: %d pixels inside, %d on shared edges, %d cracks\n", 2 * cols * rows, inside,
              on_edges, cracks);
  EXPECT_GT(on_edges, 500);
  EXPECT_EQ(cracks, 0);
}

}  // namespace
