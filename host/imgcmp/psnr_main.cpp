// mc1-psnr A.png B.png [--diff D.png] [--scale K] [--min DB]
// Prints PSNR (dB, "inf" when identical), MSE and the largest sample
// difference; exits 1 when --min is given and the PSNR is below it.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "image.hpp"

using namespace mc1::imgcmp;

namespace {

[[noreturn]] void usage(const std::string& msg) {
  std::fprintf(stderr, "mc1-psnr: %s\nusage: mc1-psnr A.png B.png [--diff D.png] [--scale K] [--min DB]\n",
               msg.c_str());
  std::exit(2);
}

double parse_number(const std::string& opt, const char* text) {
  char* end = nullptr;
  double v = std::strtod(text, &end);
  if (end == text || *end) usage(opt + ": not a number: " + text);
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  std::string files[2], diff_path;
  int nfiles = 0, scale = 8;
  double min_db = -1;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if ((a == "--diff" || a == "--scale" || a == "--min") && i + 1 >= argc) usage(a + " needs a value");
    if (a == "--diff") diff_path = argv[++i];
    else if (a == "--scale") scale = static_cast<int>(parse_number(a, argv[++i]));
    else if (a == "--min") min_db = parse_number(a, argv[++i]);
    else if (!a.empty() && a[0] == '-') usage("unknown option " + a);
    else if (nfiles < 2) files[nfiles++] = a;
    else usage("too many files");
  }
  if (nfiles != 2) usage("two PNG files expected");
  if (scale < 1) usage("--scale must be at least 1");
  try {
    Image a = read_png(files[0]), b = read_png(files[1]);
    double p = psnr(a, b);
    if (std::isinf(p)) std::printf("PSNR inf dB  MSE 0  max diff 0\n");
    else std::printf("PSNR %.4f dB  MSE %.6f  max diff %d\n", p, mse(a, b), max_abs_diff(a, b));
    if (!diff_path.empty()) write_png(diff_path, difference(a, b, scale));
    return (min_db >= 0 && p < min_db) ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mc1-psnr: %s\n", e.what());
    return 2;
  }
}
