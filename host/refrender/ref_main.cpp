// mc1-ref SCENE.json [--size WxH] --out REF.png
// Renders a scene with the double-precision reference renderer.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "cmdline.hpp"
#include "refrender.hpp"

namespace {

namespace cli = mc1::cmdline;

constexpr int kMaxSide = 8192;

struct Options {
  std::string scene_path, out_path, size;
  int width = 0, height = 0;  // 0: the scene camera's
};

// "WxH", each side in [1, kMaxSide].
void parse_size(Options& o) {
  const auto x = o.size.find('x');
  if (x == std::string::npos) throw cli::UsageError("--size: expected WxH, e.g. 320x240, not '" + o.size + "'");
  o.width = static_cast<int>(cli::parse_unsigned("--size " + o.size, o.size.substr(0, x), 1, kMaxSide));
  o.height = static_cast<int>(cli::parse_unsigned("--size " + o.size, o.size.substr(x + 1), 1, kMaxSide));
}

// The file options are declared in `files` (cmdline::Files), checked after parsing.
void add_options(CLI::App& app, Options& o, cli::Files& files) {
  files.input(app.add_option("SCENE", o.scene_path, "the scene (JSON, docs/scene-format.md)")
                  ->required()
                  ->check(cli::input_file()),
              "the scene");
  app.add_option("--size", o.size, "image size instead of the camera's (each side 1 to 8192)")->type_name("WxH");
  files.output(app.add_option("--out", o.out_path, "the PNG to write")->required()->type_name("FILE"));
}

// Rows done on a terminal, at most ten times a second: "  [####....]
// 345/768 rows, 3 s elapsed, ~4 s left".
class RowProgress {
 public:
  RowProgress(bool on, int rows) : on_(on), rows_(rows) {}
  void update(int done) {
    if (!on_) return;
    const auto now = std::chrono::steady_clock::now();
    if (done != rows_ && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    drawn_ = true;
    constexpr int kWidth = 30;
    const double fraction = static_cast<double>(done) / rows_;
    const int fill = static_cast<int>(kWidth * fraction);
    std::fprintf(stderr, "\r  [%s%s] %d/%d rows, %s   ", std::string(fill, '#').c_str(),
                 std::string(kWidth - fill, '.').c_str(), done, rows_,
                 cli::progress_times(std::chrono::duration<double>(now - start_).count(), fraction).c_str());
    std::fflush(stderr);
  }
  void done() {
    if (drawn_) std::fputc('\n', stderr);
    drawn_ = false;
  }

 private:
  bool on_;
  int rows_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mc1-ref: renders a scene with the double-precision reference renderer.", "mc1-ref"};
  cli::conventions(app,
                   "Exit status: 0 done; 1 the PNG could not be written; 2 usage or input error (a missing\n"
                   "or bad scene file).");
  Options o;
  cli::Files files;
  add_options(app, o, files);
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
  mc1::scene::Scene scene;
  try {
    if (!o.size.empty()) parse_size(o);
    files.check();  // --out not the scene, and writable: before the render, not after it
    scene = mc1::scene::load_scene(o.scene_path);
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mc1-ref: %s\n", e.what());
    return cli::kExitUsage;
  }
  if (o.width == 0) {
    o.width = scene.camera.width;
    o.height = scene.camera.height;
  }
  try {
    const auto start = std::chrono::steady_clock::now();
    mc1::refrender::Renderer renderer(scene);
    RowProgress progress(isatty(fileno(stderr)), o.height);
    const auto image = renderer.render(o.width, o.height, [&progress](int rows) { progress.update(rows); });
    progress.done();
    mc1::imgcmp::write_png(o.out_path, image);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "mc1-ref: %s: %dx%d, %zu primitives, %.2f s -> %s\n", o.scene_path.c_str(), o.width,
                 o.height, scene.primitive_count(), s, o.out_path.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mc1-ref: %s\n", e.what());
    return cli::kExitFailed;
  }
  return cli::kExitOk;
}
