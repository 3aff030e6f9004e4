// libFuzzer: the Bezier mesh reader (docs/scene-format.md "bezier_mesh"),
// reached as a user reaches it: a scene naming the mesh file. Bad input is
// refused with SceneError naming file:line.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "scene.hpp"

namespace {

const std::string& folder() {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/mc1-fuzz-mesh-XXXXXX";
    if (!mkdtemp(tmpl)) std::abort();
    return std::string(tmpl);
  }();
  return dir;
}

const char* kScene = R"({
  "camera": {"eye": [0, 1, 8], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov": 40, "width": 8, "height": 8},
  "lights": [{"position": [5, 5, 5], "intensity": [1, 1, 1]}],
  "materials": [{"name": "m", "colour": [1, 1, 1]}],
  "objects": [{"name": "mesh", "kind": "surface", "material": "m",
               "primitives": [{"type": "bezier_mesh", "file": "mesh.txt", "level": 1}]}]
})";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream out(folder() + "/mesh.txt", std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    mc1::scene::parse_scene(kScene, folder() + "/scene.json", folder());
  } catch (const mc1::scene::SceneError&) {
  }
  return 0;
}
