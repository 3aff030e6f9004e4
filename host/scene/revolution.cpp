// Solids of revolution (paper section 7): a profile of straight segments
// revolved about an axis parallel to a world axis, as one quadric frustum
// per segment (docs/scene-format.md "Solids of revolution").
#include <algorithm>
#include <cmath>

#include "scene.hpp"

namespace mc1::scene {

// Segment (r0, h0) - (r1, h1), h1 > h0, about the line through `base` along
// world axis k: the radius at height h (above base[k]) is c + s h with
// s = (r1 - r0) / (h1 - h0), c = r0 - s h0, so the cone is
//   q = (x_i - b_i)^2 + (x_j - b_j)^2 - (c + s (x_k - b_k))^2 <= 0
// (i, j the other two axes), expanded into a1..a10, and clipped to the slab
// h0 <= x_k - b_k <= h1. The box's sides lie a quarter of the largest radius
// outside the cone, so only its two slab faces cut the surface. The NC's
// form about the box's centre (Primitive::centred_linear) comes from the
// axis frame directly.
Primitive revolved_segment(int k, const glm::dvec3& base, const glm::dvec2& p0, const glm::dvec2& p1) {
  const double s = (p1.x - p0.x) / (p1.y - p0.y), c = p0.x - s * p0.y;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  Primitive p;
  p.kind = PrimitiveKind::quadric;
  auto& a = p.coefficients;
  a.fill(0.0);
  a[i] = a[j] = 1.0;  // a1, a2, a3 are x^2, y^2, z^2
  a[k] = -s * s;
  a[6 + i] = -2 * base[i];
  a[6 + j] = -2 * base[j];
  a[6 + k] = 2 * s * s * base[k] - 2 * c * s;
  a[9] = base[i] * base[i] + base[j] * base[j] - s * s * base[k] * base[k] + 2 * c * s * base[k] - c * c;
  const double side = 1.25 * std::max(p0.x, p1.x);
  p.box_min = p.box_max = base;
  p.box_min[i] -= side;
  p.box_max[i] += side;
  p.box_min[j] -= side;
  p.box_max[j] += side;
  p.box_min[k] += p0.y;
  p.box_max[k] += p1.y;
  // About the box's centre (base + hm along the axis, hm the slab's middle
  // height) the cone is y_i^2 + y_j^2 - (rm + s y_k)^2, rm = c + s hm the
  // radius there: a7..a10 exactly, with no far-away coordinate in them.
  const double rm = c + s * 0.5 * (p0.y + p1.y);
  p.centred_linear = {0.0, 0.0, 0.0, -rm * rm};
  p.centred_linear[k] = -2 * s * rm;
  return p;
}

}  // namespace mc1::scene
