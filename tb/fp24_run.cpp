// fp24-run: the FP24 vector interface of docs/fp24.md over any engine.
//   fp24-run --engine model|rtl|oracle [--trace FILE.fst] < vectors > results
// Like TestFloat's testfloat_gen | testfloat_ver, two engines are compared by
// feeding both the same vectors and diffing their outputs.
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "fp24.hpp"
#include "fp24_oracle.hpp"
#include "fp24_rtl.hpp"
#include "fp24_vectors.hpp"

namespace {

using namespace mc1::fp24;
using namespace mc1::fp24::tb;

constexpr const char* kUsage =
    "usage: fp24-run --engine model|rtl|oracle [--trace FILE.fst]\n"
    "\n"
    "Reads FP24 vectors `OP A [B]` (hex; float's A is a 16-bit integer) from\n"
    "standard input, one per line, and writes `RESULT FLAGS` (%06x %02x) per\n"
    "vector, in order. Ops: add sub mul recip sqrt sin cos cmp float fix neg abs.\n"
    "Blank lines and lines starting with '#' are skipped and produce no output.\n"
    "All input is checked before anything is computed: a malformed line is\n"
    "reported as <stdin>:LINE: ... on standard error, with exit status 2.\n"
    "\n"
    "  --engine model   the bit-accurate C++ model (hw/apu)\n"
    "  --engine rtl     the verilated RTL (apu_rtl/fp24_units.sv); the three units\n"
    "                   run concurrently, each taking its ops in input order\n"
    "  --engine oracle  the MPFR oracle (tb/fp24_oracle.cpp)\n"
    "  --trace FILE     rtl only: write an FST waveform of fp24_units to FILE\n"
    "  --help           this text\n";

struct Options {
  std::string engine;
  std::string trace;
};

[[noreturn]] void usage_error(const std::string& what) {
  std::fprintf(stderr, "fp24-run: %s\n%s", what.c_str(), kUsage);
  std::exit(2);
}

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error("option " + arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (arg == "--engine") {
      o.engine = value();
    } else if (arg == "--trace") {
      o.trace = value();
    } else {
      usage_error("unknown argument '" + arg + "'");
    }
  }
  if (o.engine != "model" && o.engine != "rtl" && o.engine != "oracle")
    usage_error(o.engine.empty() ? "--engine is required" : "unknown engine '" + o.engine + "'");
  if (!o.trace.empty() && o.engine != "rtl") usage_error("--trace needs --engine rtl");
  return o;
}

std::vector<Result> compute(const Options& o, const std::vector<Issue>& vectors) {
  std::vector<Result> results;
  results.reserve(vectors.size());
  if (o.engine == "rtl") return RtlUnits(o.trace).run(vectors);
  if (o.engine == "oracle") {
    Oracle oracle;
    for (const Issue& v : vectors) results.push_back(oracle.run(v.op, v.a, v.b));
  } else {
    for (const Issue& v : vectors) results.push_back(execute(v.op, v.a, v.b));
  }
  return results;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  std::ios::sync_with_stdio(false);
  std::vector<Issue> vectors;
  try {
    vectors = read_vectors(std::cin, "<stdin>");
  } catch (const VectorError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  try {
    const std::vector<Result> results = compute(o, vectors);
    std::string out;
    out.reserve(results.size() * 10);
    for (const Result& r : results) out += format_result(r) + '\n';
    std::fwrite(out.data(), 1, out.size(), stdout);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fp24-run: %s\n", e.what());
    return 1;
  }
  return std::fflush(stdout) == 0 ? 0 : 1;
}
