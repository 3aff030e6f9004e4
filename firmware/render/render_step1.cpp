// Step 1 of fig. 3 (r_xform): the broadcast scene to view coordinates on
// the APU, with the eye-ray constants and each object's view box, and the
// frame's lists that follow from the view scene.
#include <stdexcept>

#include "render_internal.hpp"

namespace mc1::render {

using namespace layout;

namespace {

constexpr std::uint32_t kPiOver360 = 0x381DF4;  // fp24(pi / 360), degrees to half-angle radians
constexpr std::uint32_t kBig = 0x7ABC17;        // fp24(1e18): "no hit"

// r_xform's items and its results copy whole runs of words between the
// image, the item and the view records: the runs must agree.
static_assert(XC_U - XC_O == M_CKU - M_CKO && XC_V - XC_O == M_CKV - M_CKO, "checker frame O, U, V");
static_assert(XT_N - XT_V0 == image_words::kN - image_words::kV0, "triangle v0 v1 v2 N");
static_assert(XE_B - XE_A == image_words::kEllB - image_words::kEllA, "ellipsoid A, b");
static_assert(XT_P1 - XT_V0 == P_P1 - P_P0 && XT_P2 - XT_V0 == P_P2 - P_P0 && XT_N - XT_V0 == P_N - P_P0 &&
                  XT_UA - XT_V0 == P_UA - P_P0 && XT_VA - XT_V0 == P_VA - P_P0 && XT_RVN - XT_V0 == P_VN0 - P_P0,
              "r_xform's triangle results in the order of the primitive record");
static_assert(XE_B - XE_A == P_B - P_A, "ellipsoid record");
static_assert(image_words::kBMin - image_words::kQ == P_BMIN - P_Q &&
                  image_words::kBMax - image_words::kQ == P_BMAX - P_Q &&
                  image_words::kQL - image_words::kQ == P_QL - P_Q,
              "quadric record");
static_assert(P_SLABH - P_SLABA == image_words::kSlabH - image_words::kSlabA, "quadric slab record");
static_assert(XB_MAX - XB_MIN == 3, "view box min xyz, max xyz");

void check_limits(std::size_t lights, std::size_t materials) {
  if (lights > static_cast<std::size_t>(kMaxLights) || materials > static_cast<std::size_t>(kMaxMaterials))
    throw std::invalid_argument("render: at most " + std::to_string(kMaxLights) + " lights and " +
                                std::to_string(kMaxMaterials) + " materials");
}

// The mode-XM_ITEMS work of a scene: one item per light, material (its
// checker frame), triangle, ellipsoid and object box, and which item each
// came from (-1: none, quadrics stay in world coordinates).
struct XformItems {
  using Item = std::array<std::uint32_t, X_SIZE>;
  std::vector<Item> items;
  std::vector<int> light, mat, prim, box;

  int add(int kind, const std::uint32_t* in, int at, int n) {
    Item it{};
    it[X_KIND] = static_cast<std::uint32_t>(kind);
    std::copy(in, in + n, it.begin() + at);
    items.push_back(it);
    return static_cast<int>(items.size()) - 1;
  }
  const Item& of(int k) const { return items[k]; }
};

XformItems xform_items(const SceneImage& img) {
  using namespace image_words;
  XformItems x;
  for (const auto& l : img.lights) x.light.push_back(x.add(XK_LIGHT, l.data() + kLightPos, XL_P, 3));
  for (const auto& m : img.materials) {
    const int k = x.add(XK_CHECK, m.w.data() + M_CKO, XC_O, XC_S - XC_O);
    x.items[k][XC_S] = m.checker_scale;
    x.mat.push_back(k);
  }
  for (const auto& p : img.prims) {
    int k = -1;
    if (is_triangle(p.type)) {
      k = x.add(XK_TRI, p.w.data() + kV0, XT_V0, kN + 3 - kV0);
      std::copy(p.w.begin() + kVN, p.w.begin() + kVN + 9, x.items[k].begin() + XT_VN);
    } else if (p.type == kEllipsoid) {
      k = x.add(XK_ELL, p.w.data() + kEllA, XE_A, kEllB + 3 - kEllA);
    }
    x.prim.push_back(k);
  }
  for (const auto& o : img.objects) {
    const int k = x.add(XK_BOX, o.box_min.data(), XB_MIN, 3);
    std::copy(o.box_max.begin(), o.box_max.end(), x.items[k].begin() + XB_MAX);
    x.box.push_back(k);
  }
  return x;
}

// ViewScene::constants from r_xform's camera batch and the image.
void set_constants(ViewScene& v, const SceneImage& img, const ViewScene::Constants& cam) {
  v.constants = cam;
  auto at = [&](int word) { return v.constants.begin() + (word - C_D0); };
  *at(C_EPS) = img.epsilon;
  *at(C_BIG) = kBig;
  *at(C_NLIGHTS) = static_cast<std::uint32_t>(img.lights.size());
  std::copy(img.background.begin(), img.background.end(), at(C_BG));
}

void add_lights_and_materials(ViewScene& v, const SceneImage& img, const XformItems& x) {
  for (std::size_t l = 0; l < img.lights.size(); ++l) {
    ViewScene::Light w{};
    const auto& it = x.of(x.light[l]);
    std::copy(it.begin() + XL_P, it.begin() + XL_P + 3, w.begin() + L_POS);
    std::copy(img.lights[l].begin() + image_words::kLightI, img.lights[l].begin() + image_words::kLightI + 3,
              w.begin() + L_I);
    v.lights.push_back(w);
  }
  for (std::size_t m = 0; m < img.materials.size(); ++m) {
    auto w = img.materials[m].w;
    const auto& it = x.of(x.mat[m]);
    std::copy(it.begin() + XC_O, it.begin() + XC_S, w.begin() + M_CKO);
    v.materials.push_back(w);
  }
}

void add_objects(ViewScene& v, const SceneImage& img, const XformItems& x) {
  for (std::size_t o = 0; o < img.objects.size(); ++o) {
    const auto& oi = img.objects[o];
    ViewScene::Object vo;
    vo.solid = oi.solid;
    vo.combine = oi.combine;
    vo.secondary = spawns_secondary(img.materials.at(oi.material));
    vo.first_prim = oi.first_prim;
    vo.prim_count = oi.prim_count;
    const auto& it = x.of(x.box[o]);
    std::copy(it.begin() + XB_MIN, it.begin() + XB_MAX + 3, vo.box.begin());
    v.objects.push_back(vo);
  }
}

// The primitive records: r_xform's results for triangles and ellipsoids,
// the world words for quadrics (r_cast takes them to world coordinates).
// P_CSG of region k of object o (scene::hides_outside, scene::flips_normal).
std::uint32_t csg_bits(const ObjectImage& o, int k) {
  std::uint32_t bits = 0;
  if (o.combine == kIntersection || (o.combine == kDifference && k == 0)) bits |= CSG_OUT;
  if (o.combine == kDifference && k > 0) bits |= CSG_FLIP;
  return bits;
}

void add_prims(ViewScene& v, const SceneImage& img, const XformItems& x) {
  for (std::size_t i = 0; i < img.prims.size(); ++i) {
    const auto& p = img.prims[i];
    ViewScene::Prim w{};
    w[P_TYPE] = static_cast<std::uint32_t>(p.type);
    w[P_MAT] = static_cast<std::uint32_t>(MATS + M_SIZE * img.objects.at(p.object).material);
    w[P_SOLID] = img.objects[p.object].solid ? 1 : 0;
    w[P_ID] = static_cast<std::uint32_t>(i);
    w[P_CSG] = csg_bits(img.objects[p.object], static_cast<int>(i) - img.objects[p.object].first_prim);
    if (is_triangle(p.type)) {
      const auto& it = x.of(x.prim[i]);
      std::copy(it.begin() + XT_V0, it.begin() + XT_RVN + 9, w.begin() + P_P0);  // P0 P1 P2 N UA VA, VN
    } else if (p.type == kEllipsoid) {
      const auto& it = x.of(x.prim[i]);
      std::copy(it.begin() + XE_A, it.begin() + XE_B + 3, w.begin() + P_A);  // A, b
    } else {
      std::copy(p.w.begin() + image_words::kQ, p.w.begin() + image_words::kQL + 4, w.begin() + P_Q);  // a1..a10, box, centred
      if (p.slab != decltype(p.slab){}) {
        std::copy(p.slab.begin(), p.slab.end(), w.begin() + P_SLABA);  // axis, half height
        w[P_SLAB] = 1;
      }
    }
    v.prims.push_back(w);
    v.prim_object.push_back(p.object);
  }
}

}  // namespace

// The camera (mode XM_CAMERA): the view rotation for the items, and the
// eye-ray and world-frame constants as r_xform left them.
void RenderFirmware::xform_camera(const SceneImage& img, std::array<std::uint32_t, 9>& rot,
                                  ViewScene::Constants& cam) {
  constexpr Step step = Step::Transform;
  stream("r_xform", 1, step,
         [&](int) {
           std::array<std::uint32_t, X_HEAD> w{};
           w[COUNT] = 1;
           w[H_MODE] = XM_CAMERA;
           std::copy(img.eye.begin(), img.eye.end(), w.begin() + X_EYE);
           std::copy(img.look_at.begin(), img.look_at.end(), w.begin() + X_LOOK);
           std::copy(img.up.begin(), img.up.end(), w.begin() + X_UP);
           w[X_FOV] = img.fov_deg;
           w[X_W] = static_cast<std::uint32_t>(img.width);
           w[X_H] = static_cast<std::uint32_t>(img.height);
           w[X_DEG] = kPiOver360;
           write(H_MODE, w.data() + H_MODE, w.size() - H_MODE, step);
           write(COUNT, w.data() + COUNT, 1, step);
         },
         [&](int) {
           const auto r = read(X_R, rot.size(), step);
           std::copy(r.begin(), r.end(), rot.begin());
           const auto c = read(C_D0, cam.size(), step);
           std::copy(c.begin(), c.end(), cam.begin());
         });
  for (auto& b : banks_) b.scene_valid = false;  // the camera batch wrote constants
}

void RenderFirmware::load_scene(const SceneImage& img) {
  constexpr Step step = Step::Transform;
  check_limits(img.lights.size(), img.materials.size());
  std::array<std::uint32_t, 9> rot{};
  ViewScene::Constants cam{};
  xform_camera(img, rot, cam);

  // Everything else (mode XM_ITEMS), in place.
  XformItems x = xform_items(img);
  ItemStream s{static_cast<int>(x.items.size()), X_PER_BATCH, X_ITEMS, X_SIZE, false};
  s.put = [&](int i, std::uint16_t addr) { write(addr, x.items[i].data(), X_SIZE, step); };
  s.end = [&](int, int) {
    write(X_R, rot.data(), rot.size(), step);
    write(X_EYE, img.eye.data(), img.eye.size(), step);
    const std::uint32_t mode = XM_ITEMS;
    write(H_MODE, &mode, 1, step);
  };
  s.get = [&](int i, std::uint16_t addr) {
    const auto& back = read(addr, X_BACK, step);
    std::copy(back.begin(), back.end(), x.items[i].begin());
  };
  stream_items("r_xform", step, s);
  for (auto& b : banks_) b.scene_valid = false;

  // The view scene: integer copies of r_xform's results into the records.
  ViewScene v;
  v.width = img.width;
  v.height = img.height;
  v.max_depth = img.max_depth;
  set_constants(v, img, cam);
  add_lights_and_materials(v, img, x);
  add_objects(v, img, x);
  add_prims(v, img, x);
  load_view_scene(v);
}

void RenderFirmware::load_view_scene(const ViewScene& view) {
  check_limits(view.lights.size(), view.materials.size());
  view_ = view;
  scene_words_.assign(PRIMS - C_D0, 0);
  std::copy(view.constants.begin(), view.constants.end(), scene_words_.begin());
  for (std::size_t l = 0; l < view.lights.size(); ++l)
    std::copy(view.lights[l].begin(), view.lights[l].end(), scene_words_.begin() + (LIGHTS - C_D0) + L_SIZE * l);
  for (std::size_t m = 0; m < view.materials.size(); ++m)
    std::copy(view.materials[m].begin(), view.materials[m].end(),
              scene_words_.begin() + (MATS - C_D0) + M_SIZE * m);
  forget_bank_data();
  project_boxes();
  build_shadow_lists();
  // [0] the block's eye rays (s1, per block), [1] every primitive in file order.
  lists_.assign(2, {});
  for (int p = 0; p < static_cast<int>(view_.prims.size()); ++p) lists_[1].push_back(p);
  build_solid_regions();
  build_triangle_boxes();
}

// Per object the union of its triangles' padded boxes (s4's culling).
void RenderFirmware::build_triangle_boxes() {
  object_tri_box_.assign(view_.objects.size(), kEmptyBox);
  for (std::size_t o = 0; o < view_.objects.size(); ++o) {
    const auto& obj = view_.objects[o];
    for (int q = obj.first_prim; q < obj.first_prim + obj.prim_count; ++q)
      if (is_triangle(view_.prims[q][P_TYPE])) grow_box(object_tri_box_[o], prim_box_[q]);
    cost(Step::BlockLists).list_elements += obj.prim_count;
  }
}

}  // namespace mc1::render
