// The scene as FP24 words: SceneImage is what the RC broadcasts (world
// coordinates, paper section 4 step 1 input); ViewScene is what step 1 makes
// of it on every NC (view coordinates, the records of r_layout.inc that
// every data bank carries). docs/renderer.md gives every record.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "render_layout.hpp"
#include "scene.hpp"

namespace mc1::scene {
struct Scene;
}

namespace mc1::render {

using Word = std::uint32_t;  // one 24-bit data-bank word
using Vec3w = std::array<Word, 3>;

// The sizes of the data bank's areas (r_layout.inc).
constexpr int kMaxLights = layout::L_SLOTS;
constexpr int kMaxMaterials = layout::M_SLOTS;
static_assert(std::size_t{kMaxLights} == scene::kMaxLights && std::size_t{kMaxMaterials} == scene::kMaxMaterials,
              "the scene loader's limits are the data bank's slots");
constexpr int kPrimSlots = layout::P_SLOTS;
constexpr int kRaysPerBatch = layout::R_SLOTS;
constexpr std::uint32_t kNoHit = layout::NO_HIT;

enum PrimType : int {
  kTriangle = layout::PT_TRIANGLE,
  kPseudoTriangle = layout::PT_PSEUDO,
  kEllipsoid = layout::PT_ELLIPSOID,
  kQuadric = layout::PT_QUADRIC
};

// The words of SceneImage's lights and of PrimImage::w (world coordinates).
namespace image_words {
constexpr int kLightPos = 0, kLightI = 3, kLightWords = 6;  // position, intensity
constexpr int kV0 = 0, kN = 9, kVN = 12, kTriWords = 21;    // triangle: v0 v1 v2, normal, 3 vertex normals
constexpr int kEllA = 0, kEllB = 9;                         // ellipsoid: A row-major, centre b
constexpr int kQ = 0, kBMin = 10, kBMax = 13, kQL = 16;     // quadric: a1..a10, clip box, a7..a10 about its centre
constexpr int kSlabA = 0, kSlabH = 3, kSlabWords = 4;        // PrimImage::slab: axis, half height
}  // namespace image_words

// World-coordinate primitive as broadcast: polygons are split into triangles
// (a quad is (v0, v1, v2) and (v0, v2, v3), docs/scene-format.md).
struct PrimImage {
  int type = kTriangle;
  int object = 0;
  std::array<Word, image_words::kTriWords> w{};  // image_words
  // Quadric: a solid of revolution's slab, unit axis and half height about
  // the clip box's centre (all 0: none; broadcast only when present).
  std::array<Word, image_words::kSlabWords> slab{};
};

struct MaterialImage {
  std::array<Word, layout::M_SIZE> w{};  // r_layout.inc M_* layout; checker frame in world (M_CKO, M_CKU, M_CKV)
  Word checker_scale = 0;                // r_xform divides M_CKU, M_CKV by it
};
// ks > 0 or kt > 0: the pixels of an object of this material get s4 rays
// (FP24 signs and exponents compared as integers).
bool spawns_secondary(const MaterialImage& m);

// How a solid's regions combine (scene::Combine).
enum CombineCode : int { kUnion = 0, kIntersection = 1, kDifference = 2 };

struct ObjectImage {
  bool solid = false;
  int combine = kUnion;  // a CombineCode
  int material = 0;
  int first_prim = 0, prim_count = 0;
  Vec3w box_min{}, box_max{};  // world
};

struct SceneImage {
  Vec3w eye{}, look_at{}, up{};
  Word fov_deg = 0;
  int width = 0, height = 0;
  int max_depth = 5;
  Vec3w background{};
  Word epsilon = 0;
  std::vector<std::array<Word, image_words::kLightWords>> lights;  // position, intensity
  std::vector<MaterialImage> materials;
  std::vector<ObjectImage> objects;
  std::vector<PrimImage> prims;
};

// Step 1's product.
struct ViewScene {
  using Constants = std::array<Word, layout::LIGHTS - layout::C_D0>;  // words C_D0 .. LIGHTS - 1 (C_*)
  using Light = std::array<Word, layout::L_SIZE>;
  using Material = std::array<Word, layout::M_SIZE>;
  using Prim = std::array<Word, layout::P_SIZE>;
  int width = 0, height = 0, max_depth = 5;
  Constants constants{};
  std::vector<Light> lights;        // LIGHTS records
  std::vector<Material> materials;  // MATS records
  std::vector<Prim> prims;          // PRIMS records, P_ID = index
  struct Object {
    bool solid = false;
    int combine = kUnion;    // a CombineCode
    bool secondary = false;  // ks > 0 or kt > 0: its pixels get s4 rays
    int first_prim = 0, prim_count = 0;
    std::array<Word, 6> box{};  // view min xyz, max xyz
  };
  std::vector<Object> objects;
  std::vector<int> prim_object;  // object of each primitive
};

// The RC's conversion of the host scene (doubles) into FP24 words: no
// arithmetic but rounding each number once (fp24_from_double).
SceneImage make_scene_image(const scene::Scene& s);

}  // namespace mc1::render
