// mc1-psnr A.png B.png [--diff D.png] [--scale K] [--min DB] [--threshold T] [--max-cluster N]
// Prints PSNR (dB, "inf" when identical), MSE and the largest sample
// difference, then the defects: 8-connected clusters of pixels with a channel
// error above T, how many, the largest's size and bounding box. Exits 1 when
// the PSNR is below --min or the largest cluster is over --max-cluster.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cmdline.hpp"
#include "image.hpp"

namespace {

using namespace mc1::imgcmp;
namespace cli = mc1::cmdline;

struct Options {
  std::vector<std::string> files;
  std::string diff_path;
  int scale = 8;
  double min_db = 0;
  int threshold = 32;
  int max_cluster = 0;
};

// The file options are declared in `files` (cmdline::Files), checked after parsing.
void add_options(CLI::App& app, Options& o, cli::Files& files) {
  files.input(app.add_option("FILES", o.files, "the two PNG files A.png B.png")
                  ->required()
                  ->expected(2)
                  ->check(cli::input_file()),
              "the image");
  files.output(app.add_option("--diff", o.diff_path, "write the difference image min(255, K |a - b|) to FILE")
                   ->type_name("FILE"));
  app.add_option("--scale", o.scale, "K, the difference image's gain")
      ->transform(cli::unsigned_in(1, 255))
      ->capture_default_str();
  app.add_option("--min", o.min_db, "exit 1 when the PSNR is below DB")->check(cli::real_in(0, 1000));
  app.add_option("--threshold", o.threshold, "T: a pixel is wrong when a channel differs by more than T")
      ->transform(cli::unsigned_in(0, 254))
      ->capture_default_str();
  app.add_option("--max-cluster", o.max_cluster, "exit 1 when a cluster of wrong pixels is larger than N")
      ->type_name("N")
      ->transform(cli::unsigned_in(0, 100000000));
}

void print_defects(const Defects& d, int threshold) {
  std::printf("clusters %zu (error > %d: %d pixels)", d.clusters.size(), threshold, d.wrong_pixels);
  if (!d.clusters.empty()) {
    const Cluster& c = d.clusters.front();
    std::printf("  largest %d px at x %d..%d y %d..%d", c.pixels, c.x0, c.x1, c.y0, c.y1);
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mc1-psnr: PSNR, MSE, the largest sample difference and the clusters of wrong pixels of two RGB8 PNG files.", "mc1-psnr"};
  cli::conventions(app,
                   "Exit status: 0 done; 1 the PSNR is below --min, a cluster is over --max-cluster, or --diff\n"
                   "could not be written;\n"
                   "2 usage or input error (a missing, unreadable or bad PNG file).");
  Options o;
  cli::Files files;
  add_options(app, o, files);
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
  try {
    files.check();
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  }
  Image a, b;
  double p = 0;
  Defects d;
  try {
    a = read_png(o.files[0]);
    b = read_png(o.files[1]);
    p = psnr(a, b);
    d = defects(a, b, o.threshold);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mc1-psnr: %s\n", e.what());
    return cli::kExitUsage;
  }
  if (std::isinf(p)) std::printf("PSNR inf dB  MSE 0  max diff 0\n");
  else std::printf("PSNR %.4f dB  MSE %.6f  max diff %d\n", p, mse(a, b), max_abs_diff(a, b));
  print_defects(d, o.threshold);
  try {
    if (!o.diff_path.empty()) write_png(o.diff_path, difference(a, b, o.scale));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mc1-psnr: %s\n", e.what());
    return cli::kExitFailed;
  }
  const int largest = d.clusters.empty() ? 0 : d.clusters.front().pixels;
  const bool failed = (app.count("--min") && p < o.min_db) || (app.count("--max-cluster") && largest > o.max_cluster);
  return cli::flush_stdout("mc1-psnr", failed ? cli::kExitFailed : cli::kExitOk);
}
