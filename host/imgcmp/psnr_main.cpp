// mc1-psnr A.png B.png [--diff D.png] [--scale K] [--min DB]
// Prints PSNR (dB, "inf" when identical), MSE and the largest sample
// difference; exits 1 when --min is given and the PSNR is below it.
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
};

void add_options(CLI::App& app, Options& o) {
  app.add_option("FILES", o.files, "the two PNG files A.png B.png")->required()->expected(2)->check(cli::input_file());
  app.add_option("--diff", o.diff_path, "write the difference image min(255, K |a - b|) to FILE")->type_name("FILE");
  app.add_option("--scale", o.scale, "K, the difference image's gain")
      ->transform(cli::unsigned_in(1, 255))
      ->capture_default_str();
  app.add_option("--min", o.min_db, "exit 1 when the PSNR is below DB")->check(cli::real_in(0, 1000));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mc1-psnr: PSNR, MSE and the largest sample difference of two RGB8 PNG files.", "mc1-psnr"};
  cli::conventions(app,
                   "Exit status: 0 done; 1 the PSNR is below --min, or --diff could not be written;\n"
                   "2 usage or input error (a missing, unreadable or bad PNG file).");
  Options o;
  add_options(app, o);
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
  Image a, b;
  double p = 0;
  try {
    a = read_png(o.files[0]);
    b = read_png(o.files[1]);
    p = psnr(a, b);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mc1-psnr: %s\n", e.what());
    return cli::kExitUsage;
  }
  if (std::isinf(p)) std::printf("PSNR inf dB  MSE 0  max diff 0\n");
  else std::printf("PSNR %.4f dB  MSE %.6f  max diff %d\n", p, mse(a, b), max_abs_diff(a, b));
  try {
    if (!o.diff_path.empty()) write_png(o.diff_path, difference(a, b, o.scale));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mc1-psnr: %s\n", e.what());
    return cli::kExitFailed;
  }
  return app.count("--min") && p < o.min_db ? cli::kExitFailed : cli::kExitOk;
}
