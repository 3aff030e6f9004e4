// Issue 39, scenes of many objects: fig. 6's shadow lists are made when a
// hit first needs them, r_slist seeing only the objects the MPU's box test
// keeps; they must equal r_slist over every (object, light, object), and the
// frame's work must grow linearly with the object count (never timed here:
// the firmware's own work counts).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "render_fw_test_util.hpp"

namespace {

using namespace mc1;
using namespace mc1::render;
using namespace mc1::render::test;

std::string vec(double x, double y, double z) {
  std::ostringstream s;
  s.precision(17);
  s << "[" << x << ", " << y << ", " << z << "]";
  return s.str();
}

std::string scene_json(const std::vector<std::string>& objects, const std::vector<std::string>& lights, int w, int h) {
  std::ostringstream s;
  s << R"({"camera": {"eye": [0, 0, 10], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 60, "width": )" << w
    << R"(, "height": )" << h << R"(}, "lights": [)";
  for (std::size_t l = 0; l < lights.size(); ++l)
    s << (l ? ", " : "") << R"({"position": )" << lights[l] << R"(, "intensity": [0.5, 0.5, 0.5]})";
  s << R"(], "materials": [{"name": "m", "colour": [0.8, 0.6, 0.4], "ko": 0.1, "kd": 0.8}], "objects": [)";
  for (std::size_t o = 0; o < objects.size(); ++o) s << (o ? ", " : "") << objects[o];
  s << "]}";
  return s.str();
}

std::string triangle_object(int k, double x, double y, double z, double s) {
  return R"({"name": "t)" + std::to_string(k) + R"(", "kind": "surface", "material": "m", "primitives": [{"type": "triangle", "vertices": [)" +
         vec(x, y, z) + ", " + vec(x + s, y, z + s / 3) + ", " + vec(x, y + s, z - s / 2) + "]}]}";
}

// tools/bench-objects.sh's scene: n one-triangle objects on a grid in z = 0.
std::string grid_scene(int n, int w, int h) {
  int k = 1;
  while (k * k < n) ++k;
  const double s = 8.0 / k;
  std::vector<std::string> objects;
  for (int i = 0; i < n; ++i) {
    const double x = -4 + (i % k) * s, y = -4 + (i / k) * s;
    objects.push_back(R"({"name": "o)" + std::to_string(i) +
                      R"(", "kind": "surface", "material": "m", "primitives": [{"type": "triangle", "vertices": [)" +
                      vec(x, y, 0) + ", " + vec(x + 0.9 * s, y, 0) + ", " + vec(x, y + 0.9 * s, 0) + "]}]}");
  }
  return scene_json(objects, {vec(0, 5, 10)}, w, h);
}

// Random scenes: triangles and spheres of all sizes, some touching others'
// boxes within a few epsilon (the pad of r_slist's test), lights among them.
TEST(RenderShadows, ListsMadeOnDemandEqualTheExhaustiveOnRandomScenes) {
  std::mt19937 rng(39);
  std::uniform_real_distribution<double> pos(-3, 3), size(0.001, 1.5), tiny(-0.01, 0.01), unit(0, 1);
  std::size_t entries = 0, pairs = 0;
  for (int round = 0; round < 12; ++round) {
    std::vector<std::string> objects;
    std::vector<std::array<double, 3>> corners;
    const int n = 20 + static_cast<int>(rng() % 40);
    for (int k = 0; k < n; ++k) {
      double x = pos(rng), y = pos(rng), z = pos(rng) - 2;
      if (!corners.empty() && unit(rng) < 0.4) {  // near another object's corner
        const auto& c = corners[rng() % corners.size()];
        x = c[0] + tiny(rng), y = c[1] + tiny(rng), z = c[2] + tiny(rng);
      }
      const double s = unit(rng) < 0.2 ? size(rng) * 0.01 : size(rng);
      if (unit(rng) < 0.25) {
        objects.push_back(R"({"name": "s)" + std::to_string(k) +
                          R"(", "kind": "solid", "material": "m", "primitives": [{"type": "sphere", "centre": )" +
                          vec(x, y, z) + R"(, "radius": )" + std::to_string(s) + "}]}");
      } else {
        objects.push_back(triangle_object(k, x, y, z, s));
      }
      corners.push_back({x + s, y + s, z + s / 3});
    }
    std::vector<std::string> lights;
    const int nl = 1 + static_cast<int>(rng() % 3);
    for (int l = 0; l < nl; ++l) {
      if (unit(rng) < 0.3) {  // a light at an object's corner
        const auto& c = corners[rng() % corners.size()];
        lights.push_back(vec(c[0] + tiny(rng), c[1] + tiny(rng), c[2] + tiny(rng)));
      } else {
        lights.push_back(vec(pos(rng) * 2, pos(rng) * 2, pos(rng) * 2 + 4));
      }
    }
    const scene::Scene sc = scene::parse_scene(scene_json(objects, lights, 32, 24), "random.json", ".");
    Rig rig;
    rig.fw.load_scene(make_scene_image(sc));
    const std::vector<std::vector<int>> all = rig.fw.exhaustive_shadow_lists();
    const int nobj = static_cast<int>(rig.fw.view().objects.size());
    for (int o = 0; o < nobj; ++o)
      for (int l = 0; l < nl; ++l) {
        EXPECT_EQ(rig.fw.shadow_list(o, l), all[static_cast<std::size_t>(o) * nl + l])
            << "round " << round << " object " << o << " light " << l;
        entries += all[static_cast<std::size_t>(o) * nl + l].size();
        ++pairs;
      }
  }
  std::printf("shadow lists: %zu entries in %zu lists\n", entries, pairs);
  EXPECT_GT(entries, pairs);  // not trivially empty
}

struct Work {
  std::uint64_t slist_cycles = 0, shadow_list_elements = 0, total_apu_cycles = 0;
};

Work frame_work(int n) {
  const scene::Scene sc = scene::parse_scene(grid_scene(n, 32, 24), "grid.json", ".");
  Rig rig;
  rig.fw.load_scene(make_scene_image(sc));
  render_frame(rig.fw, 32, 24);
  Work w;
  const RenderStats& st = rig.fw.stats();
  const auto it = st.kernels.find("r_slist");
  if (it != st.kernels.end()) w.slist_cycles = it->second.apu_cycles;
  w.shadow_list_elements = st.step[static_cast<int>(Step::Shadows)].list_elements;
  w.total_apu_cycles = st.total().apu_cycles;
  return w;
}

// N one-triangle objects at 32x24: four times the objects, at most about
// four times the work (was 16 times: r_slist over N^2 pairs). A shadow list
// is made per object hit, each of O(N) objects here (the light's box over
// the grid): from 1000 objects on, about one object per pixel, the objects
// hit no longer grow with N (below that they do, and so does the work).
TEST(RenderShadows, ManyObjectsFrameWorkGrowsLinearly) {
  const Work a = frame_work(1000), b = frame_work(4000);
  std::printf("r_slist cycles %llu -> %llu, s2 list elements %llu -> %llu, APU cycles %llu -> %llu\n",
              static_cast<unsigned long long>(a.slist_cycles), static_cast<unsigned long long>(b.slist_cycles),
              static_cast<unsigned long long>(a.shadow_list_elements),
              static_cast<unsigned long long>(b.shadow_list_elements),
              static_cast<unsigned long long>(a.total_apu_cycles), static_cast<unsigned long long>(b.total_apu_cycles));
  ASSERT_GT(a.slist_cycles, 0u);
  EXPECT_LT(b.slist_cycles, 6 * a.slist_cycles);
  EXPECT_LT(b.shadow_list_elements, 6 * a.shadow_list_elements);
  EXPECT_LT(b.total_apu_cycles, 6 * a.total_apu_cycles);
}

}  // namespace
