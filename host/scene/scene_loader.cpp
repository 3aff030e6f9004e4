// JSON scene loader (docs/scene-format.md): every bad value is refused with
// "file:line: json.path: message", unknown keys included.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>

#include "fp24_range.hpp"
#include "json.hpp"  // host/common: mc1::json
#include "scene.hpp"

namespace mc1::scene {

namespace json = mc1::json;
using json::Type;
using json::Value;

std::size_t Scene::primitive_count() const {
  std::size_t n = 0;
  for (const auto& o : objects) n += o.primitives.size();
  return n;
}

std::size_t Scene::count(PrimitiveKind kind) const {
  std::size_t n = 0;
  for (const auto& o : objects)
    for (const auto& p : o.primitives) n += p.kind == kind;
  return n;
}

void finish_polygon(Primitive& p) {
  const auto& v = p.vertices;
  glm::dvec3 n = p.vertex_count == 3 ? glm::cross(v[1] - v[0], v[2] - v[0])
                                     : glm::cross(v[2] - v[0], v[3] - v[1]);
  p.normal = glm::normalize(n);
  finish_box(p);
}

void finish_box(Primitive& p) {
  if (p.is_polygon()) {
    p.box_min = p.box_max = p.vertices[0];
    for (int i = 1; i < p.vertex_count; ++i) {
      p.box_min = glm::min(p.box_min, p.vertices[i]);
      p.box_max = glm::max(p.box_max, p.vertices[i]);
    }
  } else if (p.kind == PrimitiveKind::ellipsoid) {
    // x = b + A^-1 u with |u| <= 1: half extent on axis i is |row i of A^-1|.
    glm::dmat3 inv = glm::inverse(p.A);
    glm::dvec3 half;
    for (int i = 0; i < 3; ++i) half[i] = glm::length(glm::dvec3(inv[0][i], inv[1][i], inv[2][i]));
    p.box_min = p.centre - half;
    p.box_max = p.centre + half;
  }
}

glm::dvec3 checker_colour(const Checker& c, const glm::dvec3& p) {
  glm::dvec3 d = p - c.origin;
  double s = std::floor(glm::dot(d, c.u) / c.scale);
  double t = std::floor(glm::dot(d, c.v) / c.scale);
  double parity = std::fmod(s + t, 2.0);
  return c.colours[parity == 0.0 ? 0 : 1];
}

namespace {

// A patch file is a few KB (scenes/data/utah-teapot.txt: 7 KB), a scene some
// tens (scenes/smooth.json: 29 KB; 65535 primitives at most): these bound
// what a file that never ends (/dev/zero, a FIFO) makes the loader hold.
constexpr std::size_t kMaxMeshFileBytes = std::size_t{64} << 20;    // 64 MiB
constexpr std::size_t kMaxSceneFileBytes = std::size_t{256} << 20;  // 256 MiB

// What `in` holds, read to at most one byte past `limit`: a longer result
// means a file over the limit, of which no more was read.
std::string read_at_most(std::istream& in, std::size_t limit) {
  std::string text;
  char buf[1 << 16];
  while (text.size() <= limit) {
    in.read(buf, std::streamsize(std::min(sizeof buf, limit + 1 - text.size())));
    text.append(buf, std::size_t(in.gcount()));
    if (!in) break;
  }
  return text;
}

const char* const kTooManyPrimitives =
    "more than 65535 primitives (a quad counts as two triangles), the NC's limit";
std::size_t nc_ids(const Primitive& p) { return p.vertex_count == 4 ? 2 : 1; }

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}
std::string index(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

class Loader {
 public:
  Loader(std::string name, std::string base_dir)
      : name_(std::move(name)), base_dir_(std::move(base_dir)) {}

  Scene scene(const Value& root) {
    Scene s;
    s.source = name_;
    expect_object(root, "", {"description", "camera", "render", "lights", "materials", "objects"});
    if (const Value* d = root.find("description")) text(*d, "description");
    s.camera = camera(required(root, "", "camera"), "camera");
    if (const Value* r = root.find("render")) s.render = render(*r, "render");
    const Value& lights = array(required(root, "", "lights"), "lights");
    for (std::size_t i = 0; i < lights.items.size(); ++i)
      s.lights.push_back(light(lights.items[i], index("lights", i)));
    const Value& materials = array(required(root, "", "materials"), "materials");
    for (std::size_t i = 0; i < materials.items.size(); ++i) {
      std::string path = index("materials", i);
      Material m = material(materials.items[i], path);
      for (const auto& other : s.materials)
        if (other.name == m.name)
          fail(*materials.items[i].find("name"), join(path, "name"),
               "duplicate material \"" + m.name + "\"");
      s.materials.push_back(m);
    }
    const Value& objects = array(required(root, "", "objects"), "objects");
    for (std::size_t i = 0; i < objects.items.size(); ++i)
      s.objects.push_back(object(objects.items[i], index("objects", i), s.materials));
    return s;
  }

 private:
  std::string name_;
  std::string base_dir_;
  std::size_t ids_ = 0;  // NC primitive ids of the primitives loaded so far

  [[noreturn]] void fail(const Value& v, const std::string& path, const std::string& msg) const {
    throw SceneError(name_ + ":" + std::to_string(v.line) + ": " + (path.empty() ? "(top)" : path) +
                     ": " + msg);
  }

  void expect_object(const Value& v, const std::string& path,
                     std::initializer_list<const char*> keys) const {
    if (v.type != Type::object) fail(v, path, std::string("expected an object, got ") + json::type_name(v.type));
    for (const auto& m : v.members) {
      bool known = std::any_of(keys.begin(), keys.end(), [&](const char* k) { return m.first == k; });
      if (!known) fail(m.second, join(path, m.first), "unknown key");
    }
  }

  const Value& required(const Value& obj, const std::string& path, const char* key) const {
    const Value* v = obj.find(key);
    if (!v) fail(obj, path, std::string("missing key \"") + key + "\"");
    return *v;
  }

  const Value& array(const Value& v, const std::string& path) const {
    if (v.type != Type::array) fail(v, path, std::string("expected an array, got ") + json::type_name(v.type));
    return v;
  }

  std::string text(const Value& v, const std::string& path) const {
    if (v.type != Type::string) fail(v, path, "expected a string");
    return v.string;
  }

  bool boolean(const Value& v, const std::string& path) const {
    if (v.type != Type::boolean) fail(v, path, "expected true or false");
    return v.boolean;
  }

  double number(const Value& v, const std::string& path) const {
    if (v.type != Type::number) fail(v, path, "expected a number");
    return v.number;
  }

  // A number the NC holds as FP24.
  double fp24(const Value& v, const std::string& path) const {
    double d = number(v, path);
    if (!in_fp24_range(d)) fail(v, path, "expected " + std::string(kFp24Range) + ", got " + shortest(d));
    return d;
  }

  double non_negative(const Value& v, const std::string& path) const {
    double d = fp24(v, path);
    if (d < 0) fail(v, path, "must not be negative");
    return d;
  }

  double positive(const Value& v, const std::string& path) const {
    double d = fp24(v, path);
    if (!(d > 0)) fail(v, path, "must be positive");
    return d;
  }

  int integer(const Value& v, const std::string& path, int lo, int hi) const {
    double d = number(v, path);
    if (d != std::floor(d) || d < lo || d > hi)
      fail(v, path, "expected an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
    return static_cast<int>(d);
  }

  static bool numbers(const Value& v, std::size_t count) {
    return v.type == Type::array && v.items.size() == count &&
           std::all_of(v.items.begin(), v.items.end(), [](const Value& e) { return e.type == Type::number; });
  }

  // Three numbers, each in FP24's range.
  glm::dvec3 triple(const Value& v, const std::string& path, const char* shape) const {
    if (!numbers(v, 3)) fail(v, path, std::string("expected ") + shape);
    glm::dvec3 t;
    for (int i = 0; i < 3; ++i) t[i] = fp24(v.items[i], index(path, i));
    return t;
  }

  glm::dvec3 vec3(const Value& v, const std::string& path) const { return triple(v, path, "[x, y, z]"); }

  glm::dvec3 colour(const Value& v, const std::string& path) const {
    glm::dvec3 c = triple(v, path, "[r, g, b]");
    if (c.r < 0 || c.g < 0 || c.b < 0) fail(v, path, "colour components must not be negative");
    return c;
  }

  glm::dvec3 direction(const Value& v, const std::string& path) const {
    glm::dvec3 d = vec3(v, path);
    if (glm::length(d) <= 1e-12) fail(v, path, "zero-length vector");
    return d;
  }

  // Rows in the file: [[a11, a12, a13], [a21, ...], ...]; GLM stores A[col][row].
  glm::dmat3 matrix3(const Value& v, const std::string& path) const {
    bool ok = v.type == Type::array && v.items.size() == 3;
    for (std::size_t r = 0; ok && r < 3; ++r) ok = numbers(v.items[r], 3);
    if (!ok) fail(v, path, "expected 3x3 matrix");
    glm::dmat3 m;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m[c][r] = fp24(v.items[r].items[c], index(index(path, r), c));
    return m;
  }

  Camera camera(const Value& v, const std::string& path) const {
    expect_object(v, path, {"eye", "look_at", "up", "fov", "width", "height"});
    Camera c;
    c.eye = vec3(required(v, path, "eye"), join(path, "eye"));
    c.look_at = vec3(required(v, path, "look_at"), join(path, "look_at"));
    if (glm::length(c.look_at - c.eye) <= 1e-12) fail(*v.find("look_at"), join(path, "look_at"), "equals eye");
    if (const Value* up = v.find("up")) {
      c.up = direction(*up, join(path, "up"));
      glm::dvec3 f = glm::normalize(c.look_at - c.eye);
      if (glm::length(glm::cross(f, glm::normalize(c.up))) <= 1e-9)
        fail(*up, join(path, "up"), "parallel to the view direction");
    }
    const Value& fov = required(v, path, "fov");
    c.fov_deg = fp24(fov, join(path, "fov"));
    if (!(c.fov_deg > 0 && c.fov_deg < 180)) fail(fov, join(path, "fov"), "expected degrees in (0, 180)");
    c.width = integer(required(v, path, "width"), join(path, "width"), 1, 8192);
    c.height = integer(required(v, path, "height"), join(path, "height"), 1, 8192);
    return c;
  }

  RenderSettings render(const Value& v, const std::string& path) const {
    expect_object(v, path, {"max_depth", "background", "epsilon"});
    RenderSettings r;
    if (const Value* d = v.find("max_depth")) r.max_depth = integer(*d, join(path, "max_depth"), 0, 64);
    if (const Value* b = v.find("background")) r.background = colour(*b, join(path, "background"));
    if (const Value* e = v.find("epsilon")) r.epsilon = positive(*e, join(path, "epsilon"));
    return r;
  }

  Light light(const Value& v, const std::string& path) const {
    expect_object(v, path, {"position", "intensity"});
    Light l;
    l.position = vec3(required(v, path, "position"), join(path, "position"));
    if (const Value* i = v.find("intensity")) l.intensity = colour(*i, join(path, "intensity"));
    return l;
  }

  Material material(const Value& v, const std::string& path) const {
    expect_object(v, path, {"name", "colour", "ko", "kd", "km", "n", "ks", "kt", "index", "checker"});
    Material m;
    m.name = text(required(v, path, "name"), join(path, "name"));
    if (const Value* c = v.find("colour")) m.colour = colour(*c, join(path, "colour"));
    struct Field {
      const char* key;
      double* dst;
    };
    for (Field f : {Field{"ko", &m.ko}, Field{"kd", &m.kd}, Field{"km", &m.km}, Field{"ks", &m.ks},
                    Field{"kt", &m.kt}})
      if (const Value* x = v.find(f.key)) *f.dst = non_negative(*x, join(path, f.key));
    // Not FP24: the NC holds n as an integer part and 8 fraction bits (docs/renderer.md).
    if (const Value* x = v.find("n")) {
      m.n = number(*x, join(path, "n"));
      if (m.n < 0) fail(*x, join(path, "n"), "must not be negative");
      if (m.n > 32767) fail(*x, join(path, "n"), "expected at most 32767 (the NC's fixed-point exponent)");
    }
    if (const Value* x = v.find("index")) m.index = positive(*x, join(path, "index"));
    if (const Value* c = v.find("checker")) {
      m.textured = true;
      m.checker = checker(*c, join(path, "checker"));
    }
    return m;
  }

  Checker checker(const Value& v, const std::string& path) const {
    expect_object(v, path, {"colours", "scale", "origin", "u", "v"});
    Checker c;
    const Value& cols = required(v, path, "colours");
    if (cols.type != Type::array || cols.items.size() != 2) fail(cols, join(path, "colours"), "expected two colours");
    for (int i = 0; i < 2; ++i) c.colours[i] = colour(cols.items[i], index(join(path, "colours"), i));
    const Value& sv = required(v, path, "scale");
    c.scale = positive(sv, join(path, "scale"));
    // The NC maps with u / scale and v / scale (docs/renderer.md).
    if (!in_fp24_range(1.0 / c.scale))
      fail(sv, join(path, "scale"), "expected 1 / scale in FP24's range, got " + shortest(1.0 / c.scale));
    if (const Value* o = v.find("origin")) c.origin = vec3(*o, join(path, "origin"));
    if (const Value* u = v.find("u")) c.u = glm::normalize(direction(*u, join(path, "u")));
    if (const Value* w = v.find("v")) c.v = glm::normalize(direction(*w, join(path, "v")));
    return c;
  }

  // Counts the NC ids of out[from..] and refuses the scene beyond the limit.
  void count_ids(const Value& v, const std::string& path, const std::vector<Primitive>& out, std::size_t from) {
    for (std::size_t i = from; i < out.size(); ++i) ids_ += nc_ids(out[i]);
    if (ids_ > kMaxPrimitiveIds) fail(v, path, kTooManyPrimitives);
  }

  void add(const Primitive& p, const Value& v, const std::string& path, std::vector<Primitive>& out) {
    out.push_back(p);
    count_ids(v, path, out, out.size() - 1);
  }

  Object object(const Value& v, const std::string& path, const std::vector<Material>& materials) {
    expect_object(v, path, {"name", "kind", "combine", "material", "primitives"});
    Object o;
    if (const Value* n = v.find("name")) o.name = text(*n, join(path, "name"));
    const Value& kind = required(v, path, "kind");
    std::string k = text(kind, join(path, "kind"));
    if (k == "solid") o.kind = ObjectKind::solid;
    else if (k == "surface") o.kind = ObjectKind::surface;
    else fail(kind, join(path, "kind"), "expected \"solid\" or \"surface\"");
    const Value& mat = required(v, path, "material");
    std::string mname = text(mat, join(path, "material"));
    auto it = std::find_if(materials.begin(), materials.end(), [&](const Material& m) { return m.name == mname; });
    if (it == materials.end()) fail(mat, join(path, "material"), "unknown material \"" + mname + "\"");
    o.material = static_cast<int>(it - materials.begin());
    const Value& prims = array(required(v, path, "primitives"), join(path, "primitives"));
    for (std::size_t i = 0; i < prims.items.size(); ++i)
      primitive(prims.items[i], index(join(path, "primitives"), i), o.primitives);
    if (o.primitives.empty()) fail(prims, join(path, "primitives"), "object has no primitives");
    if (const Value* c = v.find("combine")) combine(*c, join(path, "combine"), o);
    o.box_min = o.primitives[0].box_min;
    o.box_max = o.primitives[0].box_max;
    for (const auto& p : o.primitives) {
      o.box_min = glm::min(o.box_min, p.box_min);
      o.box_max = glm::max(o.box_max, p.box_max);
    }
    return o;
  }

  // "combine": union (default), or for a solid of regions only intersection
  // or difference, of at least two of them.
  void combine(const Value& v, const std::string& path, Object& o) const {
    const std::string c = text(v, path);
    if (c == "union") return;
    if (c == "intersection") o.combine = Combine::intersection;
    else if (c == "difference") o.combine = Combine::difference;
    else fail(v, path, "expected \"union\", \"intersection\" or \"difference\"");
    if (o.kind != ObjectKind::solid) fail(v, path, "intersection and difference combine solids only");
    if (o.primitives.size() < 2) fail(v, path, "intersection and difference need at least two primitives");
    if (!std::all_of(o.primitives.begin(), o.primitives.end(), [](const Primitive& p) { return p.is_region(); }))
      fail(v, path, "intersection and difference take regions only (ellipsoid, sphere, quadric)");
  }

  void primitive(const Value& v, const std::string& path, std::vector<Primitive>& out) {
    if (v.type != Type::object) fail(v, path, "expected an object");
    const Value& type = required(v, path, "type");
    std::string t = text(type, join(path, "type"));
    if (t == "triangle" || t == "quad" || t == "pseudo_triangle" || t == "pseudo_quad")
      add(polygon(v, path, t), v, path, out);
    else if (t == "ellipsoid" || t == "sphere")
      add(ellipsoid(v, path, t == "sphere"), v, path, out);
    else if (t == "quadric")
      add(quadric(v, path), v, path, out);
    else if (t == "revolution")
      revolution(v, path, out);
    else if (t == "bezier_patch")
      bezier_patch(v, path, out);
    else if (t == "bspline_patch")
      bspline_patch(v, path, out);
    else if (t == "bezier_mesh")
      bezier_mesh(v, path, out);
    else
      fail(type, join(path, "type"), "unknown primitive type \"" + t + "\"");
  }

  std::vector<glm::dvec3> points(const Value& v, const std::string& path, std::size_t count) const {
    if (v.type != Type::array || v.items.size() != count)
      fail(v, path, "expected " + std::to_string(count) + " points");
    std::vector<glm::dvec3> pts;
    for (std::size_t i = 0; i < count; ++i) pts.push_back(vec3(v.items[i], index(path, i)));
    return pts;
  }

  static bool zero_area(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    glm::dvec3 e1 = b - a, e2 = c - a;
    double l1 = glm::length(e1), l2 = glm::length(e2);
    return l1 == 0 || l2 == 0 || glm::length(glm::cross(e1, e2)) <= 1e-9 * l1 * l2;
  }

  Primitive polygon(const Value& v, const std::string& path, const std::string& t) const {
    bool pseudo = t.rfind("pseudo_", 0) == 0;
    std::size_t count = (t == "triangle" || t == "pseudo_triangle") ? 3 : 4;
    if (pseudo) expect_object(v, path, {"type", "vertices", "normals"});
    else expect_object(v, path, {"type", "vertices"});
    Primitive p;
    p.kind = t == "triangle" ? PrimitiveKind::triangle
             : t == "quad" ? PrimitiveKind::quad
             : t == "pseudo_triangle" ? PrimitiveKind::pseudo_triangle
                                      : PrimitiveKind::pseudo_quad;
    p.vertex_count = static_cast<int>(count);
    const Value& verts = required(v, path, "vertices");
    std::vector<glm::dvec3> pts = points(verts, join(path, "vertices"), count);
    for (std::size_t i = 0; i < count; ++i) p.vertices[i] = pts[i];
    const auto& q = p.vertices;
    if (zero_area(q[0], q[1], q[2]) || (count == 4 && zero_area(q[0], q[2], q[3])))
      fail(verts, join(path, "vertices"), "degenerate polygon (zero area)");
    if (count == 4) {
      glm::dvec3 n1 = glm::normalize(glm::cross(q[1] - q[0], q[2] - q[0]));
      glm::dvec3 n2 = glm::normalize(glm::cross(q[2] - q[0], q[3] - q[0]));
      if (glm::dot(n1, n2) <= 0) fail(verts, join(path, "vertices"), "quad is not convex (vertex order?)");
      double size = std::max(glm::length(q[2] - q[0]), glm::length(q[3] - q[1]));
      if (!pseudo && std::abs(glm::dot(n1, q[3] - q[0])) > 1e-6 * size)
        fail(verts, join(path, "vertices"), "quad is not planar");
    }
    if (pseudo) {
      const Value& nv = required(v, path, "normals");
      std::vector<glm::dvec3> ns = points(nv, join(path, "normals"), count);
      for (std::size_t i = 0; i < count; ++i) {
        if (glm::length(ns[i]) <= 1e-12) fail(nv.items[i], index(join(path, "normals"), i), "zero-length normal");
        p.vertex_normals[i] = glm::normalize(ns[i]);
      }
    }
    finish_polygon(p);
    return p;
  }

  Primitive ellipsoid(const Value& v, const std::string& path, bool sphere) const {
    Primitive p;
    p.kind = PrimitiveKind::ellipsoid;
    if (sphere) {
      expect_object(v, path, {"type", "centre", "radius"});
      p.centre = vec3(required(v, path, "centre"), join(path, "centre"));
      const Value& rv = required(v, path, "radius");
      double r = positive(rv, join(path, "radius"));
      if (!in_fp24_range(1.0 / r))
        fail(rv, join(path, "radius"), "expected 1 / radius in FP24's range, got " + shortest(1.0 / r));
      p.A = glm::dmat3(1.0 / r);
    } else {
      expect_object(v, path, {"type", "A", "centre"});
      p.centre = vec3(required(v, path, "centre"), join(path, "centre"));
      const Value& a = required(v, path, "A");
      p.A = matrix3(a, join(path, "A"));
      double scale = 0;
      for (int c = 0; c < 3; ++c) scale = std::max(scale, glm::length(p.A[c]));
      if (std::abs(glm::determinant(p.A)) <= 1e-12 * scale * scale * scale)
        fail(a, join(path, "A"), "singular matrix A");
    }
    finish_box(p);
    if (!below_fp24_max(p.box_min) || !below_fp24_max(p.box_max))
      fail(v, path, "bounding box outside FP24's range (A too small)");
    return p;
  }

  // q(c + y) = y^T M y + (2 M c + g).y + q(c), c the box centre.
  static void centre_quadric(Primitive& p) {
    const auto& a = p.coefficients;
    const glm::dvec3 c = 0.5 * (p.box_min + p.box_max);
    p.centred_linear = {a[6] + 2 * a[0] * c.x + a[3] * c.y + a[4] * c.z,
                        a[7] + 2 * a[1] * c.y + a[3] * c.x + a[5] * c.z,
                        a[8] + 2 * a[2] * c.z + a[4] * c.x + a[5] * c.y,
                        a[0] * c.x * c.x + a[1] * c.y * c.y + a[2] * c.z * c.z + a[3] * c.x * c.y +
                            a[4] * c.x * c.z + a[5] * c.y * c.z + a[6] * c.x + a[7] * c.y + a[8] * c.z + a[9]};
  }

  Primitive quadric(const Value& v, const std::string& path) const {
    expect_object(v, path, {"type", "coefficients", "box"});
    Primitive p;
    p.kind = PrimitiveKind::quadric;
    const Value& cv = required(v, path, "coefficients");
    if (cv.type != Type::array || cv.items.size() != 10)
      fail(cv, join(path, "coefficients"), "expected 10 numbers a1..a10");
    for (std::size_t i = 0; i < 10; ++i) p.coefficients[i] = fp24(cv.items[i], index(join(path, "coefficients"), i));
    if (std::all_of(p.coefficients.begin(), p.coefficients.begin() + 9, [](double a) { return a == 0; }))
      fail(cv, join(path, "coefficients"), "degenerate quadric (a1..a9 all zero)");
    const Value& box = required(v, path, "box");
    std::string bpath = join(path, "box");
    expect_object(box, bpath, {"min", "max"});
    p.box_min = vec3(required(box, bpath, "min"), join(bpath, "min"));
    p.box_max = vec3(required(box, bpath, "max"), join(bpath, "max"));
    for (int i = 0; i < 3; ++i)
      if (!(p.box_min[i] < p.box_max[i])) fail(box, bpath, "min must be below max on every axis");
    centre_quadric(p);
    return p;
  }

  // A revolution's axis: "x", "y", "z" or a direction [x, y, z] (not 0),
  // as a unit vector.
  glm::dvec3 revolution_axis(const Value& av, const std::string& path) const {
    if (av.type == Type::string) {
      const std::string axis = text(av, path);
      if (axis != "x" && axis != "y" && axis != "z") fail(av, path, "expected \"x\", \"y\", \"z\" or a direction [x, y, z]");
      glm::dvec3 a(0.0);
      a[axis[0] - 'x'] = 1.0;
      return a;
    }
    const glm::dvec3 a = vec3(av, path);
    const double n = glm::length(a);
    if (!(n > 0) || !std::isfinite(n)) fail(av, path, "the direction must not be 0");
    return a / n;
  }

  // A profile of [radius, height] points revolved about an axis: one
  // quadric frustum per segment (revolved_segment).
  void revolution(const Value& v, const std::string& path, std::vector<Primitive>& out) {
    expect_object(v, path, {"type", "axis", "base", "profile"});
    const Value& av = required(v, path, "axis");
    const glm::dvec3 axis = revolution_axis(av, join(path, "axis"));
    const glm::dvec3 base = vec3(required(v, path, "base"), join(path, "base"));
    const Value& pv = required(v, path, "profile");
    const std::string ppath = join(path, "profile");
    if (pv.type != Type::array || pv.items.size() < 2) fail(pv, ppath, "expected at least 2 [radius, height] points");
    std::vector<glm::dvec2> pts;
    for (std::size_t i = 0; i < pv.items.size(); ++i) {
      const Value& q = pv.items[i];
      if (q.type != Type::array || q.items.size() != 2) fail(q, index(ppath, i), "expected [radius, height]");
      pts.emplace_back(non_negative(q.items[0], index(index(ppath, i), 0)), fp24(q.items[1], index(index(ppath, i), 1)));
      if (i == 0) continue;
      if (!(pts[i].y > pts[i - 1].y)) fail(q, index(ppath, i), "heights must increase along the profile");
      if (pts[i].x == 0 && pts[i - 1].x == 0) fail(q, index(ppath, i), "a segment on the axis (both radii 0)");
    }
    const std::size_t before = out.size();
    for (std::size_t i = 1; i < pts.size(); ++i) {
      Primitive p = revolved_segment(axis, base, pts[i - 1], pts[i]);
      for (double a : p.coefficients)
        if (!in_fp24_range(a)) fail(pv.items[i], index(ppath, i), "a coefficient of its quadric, " + shortest(a) + ", outside FP24's range");
      for (double a : p.centred_linear)
        if (!in_fp24_range(a)) fail(pv.items[i], index(ppath, i), "a coefficient of its quadric, " + shortest(a) + ", outside FP24's range");
      out.push_back(p);
    }
    count_ids(v, path, out, before);
  }

  int level(const Value& v, const std::string& path) const {
    const Value* l = v.find("level");
    return l ? integer(*l, join(path, "level"), 1, 64) : 4;
  }

  void bezier_patch(const Value& v, const std::string& path, std::vector<Primitive>& out) {
    expect_object(v, path, {"type", "points", "level"});
    std::vector<glm::dvec3> pts = points(required(v, path, "points"), join(path, "points"), 16);
    BicubicNet net;
    std::copy(pts.begin(), pts.end(), net.begin());
    tessellate_checked(net, Basis::bezier, level(v, path), v, path, out);
  }

  void bspline_patch(const Value& v, const std::string& path, std::vector<Primitive>& out) {
    expect_object(v, path, {"type", "net", "level", "wrap_u", "wrap_v"});
    const Value& nv = required(v, path, "net");
    std::string npath = join(path, "net");
    if (nv.type != Type::array || nv.items.size() < 4) fail(nv, npath, "expected at least 4 rows of points");
    std::size_t cols = nv.items[0].type == Type::array ? nv.items[0].items.size() : 0;
    if (cols < 4) fail(nv.items[0], index(npath, 0), "expected at least 4 points per row");
    std::vector<std::vector<glm::dvec3>> rows;
    for (std::size_t r = 0; r < nv.items.size(); ++r) rows.push_back(points(nv.items[r], index(npath, r), cols));
    bool wrap_u = v.find("wrap_u") ? boolean(*v.find("wrap_u"), join(path, "wrap_u")) : false;
    bool wrap_v = v.find("wrap_v") ? boolean(*v.find("wrap_v"), join(path, "wrap_v")) : false;
    std::size_t spans_u = wrap_u ? cols : cols - 3, spans_v = wrap_v ? rows.size() : rows.size() - 3;
    int lv = level(v, path);
    for (std::size_t sv = 0; sv < spans_v; ++sv)
      for (std::size_t su = 0; su < spans_u; ++su) {
        BicubicNet net;
        for (std::size_t r = 0; r < 4; ++r)
          for (std::size_t c = 0; c < 4; ++c) net[4 * r + c] = rows[(sv + r) % rows.size()][(su + c) % cols];
        tessellate_checked(net, Basis::bspline, lv, v, path, out);
      }
  }

  void tessellate_checked(const BicubicNet& net, Basis basis, int lv, const Value& v,
                          const std::string& path, std::vector<Primitive>& out) {
    std::size_t before = out.size();
    tessellate_patch(net, basis, lv, out);
    if (out.size() == before) fail(v, path, "degenerate patch (no cell has an area)");
    count_ids(v, path, out, before);
  }

  void bezier_mesh(const Value& v, const std::string& path, std::vector<Primitive>& out) {
    expect_object(v, path, {"type", "file", "level", "matrix", "offset"});
    const Value& fv = required(v, path, "file");
    std::string file = text(fv, join(path, "file"));
    glm::dmat3 m(1.0);
    if (const Value* mv = v.find("matrix")) {
      m = matrix3(*mv, join(path, "matrix"));
      if (std::abs(glm::determinant(m)) <= 1e-12) fail(*mv, join(path, "matrix"), "singular matrix");
    }
    glm::dvec3 offset(0.0);
    if (const Value* ov = v.find("offset")) offset = vec3(*ov, join(path, "offset"));
    std::string full = (file.empty() || file[0] == '/' || base_dir_.empty()) ? file : base_dir_ + "/" + file;
    if (std::filesystem::is_directory(full))
      fail(fv, join(path, "file"), "\"" + full + "\" is a directory (expected a patch file)");
    std::ifstream in(full);
    if (!in) fail(fv, join(path, "file"), "cannot open \"" + full + "\"");
    const std::string text = read_at_most(in, kMaxMeshFileBytes);
    if (text.size() > kMaxMeshFileBytes)
      fail(fv, join(path, "file"), "\"" + full + "\" is over " + std::to_string(kMaxMeshFileBytes >> 20) +
                                       " MiB, too large for a patch file");
    std::istringstream lines(text);
    std::vector<BicubicNet> patches = read_bezier_file(lines, full);
    int lv = level(v, path);
    for (std::size_t i = 0; i < patches.size(); ++i) {
      BicubicNet& net = patches[i];
      for (auto& c : net) c = m * c + offset;
      if (!std::all_of(net.begin(), net.end(), below_fp24_max))
        fail(v, path, "patch " + std::to_string(i) + " of \"" + full + "\": matrix and offset take it outside FP24's range");
      std::size_t before = out.size();
      tessellate_patch(net, Basis::bezier, lv, out);
      count_ids(v, path, out, before);
    }
  }
};

std::string dirname(const std::string& path) {
  std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& name, const std::string& base_dir) {
  // Every entry of "primitives" is at least one primitive and every object
  // holds one: a scene past the limit is refused before it is held whole.
  const std::vector<json::ItemLimit> limits = {
      {{"objects", "[]", "primitives"}, kMaxPrimitiveIds, kTooManyPrimitives},
      {{"objects"}, kMaxPrimitiveIds, "more than 65535 objects (each holds a primitive), the NC's limit"},
      {{"lights"}, kMaxLights, "more than " + std::to_string(kMaxLights) + " lights, the NC's limit"},
      {{"materials"}, kMaxMaterials, "more than " + std::to_string(kMaxMaterials) + " materials, the NC's limit"}};
  Value root;
  try {
    root = json::parse(text, name, limits);
  } catch (const json::JsonError& e) {  // already "name:line[:column]: ...", as every SceneError
    throw SceneError(e.what());
  }
  return Loader(name, base_dir).scene(root);
}

Scene load_scene(const std::string& path) {
  if (std::filesystem::is_directory(path)) throw SceneError(path + ": is a directory (expected a scene file)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open scene file");
  std::string text;
  std::streamoff size = in.seekg(0, std::ios::end) ? static_cast<std::streamoff>(in.tellg()) : -1;
  const std::string too_large =
      path + ": over " + std::to_string(kMaxSceneFileBytes >> 20) + " MiB, too large for a scene file";
  if (size > static_cast<std::streamoff>(kMaxSceneFileBytes)) throw SceneError(too_large);
  if (size >= 0) {
    // One read: a huge scene is then refused by the parse within a moment.
    text.resize(static_cast<std::size_t>(size));
    in.seekg(0);
    in.read(text.data(), size);
  } else {  // a pipe
    in.clear();
    text = read_at_most(in, kMaxSceneFileBytes);
    if (text.size() > kMaxSceneFileBytes) throw SceneError(too_large);
  }
  if (in.bad()) throw SceneError(path + ": read error");
  return parse_scene(text, path, dirname(path));
}

}  // namespace mc1::scene
