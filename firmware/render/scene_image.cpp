#include "scene_image.hpp"

#include "render_layout.hpp"

#ifdef MC1_RENDER_HAVE_SCENE
#include <stdexcept>
#include <string>

#include "fp24_convert.hpp"
#include "scene.hpp"
#endif

namespace mc1::render {

bool spawns_secondary(const MaterialImage& m) {
  // A positive FP24 number: sign clear, exponent field not zero.
  auto positive = [](Word w) { return !(w & 0x800000) && (w & 0x7F0000); };
  return positive(m.w[layout::M_KS]) || positive(m.w[layout::M_KT]);
}

#ifdef MC1_RENDER_HAVE_SCENE
namespace {

Vec3w v3(const glm::dvec3& v) { return {fp24_from_double(v.x), fp24_from_double(v.y), fp24_from_double(v.z)}; }

template <std::size_t N>
void put(std::array<Word, N>& w, int at, const glm::dvec3& v) {
  const auto x = v3(v);
  w[at] = x[0];
  w[at + 1] = x[1];
  w[at + 2] = x[2];
}

void check_limits(const scene::Scene& s) {
  if (s.lights.size() > static_cast<std::size_t>(kMaxLights))
    throw std::invalid_argument(s.source + ": the renderer takes at most " + std::to_string(kMaxLights) +
                                " lights, not " + std::to_string(s.lights.size()));
  if (s.materials.size() > static_cast<std::size_t>(kMaxMaterials))
    throw std::invalid_argument(s.source + ": the renderer takes at most " + std::to_string(kMaxMaterials) +
                                " materials, not " + std::to_string(s.materials.size()));
}

std::array<Word, image_words::kLightWords> light_image(const scene::Light& l) {
  using namespace image_words;
  std::array<Word, kLightWords> w{};
  put(w, kLightPos, l.position);
  put(w, kLightI, l.intensity);
  return w;
}

MaterialImage material_image(const scene::Material& m) {
  using namespace layout;
  MaterialImage mi;
  put(mi.w, M_C, m.colour);
  mi.w[M_KO] = fp24_from_double(m.ko);
  mi.w[M_KD] = fp24_from_double(m.kd);
  mi.w[M_KM] = fp24_from_double(m.km);
  const double n = m.n < 0 ? 0 : m.n > 32767 ? 32767 : m.n;
  // n = M_N + M_NF / 2^M_NF_BITS (docs/renderer.md: cos^n by squaring and square roots)
  const Word fixed = static_cast<Word>(n * (1 << M_NF_BITS) + 0.5);
  mi.w[M_N] = fixed >> M_NF_BITS;
  mi.w[M_NF] = fixed & ((1u << M_NF_BITS) - 1);
  mi.w[M_KS] = fp24_from_double(m.ks);
  mi.w[M_KT] = fp24_from_double(m.kt);
  mi.w[M_ETA] = fp24_from_double(m.index);
  mi.w[M_TEX] = m.textured ? 1 : 0;
  put(mi.w, M_CK0, m.checker.colours[0]);
  put(mi.w, M_CK1, m.checker.colours[1]);
  put(mi.w, M_CKO, m.checker.origin);
  put(mi.w, M_CKU, m.checker.u);
  put(mi.w, M_CKV, m.checker.v);
  mi.checker_scale = fp24_from_double(m.checker.scale);
  return mi;
}

bool is_polygon(scene::PrimitiveKind k) {
  return k == scene::PrimitiveKind::triangle || k == scene::PrimitiveKind::quad ||
         k == scene::PrimitiveKind::pseudo_triangle || k == scene::PrimitiveKind::pseudo_quad;
}

// A polygon as triangles: a quad is (v0, v1, v2) and (v0, v2, v3).
void add_polygon(const scene::Primitive& p, PrimImage pi, std::vector<PrimImage>& prims) {
  using namespace image_words;
  const bool pseudo =
      p.kind == scene::PrimitiveKind::pseudo_triangle || p.kind == scene::PrimitiveKind::pseudo_quad;
  pi.type = pseudo ? kPseudoTriangle : kTriangle;
  for (int t = 0; t + 2 < p.vertex_count; ++t) {
    const int idx[3] = {0, t + 1, t + 2};
    for (int k = 0; k < 3; ++k) {
      put(pi.w, kV0 + 3 * k, p.vertices[idx[k]]);
      put(pi.w, kVN + 3 * k, pseudo ? p.vertex_normals[idx[k]] : p.normal);
    }
    put(pi.w, kN, p.normal);
    prims.push_back(pi);
  }
}

void ellipsoid_image(const scene::Primitive& p, PrimImage& pi) {
  using namespace image_words;
  pi.type = kEllipsoid;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) pi.w[kEllA + 3 * r + c] = fp24_from_double(p.A[c][r]);
  put(pi.w, kEllB, p.centre);
}

void quadric_image(const scene::Primitive& p, PrimImage& pi) {
  using namespace image_words;
  pi.type = kQuadric;
  for (int k = 0; k < 10; ++k) pi.w[kQ + k] = fp24_from_double(p.coefficients[k]);
  put(pi.w, kBMin, p.box_min);
  put(pi.w, kBMax, p.box_max);
  for (int k = 0; k < 4; ++k) pi.w[kQL + k] = fp24_from_double(p.centred_linear[k]);
  if (p.slab_half > 0) {
    for (int k = 0; k < 3; ++k) pi.slab[kSlabA + k] = fp24_from_double(p.slab_axis[k]);
    pi.slab[kSlabH] = fp24_from_double(p.slab_half);
  }
}

// Object `o` of the scene and its primitives, appended to img.
void add_object(const scene::Object& obj, int o, SceneImage& img) {
  ObjectImage oi;
  oi.solid = obj.kind == scene::ObjectKind::solid;
  oi.combine = obj.combine == scene::Combine::intersection ? kIntersection
               : obj.combine == scene::Combine::difference ? kDifference
                                                           : kUnion;
  oi.material = obj.material;
  oi.first_prim = static_cast<int>(img.prims.size());
  oi.box_min = v3(obj.box_min);
  oi.box_max = v3(obj.box_max);
  for (const auto& p : obj.primitives) {
    PrimImage pi;
    pi.object = o;
    if (is_polygon(p.kind)) {
      add_polygon(p, pi, img.prims);
      continue;
    }
    if (p.kind == scene::PrimitiveKind::ellipsoid)
      ellipsoid_image(p, pi);
    else if (p.kind == scene::PrimitiveKind::quadric)
      quadric_image(p, pi);
    img.prims.push_back(pi);
  }
  oi.prim_count = static_cast<int>(img.prims.size()) - oi.first_prim;
  img.objects.push_back(oi);
}

}  // namespace

SceneImage make_scene_image(const scene::Scene& s) {
  SceneImage img;
  img.eye = v3(s.camera.eye);
  img.look_at = v3(s.camera.look_at);
  img.up = v3(s.camera.up);
  img.fov_deg = fp24_from_double(s.camera.fov_deg);
  img.width = s.camera.width;
  img.height = s.camera.height;
  img.max_depth = s.render.max_depth;
  img.background = v3(s.render.background);
  img.epsilon = fp24_from_double(s.render.epsilon);
  check_limits(s);
  for (const auto& l : s.lights) img.lights.push_back(light_image(l));
  for (const auto& m : s.materials) img.materials.push_back(material_image(m));
  for (std::size_t o = 0; o < s.objects.size(); ++o) add_object(s.objects[o], static_cast<int>(o), img);
  return img;
}
#endif

}  // namespace mc1::render
