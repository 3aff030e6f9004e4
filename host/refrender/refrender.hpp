// The reference renderer: the MC-1 scene and Whitted illumination model
// (paper section 4, s1-s4) by plain ray casting in double precision. It shares
// no code with the APU kernels; a co-simulated frame is compared against it.
// Every convention is in docs/scene-format.md.
#pragma once

#include <cstdint>
#include <functional>

#include <glm/glm.hpp>

#include "image.hpp"
#include "scene.hpp"

namespace mc1::refrender {

struct Ray {
  glm::dvec3 origin{0.0};
  glm::dvec3 dir{0.0, 0.0, -1.0};  // unit length: t is a distance
};

struct Hit {
  double t = 0.0;
  glm::dvec3 point{0.0};
  glm::dvec3 normal{0.0};  // unit; outward (solid) / as stored (surface), not yet turned to the ray
  int object = -1;
  int primitive = -1;
};

// Eye ray through the centre of pixel (i, j) of a width x height image.
Ray eye_ray(const scene::Camera& cam, int i, int j, int width, int height);

// clamp(c, 0, 1) * 255 rounded half up.
std::uint8_t quantise(double c);

class Renderer {
 public:
  // Keeps a reference: `s` must outlive the renderer.
  explicit Renderer(const scene::Scene& s) : scene_(s) {}

  // s1: nearest visible hit with t > epsilon (a solid hides the parts of its
  // primitives' surfaces that lie inside another of its regions).
  bool nearest_hit(const Ray& ray, Hit& hit) const;
  // s2: true when any primitive meets the open segment p -> light.
  bool shadowed(const glm::dvec3& p, const scene::Light& light) const;
  // s3 + s4: colour seen along `ray`; depth 0 is the eye ray.
  glm::dvec3 trace(const Ray& ray, int depth) const;
  // Unclamped colour of pixel (i, j).
  glm::dvec3 pixel(int i, int j, int width, int height) const;
  imgcmp::Image render(int width, int height) const;
  // The same, calling `row_done(rows)` after each row (a progress display;
  // it does not change the image).
  imgcmp::Image render(int width, int height, const std::function<void(int rows)>& row_done) const;
  imgcmp::Image render() const { return render(scene_.camera.width, scene_.camera.height); }

  // Surface colour C at p: the checker where textured.
  static glm::dvec3 surface_colour(const scene::Material& m, const glm::dvec3& p);

 private:
  const scene::Scene& scene_;

  glm::dvec3 shade(const Ray& ray, const Hit& hit, int depth) const;
  bool hidden_in_solid(const scene::Object& o, int prim, const glm::dvec3& p) const;
};

}  // namespace mc1::refrender
