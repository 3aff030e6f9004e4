#include "refrender.hpp"

#include <algorithm>
#include <cmath>

#include "intersect.hpp"

namespace mc1::refrender {

using scene::Material;
using scene::Object;
using scene::ObjectKind;

Ray eye_ray(const scene::Camera& cam, int i, int j, int width, int height) {
  glm::dvec3 f = glm::normalize(cam.look_at - cam.eye);
  glm::dvec3 r = glm::normalize(glm::cross(f, cam.up));
  glm::dvec3 u = glm::cross(r, f);
  double h = std::tan(glm::radians(cam.fov_deg) / 2.0);
  double aspect = static_cast<double>(width) / height;
  double sx = (2.0 * (i + 0.5) / width - 1.0) * h * aspect;
  double sy = (1.0 - 2.0 * (j + 0.5) / height) * h;
  return {cam.eye, glm::normalize(f + sx * r + sy * u)};
}

std::uint8_t quantise(double c) {
  double v = std::floor(std::clamp(c, 0.0, 1.0) * 255.0 + 0.5);
  return static_cast<std::uint8_t>(v);
}

glm::dvec3 Renderer::surface_colour(const Material& m, const glm::dvec3& p) {
  return m.textured ? scene::checker_colour(m.checker, p) : m.colour;
}

bool Renderer::hidden_in_solid(const Object& o, int prim, const glm::dvec3& p) const {
  if (o.kind != ObjectKind::solid) return false;
  for (int k = 0; k < static_cast<int>(o.primitives.size()); ++k) {
    if (k == prim) continue;
    const auto& region = o.primitives[k];
    if (scene::hides_outside(o, k) ? strictly_outside(region, p) : strictly_inside(region, p)) return true;
  }
  return false;
}

bool Renderer::nearest_hit(const Ray& ray, Hit& hit) const {
  double best = INFINITY;
  double eps = scene_.render.epsilon;
  for (int oi = 0; oi < static_cast<int>(scene_.objects.size()); ++oi) {
    const Object& o = scene_.objects[oi];
    if (!meets_box(o.box_min, o.box_max, ray.origin, ray.dir, best)) continue;
    for (int pi = 0; pi < static_cast<int>(o.primitives.size()); ++pi) {
      Crossing c[2];
      int n = intersect(o.primitives[pi], ray.origin, ray.dir, eps, c);
      for (int k = 0; k < n && c[k].t < best; ++k) {
        glm::dvec3 p = ray.origin + c[k].t * ray.dir;
        if (hidden_in_solid(o, pi, p)) continue;
        best = c[k].t;
        hit = {c[k].t, p, scene::flips_normal(o, pi) ? -c[k].normal : c[k].normal, oi, pi};
        break;
      }
    }
  }
  return best < INFINITY;
}

bool Renderer::shadowed(const glm::dvec3& p, const scene::Light& light) const {
  glm::dvec3 to = light.position - p;
  double dist = glm::length(to);
  double eps = scene_.render.epsilon;
  if (dist <= 2 * eps) return false;
  glm::dvec3 d = to / dist;
  for (const Object& o : scene_.objects) {
    if (!meets_box(o.box_min, o.box_max, p, d, dist)) continue;
    // A union's hidden crossings count (a segment that reaches one crosses
    // the boundary first); an intersection's or difference's do not exist.
    const bool classify = o.combine != scene::Combine::union_;
    for (int pi = 0; pi < static_cast<int>(o.primitives.size()); ++pi) {
      Crossing c[2];
      int n = intersect(o.primitives[pi], p, d, eps, c);
      for (int k = 0; k < n; ++k)
        if (c[k].t < dist - eps && !(classify && hidden_in_solid(o, pi, p + c[k].t * d))) return true;
    }
  }
  return false;
}

glm::dvec3 Renderer::trace(const Ray& ray, int depth) const {
  Hit hit;
  if (!nearest_hit(ray, hit)) return scene_.render.background;
  return shade(ray, hit, depth);
}

// s3: I = ko C + kd C x sum I_l cos(theta) + km C x sum I_l cos^n(phi) over the
// unshadowed lights; s4: + ks C x S + kt C x T.
glm::dvec3 Renderer::shade(const Ray& ray, const Hit& hit, int depth) const {
  const Object& obj = scene_.objects[hit.object];
  const Material& m = scene_.materials[obj.material];
  glm::dvec3 C = surface_colour(m, hit.point);
  const glm::dvec3& D = ray.dir;
  bool front = glm::dot(D, hit.normal) < 0.0;  // the ray arrives on the normal's side
  glm::dvec3 N = front ? hit.normal : -hit.normal;
  glm::dvec3 I = m.ko * C;
  for (const auto& light : scene_.lights) {
    glm::dvec3 L = glm::normalize(light.position - hit.point);
    double cos_theta = glm::dot(N, L);
    if (cos_theta <= 0.0 || shadowed(hit.point, light)) continue;
    glm::dvec3 R = 2.0 * cos_theta * N - L;  // the light's mirror direction
    double cos_phi = std::max(0.0, glm::dot(R, -D));
    I += m.kd * C * light.intensity * cos_theta;
    I += m.km * C * light.intensity * std::pow(cos_phi, m.n);
  }
  if (depth >= scene_.render.max_depth) return I;
  glm::dvec3 reflected = D - 2.0 * glm::dot(D, N) * N;
  if (m.ks > 0.0) I += m.ks * C * trace({hit.point, glm::normalize(reflected)}, depth + 1);
  if (m.kt > 0.0) {
    glm::dvec3 T = D;  // a surface is a thin sheet: the ray goes straight on
    if (obj.kind == ObjectKind::solid) {
      double eta = front ? 1.0 / m.index : m.index;
      double cos_i = -glm::dot(D, N);
      double k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
      T = k < 0.0 ? reflected : eta * D + (eta * cos_i - std::sqrt(k)) * N;  // k < 0: total internal reflection
    }
    I += m.kt * C * trace({hit.point, glm::normalize(T)}, depth + 1);
  }
  return I;
}

glm::dvec3 Renderer::pixel(int i, int j, int width, int height) const {
  return trace(eye_ray(scene_.camera, i, j, width, height), 0);
}

imgcmp::Image Renderer::render(int width, int height) const { return render(width, height, nullptr); }

imgcmp::Image Renderer::render(int width, int height, const std::function<void(int rows)>& row_done) const {
  imgcmp::Image img(width, height);
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      glm::dvec3 c = pixel(i, j, width, height);
      std::uint8_t* px = img.at(i, j);
      for (int k = 0; k < 3; ++k) px[k] = quantise(c[k]);
    }
    if (row_done) row_done(j + 1);
  }
  return img;
}

}  // namespace mc1::refrender
