// Helpers of the render_fw_*_test.cpp programs (the renderer's firmware and
// kernels on the ISS): a small scene built in double (TestScene), an ISS
// with the firmware (Rig), a standard scene loaded and a whole frame
// rendered block by block, an eye-ray batch's APU cycles.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "apu_driver.hpp"
#include "apu_iss.hpp"
#include "fp24_convert.hpp"
#include "image.hpp"
#include "render_fw.hpp"
#include "render_layout.hpp"
#include "scene.hpp"
#include "scene_image.hpp"

namespace mc1::render::test {

using namespace mc1::render::layout;

struct V3 {
  double x = 0, y = 0, z = 0;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline V3 norm(V3 a) { return (1.0 / std::sqrt(dot(a, a))) * a; }

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
inline std::vector<int> every_primitive(const ViewScene& v) {
  std::vector<int> all(v.prims.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
  return all;
}

struct Rig {
  apu::Iss iss;
  apu::ApuDriver drv{iss};
  RenderFirmware fw{drv};
};

// Whitted's scene (scenes/whitted.json) at a small size, plus a triangle and
// a pseudo quad so that every primitive kind but the quadric appears.
inline const char* const kWhitted = R"({
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

inline double psnr_db(const imgcmp::Image& a, const imgcmp::Image& b) { return imgcmp::psnr(a, b); }

// The whole frame of a scene, block by block (16 x 16), as the NCs make it.
inline imgcmp::Image render_frame(RenderFirmware& fw, int width, int height) {
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

inline std::string scene_path(const std::string& name) {
  const std::string src = __FILE__;
  return src.substr(0, src.rfind("/tests/")) + "/scenes/" + name + ".json";
}

// A standard scene at w x h, loaded into the rig's firmware.
inline scene::Scene load_standard_scene(Rig& rig, const std::string& name, int w, int h) {
  scene::Scene sc = scene::load_scene(scene_path(name));
  sc.camera.width = w;
  sc.camera.height = h;
  rig.fw.load_scene(make_scene_image(sc));
  return sc;
}

// The section 7 primitives' cost on the APU (docs/renderer.md "Timing"):
// 32 eye rays across a row, cast against one candidate less the same cast
// against none, per ray; the solid rule over eye hits on the lens.
inline std::uint64_t cast_cycles(Rig& rig, int row, int first_col, const std::vector<int>& list,
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

}  // namespace mc1::render::test
