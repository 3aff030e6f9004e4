// Ray-primitive intersection for the reference renderer.
#pragma once

#include <glm/glm.hpp>

#include "scene.hpp"

namespace mc1::refrender {

struct Crossing {
  double t;
  glm::dvec3 normal;  // unit, outward / as stored
};

// All crossings of the line origin + t dir (t > t_min) with the primitive's
// surface, nearest first; returns how many (0..2).
int intersect(const scene::Primitive& p, const glm::dvec3& origin, const glm::dvec3& dir,
              double t_min, Crossing out[2]);

// True when the ray may meet the box before t_max (conservative).
bool meets_box(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& origin,
               const glm::dvec3& dir, double t_max);

// Strictly inside the primitive's region (ellipsoid or boxed quadric).
bool strictly_inside(const scene::Primitive& p, const glm::dvec3& x);
// Strictly outside it: beyond the same margins on the other side.
bool strictly_outside(const scene::Primitive& p, const glm::dvec3& x);

}  // namespace mc1::refrender
