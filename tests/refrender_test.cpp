// The reference renderer on scenes/tiny.json and on one-pixel scenes, against
// values worked out by hand from the shading formula (docs/scene-format.md);
// PNG round trip and PSNR.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "image.hpp"
#include "refrender.hpp"

using namespace mc1;
using refrender::Renderer;

namespace {

std::string scenes_dir() {
  std::string f = __FILE__;
  return f.substr(0, f.rfind('/')) + "/../scenes";
}

void expect_colour(const glm::dvec3& got, const glm::dvec3& want, double tol = 1e-12) {
  EXPECT_NEAR(got.r, want.r, tol);
  EXPECT_NEAR(got.g, want.g, tol);
  EXPECT_NEAR(got.b, want.b, tol);
}

void expect_rgb8(const imgcmp::Image& img, int i, int j, int r, int g, int b) {
  const std::uint8_t* p = img.at(i, j);
  EXPECT_EQ(int(p[0]), r) << "pixel " << i << "," << j;
  EXPECT_EQ(int(p[1]), g) << "pixel " << i << "," << j;
  EXPECT_EQ(int(p[2]), b) << "pixel " << i << "," << j;
}

// tiny.json: floor C = (0.8, 0.6, 0.4), ko 0.1, kd 0.8; light (0, 4, 0) of
// intensity (1, 0.9, 0.8). Diffuse floor shading at a lit point p (y = -1).
glm::dvec3 floor_lit(const glm::dvec3& p) {
  glm::dvec3 C(0.8, 0.6, 0.4), I(1.0, 0.9, 0.8);
  double cos_theta = 5.0 / glm::length(glm::dvec3(0, 4, 0) - p);  // N = +y, light 5 above the floor
  return 0.1 * C + 0.8 * C * I * cos_theta;
}

class RefTiny : public ::testing::Test {
 protected:
  scene::Scene scene = scene::load_scene(scenes_dir() + "/tiny.json");
  Renderer renderer{scene};
  imgcmp::Image image = renderer.render();
};

}  // namespace

TEST(RefCamera, PixelCentresAndVerticalFov) {
  scene::Camera cam;
  cam.eye = {0, 0, 5};
  cam.look_at = {0, 0, 0};
  cam.fov_deg = 90;
  // 32x32, fov 90: pixel (16, 28) centre at x = 0.03125, y = -0.78125 on the plane z = 4.
  refrender::Ray r = refrender::eye_ray(cam, 16, 28, 32, 32);
  glm::dvec3 want = glm::normalize(glm::dvec3(0.03125, -0.78125, -1.0));
  expect_colour(r.dir, want, 1e-15);
  // Wider than tall: the horizontal extent grows with the aspect ratio.
  r = refrender::eye_ray(cam, 0, 0, 2, 1);
  expect_colour(r.dir, glm::normalize(glm::dvec3(-1.0, 0.0, -1.0)), 1e-15);
}

TEST(RefQuantise, ClampAndRoundHalfUp) {
  EXPECT_EQ(refrender::quantise(-0.5), 0);
  EXPECT_EQ(refrender::quantise(2.0), 255);
  EXPECT_EQ(refrender::quantise(0.1), 26);  // 25.5 rounds up
  EXPECT_EQ(refrender::quantise(0.3), 77);  // 76.5 rounds up
  EXPECT_EQ(refrender::quantise(0.2), 51);
}

TEST_F(RefTiny, MissGivesBackground) {
  expect_colour(renderer.pixel(0, 0, 32, 32), {0.1, 0.2, 0.3});
  expect_rgb8(image, 0, 0, 26, 51, 77);
}

// Pixel (16, 28): the eye ray (0.03125, -0.78125, -1) meets the floor at
// t = 1.28: p = (0.04, -1, 3.72); cos(theta) = 5 / sqrt(38.84) = 0.80228818.
TEST_F(RefTiny, LitDiffuseFloor) {
  glm::dvec3 want(0.08 + 0.64 * 0.8022881797571, 0.06 + 0.432 * 0.8022881797571, 0.04 + 0.256 * 0.8022881797571);
  expect_colour(renderer.pixel(16, 28, 32, 32), want, 1e-12);
  expect_colour(want, floor_lit({0.04, -1, 3.72}), 1e-12);
  expect_rgb8(image, 16, 28, 151, 104, 63);
}

// Pixel (16, 19) meets the floor at (0.143, -1, 0.429); the segment to the light
// passes 0.36 from the ball's centre (radius 0.5): only ko C remains.
TEST_F(RefTiny, ShadowLeavesAmbientOnly) {
  expect_colour(renderer.pixel(16, 19, 32, 32), {0.08, 0.06, 0.04});
  expect_rgb8(image, 16, 19, 20, 15, 10);
  EXPECT_TRUE(renderer.shadowed({0.0, -1.0, 0.3}, scene.lights[0]));
  EXPECT_FALSE(renderer.shadowed({0.04, -1.0, 3.72}, scene.lights[0]));
}

// Pixel (24, 17): the eye ray (0.53125, -0.09375, -1) meets the mirror (z = -2,
// C = 0.9, ks = 1) at (3.71875, -0.65625, -2); the reflection (0.53125,
// -0.09375, 1) meets the floor at (17/3, -1, 5/3): pixel = 0.9 x floor there.
TEST_F(RefTiny, MirrorShowsTheReflectedFloor) {
  glm::dvec3 seen = floor_lit({17.0 / 3.0, -1.0, 5.0 / 3.0});
  expect_colour(renderer.pixel(24, 17, 32, 32), 0.9 * seen, 1e-12);
  expect_rgb8(image, 24, 17, 113, 78, 47);
}

TEST_F(RefTiny, DepthZeroDropsTheReflection) {
  scene.render.max_depth = 0;
  expect_colour(renderer.pixel(24, 17, 32, 32), glm::dvec3(0.0));
}

namespace {

// One pixel looking down -z from (0, 0, 5) at a quad in z = 0 facing +z.
scene::Scene one_pixel(const std::string& material, const std::string& primitive, const std::string& kind,
                       const std::string& light = "[3, 0, 4]") {
  std::string text =
      "{\"camera\": {\"eye\": [0, 0, 5], \"look_at\": [0, 0, 0], \"fov\": 30, \"width\": 1, \"height\": 1},\n"
      "\"render\": {\"background\": [0.5, 0.25, 1]},\n"
      "\"lights\": [{\"position\": " + light + ", \"intensity\": [1, 0.5, 0.25]}],\n"
      "\"materials\": [{\"name\": \"m\", " + material + "}],\n"
      "\"objects\": [{\"kind\": \"" + kind + "\", \"material\": \"m\", \"primitives\": [" + primitive + "]}]}\n";
  return scene::parse_scene(text, "one.json", "");
}

const char* kQuad = "{\"type\": \"quad\", \"vertices\": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]}";

}  // namespace

// Light at (3, 0, 4): L = (0.6, 0, 0.8), cos(theta) = 0.8; its mirror direction
// (-0.6, 0, 0.8) against V = (0, 0, 1): cos(phi) = 0.8, cos^5 = 0.32768.
TEST(RefShading, DiffuseAndMetallicTerms) {
  scene::Scene s = one_pixel("\"colour\": [1, 0.5, 0.5], \"ko\": 0.1, \"kd\": 0.5, \"km\": 0.25, \"n\": 5", kQuad,
                             "surface");
  glm::dvec3 C(1, 0.5, 0.5), I(1, 0.5, 0.25);
  glm::dvec3 want = 0.1 * C + 0.5 * C * I * 0.8 + 0.25 * C * I * 0.32768;
  expect_colour(Renderer(s).pixel(0, 0, 1, 1), want);
}

TEST(RefShading, LightBehindTheSurfaceContributesNothing) {
  scene::Scene s = one_pixel("\"colour\": [1, 1, 1], \"ko\": 0.1, \"kd\": 0.5, \"km\": 0.5", kQuad, "surface",
                             "[0, 0, -4]");
  expect_colour(Renderer(s).pixel(0, 0, 1, 1), glm::dvec3(0.1));
}

TEST(RefShading, SurfaceNormalTurnsToTheRay) {
  // The same quad listed clockwise (normal -z) shades the same as a surface.
  scene::Scene s = one_pixel("\"colour\": [1, 1, 1], \"kd\": 1",
                             "{\"type\": \"quad\", \"vertices\": [[-1, -1, 0], [-1, 1, 0], [1, 1, 0], [1, -1, 0]]}",
                             "surface");
  expect_colour(Renderer(s).pixel(0, 0, 1, 1), glm::dvec3(1, 0.5, 0.25) * 0.8);
}

// Along the axis through a glass sphere there is no bending: with kt = 1 and
// nothing else the pixel is C x C x background (in, then out); with depth 1
// the exit point is shaded without a further ray: C x (ko C = 0) = 0.
TEST(RefTransmission, ThroughASolidSphere) {
  scene::Scene s = one_pixel("\"colour\": [0.5, 0.8, 1], \"kt\": 1, \"index\": 1.5",
                             "{\"type\": \"sphere\", \"centre\": [0, 0, 0], \"radius\": 1}", "solid");
  glm::dvec3 C(0.5, 0.8, 1), bg(0.5, 0.25, 1);
  expect_colour(Renderer(s).pixel(0, 0, 1, 1), C * C * bg);
  s.render.max_depth = 1;
  expect_colour(Renderer(s).pixel(0, 0, 1, 1), glm::dvec3(0.0));
}

TEST(RefTransmission, SurfaceIsAThinSheet) {
  scene::Scene s = one_pixel("\"colour\": [0.5, 0.8, 1], \"kt\": 0.5, \"index\": 1.5", kQuad, "surface");
  expect_colour(Renderer(s).pixel(0, 0, 1, 1), 0.5 * glm::dvec3(0.5, 0.8, 1) * glm::dvec3(0.5, 0.25, 1));
}

TEST(RefQuadric, CylinderInItsBox) {
  // x^2 + y^2 - 1 <= 0 (axis z) clipped to |z| <= 0.5, no caps: the eye ray
  // runs down the axis inside the tube and meets nothing.
  scene::Scene s = one_pixel("\"colour\": [1, 1, 1], \"ko\": 1",
                             "{\"type\": \"quadric\", \"coefficients\": [1, 1, 0, 0, 0, 0, 0, 0, 0, -1], "
                             "\"box\": {\"min\": [-1, -1, -0.5], \"max\": [1, 1, 0.5]}}",
                             "solid");
  expect_colour(Renderer(s).pixel(0, 0, 1, 1), {0.5, 0.25, 1});
  // A ray across the axis meets the wall at x = -1 with the outward normal.
  refrender::Hit hit;
  ASSERT_TRUE(Renderer(s).nearest_hit({{-5, 0, 0}, {1, 0, 0}}, hit));
  EXPECT_NEAR(hit.t, 4.0, 1e-12);
  expect_colour(hit.normal, {-1, 0, 0});
  EXPECT_FALSE(Renderer(s).nearest_hit({{-5, 0, 0.6}, {1, 0, 0}}, hit));  // above the box
}

TEST(RefSolid, UnionHidesInnerSurfaces) {
  // Two overlapping spheres in one solid: from inside the first, the ray
  // skips the second's surface that lies inside the first.
  std::string two = "{\"type\": \"sphere\", \"centre\": [0, 0, 0], \"radius\": 1}, "
                    "{\"type\": \"sphere\", \"centre\": [1, 0, 0], \"radius\": 1}";
  scene::Scene s = one_pixel("\"colour\": [1, 1, 1], \"ko\": 1", two, "solid");
  refrender::Hit hit;
  ASSERT_TRUE(Renderer(s).nearest_hit({{-0.5, 0, 0}, {1, 0, 0}}, hit));
  EXPECT_NEAR(hit.t, 2.5, 1e-12);  // x = 2, the far side of the second sphere
  EXPECT_EQ(hit.primitive, 1);
}

// Two unit spheres at x = 0 and x = 1 combined (docs/scene-format.md "Objects").
scene::Scene two_spheres(const std::string& combine) {
  return one_pixel("\"colour\": [1, 1, 1], \"ko\": 1",
                   "{\"type\": \"sphere\", \"centre\": [0, 0, 0], \"radius\": 1}, "
                   "{\"type\": \"sphere\", \"centre\": [1, 0, 0], \"radius\": 1}",
                   "solid\", \"combine\": \"" + combine);
}

TEST(RefCsg, IntersectionIsTheLens) {
  // Along +x from x = -5: the first sphere's surface at x = -1 lies outside
  // the second (hidden); the second's at x = 0 inside the first is the lens.
  scene::Scene s = two_spheres("intersection");
  ASSERT_EQ(s.objects[0].combine, scene::Combine::intersection);
  refrender::Hit hit;
  ASSERT_TRUE(Renderer(s).nearest_hit({{-5, 0, 0}, {1, 0, 0}}, hit));
  EXPECT_NEAR(hit.t, 5.0, 1e-12);
  EXPECT_EQ(hit.primitive, 1);
  expect_colour(hit.normal, {-1, 0, 0});
  // A line through the first sphere only meets no surface of the lens.
  EXPECT_FALSE(Renderer(s).nearest_hit({{-0.5, -5, 0}, {0, 1, 0}}, hit));
}

TEST(RefCsg, DifferenceShowsTheBiteWithTheSolidsNormal) {
  // Along -x from x = 5: the second sphere's far side (x = 2) is outside the
  // first, the first's at x = 1 inside the second: both hidden. The second's
  // at x = 0, inside the first, bounds the bite: its inward normal, +x.
  scene::Scene s = two_spheres("difference");
  refrender::Hit hit;
  ASSERT_TRUE(Renderer(s).nearest_hit({{5, 0, 0}, {-1, 0, 0}}, hit));
  EXPECT_NEAR(hit.t, 5.0, 1e-12);
  EXPECT_EQ(hit.primitive, 1);
  expect_colour(hit.normal, {1, 0, 0});
  ASSERT_TRUE(Renderer(s).nearest_hit({{-5, 0, 0}, {1, 0, 0}}, hit));  // the first's near side
  EXPECT_NEAR(hit.t, 4.0, 1e-12);
  EXPECT_EQ(hit.primitive, 0);
}

TEST(RefCsg, ShadowRaysMeetOnlyTheCombinedSurface) {
  // The segment x = -0.5 from y = -3 to the light at y = 3 crosses the first
  // sphere, not the second: it blocks the light for the union, not for the
  // intersection; x = 0.5 crosses both: the lens blocks it too.
  const scene::Light up{{-0.5, 3, 0}, {1, 1, 1}}, up2{{0.5, 3, 0}, {1, 1, 1}};
  scene::Scene lens = two_spheres("intersection"), both = two_spheres("union");
  EXPECT_FALSE(Renderer(lens).shadowed({-0.5, -3, 0}, up));
  EXPECT_TRUE(Renderer(both).shadowed({-0.5, -3, 0}, up));
  EXPECT_TRUE(Renderer(lens).shadowed({0.5, -3, 0}, up2));
  scene::Scene bite = two_spheres("difference");
  EXPECT_TRUE(Renderer(bite).shadowed({-0.5, -3, 0}, up));
  EXPECT_FALSE(Renderer(bite).shadowed({1.5, -3, 0}, {{1.5, 3, 0}, {1, 1, 1}}));  // the subtrahend alone
}

TEST(RefRevolution, ConeAndCylinderFrustums) {
  // A profile (0, 0) - (1, 1) - (1, 2) about the z axis through the origin:
  // a cone x^2 + y^2 = z^2 below z = 1, a cylinder of radius 1 above.
  scene::Scene s = one_pixel("\"colour\": [1, 1, 1], \"ko\": 1",
                             "{\"type\": \"revolution\", \"axis\": \"z\", \"base\": [0, 0, 0], "
                             "\"profile\": [[0, 0], [1, 1], [1, 2]]}",
                             "solid");
  ASSERT_EQ(s.objects[0].primitives.size(), 2u);
  refrender::Hit hit;
  ASSERT_TRUE(Renderer(s).nearest_hit({{-5, 0, 0.5}, {1, 0, 0}}, hit));  // the cone at radius 0.5
  EXPECT_NEAR(hit.t, 4.5, 1e-12);
  expect_colour(hit.normal, glm::normalize(glm::dvec3(-1, 0, -1)));
  ASSERT_TRUE(Renderer(s).nearest_hit({{-5, 0, 1.5}, {1, 0, 0}}, hit));  // the cylinder
  EXPECT_NEAR(hit.t, 4.0, 1e-12);
  EXPECT_EQ(hit.primitive, 1);
  expect_colour(hit.normal, {-1, 0, 0});
  EXPECT_FALSE(Renderer(s).nearest_hit({{-5, 0, 2.5}, {1, 0, 0}}, hit));  // above the profile
}

TEST(RefRevolution, TiltedAxisIsClippedToItsSlab) {
  // A cylinder of radius 1 from height 0 to 2 about the direction (0, 1, 1)
  // through the origin: a ray along -a meets the end cap's plane only (no
  // caps); a ray across the axis at height 1 meets the side at distance 1
  // from the axis; one at height 2.5 misses (beyond the slab, inside the box).
  scene::Scene s = one_pixel("\"colour\": [1, 1, 1], \"ko\": 1",
                             "{\"type\": \"revolution\", \"axis\": [0, 1, 1], \"base\": [0, 0, 0], "
                             "\"profile\": [[1, 0], [1, 2]]}",
                             "surface");
  const glm::dvec3 a = glm::normalize(glm::dvec3(0, 1, 1));
  refrender::Hit hit;
  ASSERT_TRUE(Renderer(s).nearest_hit({a - glm::dvec3(5, 0, 0), {1, 0, 0}}, hit));
  EXPECT_NEAR(hit.t, 4.0, 1e-12);
  expect_colour(hit.normal, {-1, 0, 0});
  EXPECT_FALSE(Renderer(s).nearest_hit({2.5 * a - glm::dvec3(5, 0, 0), {1, 0, 0}}, hit));
  EXPECT_FALSE(Renderer(s).nearest_hit({-0.5 * a - glm::dvec3(5, 0, 0), {1, 0, 0}}, hit));
}

TEST(ImgcmpPsnr, IdenticalIsInfinite) {
  imgcmp::Image a(4, 4);
  EXPECT_TRUE(std::isinf(imgcmp::psnr(a, a)));
  EXPECT_EQ(imgcmp::mse(a, a), 0.0);
}

TEST(ImgcmpPsnr, KnownPerturbation) {
  imgcmp::Image a(4, 4), b(4, 4);
  b.at(2, 1)[1] = 10;  // one of 48 samples off by 10: MSE = 100 / 48
  EXPECT_DOUBLE_EQ(imgcmp::mse(a, b), 100.0 / 48.0);
  EXPECT_NEAR(imgcmp::psnr(a, b), 44.94321598243498, 1e-12);
  EXPECT_EQ(imgcmp::max_abs_diff(a, b), 10);
  imgcmp::Image d = imgcmp::difference(a, b, 8);
  EXPECT_EQ(d.at(2, 1)[1], 80);
  EXPECT_EQ(imgcmp::difference(a, b, 30).at(2, 1)[1], 255);
  EXPECT_THROW(imgcmp::psnr(a, imgcmp::Image(4, 3)), imgcmp::ImageError);
}

TEST(ImgcmpPng, RoundTripAndCrc) {
  imgcmp::Image a(5, 3);
  for (std::size_t i = 0; i < a.rgb.size(); ++i) a.rgb[i] = static_cast<std::uint8_t>(i * 37 + 11);
  std::vector<std::uint8_t> bytes = imgcmp::encode_png(a);
  imgcmp::Image b = imgcmp::decode_png(bytes, "mem");
  EXPECT_EQ(b.width, 5);
  EXPECT_EQ(b.height, 3);
  EXPECT_EQ(a.rgb, b.rgb);
  bytes[20] ^= 1;  // inside IHDR: the CRC no longer matches
  EXPECT_THROW(imgcmp::decode_png(bytes, "mem"), imgcmp::ImageError);
}
