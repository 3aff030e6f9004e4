// Solids of revolution (paper section 7): a profile of straight segments
// revolved about an axis of any direction, as one quadric frustum per
// segment (docs/scene-format.md "Solids of revolution").
#include <algorithm>
#include <cmath>

#include "scene.hpp"

namespace mc1::scene {

// Segment (r0, h0) - (r1, h1), h1 > h0, about the line through `base` along
// the unit vector `a`: the radius at height H = (x - base).a is c + s H with
// s = (r1 - r0) / (h1 - h0), c = r0 - s h0, so the cone is
//   q = |x - base|^2 - H^2 - (c + s H)^2 <= 0,
// a quadratic form with the matrix M = I - (1 + s^2) a a^T, expanded into
// a1..a10 (for an axis along a world axis the cross terms are 0 and the
// form is the axis-frame one). The segment is the slab h0 <= H <= h1
// (slab_axis, slab_half about the box's centre, which lies on the axis at
// the slab's middle height); the box bounds the slab's cylinder of a
// quarter more than the largest radius, so its sides never meet the
// surface and for a world axis its end faces are the slab's. The NC's form
// about the box's centre (Primitive::centred_linear) comes from the axis
// frame directly.
Primitive revolved_segment(const glm::dvec3& a, const glm::dvec3& base, const glm::dvec2& p0, const glm::dvec2& p1) {
  const double s = (p1.x - p0.x) / (p1.y - p0.y), c = p0.x - s * p0.y, k = 1 + s * s;
  Primitive p;
  p.kind = PrimitiveKind::quadric;
  glm::dmat3 m(1.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[j][i] -= k * a[i] * a[j];
  // q(x) = (x - b)^T M (x - b) - 2 c s a.(x - b) - c^2.
  const glm::dvec3 g = -2 * c * s * a, mb = m * base, lin = -2.0 * mb + g;
  auto& q = p.coefficients;
  q = {m[0][0], m[1][1], m[2][2], 2 * m[1][0], 2 * m[2][0], 2 * m[2][1], lin.x, lin.y, lin.z,
       glm::dot(base, mb) - glm::dot(g, base) - c * c};
  const double side = 1.25 * std::max(p0.x, p1.x);
  const glm::dvec3 e0 = base + p0.y * a, e1 = base + p1.y * a;
  for (int i = 0; i < 3; ++i) {
    const double across = side * std::sqrt(std::max(0.0, 1 - a[i] * a[i]));
    p.box_min[i] = std::min(e0[i], e1[i]) - across;
    p.box_max[i] = std::max(e0[i], e1[i]) + across;
  }
  p.slab_axis = a;
  p.slab_half = 0.5 * (p1.y - p0.y);
  // About the box's centre m (on the axis at height hm) the cone is
  // |y|^2 - (y.a)^2 - (rm + s y.a)^2, rm = c + s hm the radius there.
  const glm::dvec3 centre = 0.5 * (p.box_min + p.box_max);
  const double rm = c + s * glm::dot(centre - base, a);
  p.centred_linear = {-2 * s * rm * a.x, -2 * s * rm * a.y, -2 * s * rm * a.z, -rm * rm};
  for (double& v : q) v += 0.0;  // no -0 (the FP24 words of an axis-frame form)
  for (double& v : p.centred_linear) v += 0.0;
  return p;
}

}  // namespace mc1::scene
