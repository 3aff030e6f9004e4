// The renderer's firmware and kernels on the ISS (docs/renderer.md): every
// expected value below is computed here in double from the same scene, or
// written out by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "apu_driver.hpp"
#include "apu_iss.hpp"
#include "fp24_convert.hpp"
#include "render_fw.hpp"
#include "render_layout.hpp"
#include "scene_image.hpp"

#ifdef MC1_RENDER_HAVE_SCENE
#include "image.hpp"
#include "refrender.hpp"
#include "scene.hpp"
#endif

namespace {

using namespace mc1;
using namespace mc1::render;
using namespace mc1::render::layout;

struct V3 {
  double x = 0, y = 0, z = 0;
};
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 norm(V3 a) { return (1.0 / std::sqrt(dot(a, a))) * a; }

template <class Words>
void put(Words& w, int at, V3 v) {
  Word* p = w.data() + at;
  p[0] = fp24_from_double(v.x);
  p[1] = fp24_from_double(v.y);
  p[2] = fp24_from_double(v.z);
}

// A small scene in view coordinates (eye at 0, looking down +z, y up),
// built in double: what step 1 would produce.
struct TestScene {
  int width = 16, height = 16;
  double fov_deg = 60;
  struct Mat {
    V3 c{1, 1, 1};
    double ko = 0.1, kd = 0.7, km = 0, ks = 0, kt = 0, eta = 1;
    int n = 1;
    bool checker = false;
    V3 ck0{1, 1, 1}, ck1{0, 0, 0}, cko{}, cku{1, 0, 0}, ckv{0, 0, 1};
  };
  struct Prim {
    int type = kTriangle;
    int object = 0, material = 0;
    V3 v[3], vn[3];
    V3 centre;
    double radius = 1;
  };
  struct Light {
    V3 pos, intensity{1, 1, 1};
  };
  std::vector<Mat> mats{Mat{}};
  std::vector<Prim> prims;
  std::vector<Light> lights;
  std::vector<bool> solid;
  double eps = 1e-3;
  V3 bg{0, 0, 0};

  // Eye ray of pixel (i, j): the conventions of docs/scene-format.md.
  V3 eye_dir(int i, int j) const {
    const double h = std::tan(fov_deg * M_PI / 360.0);
    const double s = 2 * h / height;
    return norm({(i + 0.5 - width / 2.0) * s, (height / 2.0 - j - 0.5) * s, 1});
  }

  int add_sphere(V3 c, double r, int mat, int object) {
    Prim p;
    p.type = kEllipsoid;
    p.centre = c;
    p.radius = r;
    p.material = mat;
    p.object = object;
    prims.push_back(p);
    return static_cast<int>(prims.size()) - 1;
  }
  int add_triangle(V3 a, V3 b, V3 c, int mat, int object) {
    Prim p;
    p.v[0] = a, p.v[1] = b, p.v[2] = c;
    p.material = mat;
    p.object = object;
    prims.push_back(p);
    return static_cast<int>(prims.size()) - 1;
  }

  ViewScene view() const {
    ViewScene v;
    v.width = width;
    v.height = height;
    const double h = std::tan(fov_deg * M_PI / 360.0);
    const double s = 2 * h / height;
    auto& k = v.constants;
    auto at = [](int addr) { return addr - C_D0; };
    put(k, at(C_D0), V3{(0.5 - width / 2.0) * s, (height / 2.0 - 0.5) * s, 1});
    put(k, at(C_DX), V3{s, 0, 0});
    put(k, at(C_DY), V3{0, -s, 0});
    k[at(C_EPS)] = fp24_from_double(eps);
    k[at(C_BIG)] = fp24_from_double(1e18);
    k[at(C_NLIGHTS)] = static_cast<Word>(lights.size());
    put(k, at(C_BG), bg);
    put(k, at(C_WR), V3{1, 0, 0});
    put(k, at(C_WR + 3), V3{0, 1, 0});
    put(k, at(C_WR + 6), V3{0, 0, 1});
    for (const auto& l : lights) {
      std::array<Word, 8> w{};
      put(w, L_POS, l.pos);
      put(w, L_I, l.intensity);
      v.lights.push_back(w);
    }
    for (const auto& m : mats) {
      std::array<Word, 32> w{};
      put(w, M_C, m.c);
      w[M_KO] = fp24_from_double(m.ko);
      w[M_KD] = fp24_from_double(m.kd);
      w[M_KM] = fp24_from_double(m.km);
      w[M_N] = static_cast<Word>(m.n);
      w[M_KS] = fp24_from_double(m.ks);
      w[M_KT] = fp24_from_double(m.kt);
      w[M_ETA] = fp24_from_double(m.eta);
      w[M_TEX] = m.checker ? 1 : 0;
      put(w, M_CK0, m.ck0);
      put(w, M_CK1, m.ck1);
      put(w, M_CKO, m.cko);
      put(w, M_CKU, m.cku);
      put(w, M_CKV, m.ckv);
      v.materials.push_back(w);
    }
    int objects = 0;
    for (std::size_t i = 0; i < prims.size(); ++i) {
      const auto& p = prims[i];
      std::array<Word, 32> w{};
      w[P_TYPE] = static_cast<Word>(p.type);
      w[P_MAT] = static_cast<Word>(MATS + M_SIZE * p.material);
      if (p.type == kEllipsoid) {
        const double a = 1 / p.radius;
        put(w, P_A, V3{a, 0, 0});
        put(w, P_A + 3, V3{0, a, 0});
        put(w, P_A + 6, V3{0, 0, a});
        put(w, P_B, p.centre);
      } else {
        const V3 e1 = p.v[1] - p.v[0], e2 = p.v[2] - p.v[0];
        const V3 n = norm(cross(e1, e2));
        const V3 ua = cross(e2, n), va = cross(n, e1);
        put(w, P_P0, p.v[0]);
        put(w, P_P1, p.v[1]);
        put(w, P_P2, p.v[2]);
        put(w, P_N, n);
        put(w, P_UA, (1 / dot(e1, ua)) * ua);
        put(w, P_VA, (1 / dot(e2, va)) * va);
        for (int k2 = 0; k2 < 3; ++k2) put(w, P_VN0 + 3 * k2, p.type == kPseudoTriangle ? p.vn[k2] : n);
      }
      const bool is_solid = p.object < static_cast<int>(solid.size()) && solid[p.object];
      w[P_SOLID] = is_solid ? 1 : 0;
      w[P_ID] = static_cast<Word>(i);
      v.prims.push_back(w);
      v.prim_object.push_back(p.object);
      objects = std::max(objects, p.object + 1);
    }
    v.objects.resize(objects);
    for (int o = 0; o < objects; ++o) {
      v.objects[o].solid = o < static_cast<int>(solid.size()) && solid[o];
      v.objects[o].first_prim = -1;
    }
    for (std::size_t i = 0; i < prims.size(); ++i) {
      auto& o = v.objects[prims[i].object];
      if (o.first_prim < 0) o.first_prim = static_cast<int>(i);
      o.prim_count++;
      const auto& m = mats[prims[i].material];
      o.secondary = o.secondary || m.ks > 0 || m.kt > 0;
    }
    return v;
  }

  // Nearest hit of a ray in double: (t, prim) or (inf, -1).
  std::pair<double, int> hit(V3 o, V3 d, double tmin, double tmax) const {
    double best = tmax;
    int id = -1;
    for (std::size_t i = 0; i < prims.size(); ++i) {
      const auto& p = prims[i];
      double t = -1;
      if (p.type == kEllipsoid) {
        const V3 oc = o - p.centre;
        const double b = dot(oc, d), c = dot(oc, oc) - p.radius * p.radius;
        const double disc = b * b - c;
        if (disc < 0) continue;
        const double t1 = -b - std::sqrt(disc), t2 = -b + std::sqrt(disc);
        t = t1 > tmin ? t1 : t2;
      } else {
        const V3 e1 = p.v[1] - p.v[0], e2 = p.v[2] - p.v[0];
        const V3 n = norm(cross(e1, e2));
        const double den = dot(n, d);
        if (den == 0) continue;
        t = dot(n, p.v[0] - o) / den;
        const V3 q = o + t * d - p.v[0];
        const V3 ua = cross(e2, n), va = cross(n, e1);
        const double u = dot(q, ua) / dot(e1, ua), v = dot(q, va) / dot(e2, va);
        if (u < 0 || v < 0 || u + v > 1) continue;
      }
      if (t > tmin && t < best) best = t, id = static_cast<int>(i);
    }
    return {best, id};
  }
};

// Every primitive of a view scene, in file order (a candidate list).
std::vector<int> every_primitive(const ViewScene& v) {
  std::vector<int> all(v.prims.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
  return all;
}

struct Rig {
  apu::Iss iss;
  apu::ApuDriver drv{iss};
  RenderFirmware fw{drv};
};

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

#ifdef MC1_RENDER_HAVE_SCENE
// Whitted's scene (scenes/whitted.json) at a small size, plus a triangle and
// a pseudo quad so that every primitive kind but the quadric appears.
const char* kWhitted = R"({
  "camera": {"eye": [0, 1.6, 6], "look_at": [0, 0.8, 0], "up": [0, 1, 0], "fov": 45, "width": 48, "height": 36},
  "render": {"max_depth": 5, "background": [0.3, 0.5, 0.8]},
  "lights": [
    {"position": [-4, 6, 4], "intensity": [0.7, 0.7, 0.7]},
    {"position": [5, 5, 3], "intensity": [0.5, 0.5, 0.5]}
  ],
  "materials": [
    {"name": "checker", "colour": [1, 1, 1], "ko": 0.1, "kd": 0.8, "checker": {"colours": [[0.9, 0.2, 0.15], [0.95, 0.9, 0.3]], "scale": 1}},
    {"name": "mirror", "colour": [0.9, 0.9, 0.9], "ko": 0.05, "kd": 0.1, "km": 0.5, "n": 40, "ks": 0.8},
    {"name": "glass", "colour": [1, 1, 1], "ko": 0, "kd": 0.05, "km": 0.6, "n": 80, "ks": 0.1, "kt": 0.85, "index": 1.5},
    {"name": "red", "colour": [0.9, 0.1, 0.1], "ko": 0.1, "kd": 0.6, "km": 0.3, "n": 10.5}
  ],
  "objects": [
    {"name": "floor", "kind": "surface", "material": "checker", "primitives": [
        {"type": "quad", "vertices": [[-8, 0, 6], [0, 0, 6], [0, 0, -2], [-8, 0, -2]]},
        {"type": "quad", "vertices": [[0, 0, 6], [8, 0, 6], [8, 0, -2], [0, 0, -2]]},
        {"type": "quad", "vertices": [[-8, 0, -2], [0, 0, -2], [0, 0, -10], [-8, 0, -10]]},
        {"type": "quad", "vertices": [[0, 0, -2], [8, 0, -2], [8, 0, -10], [0, 0, -10]]}]},
    {"name": "mirror sphere", "kind": "solid", "material": "mirror",
     "primitives": [{"type": "sphere", "centre": [-1.1, 1, -0.8], "radius": 1}]},
    {"name": "glass sphere", "kind": "solid", "material": "glass",
     "primitives": [{"type": "sphere", "centre": [1.1, 0.9, 0.9], "radius": 0.9}]},
    {"name": "flag", "kind": "surface", "material": "red", "primitives": [
        {"type": "triangle", "vertices": [[2.2, 0, -3], [3.4, 0, -3], [2.8, 2.2, -3.5]]},
        {"type": "pseudo_quad", "vertices": [[-3.6, 0, -2], [-2.4, 0, -2], [-2.4, 1.4, -2.6], [-3.6, 1.4, -2.6]],
         "normals": [[-0.6, 0.3, 0.74], [0.6, 0.3, 0.74], [0.6, 0.4, 0.69], [-0.6, 0.4, 0.69]]}]}
  ]
})";

double psnr_db(const imgcmp::Image& a, const imgcmp::Image& b) { return imgcmp::psnr(a, b); }

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

// The whole frame of a scene, block by block (16 x 16), as the NCs make it.
imgcmp::Image render_frame(RenderFirmware& fw, int width, int height) {
  imgcmp::Image img(width, height);
  for (int y0 = 0; y0 < height; y0 += 16)
    for (int x0 = 0; x0 < width; x0 += 16) {
      const Block b{x0, y0, std::min(16, width - x0), std::min(16, height - y0)};
      const auto px = fw.render_block(fw.build_block_list(b));
      for (int j = 0; j < b.h; ++j)
        for (int i = 0; i < b.w; ++i) {
          auto* p = img.at(x0 + i, y0 + j);
          p[0] = px[j * b.w + i].r, p[1] = px[j * b.w + i].g, p[2] = px[j * b.w + i].b;
        }
    }
  return img;
}

std::string scene_path(const std::string& name) {
  const std::string src = __FILE__;
  return src.substr(0, src.rfind("/tests/")) + "/scenes/" + name + ".json";
}

// A standard scene at w x h, loaded into the rig's firmware.
scene::Scene load_standard_scene(Rig& rig, const std::string& name, int w, int h) {
  scene::Scene sc = scene::load_scene(scene_path(name));
  sc.camera.width = w;
  sc.camera.height = h;
  rig.fw.load_scene(make_scene_image(sc));
  return sc;
}

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
// 55.41, lathe 78.75 dB.
TEST(RenderScenes, WhittedNearTheReference) { expect_near_reference("whitted", 64, 48, 64.0); }
TEST(RenderScenes, RoomNearTheReference) { expect_near_reference("room", 64, 48, 70.0); }
TEST(RenderScenes, SmoothNearTheReference) { expect_near_reference("smooth", 64, 48, 47.0); }
TEST(RenderScenes, TeapotNearTheReference) { expect_near_reference("teapot", 32, 24, 72.0); }
TEST(RenderScenes, TeapotAt64x48NearTheReference) { expect_near_reference("teapot", 64, 48, 73.0); }

// Section 7's scenes (docs/renderer.md "CSG and solids of revolution").
TEST(RenderScenes, CsgNearTheReference) { expect_near_reference("csg", 64, 48, 52.0); }
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
  EXPECT_LE(other_flags, 3);      // measured 1
}

// The section 7 primitives' cost on the APU (docs/renderer.md "Timing"):
// 32 eye rays across a row, cast against one candidate less the same cast
// against none, per ray; the solid rule over eye hits on the lens.
std::uint64_t cast_cycles(Rig& rig, int row, int first_col, const std::vector<int>& list,
                          std::vector<RenderFirmware::Ray>* out = nullptr) {
  std::vector<RenderFirmware::Ray> rays(kRaysPerBatch);
  for (int k = 0; k < kRaysPerBatch; ++k) {
    rays[k].rec[R_KIND] = RK_EYE;
    rays[k].rec[R_ARG] = static_cast<std::uint32_t>(first_col + k);
    rays[k].rec[R_ARG2] = static_cast<std::uint32_t>(row);
    rays[k].rec[R_ID] = kNoHit;
  }
  rig.fw.reset_stats();
  rig.fw.cast(rays, {list}, Step::HiddenSurface);
  if (out) *out = rays;
  return rig.fw.stats().step[static_cast<int>(Step::HiddenSurface)].apu_cycles;
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

// How far a world point lies inside a region primitive, relative to its size
// (> 0 inside): 1 - |A (x - b)|^2 for an ellipsoid; for a quadric the smaller
// of -q(x) / max|a_i| and the distance to the clip box's faces over its
// diagonal. Polygons hold nothing (-1).
double inside_depth(const scene::Primitive& p, const glm::dvec3& x) {
  if (p.kind == scene::PrimitiveKind::ellipsoid) {
    const glm::dvec3 u = p.A * (x - p.centre);
    return 1.0 - glm::dot(u, u);
  }
  if (p.kind != scene::PrimitiveKind::quadric) return -1.0;
  const auto& a = p.coefficients;
  double scale = 0;
  for (double c : a) scale = std::max(scale, std::abs(c));
  const double q = a[0] * x.x * x.x + a[1] * x.y * x.y + a[2] * x.z * x.z + a[3] * x.x * x.y + a[4] * x.x * x.z +
                   a[5] * x.y * x.z + a[6] * x.x + a[7] * x.y + a[8] * x.z + a[9];
  double box = INFINITY;
  for (int k = 0; k < 3; ++k) box = std::min({box, x[k] - p.box_min[k], p.box_max[k] - x[k]});
  return std::min(-q / scale, box / glm::length(p.box_max - p.box_min));
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

// Over a generation of rays: hits deeper than 1e-3 inside a sibling region
// of their solid, and rays whose hit (object; primitive within a solid;
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
    n.hidden += got.hidden_depth > 1e-3;
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
TEST(RenderSolids, UnionSolidsMatchTheReferenceRenderer) {
  const scene::Scene sc = scene::parse_scene(kSolids, "solids.json", ".");
  Rig rig;
  rig.fw.load_scene(make_scene_image(sc));
  const int w = sc.camera.width, h = sc.camera.height;
  const imgcmp::Image img = render_frame(rig.fw, w, h);
  const imgcmp::Image want = refrender::Renderer(sc).render();
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
#endif

}  // namespace
