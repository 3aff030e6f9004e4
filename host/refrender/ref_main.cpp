// mc1-ref SCENE.json [--size WxH] --out REF.png
// Renders a scene with the double-precision reference renderer.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "refrender.hpp"

namespace {

[[noreturn]] void usage(const std::string& msg) {
  std::fprintf(stderr, "mc1-ref: %s\nusage: mc1-ref SCENE.json [--size WxH] --out REF.png\n", msg.c_str());
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path, out_path;
  int width = 0, height = 0;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if ((a == "--size" || a == "--out") && i + 1 >= argc) usage(a + " needs a value");
    if (a == "--out") {
      out_path = argv[++i];
    } else if (a == "--size") {
      std::string s = argv[++i];
      char x = 0, extra = 0;
      if (std::sscanf(s.c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 || x != 'x' || width < 1 ||
          height < 1 || width > 8192 || height > 8192)
        usage("--size: expected WxH, e.g. 320x240, got " + s);
    } else if (!a.empty() && a[0] == '-') {
      usage("unknown option " + a);
    } else if (scene_path.empty()) {
      scene_path = a;
    } else {
      usage("more than one scene given");
    }
  }
  if (scene_path.empty()) usage("no scene given");
  if (out_path.empty()) usage("--out is required");
  try {
    mc1::scene::Scene scene = mc1::scene::load_scene(scene_path);
    if (width == 0) {
      width = scene.camera.width;
      height = scene.camera.height;
    }
    auto start = std::chrono::steady_clock::now();
    mc1::refrender::Renderer renderer(scene);
    mc1::imgcmp::write_png(out_path, renderer.render(width, height));
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "mc1-ref: %s: %dx%d, %zu primitives, %.2f s -> %s\n", scene_path.c_str(), width, height,
                 scene.primitive_count(), s, out_path.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
