// The patch file of a "bezier mesh" object (docs/scene-format.md), e.g.
// scenes/data/utah-teapot.txt.
#include <sstream>
#include <string>
#include <vector>

#include "fp24_range.hpp"
#include "scene.hpp"

namespace mc1::scene {

// "patches N", N lines of 16 zero-based indices, "points M", M lines "x y z";
// '#' starts a comment (scenes/data/utah-teapot.txt).
namespace {
constexpr long kMaxPatches = 65535;  // the NC's primitive ids (scene_loader.cpp)
}  // namespace

std::vector<BicubicNet> read_bezier_file(std::istream& in, const std::string& file) {
  std::vector<std::array<long, 16>> idx;
  std::vector<int> idx_line;  // the line of each patch's indices
  std::vector<glm::dvec3> pts;
  std::string raw;
  int line = 0;
  std::size_t want_patches = 0, want_points = 0;
  int state = 0;  // 0: expect "patches", 1: indices, 2: expect "points", 3: points
  auto bad = [&](const std::string& msg) { throw SceneError(file + ":" + std::to_string(line) + ": " + msg); };
  while (std::getline(in, raw)) {
    ++line;
    std::string body = raw.substr(0, raw.find('#'));
    std::istringstream ls(body);
    std::string first;
    if (!(ls >> first)) continue;
    ls.seekg(0);
    if (state == 0 || state == 2) {
      std::string word;
      long n = -1;
      ls >> word >> n;
      const char* expect = state == 0 ? "patches" : "points";
      // Counts past these could not be rendered anyway (65535 primitives,
      // 16 points a patch), and would have the reader take the lines
      // after them for what they are not.
      const long most = state == 0 ? kMaxPatches : 16 * kMaxPatches;
      if (word != expect || !ls || n < 1 || n > most)
        bad(std::string("expected '") + expect + " N' with N in 1.." + std::to_string(most));
      (state == 0 ? want_patches : want_points) = static_cast<std::size_t>(n);
      state += 1;
    } else if (state == 1) {
      std::array<long, 16> a;
      for (auto& i : a)
        if (!(ls >> i) || i < 0) bad("expected 16 control-point indices");
      idx.push_back(a);
      idx_line.push_back(line);
      if (idx.size() == want_patches) state = 2;
    } else {
      glm::dvec3 p;
      if (!(ls >> p.x >> p.y >> p.z)) bad("expected 'x y z'");
      for (int i = 0; i < 3; ++i)
        if (!in_fp24_range(p[i])) bad("expected " + std::string(kFp24Range) + ", got " + shortest(p[i]));
      pts.push_back(p);
      if (pts.size() == want_points) state = 4;
    }
    if (state == 4) break;
  }
  if (state != 4) bad("file ends early");
  std::vector<BicubicNet> nets;
  for (std::size_t n = 0; n < idx.size(); ++n) {
    const auto& a = idx[n];
    BicubicNet net;
    for (int k = 0; k < 16; ++k) {
      if (static_cast<std::size_t>(a[k]) >= pts.size()) {
        line = idx_line[n];
        bad("control-point index " + std::to_string(a[k]) + " out of range (the file has " +
            std::to_string(pts.size()) + " points)");
      }
      net[k] = pts[a[k]];
    }
    nets.push_back(net);
  }
  return nets;
}

}  // namespace mc1::scene
