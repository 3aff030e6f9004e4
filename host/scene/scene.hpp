// The MC-1 scene as the RC holds it (paper section 3, fig. 2): camera, lights,
// materials (optical attributes, mapping data, texture pattern) and objects made
// of the paper's primitives. Plain doubles in world coordinates; the NC firmware
// converts to FP24 and to view coordinates itself. docs/scene-format.md is the
// normative description of every field and convention used here.
#pragma once

#include <array>
#include <cstddef>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace mc1::scene {

// A refused scene: "file:line: json.path: message" (docs/scene-format.md).
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Pinhole camera, vertical field of view; pixel (i, j) is column i (left to
// right), row j (top to bottom); eye rays go through pixel centres.
struct Camera {
  glm::dvec3 eye{0.0};
  glm::dvec3 look_at{0.0, 0.0, -1.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_deg = 45.0;  // full vertical angle
  int width = 0;
  int height = 0;
};

// Point light; intensity per RGB component, no distance attenuation.
struct Light {
  glm::dvec3 position{0.0};
  glm::dvec3 intensity{1.0};
};

// Procedural checker texture on a planar mapping: s = (p - origin).u / scale,
// t = (p - origin).v / scale; colours[(floor(s) + floor(t)) mod 2].
struct Checker {
  std::array<glm::dvec3, 2> colours{glm::dvec3(1.0), glm::dvec3(0.0)};
  double scale = 1.0;
  glm::dvec3 origin{0.0};
  glm::dvec3 u{1.0, 0.0, 0.0};  // default mapping: world x / z
  glm::dvec3 v{0.0, 0.0, 1.0};
};

// Optical attributes of the Whitted model (paper s3/s4):
// I = ko C + kd C x sum I_l cos(theta) + km C x sum I_l cos^n(phi) + ks C x S + kt C x T.
struct Material {
  std::string name;
  glm::dvec3 colour{1.0};  // C, replaced by the checker colour where textured
  double ko = 0.0;         // ambient
  double kd = 0.0;         // diffuse
  double km = 0.0;         // metallic (specular highlight)
  double n = 1.0;          // highlight exponent
  double ks = 0.0;         // mirror reflection
  double kt = 0.0;         // transmission
  double index = 1.0;      // refractive index (solids only)
  bool textured = false;   // true: use `checker` for C
  Checker checker;
};

enum class PrimitiveKind { triangle, quad, pseudo_triangle, pseudo_quad, ellipsoid, quadric };

// One primitive of fig. 2. Polygons: `vertex_count` vertices in order,
// counter-clockwise seen from the side `normal` points to; a quad is the two
// triangles (v0, v1, v2) and (v0, v2, v3). Pseudo polygons carry unit vertex
// normals, interpolated barycentrically inside each of those triangles.
// Ellipsoid: region |A (x - b)| <= 1. Quadric: q(x) <= 0 inside [box_min, box_max]
// with q = a1 x^2 + a2 y^2 + a3 z^2 + a4 xy + a5 xz + a6 yz + a7 x + a8 y + a9 z + a10.
struct Primitive {
  PrimitiveKind kind = PrimitiveKind::triangle;
  int vertex_count = 0;                      // 3 or 4 for polygons, else 0
  std::array<glm::dvec3, 4> vertices{};      // polygons
  std::array<glm::dvec3, 4> vertex_normals{};  // pseudo polygons, unit length
  glm::dvec3 normal{0.0};                    // polygons: unit plane normal
  glm::dmat3 A{1.0};                         // ellipsoid; GLM is column-major: A[col][row]
  glm::dvec3 centre{0.0};                    // ellipsoid b
  std::array<double, 10> coefficients{};     // quadric a1..a10
  // Quadric: a7..a10 of q(c + y) as a polynomial in y, c the clip box's centre
  // (a1..a6 are the same): near the box its terms are small, so FP24 evaluates
  // it without the cancellation of far-away world coordinates (loader-filled).
  std::array<double, 4> centred_linear{};
  // Quadric: also clipped to the slab |(x - c).slab_axis| <= slab_half, c the
  // clip box's centre (a solid of revolution's segment; slab_half 0: none).
  glm::dvec3 slab_axis{0.0};
  double slab_half = 0.0;
  glm::dvec3 box_min{0.0};                   // quadric clip box; for every kind, the
  glm::dvec3 box_max{0.0};                   // primitive's bounding box (loader-filled)

  bool is_polygon() const { return vertex_count != 0; }
  bool is_region() const {
    return kind == PrimitiveKind::ellipsoid || kind == PrimitiveKind::quadric;
  }
};

enum class ObjectKind { solid, surface };

// How a solid's primitives' regions combine (docs/scene-format.md "Objects"):
// union (the default: any polygons and regions), or, of regions only, the
// intersection of all (the paper's AND) or the difference of the first and
// the union of the others.
enum class Combine { union_, intersection, difference };

// An object: a bounding box, its primitives and its material (fig. 2).
// solid = union of the primitives' regions (polygons bound it, normals outward);
// surface = a shell of the primitives' surfaces.
struct Object {
  std::string name;
  ObjectKind kind = ObjectKind::surface;
  int material = 0;  // index into Scene::materials
  Combine combine = Combine::union_;  // solids only
  std::vector<Primitive> primitives;
  glm::dvec3 box_min{0.0};  // union of the primitives' boxes
  glm::dvec3 box_max{0.0};
};

// The classification rule of a solid's surfaces, one region k of object o at a
// time (docs/scene-format.md "Objects"): a crossing of primitive j's surface
// is hidden when some other region k holds the point on the side that hides:
// strictly inside for a region of a union or a subtrahend of a difference,
// strictly outside for every region of an intersection and for the minuend
// of a difference.
inline bool hides_outside(const Object& o, int k) {
  return o.combine == Combine::intersection || (o.combine == Combine::difference && k == 0);
}
// A subtrahend's surface bounds the difference from its inside: the solid's
// outward normal is the subtrahend's inward one.
inline bool flips_normal(const Object& o, int k) { return o.combine == Combine::difference && k > 0; }

struct RenderSettings {
  int max_depth = 5;             // levels of ks/kt secondary rays below the eye ray
  glm::dvec3 background{0.0};    // colour of a ray that hits nothing
  double epsilon = 1e-3;         // secondary rays ignore hits with t <= epsilon
};

// The NC names a primitive by a 16-bit id (0xFFFF: no hit) and holds a quad
// as two triangles: at most this many ids per scene, quads counting twice.
// The loader refuses a scene beyond it (docs/scene-format.md).
constexpr std::size_t kMaxPrimitiveIds = 65535;
// The NC's data bank holds this many lights and materials (r_layout.inc's
// L_SLOTS and M_SLOTS; firmware/render/scene_image.hpp asserts they agree):
// the loader refuses a scene beyond them, naming the first one too many, so
// that both renderers take the same scenes.
constexpr std::size_t kMaxLights = 8;
constexpr std::size_t kMaxMaterials = 16;

struct Scene {
  std::string source;  // file the scene was loaded from
  Camera camera;
  RenderSettings render;
  std::vector<Light> lights;
  std::vector<Material> materials;
  std::vector<Object> objects;

  std::size_t primitive_count() const;
  std::size_t count(PrimitiveKind kind) const;
};

// Loads a JSON scene (docs/scene-format.md); mesh files are relative to it.
// Throws SceneError with file, line and JSON path on any bad input.
Scene load_scene(const std::string& path);
// Same, from text; `name` is used in messages, `base_dir` resolves mesh files.
Scene parse_scene(const std::string& text, const std::string& name,
                  const std::string& base_dir);

// Tessellation of bicubic patches into pseudo polygons (docs/scene-format.md).
// A 4x4 control net, row-major: net[4 * row + col]; u runs along a row, v down.
using BicubicNet = std::array<glm::dvec3, 16>;
enum class Basis { bezier, bspline };
// Appends level x level cells of the patch as pseudo-quads (a cell with a
// collapsed edge becomes a pseudo-triangle; a cell collapsed further is dropped).
void tessellate_patch(const BicubicNet& net, Basis basis, int level,
                      std::vector<Primitive>& out);
// A patch file ("patches N", N lines of 16 control-point indices, "points M",
// M lines "x y z"); throws SceneError "file:line: message" for bad content.
std::vector<BicubicNet> read_bezier_file(std::istream& in, const std::string& file);

// Solid of revolution: the quadric frustum of one profile segment (radius,
// height) p0 - p1 (p1.y > p0.y, radii >= 0, not both 0) about the line
// through `base` along the unit vector `axis`; heights from base.
Primitive revolved_segment(const glm::dvec3& axis, const glm::dvec3& base, const glm::dvec2& p0, const glm::dvec2& p1);

// The loader's derived data, shared with tests and tools.
void finish_polygon(Primitive& p);  // plane normal and box from the vertices
void finish_box(Primitive& p);      // box of an ellipsoid or polygon
glm::dvec3 checker_colour(const Checker& c, const glm::dvec3& p);

}  // namespace mc1::scene
