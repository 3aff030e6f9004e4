// The renderer's firmware and kernels on the ISS (docs/renderer.md): every
// expected value below is computed here in double from the same scene, or
// written out by hand.
// Here: the solid rule (RenderSolids).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "refrender.hpp"

#include "render_fw_test_util.hpp"

namespace {

using namespace mc1;
using namespace mc1::render;
using namespace mc1::render::layout;
using namespace mc1::render::test;

// The solid rule (docs/renderer.md, solid_rule and r_inside): a solid of two
// overlapping glass spheres, whose refracted rays meet the spheres' inner
// surfaces, and an open tube (a quadric without caps) with a ball in its far
// end, seen through the opening, so that eye rays meet the part of the ball
// inside the tube. Light 1 shines into the tube.
const char* kSolids = R"({
  "camera": {"eye": [0.4, 1.6, 6], "look_at": [0.4, 0.9, 0], "up": [0, 1, 0], "fov": 40, "width": 64, "height": 48},
  "render": {"max_depth": 4, "background": [0.3, 0.5, 0.8]},
  "lights": [
    {"position": [-4, 6, 5], "intensity": [0.7, 0.7, 0.7]},
    {"position": [1.3, 1.2, 5], "intensity": [0.6, 0.6, 0.6]}
  ],
  "materials": [
    {"name": "checker", "ko": 0.1, "kd": 0.8, "checker": {"colours": [[0.9, 0.2, 0.15], [0.95, 0.9, 0.3]], "scale": 0.5}},
    {"name": "glass", "colour": [1, 1, 1], "ko": 0, "kd": 0.05, "km": 0.6, "n": 60, "ks": 0.1, "kt": 0.85, "index": 1.5},
    {"name": "clay", "colour": [0.3, 0.8, 0.4], "ko": 0.15, "kd": 0.7, "km": 0.3, "n": 12}
  ],
  "objects": [
    {"name": "floor", "kind": "surface", "material": "checker", "primitives": [
        {"type": "quad", "vertices": [[-5, 0, 4], [5, 0, 4], [5, 0, -6], [-5, 0, -6]]}]},
    {"name": "glass union", "kind": "solid", "material": "glass", "primitives": [
        {"type": "sphere", "centre": [-0.75, 0.9, 0.2], "radius": 0.75},
        {"type": "sphere", "centre": [0.0, 0.9, 0.0], "radius": 0.7}]},
    {"name": "tube and ball", "kind": "solid", "material": "clay", "primitives": [
        {"type": "quadric", "coefficients": [1, 1, 0, 0, 0, 0, -3.2, -1.8, 0, 3.12], "box": {"min": [1.1, 0.4, -2.2], "max": [2.1, 1.4, -0.4]}},
        {"type": "sphere", "centre": [1.6, 0.9, -2.0], "radius": 0.62}]}
  ]
})";

// How far a world point lies inside a region primitive, in the units of the
// solid rule's band (CSG_EPS, docs/renderer.md "CSG and solids of revolution"; > 0
// inside): 1 - |A (x - b)|^2 for an ellipsoid; for a quadric the smaller of
// -q(x) / sum |a_i| and the distance to the clip box's faces over the sum of
// its extents. Polygons hold nothing (-1).
double inside_depth(const scene::Primitive& p, const glm::dvec3& x) {
  if (p.kind == scene::PrimitiveKind::ellipsoid) {
    const glm::dvec3 u = p.A * (x - p.centre);
    return 1.0 - glm::dot(u, u);
  }
  if (p.kind != scene::PrimitiveKind::quadric) return -1.0;
  const auto& a = p.coefficients;
  double scale = 0;
  for (double c : a) scale += std::abs(c);
  const double q = a[0] * x.x * x.x + a[1] * x.y * x.y + a[2] * x.z * x.z + a[3] * x.x * x.y + a[4] * x.x * x.z +
                   a[5] * x.y * x.z + a[6] * x.x + a[7] * x.y + a[8] * x.z + a[9];
  double box = INFINITY;
  for (int k = 0; k < 3; ++k) box = std::min({box, x[k] - p.box_min[k], p.box_max[k] - x[k]});
  const glm::dvec3 e = p.box_max - p.box_min;
  return std::min(-q / scale, box / (e.x + e.y + e.z));
}

// A co-simulated ray's nearest hit, seen from the world: its point, and how
// deep it lies inside another region primitive of its own solid (the largest
// inside_depth; -1 when none holds it).
struct WorldHit {
  int object = -1, prim = -1;  // prim: index within the object (-1 miss)
  glm::dvec3 point{0.0};
  double hidden_depth = -1;
};
WorldHit world_hit(const scene::Scene& sc, const ViewScene& v, const RenderFirmware::Ray& r) {
  WorldHit h;
  if (r.rec[R_ID] == kNoHit) return h;
  auto f = [&](int addr) { return fp24_to_double(r.rec[addr]); };
  auto c = [&](int addr) { return fp24_to_double(v.constants[addr - C_D0]); };
  const double t = f(R_T);
  const glm::dvec3 xv(f(R_O) + t * f(R_D), f(R_O + 1) + t * f(R_D + 1), f(R_O + 2) + t * f(R_D + 2));
  for (int i = 0; i < 3; ++i)
    h.point[i] = c(C_WR + 3 * i) * xv.x + c(C_WR + 3 * i + 1) * xv.y + c(C_WR + 3 * i + 2) * xv.z + c(C_WT + i);
  const int id = static_cast<int>(r.rec[R_ID]);
  h.object = v.prim_object[id];
  h.prim = id - v.objects[h.object].first_prim;
  const scene::Object& o = sc.objects[h.object];
  if (o.kind != scene::ObjectKind::solid) return h;
  for (int k = 0; k < static_cast<int>(o.primitives.size()); ++k)
    if (k != h.prim) h.hidden_depth = std::max(h.hidden_depth, inside_depth(o.primitives[k], h.point));
  return h;
}

// World ray of a co-simulated ray record (view -> world with C_WR, C_WT).
refrender::Ray world_ray(const ViewScene& v, const RenderFirmware::Ray& r) {
  auto f = [&](int addr) { return fp24_to_double(r.rec[addr]); };
  auto c = [&](int addr) { return fp24_to_double(v.constants[addr - C_D0]); };
  refrender::Ray w;
  for (int i = 0; i < 3; ++i) {
    w.origin[i] = c(C_WT + i);
    w.dir[i] = 0;
    for (int k = 0; k < 3; ++k) {
      w.origin[i] += c(C_WR + 3 * i + k) * f(R_O + k);
      w.dir[i] += c(C_WR + 3 * i + k) * f(R_D + k);
    }
  }
  w.dir = glm::normalize(w.dir);
  return w;
}

// Over a generation of rays: hits deeper than 2 CSG_EPS (2^-9) inside a
// sibling region of their solid (within CSG_EPS a point is on its boundary,
// and FP24's hit point may stray as much again), and rays whose hit (object; primitive within a solid;
// point within 0.01) differs from the reference's nearest_hit along the same
// world ray.
struct SolidCounts {
  int hidden = 0, other = 0, hits = 0;
};
SolidCounts solid_counts(const scene::Scene& sc, const ViewScene& v, const std::vector<RenderFirmware::Ray>& rays,
                         bool eye, int w, int h) {
  const refrender::Renderer ref(sc);
  SolidCounts n;
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const WorldHit got = world_hit(sc, v, rays[k]);
    n.hits += got.object >= 0;
    n.hidden += got.hidden_depth > 0x1p-9;
    const refrender::Ray ray = eye ? refrender::eye_ray(sc.camera, static_cast<int>(k) % w,
                                                        static_cast<int>(k) / w, w, h)
                                   : world_ray(v, rays[k]);
    refrender::Hit want;
    if (!ref.nearest_hit(ray, want)) want.object = want.primitive = -1;
    const bool solid = want.object >= 0 && sc.objects[want.object].kind == scene::ObjectKind::solid;
    n.other += got.object != want.object || (solid && got.prim != want.primitive) ||
               (got.object >= 0 && glm::length(got.point - want.point) > 1e-2);
  }
  return n;
}

std::vector<RenderFirmware::Ray> eye_rays(int w, int h) {
  std::vector<RenderFirmware::Ray> rays;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      RenderFirmware::Ray r;
      r.rec[R_KIND] = RK_EYE;
      r.rec[R_ARG] = static_cast<Word>(i);
      r.rec[R_ARG2] = static_cast<Word>(j);
      r.rec[R_ID] = kNoHit;
      r.rec[R_W] = r.rec[R_W + 1] = r.rec[R_W + 2] = fp24_from_double(1.0);
      r.rec[R_CHILD] = CHILD_BOTH;
      rays.push_back(r);
    }
  return rays;
}

// The frame: the standard bound against the reference renderer, which
// implements the rule in double (Renderer::hidden_in_solid).
// Scene `sc`'s frame on `rig`'s firmware, and the reference renderer's.
std::pair<imgcmp::Image, imgcmp::Image> frame_and_reference(Rig& rig, const scene::Scene& sc) {
  rig.fw.load_scene(make_scene_image(sc));
  return {render_frame(rig.fw, sc.camera.width, sc.camera.height), refrender::Renderer(sc).render()};
}

TEST(RenderSolids, UnionSolidsMatchTheReferenceRenderer) {
  const scene::Scene sc = scene::parse_scene(kSolids, "solids.json", ".");
  Rig rig;
  const auto [img, want] = frame_and_reference(rig, sc);
  const int w = sc.camera.width, h = sc.camera.height;
  const double db = psnr_db(img, want);
  int far = 0;
  for (std::size_t k = 0; k < img.rgb.size(); ++k) far += std::abs(int(img.rgb[k]) - int(want.rgb[k])) > 24;
  const auto& st = rig.fw.stats();
  std::printf("solids %dx%d: PSNR %.2f dB, max diff %d, %d samples off by more than 24, %llu hidden hits, "
              "APU %llu cycles\n",
              w, h, db, imgcmp::max_abs_diff(img, want), far, (unsigned long long)st.hidden_hits,
              (unsigned long long)st.total().apu_cycles);
  if (db < 75.0 || std::getenv("MC1_RENDER_DUMP")) {
    imgcmp::write_png("render_fw_solids_fw.png", img);
    imgcmp::write_png("render_fw_solids_ref.png", want);
    imgcmp::write_png("render_fw_solids_diff.png", imgcmp::difference(img, want, 8));
  }
  EXPECT_GE(db, 75.0);  // measured 78.75 dB, less about 3 (issue 40)
  EXPECT_GT(st.hidden_hits, 100u);  // the rule was at work (eye rays into the tube, refracted rays)
}

// Eye rays: through the tube's opening they meet the ball's surface inside
// the tube; solid_rule (r_inside, then r_cast past the hidden hit) leaves no
// hit inside a sibling region, and every ray's hit is the reference's.
TEST(RenderSolids, EyeRaysGoPastSurfacesInsideTheSolid) {
  const scene::Scene sc = scene::parse_scene(kSolids, "solids.json", ".");
  const int w = sc.camera.width, h = sc.camera.height;
  Rig rig;
  rig.fw.load_scene(make_scene_image(sc));
  const auto& v = rig.fw.view();
  const std::vector<int> all = every_primitive(v);
  auto rays = eye_rays(w, h);
  rig.fw.cast(rays, {all}, Step::HiddenSurface);
  const SolidCounts before = solid_counts(sc, v, rays, true, w, h);
  const auto cycles = [&] { return rig.fw.stats().step[static_cast<int>(Step::HiddenSurface)].apu_cycles; };
  const std::uint64_t cast_cycles = cycles();
  rig.fw.solid_rule(rays, {all}, Step::HiddenSurface);
  const SolidCounts after = solid_counts(sc, v, rays, true, w, h);
  int moved = 0;
  for (const auto& r : rays) moved += r.rec[R_TMIN] != 0;
  std::printf("eye rays: without the rule %d hidden hits, %d unlike the reference; with it %d, %d (%d rays moved; "
              "APU cycles: cast %llu, solid_rule %llu)\n",
              before.hidden, before.other, after.hidden, after.other, moved, (unsigned long long)cast_cycles,
              (unsigned long long)(cycles() - cast_cycles));
  EXPECT_GT(before.hidden, 30);
  EXPECT_GT(before.other, 30);
  EXPECT_EQ(after.hidden, 0);
  EXPECT_LE(after.other, 2);
  EXPECT_GE(moved, before.hidden);
  EXPECT_EQ(after.hits, before.hits);  // the ball closes the tube: a moved ray meets its far side or the wall
}

// Secondary rays: the refracted rays inside the glass union meet the other
// sphere's surface inside the solid; with the rule they go on to the union's
// boundary, as in the reference.
TEST(RenderSolids, RefractedRaysGoPastSurfacesInsideTheSolid) {
  const scene::Scene sc = scene::parse_scene(kSolids, "solids.json", ".");
  const int w = sc.camera.width, h = sc.camera.height;
  Rig rig;
  rig.fw.load_scene(make_scene_image(sc));
  const auto& v = rig.fw.view();
  const std::vector<int> all = every_primitive(v);
  auto rays = eye_rays(w, h);
  rig.fw.cast(rays, {all}, Step::HiddenSurface);
  rig.fw.solid_rule(rays, {all}, Step::HiddenSurface);
  rig.fw.surface(rays, Step::HiddenSurface);
  rig.fw.shade(rays, Step::Shading);  // no shadow rays: R_SHADOW 0 does not change the directions
  std::vector<RenderFirmware::Ray> refracted;  // as render_block makes them
  for (const auto& r : rays) {
    if (!(r.rec[R_CHILD] & CHILD_TD)) continue;
    RenderFirmware::Ray k;
    std::copy(r.rec.begin() + R_P, r.rec.begin() + R_P + 3, k.rec.begin() + R_O);
    std::copy(r.rec.begin() + R_TD, r.rec.begin() + R_TD + 3, k.rec.begin() + R_D);
    k.rec[R_T] = fp24_from_double(1e18);
    k.rec[R_ID] = kNoHit;
    k.from = static_cast<int>(r.rec[R_ID]);
    refracted.push_back(k);
  }
  rig.fw.cast(refracted, {all}, Step::Secondary);
  const SolidCounts before = solid_counts(sc, v, refracted, false, w, h);
  rig.fw.solid_rule(refracted, {all}, Step::Secondary);
  const SolidCounts after = solid_counts(sc, v, refracted, false, w, h);
  std::printf("refracted rays (%zu): without the rule %d hidden hits, %d unlike the reference; with it %d, %d\n",
              refracted.size(), before.hidden, before.other, after.hidden, after.other);
  EXPECT_GT(refracted.size(), 200u);
  EXPECT_GT(before.hidden, 50);
  EXPECT_GT(before.other, 50);
  EXPECT_EQ(after.hidden, 0);
  EXPECT_LE(after.other, 3);
}

// Coincident regions (issue 39; docs/renderer.md "CSG and solids of revolution"):
// a sphere combined with itself, with a quadric sphere of the same shape,
// and a boxed cylinder with itself, by union, intersection and difference,
// over a floor. A hit on one region's surface lies on its twin's boundary:
// r_inside's FP24 test of it used to fall either way at random (a speckled
// frame, 24 to 26 dB against the reference, which computed |A(x-b)|^2 = 1
// exactly). Both renderers now take a point within CSG_EPS (2^-10, relative)
// of another region's boundary as on it, which hides neither way: the
// solid's boundary is the twin's surface in all three (the difference
// removes only the subtrahend's interior).
TEST(RenderSolids, CoincidentRegionsMatchTheReferenceRenderer) {
  const std::string head = R"({
  "camera": {"eye": [0, 1.5, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 45, "width": 64, "height": 48},
  "render": {"max_depth": 3, "background": [0.3, 0.5, 0.8]},
  "lights": [{"position": [-4, 6, 5], "intensity": [0.7, 0.7, 0.7]}],
  "materials": [
    {"name": "red", "colour": [0.9, 0.2, 0.15], "ko": 0.1, "kd": 0.7, "km": 0.4, "n": 30},
    {"name": "floor", "colour": [0.8, 0.8, 0.8], "ko": 0.1, "kd": 0.8}
  ],
  "objects": [
    {"name": "floor", "kind": "surface", "material": "floor", "primitives": [
        {"type": "quad", "vertices": [[-5, -1, 5], [5, -1, 5], [5, -1, -5], [-5, -1, -5]]}]},
    {"name": "self", "kind": "solid", "material": "red", "combine": ")";
  const std::string sphere = R"({"type": "sphere", "centre": [0, 0, 0], "radius": 1})";
  const std::string qsphere =
      R"({"type": "quadric", "coefficients": [1, 1, 1, 0, 0, 0, 0, 0, 0, -1], "box": {"min": [-1.2, -1.2, -1.2], "max": [1.2, 1.2, 1.2]}})";
  const std::string cylinder =
      R"({"type": "quadric", "coefficients": [1, 0, 1, 0, 0, 0, 0, 0, 0, -0.64], "box": {"min": [-1, -0.9, -1], "max": [1, 0.6, 1]}})";
  const std::pair<const char*, std::string> pairs[] = {
      {"sphere", sphere + ", " + sphere}, {"sphere-quadric", sphere + ", " + qsphere}, {"cylinder", cylinder + ", " + cylinder}};
  for (const auto& [pair_name, prims] : pairs)
    for (const char* combine : {"union", "intersection", "difference"}) {
      const std::string json = head + combine + R"(", "primitives": [)" + prims + "]}]}";
      const scene::Scene sc = scene::parse_scene(json, "coincident.json", ".");
      Rig rig;
      const auto [img, want] = frame_and_reference(rig, sc);
      const double db = psnr_db(img, want);
      std::printf("%s %s %dx%d: PSNR %.2f dB, max diff %d\n", pair_name, combine, sc.camera.width, sc.camera.height, db,
                  imgcmp::max_abs_diff(img, want));
      EXPECT_GE(db, 72.0) << pair_name << " " << combine;  // measured 76.02 to 76.98 (22.6 to 27.9 dB before)
    }
}

}  // namespace
