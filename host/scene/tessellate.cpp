// Bicubic patches to pseudo polygons (paper section 3: free-form surfaces are
// B-spline patches interpolated into pseudo triangles/quads).
#include <algorithm>
#include <cmath>

#include "scene.hpp"

namespace mc1::scene {
namespace {

struct Basis4 {
  std::array<double, 4> b;   // weights
  std::array<double, 4> db;  // their derivatives
};

Basis4 basis_at(Basis basis, double t) {
  double s = 1.0 - t;
  if (basis == Basis::bezier)
    return {{s * s * s, 3 * t * s * s, 3 * t * t * s, t * t * t},
            {-3 * s * s, 3 * s * s - 6 * t * s, 6 * t * s - 3 * t * t, 3 * t * t}};
  // Uniform cubic B-spline span.
  return {{s * s * s / 6, (3 * t * t * t - 6 * t * t + 4) / 6,
           (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, t * t * t / 6},
          {-s * s / 2, 1.5 * t * t - 2 * t, -1.5 * t * t + t + 0.5, t * t / 2}};
}

struct PatchPoint {
  glm::dvec3 p, pu, pv;
};

PatchPoint evaluate(const BicubicNet& net, Basis basis, double u, double v) {
  Basis4 bu = basis_at(basis, u), bv = basis_at(basis, v);
  PatchPoint r{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      const glm::dvec3& c = net[4 * row + col];
      r.p += bv.b[row] * bu.b[col] * c;
      r.pu += bv.b[row] * bu.db[col] * c;
      r.pv += bv.db[row] * bu.b[col] * c;
    }
  return r;
}

double extent(const BicubicNet& net) {
  glm::dvec3 lo = net[0], hi = net[0];
  for (const auto& c : net) {
    lo = glm::min(lo, c);
    hi = glm::max(hi, c);
  }
  return std::max(glm::length(hi - lo), 1e-300);
}

// Analytic normal Pu x Pv. Where an edge of the patch collapses to a point (the
// teapot's lid and bottom) Pu x Pv vanishes; take the limit by stepping toward
// the patch centre.
glm::dvec3 patch_normal(const BicubicNet& net, Basis basis, double u, double v, double size) {
  for (double step : {0.0, 1e-5, 1e-3, 1e-2}) {
    double uu = u + (0.5 - u) * step, vv = v + (0.5 - v) * step;
    PatchPoint pp = evaluate(net, basis, uu, vv);
    glm::dvec3 n = glm::cross(pp.pu, pp.pv);
    if (glm::length(n) > 1e-10 * size * size) return glm::normalize(n);
  }
  return glm::dvec3(0.0);
}

bool degenerate_triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  glm::dvec3 e1 = b - a, e2 = c - a;
  return glm::length(glm::cross(e1, e2)) <= 1e-9 * glm::length(e1) * glm::length(e2) ||
         glm::length(e1) == 0.0 || glm::length(e2) == 0.0;
}

void emit(std::vector<glm::dvec3> pts, std::vector<glm::dvec3> nrm,
          std::vector<Primitive>& out) {
  Primitive p;
  if (pts.size() == 4) {
    bool bad012 = degenerate_triangle(pts[0], pts[1], pts[2]);
    bool bad023 = degenerate_triangle(pts[0], pts[2], pts[3]);
    if (bad012 && bad023) return;
    if (bad012 || bad023) {
      // Keep the half that has an area.
      int drop = bad012 ? 1 : 3;
      pts.erase(pts.begin() + drop);
      nrm.erase(nrm.begin() + drop);
    }
  }
  if (pts.size() == 3 && degenerate_triangle(pts[0], pts[1], pts[2])) return;
  if (pts.size() < 3) return;
  for (const auto& n : nrm)
    if (n == glm::dvec3(0.0)) return;
  p.kind = pts.size() == 4 ? PrimitiveKind::pseudo_quad : PrimitiveKind::pseudo_triangle;
  p.vertex_count = static_cast<int>(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    p.vertices[i] = pts[i];
    p.vertex_normals[i] = nrm[i];
  }
  finish_polygon(p);
  out.push_back(p);
}

}  // namespace

void tessellate_patch(const BicubicNet& net, Basis basis, int level,
                      std::vector<Primitive>& out) {
  double size = extent(net);
  double same = 1e-9 * size;
  std::vector<glm::dvec3> grid_p((level + 1) * (level + 1)), grid_n(grid_p.size());
  for (int j = 0; j <= level; ++j)
    for (int i = 0; i <= level; ++i) {
      double u = static_cast<double>(i) / level, v = static_cast<double>(j) / level;
      grid_p[j * (level + 1) + i] = evaluate(net, basis, u, v).p;
      grid_n[j * (level + 1) + i] = patch_normal(net, basis, u, v, size);
    }
  for (int j = 0; j < level; ++j)
    for (int i = 0; i < level; ++i) {
      // (u, v), (u+1, v), (u+1, v+1), (u, v+1): counter-clockwise about Pu x Pv.
      int idx[4] = {j * (level + 1) + i, j * (level + 1) + i + 1,
                    (j + 1) * (level + 1) + i + 1, (j + 1) * (level + 1) + i};
      std::vector<glm::dvec3> pts, nrm;
      for (int k : idx) {
        if (!pts.empty() && glm::length(grid_p[k] - pts.back()) <= same) continue;
        pts.push_back(grid_p[k]);
        nrm.push_back(grid_n[k]);
      }
      if (pts.size() > 1 && glm::length(pts.front() - pts.back()) <= same) {
        pts.pop_back();
        nrm.pop_back();
      }
      emit(pts, nrm, out);
    }
}

}  // namespace mc1::scene
