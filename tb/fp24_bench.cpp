// fp24-bench: operations per second of the C++ model (one core) and of each
// verilated RTL unit (one model, one op per cycle), as a table.
#include <time.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "fp24.hpp"
#include "fp24_rtl.hpp"

namespace {

using namespace mc1::fp24;
using namespace mc1::fp24::tb;

// The machine is shared, so rates are per second of this thread's CPU time,
// not wall time: a busy neighbour then does not halve the figures.
double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

constexpr const char* kUsage =
    "usage: fp24-bench [--seconds S] [--no-rtl]\n"
    "Measures the model's ops/s per op on one core and the verilated RTL's\n"
    "ops/s per unit (streaming one op per cycle through the unit's own model),\n"
    "per second of the thread's CPU time (the figures hold on a loaded machine).\n"
    "  --seconds S  minimum CPU time per measurement (default 0.5)\n"
    "  --no-rtl     model only\n";

// Operands drawn from normal numbers of moderate exponent, so every op runs
// its main path (no early-out on special values).
std::vector<Bits> operands(std::size_t n, std::uint32_t seed) {
  std::vector<Bits> v(n);
  std::uint64_t x = seed;
  for (Bits& b : v) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    const Bits e = 40 + Bits(x >> 58) % 46;  // 40..85
    b = (Bits(x >> 33) & (kSignBit | 0xFFFF)) | e << 16;
  }
  return v;
}

// The XOR of all results is printed so the compiler cannot drop the calls.
template <class F>
double rate(double seconds, std::size_t n, F&& f, Bits* sink) {
  std::uint64_t ops = 0;
  const double start = cpu_seconds();
  double elapsed = 0;
  do {
    for (std::size_t i = 0; i < n; ++i) *sink ^= f(i).value;
    ops += n;
    elapsed = cpu_seconds() - start;
  } while (elapsed < seconds);
  return double(ops) / elapsed;
}

double model_rate(Op op, const std::vector<Bits>& a, const std::vector<Bits>& b, double seconds, Bits* sink) {
  switch (op) {  // direct calls: execute()'s dispatch is not what is measured
    case Op::Add: return rate(seconds, a.size(), [&](std::size_t i) { return add(a[i], b[i]); }, sink);
    case Op::Mul: return rate(seconds, a.size(), [&](std::size_t i) { return mul(a[i], b[i]); }, sink);
    default: return rate(seconds, a.size(), [&](std::size_t i) { return execute(op, a[i], b[i]); }, sink);
  }
}

double rtl_rate(Op op, const std::vector<Bits>& a, const std::vector<Bits>& b, double seconds) {
  RtlUnit unit(info(op).unit);
  std::vector<Result> out(a.size());
  std::uint64_t ops = 0;
  const double start = cpu_seconds();
  double elapsed = 0;
  do {
    unit.run(op, a.data(), b.data(), out.data(), a.size());
    ops += a.size();
    elapsed = cpu_seconds() - start;
  } while (elapsed < seconds);
  return double(ops) / elapsed;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 0.5;
  bool rtl = true;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (arg == "--no-rtl") {
      rtl = false;
    } else if (arg == "--seconds" && i + 1 < argc) {
      char* end = nullptr;
      seconds = std::strtod(argv[++i], &end);
      if (*end != '\0' || !(seconds > 0)) {
        std::fprintf(stderr, "fp24-bench: --seconds: '%s' is not a positive number\n", argv[i]);
        return 2;
      }
    } else {
      std::fprintf(stderr, "fp24-bench: unknown argument '%s'\n%s", arg.c_str(), kUsage);
      return 2;
    }
  }
  const std::vector<Bits> a = operands(1 << 16, 1), b = operands(1 << 16, 2);
  Bits sink = 0;
  std::printf("%-6s %-10s %14s %14s   (M ops per CPU second, one thread)\n", "op", "unit", "model", "rtl");
  static const char* const kUnits[] = {"multiplier", "adder", "function"};
  for (int k = 0; k < kOpCount; ++k) {
    const Op op = static_cast<Op>(k);
    const double m = model_rate(op, a, b, seconds, &sink) / 1e6;
    char r[32] = "-";
    if (rtl) std::snprintf(r, sizeof r, "%.2f", rtl_rate(op, a, b, seconds) / 1e6);
    std::printf("%-6s %-10s %14.2f %14s\n", info(op).name.data(), kUnits[int(info(op).unit)], m, r);
    std::fflush(stdout);
  }
  std::printf("(checksum %06x)\n", sink);
  return 0;
}
