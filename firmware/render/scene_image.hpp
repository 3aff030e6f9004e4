// The scene as FP24 words: SceneImage is what the RC broadcasts (world
// coordinates, paper section 4 step 1 input); ViewScene is what step 1 makes
// of it on every NC (view coordinates, the records of r_layout.inc that
// every data bank carries). docs/renderer.md gives every record.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace mc1::scene {
struct Scene;
}

namespace mc1::render {

using Word = std::uint32_t;  // one 24-bit data-bank word
using Vec3w = std::array<Word, 3>;

constexpr int kMaxLights = 8;
constexpr int kMaxMaterials = 16;
constexpr int kPrimSlots = 48;
constexpr int kRaysPerBatch = 32;
constexpr std::uint32_t kNoHit = 0xFFFF;

enum PrimType : int { kTriangle = 1, kPseudoTriangle = 2, kEllipsoid = 3, kQuadric = 4 };

// World-coordinate primitive as broadcast: polygons are split into triangles
// (a quad is (v0, v1, v2) and (v0, v2, v3), docs/scene-format.md).
struct PrimImage {
  int type = kTriangle;
  int object = 0;
  // Triangle: v0, v1, v2, plane normal, vertex normals (pseudo): 21 words.
  // Ellipsoid: A row-major (9), b (3). Quadric: a1..a10, box min, box max.
  std::array<Word, 21> w{};
};

struct MaterialImage {
  std::array<Word, 32> w{};  // r_layout.inc M_* layout; checker frame in world (M_CKO, M_CKU, M_CKV)
  Word checker_scale = 0;    // r_xform divides M_CKU, M_CKV by it
};

struct ObjectImage {
  bool solid = false;
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
  std::vector<std::array<Word, 6>> lights;  // position, intensity
  std::vector<MaterialImage> materials;
  std::vector<ObjectImage> objects;
  std::vector<PrimImage> prims;
};

// Step 1's product.
struct ViewScene {
  int width = 0, height = 0, max_depth = 5;
  std::array<Word, 32> constants{};             // words 32..63 (C_*)
  std::vector<std::array<Word, 8>> lights;      // LIGHTS records
  std::vector<std::array<Word, 32>> materials;  // MATS records
  std::vector<std::array<Word, 32>> prims;      // PRIMS records, P_ID = index
  struct Object {
    bool solid = false;
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
