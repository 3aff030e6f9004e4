// fp24-bench: operations per second of the C++ model (one core) and of each
// verilated RTL unit (one model, one op per cycle), as a table.
#include <time.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cmdline.hpp"
#include "fp24.hpp"
#include "fp24_rtl.hpp"

namespace {

using namespace mc1::fp24;
using namespace mc1::fp24::tb;
namespace cli = mc1::cmdline;

// The machine is shared, so rates are per second of this thread's CPU time,
// not wall time: a busy neighbour then does not halve the figures.
double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

constexpr const char* kDescription =
    "fp24-bench: measures the model's ops/s per op on one core and the verilated\n"
    "RTL's ops/s per unit (streaming one op per cycle through the unit's own\n"
    "model), per second of the thread's CPU time (the figures hold on a loaded\n"
    "machine).";

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
  CLI::App app{kDescription, "fp24-bench"};
  cli::conventions(app);
  double seconds = 0.5;
  bool rtl = true;
  app.add_option("--seconds", seconds, "minimum CPU time per measurement")
      ->check(cli::real_in(1e-6, 3600))
      ->capture_default_str();
  app.add_flag("--no-rtl{false}", rtl, "model only");
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
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
  return cli::flush_stdout("fp24-bench", cli::kExitOk);  // the table is the output
}
