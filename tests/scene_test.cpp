// The scene loader (docs/scene-format.md): the standard scenes with their
// exact primitive counts, every kind of bad input refused with its JSON path
// and line, and the Bezier/B-spline tessellation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "scene.hpp"

using namespace mc1::scene;

namespace {

std::string scenes_dir() {
  std::string f = __FILE__;
  return f.substr(0, f.rfind('/')) + "/../scenes";
}

// A valid scene whose "objects" array is `objects`; the camera, light and
// material take lines 2-6, so objects start on line 8.
std::string scene_text(const std::string& objects, const std::string& camera_extra = "",
                       const std::string& material_extra = "") {
  return "{\n"
         "\"camera\": {\"eye\": [0, 0, 5], \"look_at\": [0, 0, 0], \"fov\": 60, \"width\": 8, \"height\": 8" +
         camera_extra +
         "},\n"
         "\"lights\": [{\"position\": [0, 5, 5]}],\n"
         "\"materials\": [\n"
         "  {\"name\": \"m\", \"colour\": [1, 0.5, 0.25], \"kd\": 0.5" +
         material_extra +
         "}\n"
         "],\n"
         "\"objects\": [\n" +
         objects + "\n]}\n";
}

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "t.json", scenes_dir());
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(accepted)";
}

const std::string kSphere =
    "{\"kind\": \"solid\", \"material\": \"m\", \"primitives\": [{\"type\": \"sphere\", \"centre\": [0, 0, 0], "
    "\"radius\": 1}]}";

std::string object_with(const std::string& primitive) {
  return "{\"kind\": \"surface\", \"material\": \"m\", \"primitives\": [\n" + primitive + "\n]}";
}

// `count` copies of `primitive`, comma-separated, one per line.
std::string repeated(const std::string& primitive, std::size_t count) {
  std::string out;
  out.reserve((primitive.size() + 2) * count);
  for (std::size_t i = 0; i < count; ++i) out += (i ? ",\n" : "") + primitive;
  return out;
}

const std::string kTriangle = "{\"type\": \"triangle\", \"vertices\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}";
const std::string kQuad = "{\"type\": \"quad\", \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}";
const char* const kFp24Range = "0 or a magnitude in [2.168e-19, 1.8447e19], FP24's range";

// A file of `size` zero bytes that takes no disk space (ftruncate).
void make_sparse(const std::string& path, std::uintmax_t size) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).close();
  std::filesystem::resize_file(path, size);
}

}  // namespace

TEST(SceneStandard, Whitted) {
  Scene s = load_scene(scenes_dir() + "/whitted.json");
  EXPECT_EQ(s.primitive_count(), 6u);
  EXPECT_EQ(s.count(PrimitiveKind::quad), 4u);
  EXPECT_EQ(s.count(PrimitiveKind::ellipsoid), 2u);
  EXPECT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.render.max_depth, 5);
  EXPECT_TRUE(s.materials[0].textured);
  EXPECT_EQ(s.camera.width, 320);
}

// 32 patches at level 6: 24 regular patches give 36 cells each; the 8 lid and
// bottom patches with a collapsed edge give 6 triangles and 30 quads each.
TEST(SceneStandard, TeapotTessellation) {
  Scene s = load_scene(scenes_dir() + "/teapot.json");
  EXPECT_EQ(s.count(PrimitiveKind::pseudo_quad), 24u * 36 + 8 * 30);
  EXPECT_EQ(s.count(PrimitiveKind::pseudo_triangle), 8u * 6);
  EXPECT_EQ(s.count(PrimitiveKind::quad), 1u);
  EXPECT_EQ(s.primitive_count(), 1153u);
  // Turned y up: it stands on y = 0 and is 3.15 tall.
  const Object& pot = s.objects[1];
  EXPECT_NEAR(pot.box_min.y, 0.0, 1e-12);
  EXPECT_NEAR(pot.box_max.y, 3.15, 1e-12);
  for (const auto& p : pot.primitives)
    for (int k = 0; k < p.vertex_count; ++k) EXPECT_NEAR(glm::length(p.vertex_normals[k]), 1.0, 1e-12);
}

TEST(SceneStandard, Room) {
  Scene s = load_scene(scenes_dir() + "/room.json");
  EXPECT_EQ(s.primitive_count(), 18u);
  EXPECT_EQ(s.count(PrimitiveKind::quad), 10u);
  EXPECT_EQ(s.count(PrimitiveKind::triangle), 4u);
  EXPECT_EQ(s.count(PrimitiveKind::quadric), 3u);
  EXPECT_EQ(s.count(PrimitiveKind::ellipsoid), 1u);
}

TEST(SceneStandard, Smooth) {
  Scene s = load_scene(scenes_dir() + "/smooth.json");
  // Periodic 8x6 B-spline net: 48 spans at level 3; octahedron split twice.
  EXPECT_EQ(s.count(PrimitiveKind::pseudo_quad), 48u * 9);
  EXPECT_EQ(s.count(PrimitiveKind::pseudo_triangle), 128u);
  EXPECT_EQ(s.primitive_count(), 561u);
}

TEST(SceneStandard, CsgAndLathe) {
  Scene c = load_scene(scenes_dir() + "/csg.json");
  EXPECT_EQ(c.count(PrimitiveKind::quad), 2u);
  EXPECT_EQ(c.count(PrimitiveKind::ellipsoid), 6u);
  EXPECT_EQ(c.count(PrimitiveKind::quadric), 3u);
  const Combine want[] = {Combine::union_, Combine::intersection, Combine::difference, Combine::difference,
                          Combine::intersection};
  ASSERT_EQ(c.objects.size(), 5u);
  for (std::size_t o = 0; o < 5; ++o) EXPECT_EQ(c.objects[o].combine, want[o]) << o;
  Scene l = load_scene(scenes_dir() + "/lathe.json");
  EXPECT_EQ(l.count(PrimitiveKind::quad), 2u);
  EXPECT_EQ(l.count(PrimitiveKind::quadric), 7u + 11 + 5 + 6);  // one frustum per profile segment
  EXPECT_EQ(l.primitive_count(), 31u);
}

TEST(SceneStandard, Tiny) {
  Scene s = load_scene(scenes_dir() + "/tiny.json");
  EXPECT_EQ(s.primitive_count(), 3u);
  EXPECT_EQ(s.camera.width, 32);
  EXPECT_EQ(s.camera.height, 32);
  const Primitive& ball = s.objects[1].primitives[0];
  EXPECT_EQ(ball.kind, PrimitiveKind::ellipsoid);
  EXPECT_DOUBLE_EQ(ball.A[0][0], 2.0);  // sphere radius 0.5 -> A = I / 0.5
  EXPECT_EQ(ball.box_min, glm::dvec3(-0.5));
  const Primitive& floor = s.objects[0].primitives[0];
  EXPECT_EQ(floor.normal, glm::dvec3(0, 1, 0));
}

TEST(SceneLoader, DefaultsAndEllipsoidBox) {
  Scene s = parse_scene(scene_text(object_with(
                            "{\"type\": \"ellipsoid\", \"A\": [[2, 0, 0], [0, 1, 0], [0, 0, 0.5]], \"centre\": [1, 2, 3]}")),
                        "t.json", "");
  EXPECT_EQ(s.render.max_depth, 5);
  EXPECT_EQ(s.render.background, glm::dvec3(0.0));
  EXPECT_EQ(s.camera.up, glm::dvec3(0, 1, 0));
  EXPECT_EQ(s.lights[0].intensity, glm::dvec3(1.0));
  EXPECT_EQ(s.materials[0].ko, 0.0);
  EXPECT_EQ(s.materials[0].index, 1.0);
  const Primitive& e = s.objects[0].primitives[0];
  EXPECT_DOUBLE_EQ(e.A[0][0], 2.0);   // row 0, column 0
  EXPECT_DOUBLE_EQ(e.A[2][2], 0.5);
  EXPECT_EQ(e.box_min, glm::dvec3(0.5, 1, 1));
  EXPECT_EQ(e.box_max, glm::dvec3(1.5, 3, 5));
}

TEST(SceneErrors, MatrixShapeNamesPathAndLine) {
  std::string text = scene_text(kSphere + ",\n" +
                                object_with("{\"type\": \"ellipsoid\", \"A\": [[1, 0], [0, 1]], \"centre\": [0, 0, 0]}"));
  EXPECT_EQ(error_of(text), "t.json:10: objects[1].primitives[0].A: expected 3x3 matrix");
}

TEST(SceneErrors, UnknownKey) {
  EXPECT_EQ(error_of(scene_text(kSphere, "", ", \"colr\": [1, 1, 1]")), "t.json:5: materials[0].colr: unknown key");
  EXPECT_EQ(error_of(scene_text(kSphere, ", \"zoom\": 2")), "t.json:2: camera.zoom: unknown key");
}

TEST(SceneErrors, MissingKeyWrongTypeRange) {
  std::string no_fov = "{\n\"camera\": {\"eye\": [0, 0, 5], \"look_at\": [0, 0, 0], \"width\": 8, \"height\": 8},\n"
                       "\"lights\": [], \"materials\": [], \"objects\": []}";
  EXPECT_EQ(error_of(no_fov), "t.json:2: camera: missing key \"fov\"");
  std::string text = scene_text(kSphere);
  std::string bad_fov = text;
  bad_fov.replace(bad_fov.find("\"fov\": 60"), 9, "\"fov\": \"wide\"");
  EXPECT_EQ(error_of(bad_fov), "t.json:2: camera.fov: expected a number");
  std::string negative_ks = scene_text(kSphere, "", ", \"ks\": -1");
  EXPECT_EQ(error_of(negative_ks), "t.json:5: materials[0].ks: must not be negative");
  std::string width = text;
  width.replace(width.find("\"width\": 8"), 10, "\"width\": 8.5");
  EXPECT_EQ(error_of(width), "t.json:2: camera.width: expected an integer in 1..8192");
}

TEST(SceneErrors, JsonSyntaxHasLineAndColumn) {
  EXPECT_EQ(error_of("{\n  \"camera\": {\"eye\": [0, 0 5]}\n}"), "t.json:2:27: JSON syntax: expected ',' or ']'");
  EXPECT_EQ(error_of("{\"a\": 1, \"a\": 2}"), "t.json:1:10: JSON syntax: duplicate key \"a\"");
  EXPECT_EQ(error_of("{\"a\": tru}"), "t.json:1:7: JSON syntax: invalid literal 'tru' (expected true, false or null)");
  EXPECT_EQ(error_of("{\"a\": @}"), "t.json:1:7: JSON syntax: unexpected character '@'");
  EXPECT_EQ(error_of("{\"a\" 1}"), "t.json:1:6: JSON syntax: expected ':'");
  EXPECT_EQ(error_of("{\"a\": 1,\n }"), "t.json:2:2: JSON syntax: expected a key string");
  EXPECT_EQ(error_of("{\"a\": [1,,2]}"), "t.json:1:10: JSON syntax: expected a value");
  EXPECT_EQ(error_of("{\"a\": [01]}"), "t.json:1:9: JSON syntax: expected ',' or ']'");
  EXPECT_EQ(error_of("{\"a\": 1} {"), "t.json:1:10: JSON syntax: unexpected text after the JSON value");
  EXPECT_EQ(error_of("{\"a\": [1,\n"), "t.json:2:1: JSON syntax: unexpected end of input");
  EXPECT_EQ(error_of("{\"a\": 1e400}"), "t.json:1:7: JSON syntax: number out of range");
  EXPECT_EQ(error_of("{\"a\":\n  \"x\\qy\"}"), "t.json:2:3: JSON syntax: invalid string: forbidden character after backslash");
  EXPECT_EQ(error_of(std::string(70, '[') + std::string(70, ']')),
            "t.json:1:65: JSON syntax: nesting too deep (over 64 levels)");
}

// The duplicate check was quadratic (5.8 s for 40,000 keys; 0.1 s now, measured
// by hand: tests assert values, not speed).
TEST(SceneErrors, DuplicateKeyInALargeObject) {
  std::string text = "{";
  for (int i = 0; i < 40000; ++i) text += "\"k" + std::to_string(i) + "\": " + std::to_string(i) + ",\n";
  text += "\"k39999\": 0}";
  EXPECT_EQ(error_of(text), "t.json:40001:1: JSON syntax: duplicate key \"k39999\"");
}

TEST(SceneErrors, UnknownMaterialAndType) {
  std::string text = scene_text("{\"kind\": \"solid\", \"material\": \"steel\", \"primitives\": []}");
  EXPECT_EQ(error_of(text), "t.json:8: objects[0].material: unknown material \"steel\"");
  EXPECT_EQ(error_of(scene_text(object_with("{\"type\": \"torus\"}"))),
            "t.json:9: objects[0].primitives[0].type: unknown primitive type \"torus\"");
  EXPECT_EQ(error_of(scene_text("{\"kind\": \"hollow\", \"material\": \"m\", \"primitives\": []}")),
            "t.json:8: objects[0].kind: expected \"solid\" or \"surface\"");
}

TEST(SceneErrors, DegenerateGeometry) {
  EXPECT_EQ(error_of(scene_text(object_with("{\"type\": \"triangle\", \"vertices\": [[0, 0, 0], [1, 1, 1], [2, 2, 2]]}"))),
            "t.json:9: objects[0].primitives[0].vertices: degenerate polygon (zero area)");
  EXPECT_EQ(error_of(scene_text(object_with(
                "{\"type\": \"ellipsoid\", \"A\": [[1, 0, 0], [0, 1, 0], [1, 1, 0]], \"centre\": [0, 0, 0]}"))),
            "t.json:9: objects[0].primitives[0].A: singular matrix A");
  EXPECT_EQ(error_of(scene_text(object_with("{\"type\": \"pseudo_triangle\", \"vertices\": [[0, 0, 0], [1, 0, 0], "
                                            "[0, 1, 0]],\n\"normals\": [[0, 0, 1], [0, 0, 0], [0, 0, 1]]}"))),
            "t.json:10: objects[0].primitives[0].normals[1]: zero-length normal");
  EXPECT_EQ(error_of(scene_text(object_with(
                "{\"type\": \"quad\", \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0.5]]}"))),
            "t.json:9: objects[0].primitives[0].vertices: quad is not planar");
  EXPECT_EQ(error_of(scene_text(object_with("{\"type\": \"sphere\", \"centre\": [0, 0, 0], \"radius\": 0}"))),
            "t.json:9: objects[0].primitives[0].radius: must be positive");
  EXPECT_EQ(error_of(scene_text(object_with("{\"type\": \"quadric\", \"coefficients\": [1, 1, 1, 0, 0, 0, 0, 0, 0, "
                                            "-1], \"box\": {\"min\": [-1, 1, -1], \"max\": [1, 1, 1]}}"))),
            "t.json:9: objects[0].primitives[0].box: min must be below max on every axis");
}

TEST(SceneCsg, CombineAndItsErrors) {
  const std::string two =
      "{\"type\": \"sphere\", \"centre\": [0, 0, 0], \"radius\": 1}, "
      "{\"type\": \"sphere\", \"centre\": [1, 0, 0], \"radius\": 1}";
  auto solid = [&](const std::string& kind, const std::string& combine, const std::string& prims) {
    return scene_text("{\"kind\": \"" + kind + "\", \"combine\": \"" + combine +
                      "\", \"material\": \"m\", \"primitives\": [" + prims + "]}");
  };
  Scene s = parse_scene(solid("solid", "difference", two), "t.json", "");
  EXPECT_EQ(s.objects[0].combine, Combine::difference);
  EXPECT_TRUE(hides_outside(s.objects[0], 0));
  EXPECT_FALSE(hides_outside(s.objects[0], 1));
  EXPECT_TRUE(flips_normal(s.objects[0], 1));
  EXPECT_EQ(parse_scene(solid("solid", "union", two), "t.json", "").objects[0].combine, Combine::union_);
  EXPECT_EQ(error_of(solid("solid", "and", two)),
            "t.json:8: objects[0].combine: expected \"union\", \"intersection\" or \"difference\"");
  EXPECT_EQ(error_of(solid("surface", "intersection", two)),
            "t.json:8: objects[0].combine: intersection and difference combine solids only");
  EXPECT_EQ(error_of(solid("solid", "intersection", "{\"type\": \"sphere\", \"centre\": [0, 0, 0], \"radius\": 1}")),
            "t.json:8: objects[0].combine: intersection and difference need at least two primitives");
  EXPECT_EQ(error_of(solid("solid", "intersection", two + ", " + kTriangle)),
            "t.json:8: objects[0].combine: intersection and difference take regions only (ellipsoid, sphere, quadric)");
}

TEST(SceneRevolution, FrustumsOfTheProfile) {
  // (0.5, 1) - (1.5, 3) about the y axis through (2, 1, -1): radius
  // 0.5 + (h - 1) / 2, i.e. c = 0, s = 1/2 (the apex at h = 0).
  Scene s = parse_scene(scene_text(object_with("{\"type\": \"revolution\", \"axis\": \"y\", \"base\": [2, 1, -1], "
                                               "\"profile\": [[0.5, 1], [1.5, 3], [1.5, 4]]}")),
                        "t.json", "");
  const auto& prims = s.objects[0].primitives;
  ASSERT_EQ(prims.size(), 2u);
  const Primitive& cone = prims[0];
  EXPECT_EQ(cone.kind, PrimitiveKind::quadric);
  // (x - 2)^2 + (z + 1)^2 - (y - 1)^2 / 4
  const std::array<double, 10> want = {1, -0.25, 1, 0, 0, 0, -4, 0.5, 2, 4 + 1 - 0.25};
  for (int k = 0; k < 10; ++k) EXPECT_DOUBLE_EQ(cone.coefficients[k], want[k]) << "a" << k + 1;
  // About the box centre (2, 3, -1): (x - 2)^2 + (z + 1)^2 - (1 + (y - 3) / 2)^2.
  const std::array<double, 4> centred = {0, -1, 0, -1};
  for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(cone.centred_linear[k], centred[k]) << "centred a" << k + 7;
  EXPECT_EQ(cone.box_min, glm::dvec3(2 - 1.875, 2, -1 - 1.875));
  EXPECT_EQ(cone.box_max, glm::dvec3(2 + 1.875, 4, -1 + 1.875));
  EXPECT_EQ(prims[1].box_min.y, 4.0);
  EXPECT_EQ(prims[1].box_max.y, 5.0);
  EXPECT_DOUBLE_EQ(prims[1].coefficients[1], 0.0);  // a cylinder: no y^2
  auto error = [&](const std::string& profile, const std::string& axis = "y") {
    return error_of(scene_text(object_with("{\"type\": \"revolution\", \"axis\": \"" + axis +
                                           "\", \"base\": [0, 0, 0], \"profile\": " + profile + "}")));
  };
  EXPECT_EQ(error("[[1, 0], [1, 0]]"), "t.json:9: objects[0].primitives[0].profile[1]: heights must increase along the profile");
  EXPECT_EQ(error("[[0, 0], [0, 1]]"), "t.json:9: objects[0].primitives[0].profile[1]: a segment on the axis (both radii 0)");
  EXPECT_EQ(error("[[-1, 0], [0, 1]]"), "t.json:9: objects[0].primitives[0].profile[0][0]: must not be negative");
  EXPECT_EQ(error("[[1, 0]]"), "t.json:9: objects[0].primitives[0].profile: expected at least 2 [radius, height] points");
  EXPECT_EQ(error("[[1, 0], [0, 1]]", "w"),
            "t.json:9: objects[0].primitives[0].axis: expected \"x\", \"y\", \"z\" or a direction [x, y, z]");
  EXPECT_EQ(error_of(scene_text(object_with("{\"type\": \"revolution\", \"axis\": [0, 0, 0], \"base\": [0, 0, 0], "
                                           "\"profile\": [[1, 0], [0, 1]]}"))),
            "t.json:9: objects[0].primitives[0].axis: the direction must not be 0");
  // Every segment's slab: the unit axis, half its height, about the box's centre.
  EXPECT_EQ(cone.slab_axis, glm::dvec3(0, 1, 0));
  EXPECT_EQ(cone.slab_half, 1.0);
  EXPECT_EQ(prims[1].slab_half, 0.5);
}

TEST(SceneRevolution, AnyAxisDirection) {
  // The same profile about the direction (1, 2, 2) / 3 through (2, 1, -1):
  // the frustum is the set of x with |x - b|^2 - H^2 <= (H / 2)^2,
  // H = (x - b).a, on 1 <= H <= 3; its box bounds the end discs of radius
  // 1.25 * 1.5.
  Scene s = parse_scene(scene_text(object_with("{\"type\": \"revolution\", \"axis\": [1, 2, 2], \"base\": [2, 1, -1], "
                                               "\"profile\": [[0.5, 1], [1.5, 3]]}")),
                        "t.json", "");
  const Primitive& p = s.objects[0].primitives.at(0);
  const glm::dvec3 a(1.0 / 3, 2.0 / 3, 2.0 / 3), b(2, 1, -1);
  EXPECT_NEAR(glm::length(p.slab_axis - a), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(p.slab_half, 1.0);
  const glm::dvec3 centre = 0.5 * (p.box_min + p.box_max);
  EXPECT_NEAR(glm::length(centre - (b + 2.0 * a)), 0.0, 1e-14);  // on the axis at H = 2
  auto q = [&](const glm::dvec3& x) {
    const auto& c = p.coefficients;
    return c[0] * x.x * x.x + c[1] * x.y * x.y + c[2] * x.z * x.z + c[3] * x.x * x.y + c[4] * x.x * x.z +
           c[5] * x.y * x.z + c[6] * x.x + c[7] * x.y + c[8] * x.z + c[9];
  };
  auto centred = [&](const glm::dvec3& y) {
    const auto& c = p.coefficients;
    const auto& l = p.centred_linear;
    return c[0] * y.x * y.x + c[1] * y.y * y.y + c[2] * y.z * y.z + c[3] * y.x * y.y + c[4] * y.x * y.z +
           c[5] * y.y * y.z + l[0] * y.x + l[1] * y.y + l[2] * y.z + l[3];
  };
  const glm::dvec3 u = glm::normalize(glm::cross(a, glm::dvec3(1, 0, 0)));
  for (double h : {1.0, 1.7, 3.0})
    for (double r : {0.0, h / 2, 2.0}) {
      const glm::dvec3 x = b + h * a + r * u;
      const double want = r * r - h * h / 4;
      EXPECT_NEAR(q(x), want, 1e-12) << h << " " << r;
      EXPECT_NEAR(centred(x - centre), want, 1e-12) << h << " " << r;
    }
  for (const glm::dvec3& e : {b + a, b + 3.0 * a})
    for (const glm::dvec3& v : {glm::normalize(glm::cross(a, glm::dvec3(0, 0, 1))), u})
      for (double sgn : {-1.0, 1.0}) {
        const glm::dvec3 x = e + sgn * 1.875 * v;  // on the slab's cylinder: within the box
        for (int k = 0; k < 3; ++k) {
          EXPECT_GE(x[k], p.box_min[k] - 1e-12);
          EXPECT_LE(x[k], p.box_max[k] + 1e-12);
        }
      }
}

TEST(SceneErrors, MeshFile) {
  EXPECT_EQ(error_of(scene_text(object_with("{\"type\": \"bezier_mesh\", \"file\": \"no-such.txt\"}"))),
            "t.json:9: objects[0].primitives[0].file: cannot open \"" + scenes_dir() + "/no-such.txt\"");
  // A directory opens as a stream and reads as empty ("file ends early").
  EXPECT_EQ(error_of(scene_text(object_with("{\"type\": \"bezier_mesh\", \"file\": \"data\"}"))),
            "t.json:9: objects[0].primitives[0].file: \"" + scenes_dir() + "/data\" is a directory (expected a patch file)");
}

// A patch file's errors name the line they are about.
TEST(SceneErrors, PatchFileLines) {
  auto error_in = [](const std::string& text) {
    std::istringstream in(text);
    try {
      read_bezier_file(in, "p.txt");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  std::string indices;
  for (int i = 0; i < 16; ++i) indices += (i ? " " : "") + std::to_string(i == 5 ? 999 : i);
  std::string points;
  for (int i = 0; i < 16; ++i) points += "0 0 " + std::to_string(i) + "\n";
  EXPECT_EQ(error_in("patches 1\n# the net\n" + indices + "\npoints 16\n" + points),
            "p.txt:3: control-point index 999 out of range (the file has 16 points)");
  EXPECT_EQ(error_in("patches 99999999999999999999\n"), "p.txt:1: expected 'patches N' with N in 1..65535");
  EXPECT_EQ(error_in("patches 65536\n"), "p.txt:1: expected 'patches N' with N in 1..65535");
  EXPECT_EQ(error_in("patches 1\n" + indices + "\npoints 0\n"), "p.txt:3: expected 'points N' with N in 1..1048560");
}

// A file that never ends (/dev/zero, a FIFO) is refused after one byte past
// the limit, not held whole: sparse files that size stand in for it.
TEST(SceneLimits, MeshFileOver64MiBRefusedAfterOneByteMore) {
  const std::string mesh = ::testing::TempDir() + "scene_test_big_mesh.txt";
  make_sparse(mesh, (std::uintmax_t{64} << 20) + 1);
  EXPECT_EQ(error_of(scene_text(object_with("{\"type\": \"bezier_mesh\", \"file\": \"" + mesh + "\"}"))),
            "t.json:9: objects[0].primitives[0].file: \"" + mesh + "\" is over 64 MiB, too large for a patch file");
  std::remove(mesh.c_str());
}

TEST(SceneLimits, SceneFileOver256MiBRefusedUnread) {
  const std::string scene = ::testing::TempDir() + "scene_test_big.json";
  make_sparse(scene, (std::uintmax_t{256} << 20) + 1);
  try {
    load_scene(scene);
    FAIL() << "a scene over the limit was loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), scene + ": over 256 MiB, too large for a scene file");
  }
  std::remove(scene.c_str());
}

TEST(SceneErrors, DirectoryIsNotAScene) {
  try {
    load_scene(scenes_dir());
    FAIL() << "a directory was loaded as a scene";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), scenes_dir() + ": is a directory (expected a scene file)");
  }
}

// The NC's 16-bit primitive ids: 65535 of them, a quad taking two.
TEST(SceneLimits, PrimitiveIdsQuadsCountTwice) {
  Scene s = parse_scene(scene_text(object_with(repeated(kQuad, 32767) + ",\n" + kTriangle)), "t.json", "");
  EXPECT_EQ(s.primitive_count(), 32768u);
  EXPECT_EQ(error_of(scene_text(object_with(repeated(kQuad, 32767) + ",\n" + kQuad))),
            "t.json:32776: objects[0].primitives[32767]: more than 65535 primitives (a quad counts as two "
            "triangles), the NC's limit");
}

// The NC's data bank holds 8 lights and 16 materials: the loader refuses
// the ninth light (lights[8]) and the seventeenth material where they stand (both
// renderers take the same scenes; mc1 render used to fail with exit 1 and
// no line, mc1-ref to accept it).
TEST(SceneLimits, LightsAndMaterialsOfTheDataBank) {
  std::string lights = "\"lights\": [";
  for (int i = 0; i < 9; ++i) lights += std::string(i ? ",\n" : "\n") + "{\"position\": [0, 5, 5]}";
  std::string text = scene_text(kSphere);
  text.replace(text.find("\"lights\": ["), std::string("\"lights\": [").size(), lights + ",\n");
  EXPECT_EQ(error_of(text), "t.json:12: lights[8]: more than 8 lights, the NC's limit");
  std::string materials;
  for (int i = 0; i < 15; ++i) materials += "},\n{\"name\": \"m" + std::to_string(i) + "\", \"colour\": [1, 1, 1]";
  EXPECT_EQ(error_of(scene_text(kSphere, "", materials)), "(accepted)");
  materials += "},\n{\"name\": \"too_many\", \"colour\": [1, 1, 1]";
  EXPECT_EQ(error_of(scene_text(kSphere, "", materials)), "t.json:21: materials[16]: more than 16 materials, the NC's limit");
}

// Refused at the first entry past the limit, before the rest is read.
TEST(SceneLimits, AMillionTrianglesRefusedAtTheFirstPastTheLimit) {
  std::string text = scene_text(object_with(repeated(kTriangle, 1000000)));
  EXPECT_EQ(error_of(text), "t.json:65544: objects[0].primitives[65535]: more than 65535 primitives (a quad counts as two "
                   "triangles), the NC's limit");
}

// Counted after tessellation: a level-64 patch is 4096 pseudo-quads, 8192 ids.
TEST(SceneLimits, TessellatedPatchesCount) {
  std::string pts = "[";
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) pts += std::string(r + c ? ", " : "") + "[" + std::to_string(c) + ", " + std::to_string(r) + ", 0]";
  pts += "]";
  std::string patch = "{\"type\": \"bezier_patch\", \"level\": 64, \"points\": " + pts + "}";
  EXPECT_EQ(parse_scene(scene_text(object_with(repeated(patch, 7))), "t.json", "").primitive_count(), 7u * 4096);
  EXPECT_EQ(error_of(scene_text(object_with(repeated(patch, 8)))),
            "t.json:16: objects[0].primitives[7]: more than 65535 primitives (a quad counts as two triangles), "
            "the NC's limit");
}

// Values the NC would hold as FP24 inf or 0 are refused where the path is known.
TEST(SceneErrors, ValuesOutsideFp24Range) {
  const std::string range = std::string(kFp24Range);
  struct Case {
    const char* primitive;
    const char* path;  // below objects[0].primitives[0]
    const char* got;
  };
  for (const Case& c : {
           Case{"{\"type\": \"quadric\", \"coefficients\": [1, 1, 1, 0, 0, 0, 0, 0, 0, -1], "
                "\"box\": {\"min\": [-1e300, -1e300, -1e300], \"max\": [1e300, 1e300, 1e300]}}",
                "box.min[0]", "-1e+300"},
           Case{"{\"type\": \"triangle\", \"vertices\": [[0, 0, 0], [1e300, 0, 0], [0, 1e300, 0]]}",  // was "zero area"
                "vertices[1][0]", "1e+300"},
           Case{"{\"type\": \"ellipsoid\", \"A\": [[1e200, 0, 0], [0, 1e200, 0], [0, 0, 1e200]], "  // was "singular"
                "\"centre\": [0, 0, 0]}",
                "A[0][0]", "1e+200"},
           Case{"{\"type\": \"quadric\", \"coefficients\": [1, 1, 1, 0, 0, 0, 0, 0, 0, -1e20], "
                "\"box\": {\"min\": [-1, -1, -1], \"max\": [1, 1, 1]}}",
                "coefficients[9]", "-1e+20"}})
    EXPECT_EQ(error_of(scene_text(object_with(c.primitive))),
              std::string("t.json:9: objects[0].primitives[0].") + c.path + ": expected " + range + ", got " + c.got);
  // Below the smallest normal: it would be flushed to 0.
  EXPECT_EQ(error_of(scene_text(kSphere, "", ", \"ks\": 1e-20")),
            "t.json:5: materials[0].ks: expected " + range + ", got 1e-20");
  std::string eye = scene_text(kSphere);
  eye.replace(eye.find("[0, 0, 5]"), 9, "[0, 1e-30, 5]");
  EXPECT_EQ(error_of(eye), "t.json:2: camera.eye[1]: expected " + range + ", got 1e-30");
  // Derived values the NC holds: A = I / radius, the checker's u / scale.
  EXPECT_EQ(error_of(scene_text(object_with("{\"type\": \"sphere\", \"centre\": [0, 0, 0], \"radius\": 1e19}"))),
            "t.json:9: objects[0].primitives[0].radius: expected 1 / radius in FP24's range, got 1e-19");
  EXPECT_EQ(error_of(scene_text(kSphere, "", ", \"checker\": {\"colours\": [[1, 1, 1], [0, 0, 0]], \"scale\": 1e19}")),
            "t.json:5: materials[0].checker.scale: expected 1 / scale in FP24's range, got 1e-19");
  // The highlight exponent is 8.8 fixed point on the NC.
  EXPECT_EQ(error_of(scene_text(kSphere, "", ", \"n\": 40000")),
            "t.json:5: materials[0].n: expected at most 32767 (the NC's fixed-point exponent)");
}

// Each limit at its exact boundary (tools/mutants.txt: an off-by-one there
// passed every test that tried values far outside).
TEST(SceneErrors, LimitsHoldAtTheirExactBoundaries) {
  // FP24's range includes both ends: 2^-62 and (2 - 2^-16) 2^63.
  EXPECT_EQ(error_of(scene_text(kSphere, "", ", \"ks\": 2.1684043449710089e-19")), "(accepted)");
  EXPECT_EQ(error_of(scene_text(kSphere, "", ", \"ko\": 18446603336221196288")), "(accepted)");
  EXPECT_EQ(error_of(scene_text(kSphere, "", ", \"n\": 32767")), "(accepted)");
  EXPECT_EQ(error_of(scene_text(kSphere, "", ", \"n\": 32768")),
            "t.json:5: materials[0].n: expected at most 32767 (the NC's fixed-point exponent)");
  std::string fov = scene_text(kSphere);
  fov.replace(fov.find("\"fov\": 60"), 9, "\"fov\": 180");
  EXPECT_EQ(error_of(fov), "t.json:2: camera.fov: expected degrees in (0, 180)");
}

TEST(SceneTessellation, PlanarBezierIsExact) {
  // Control points on a uniform grid: P(u, v) = (u, v, 0), normal +z.
  BicubicNet net;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) net[4 * r + c] = glm::dvec3(c / 3.0, r / 3.0, 0.0);
  std::vector<Primitive> out;
  tessellate_patch(net, Basis::bezier, 2, out);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0].kind, PrimitiveKind::pseudo_quad);
  EXPECT_NEAR(glm::length(out[3].vertices[2] - glm::dvec3(1, 1, 0)), 0.0, 1e-15);
  EXPECT_NEAR(glm::length(out[1].vertices[0] - glm::dvec3(0.5, 0, 0)), 0.0, 1e-15);
  for (const auto& p : out) {
    EXPECT_NEAR(glm::length(p.normal - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(p.vertex_normals[0] - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
  }
}

TEST(SceneTessellation, CollapsedEdgeGivesTriangles) {
  // A cone-like patch: row 0 collapses to the apex (0, 0, 1).
  BicubicNet net;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      double rad = r / 3.0, a = c * 0.5;
      net[4 * r + c] = glm::dvec3(rad * std::cos(a), rad * std::sin(a), 1.0 - rad);
    }
  std::vector<Primitive> out;
  tessellate_patch(net, Basis::bezier, 4, out);
  ASSERT_EQ(out.size(), 16u);
  int triangles = 0;
  for (const auto& p : out) triangles += p.kind == PrimitiveKind::pseudo_triangle;
  EXPECT_EQ(triangles, 4);
  // The apex normal is the limit: finite, unit.
  EXPECT_NEAR(glm::length(out[0].vertex_normals[0]), 1.0, 1e-12);
}

TEST(SceneTessellation, UniformBsplineOfFlatNet) {
  // A uniform B-spline of control points on a plane lies in that plane;
  // a 5x4 net has 2x1 spans.
  std::string row = "[[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0], [4, 0, 0]]";
  std::string net = "[";
  for (int r = 0; r < 4; ++r) {
    std::string shifted = row;
    for (std::size_t p = 0; (p = shifted.find(", 0, 0]", p)) != std::string::npos; p += 7)
      shifted.replace(p, 7, ", " + std::to_string(r) + ", 0]");
    net += (r ? ", " : "") + shifted;
  }
  net += "]";
  Scene s = parse_scene(scene_text(object_with("{\"type\": \"bspline_patch\", \"level\": 2, \"net\": " + net + "}")),
                        "t.json", "");
  ASSERT_EQ(s.primitive_count(), 8u);
  const Primitive& first = s.objects[0].primitives[0];
  // B-spline span 0 starts at (P0 + 4 P1 + P2) / 6 in each direction: (1, 1, 0).
  EXPECT_NEAR(glm::length(first.vertices[0] - glm::dvec3(1, 1, 0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(first.vertex_normals[0] - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
}

TEST(SceneChecker, MappingOnWorldXZ) {
  Checker c;
  c.colours = {glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1)};
  c.scale = 2.0;
  EXPECT_EQ(checker_colour(c, {0.5, 7, 0.5}), glm::dvec3(1, 0, 0));   // cell (0, 0)
  EXPECT_EQ(checker_colour(c, {2.5, 7, 0.5}), glm::dvec3(0, 0, 1));   // cell (1, 0)
  EXPECT_EQ(checker_colour(c, {-0.5, 0, 0.5}), glm::dvec3(0, 0, 1));  // cell (-1, 0)
  EXPECT_EQ(checker_colour(c, {-0.5, 0, -0.5}), glm::dvec3(1, 0, 0)); // cell (-1, -1)
}
