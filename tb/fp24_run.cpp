// fp24-run: the FP24 vector interface of docs/fp24.md over any engine.
//   fp24-run --engine model|rtl|oracle [--trace FILE.fst] < vectors > results
// Like TestFloat's testfloat_gen | testfloat_ver, two engines are compared by
// feeding both the same vectors and diffing their outputs.
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "cmdline.hpp"
#include "fp24.hpp"
#include "fp24_oracle.hpp"
#include "fp24_rtl.hpp"
#include "fp24_vectors.hpp"

namespace {

using namespace mc1::fp24;
using namespace mc1::fp24::tb;
namespace cli = mc1::cmdline;

constexpr const char* kDescription =
    "fp24-run: the FP24 vector interface of docs/fp24.md over one engine.\n"
    "Reads FP24 vectors `OP A [B]` (hex; float's A is a 16-bit integer) from\n"
    "standard input, one per line, and writes `RESULT FLAGS` (%06x %02x) per\n"
    "vector, in order. Ops: add sub mul recip sqrt sin cos cmp float fix neg abs.\n"
    "Blank lines and lines starting with '#' are skipped and produce no output.\n"
    "All input is checked before anything is computed: a malformed line is\n"
    "reported as <stdin>:LINE: ... on standard error, with exit status 2.";

struct Options {
  std::string engine;
  std::string trace;
};

void add_options(CLI::App& app, Options& o) {
  app.add_option("--engine", o.engine,
                 "model: the bit-accurate C++ model (hw/apu); rtl: the verilated RTL\n"
                 "(apu_rtl/fp24_units.sv; the three units run concurrently, each taking\n"
                 "its ops in input order); oracle: the MPFR oracle (tb/fp24_oracle.cpp)")
      ->required()
      ->check(CLI::IsMember({"model", "rtl", "oracle"}));
  app.add_option("--trace", o.trace, "rtl only: write an FST waveform of fp24_units to FILE")->type_name("FILE");
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

// Every vector of standard input; a directory or a read error is a usage
// error, not an empty file.
std::vector<Issue> read_stdin() {
  cli::require_stdin_not_directory();
  std::vector<Issue> vectors = read_vectors(std::cin, "<stdin>");
  if (std::cin.bad()) throw cli::UsageError("<stdin>: read error");
  return vectors;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{kDescription, "fp24-run"};
  cli::conventions(app, "Exit status: 0 done; 1 an RTL timing-contract violation; 2 usage or input error.");
  Options o;
  add_options(app, o);
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
  if (!o.trace.empty() && o.engine != "rtl") return cli::usage_error(app, "--trace needs --engine rtl");
  std::ios::sync_with_stdio(false);
  std::vector<Issue> vectors;
  try {
    vectors = read_stdin();
  } catch (const VectorError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return cli::kExitUsage;
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  }
  try {
    const std::vector<Result> results = compute(o, vectors);
    std::string out;
    out.reserve(results.size() * 10);
    for (const Result& r : results) out += format_result(r) + '\n';
    std::fwrite(out.data(), 1, out.size(), stdout);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fp24-run: %s\n", e.what());
    return cli::kExitFailed;
  }
  return std::fflush(stdout) == 0 ? cli::kExitOk : cli::kExitFailed;
}
