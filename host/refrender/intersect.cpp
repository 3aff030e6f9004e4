#include "intersect.hpp"

#include <algorithm>
#include <cmath>

namespace mc1::refrender {

using scene::Primitive;
using scene::PrimitiveKind;

namespace {

// Moller-Trumbore with inclusive edges; b1, b2 barycentric weights of c1, c2.
bool triangle(const glm::dvec3& c0, const glm::dvec3& c1, const glm::dvec3& c2, const glm::dvec3& o,
              const glm::dvec3& d, double& t, double& b1, double& b2) {
  glm::dvec3 e1 = c1 - c0, e2 = c2 - c0, pv = glm::cross(d, e2);
  double det = glm::dot(e1, pv);
  if (det == 0.0) return false;
  double inv = 1.0 / det;
  glm::dvec3 tv = o - c0;
  b1 = glm::dot(tv, pv) * inv;
  if (b1 < 0.0 || b1 > 1.0) return false;
  glm::dvec3 qv = glm::cross(tv, e1);
  b2 = glm::dot(d, qv) * inv;
  if (b2 < 0.0 || b1 + b2 > 1.0) return false;
  t = glm::dot(e2, qv) * inv;
  return true;
}

int polygon(const Primitive& p, const glm::dvec3& o, const glm::dvec3& d, double t_min, Crossing out[2]) {
  bool pseudo = p.kind == PrimitiveKind::pseudo_triangle || p.kind == PrimitiveKind::pseudo_quad;
  static const int kHalves[2][3] = {{0, 1, 2}, {0, 2, 3}};
  int halves = p.vertex_count == 4 ? 2 : 1;
  for (int h = 0; h < halves; ++h) {
    const int* k = kHalves[h];
    double t, b1, b2;
    if (!triangle(p.vertices[k[0]], p.vertices[k[1]], p.vertices[k[2]], o, d, t, b1, b2) || t <= t_min)
      continue;
    glm::dvec3 n = p.normal;
    if (pseudo) {
      n = (1.0 - b1 - b2) * p.vertex_normals[k[0]] + b1 * p.vertex_normals[k[1]] + b2 * p.vertex_normals[k[2]];
      n = glm::length(n) > 0 ? glm::normalize(n) : p.normal;
    }
    out[0] = {t, n};
    return 1;  // the halves share only the diagonal, where both give the same t
  }
  return 0;
}

// Roots of a t^2 + b t + c = 0, ascending; returns how many.
int solve_quadratic(double a, double b, double c, double r[2]) {
  double scale = std::max({std::abs(a), std::abs(b), std::abs(c)});
  if (scale == 0.0) return 0;
  if (std::abs(a) <= 1e-12 * scale) {
    if (b == 0.0) return 0;
    r[0] = -c / b;
    return 1;
  }
  double disc = b * b - 4 * a * c;
  if (disc < 0) return 0;
  double s = std::sqrt(disc);
  double q = -0.5 * (b + (b >= 0 ? s : -s));  // the stable form
  double r0 = q / a, r1 = q != 0.0 ? c / q : r0;
  r[0] = std::min(r0, r1);
  r[1] = std::max(r0, r1);
  return 2;
}

glm::dmat3 quadric_matrix(const Primitive& p) {
  const auto& a = p.coefficients;
  return glm::dmat3(a[0], a[3] / 2, a[4] / 2,  // symmetric: columns = rows
                    a[3] / 2, a[1], a[5] / 2,
                    a[4] / 2, a[5] / 2, a[2]);
}

double quadric_value(const Primitive& p, const glm::dvec3& x) {
  const auto& a = p.coefficients;
  return a[0] * x.x * x.x + a[1] * x.y * x.y + a[2] * x.z * x.z + a[3] * x.x * x.y + a[4] * x.x * x.z +
         a[5] * x.y * x.z + a[6] * x.x + a[7] * x.y + a[8] * x.z + a[9];
}

// The clip box, and a solid of revolution's slab about the box's centre.
bool in_box(const Primitive& p, const glm::dvec3& x, double pad) {
  for (int i = 0; i < 3; ++i)
    if (x[i] < p.box_min[i] - pad || x[i] > p.box_max[i] + pad) return false;
  return p.slab_half == 0 ||
         std::abs(glm::dot(x - 0.5 * (p.box_min + p.box_max), p.slab_axis)) <= p.slab_half + pad;
}

int region(const Primitive& p, const glm::dvec3& o, const glm::dvec3& d, double t_min, Crossing out[2]) {
  double r[2];
  int n;
  if (p.kind == PrimitiveKind::ellipsoid) {
    glm::dvec3 u = p.A * (o - p.centre), w = p.A * d;
    n = solve_quadratic(glm::dot(w, w), 2 * glm::dot(u, w), glm::dot(u, u) - 1.0, r);
  } else {
    glm::dmat3 m = quadric_matrix(p);
    glm::dvec3 g(p.coefficients[6], p.coefficients[7], p.coefficients[8]);
    n = solve_quadratic(glm::dot(d, m * d), 2 * glm::dot(o, m * d) + glm::dot(g, d), quadric_value(p, o), r);
  }
  double pad = 1e-9 * (1.0 + glm::length(p.box_max - p.box_min));
  int count = 0;
  for (int i = 0; i < n; ++i) {
    if (r[i] <= t_min) continue;
    glm::dvec3 x = o + r[i] * d, grad;
    if (p.kind == PrimitiveKind::ellipsoid) {
      grad = glm::transpose(p.A) * (p.A * (x - p.centre));
    } else {
      if (!in_box(p, x, pad)) continue;
      const auto& a = p.coefficients;
      grad = {2 * a[0] * x.x + a[3] * x.y + a[4] * x.z + a[6], 2 * a[1] * x.y + a[3] * x.x + a[5] * x.z + a[7],
              2 * a[2] * x.z + a[4] * x.x + a[5] * x.y + a[8]};
    }
    // A vanishing gradient (a cone's apex): face the ray.
    glm::dvec3 normal = glm::length(grad) > 0 ? glm::normalize(grad) : -d;
    out[count++] = {r[i], normal};
  }
  return count;
}

}  // namespace

int intersect(const Primitive& p, const glm::dvec3& origin, const glm::dvec3& dir, double t_min,
              Crossing out[2]) {
  return p.is_polygon() ? polygon(p, origin, dir, t_min, out) : region(p, origin, dir, t_min, out);
}

bool meets_box(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& o, const glm::dvec3& d,
               double t_max) {
  double pad = 1e-7 * (1.0 + glm::length(hi - lo));
  double t0 = -INFINITY, t1 = t_max;
  for (int i = 0; i < 3; ++i) {
    double a = (lo[i] - pad - o[i]) / d[i], b = (hi[i] + pad - o[i]) / d[i];
    if (std::isnan(a) || std::isnan(b)) continue;  // on a slab plane, parallel: undecided, keep
    t0 = std::max(t0, std::min(a, b));
    t1 = std::min(t1, std::max(a, b));
  }
  return t0 <= t1 && t1 >= 0.0;
}

namespace {

// The solid rule's band about a region's boundary (docs/scene-format.md
// "Objects", docs/renderer.md "CSG"): a point within kCsgEps of |A(x-b)|^2 = 1,
// of kCsgEps sum |a_i| of q = 0 or of kCsgEps x the sum of the box's extents
// of a box face is on the boundary, which hides neither way. The same band
// as r_inside's (CSG_EPS), wide enough for FP24's rounding of the hit point.
constexpr double kCsgEps = 0x1p-10;

double coefficient_margin(const Primitive& p) {
  double sum = 0;
  for (double a : p.coefficients) sum += std::abs(a);
  return kCsgEps * sum;
}

double box_pad(const Primitive& p) {
  glm::dvec3 e = p.box_max - p.box_min;
  return kCsgEps * (e.x + e.y + e.z);
}

}  // namespace

bool strictly_inside(const Primitive& p, const glm::dvec3& x) {
  if (p.kind == PrimitiveKind::ellipsoid) {
    glm::dvec3 u = p.A * (x - p.centre);
    return glm::dot(u, u) < 1.0 - kCsgEps;
  }
  if (p.kind != PrimitiveKind::quadric) return false;
  return in_box(p, x, -box_pad(p)) && quadric_value(p, x) < -coefficient_margin(p);
}

bool strictly_outside(const Primitive& p, const glm::dvec3& x) {
  if (p.kind == PrimitiveKind::ellipsoid) {
    glm::dvec3 u = p.A * (x - p.centre);
    return glm::dot(u, u) > 1.0 + kCsgEps;
  }
  if (p.kind != PrimitiveKind::quadric) return false;
  return !in_box(p, x, box_pad(p)) || quadric_value(p, x) > coefficient_margin(p);
}

}  // namespace mc1::refrender
