// fp24-run: the FP24 vector interface of docs/fp24.md over any engine.
//   fp24-run --engine model|rtl|oracle [--trace FILE.fst] < vectors > results
//   fp24-run --check FILE|- [--engine model|rtl|oracle|all]
// The first is TestFloat's testfloat_gen | testfloat_ver split in two; the
// second checks a golden file (`op a [b] result flags` lines) and reports each
// mismatch by file:line with its values decoded.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <unistd.h>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cmdline.hpp"
#include "fp24.hpp"
#include "fp24_golden.hpp"
#include "fp24_oracle.hpp"
#include "fp24_rtl.hpp"
#include "fp24_vectors.hpp"

extern const char* const kFp24UnitsGtkw;

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
    "reported as <stdin>:LINE: ... on standard error, with exit status 2.\n"
    "Flags (RESULT FLAGS's second field): NV 10 invalid, DZ 08 divide by zero,\n"
    "OF 04 overflow, UF 02 underflow, NX 01 inexact. CMP's result: LT 1, EQ 2,\n"
    "GT 4, UN 8. FIX's result: a 16-bit two's-complement integer.\n"
    "--check FILE reads a golden file instead: `OP A [B] RESULT FLAGS` lines\n"
    "(TestFloat style; any case of op, optional 0x, # comments), runs them on\n"
    "--engine (default all: model, rtl and oracle) and prints one line per\n"
    "mismatch, FILE:LINE: ENGINES: the vector, expected and got in hex, decimal\n"
    "and flag names (engines that got the same wrong result share a line); then\n"
    "a summary by op and by flag, per engine, and the mismatches: the vectors some\n"
    "engine got wrong, each counted once. fp24-conv writes values\n"
    "by hand. The oracle is correctly rounded: on SIN/COS it may differ from\n"
    "the model and RTL, which are faithful (docs/fp24.md).";

struct Options {
  std::string engine;
  std::string trace;
  std::string fst;  // the file the RTL writes --trace's waveform to: its staged temporary
  std::string check;  // a golden file, "-" for standard input
};

// The translate filters of docs/fp24-units.gtkw (docs/fp24-units.<name>.txt),
// from the model's tables: a unit's op codes on its RTL `in_op` port, and
// the five flag bits by name. Keys in upper-case hex, as GTKWave prints them.
const std::vector<std::pair<std::string, std::string>>& trace_filters() {
  static const std::vector<std::pair<std::string, std::string>> filters = [] {
    const std::string head = "# GTKWave translate filter written by fp24-run (tb/fp24_run.cpp) for ";
    auto ops = [&](Unit unit, const char* port) {
      std::string text = head + port + ": the op code in hex, then the op\n";
      for (int op = 0; op < kOpCount; ++op)
        if (info(Op(op)).unit == unit) {
          char key[8];
          std::snprintf(key, sizeof key, "%X", unsigned(info(Op(op)).rtl_code));
          text += std::string(key) + " " + std::string(info(Op(op)).name) + "\n";
        }
      return text;
    };
    std::string flags = head + "out_flags: the flags in hex, then their names (docs/fp24.md)\n";
    for (unsigned v = 0; v <= kFlagMask; ++v) {
      char key[8];
      std::snprintf(key, sizeof key, "%02X", v);
      flags += std::string(key) + " " + flag_names(std::uint8_t(v)) + "\n";
    }
    return std::vector<std::pair<std::string, std::string>>{
        {"add_op", ops(Unit::Adder, "u_add.in_op")}, {"func_op", ops(Unit::Func, "u_func.in_op")}, {"flags", flags}};
  }();
  return filters;
}

// What --trace FILE writes beside FILE: FILE.gtkw and the filters it loads.
std::vector<std::string> trace_side_suffixes() {
  std::vector<std::string> suffixes{".gtkw"};
  for (const auto& [name, text] : trace_filters()) suffixes.push_back("." + name + ".txt");
  return suffixes;
}

// The side files of --trace FILE, (path, text): the save file is
// docs/fp24-units.gtkw with FILE as its dump file and its filters' paths
// (docs/fp24-units.NAME.txt) those beside FILE, absolute.
std::vector<std::pair<std::string, std::string>> trace_side_files(const std::string& trace) {
  std::string abs = trace;
  if (abs.empty() || abs[0] != '/') {
    char buf[4096];
    if (getcwd(buf, sizeof buf)) abs = std::string(buf) + "/" + trace;
  }
  std::string save = "[*] GTKWave save file written by fp24-run --trace for " + abs + "\n[dumpfile] \"" + abs + "\"\n";
  std::istringstream lines(kFp24UnitsGtkw);
  const std::string from = "docs/fp24-units.";
  for (std::string line; std::getline(lines, line);) {
    if (line.size() > 1 && line[0] == '^' && line.find(from) != std::string::npos)
      line.replace(line.find(from), from.size(), abs + ".");
    save += line + "\n";
  }
  std::vector<std::pair<std::string, std::string>> files{{trace + ".gtkw", save}};
  for (const auto& [name, text] : trace_filters()) files.emplace_back(trace + "." + name + ".txt", text);
  return files;
}

// Every file option is declared in `files` (cmdline::Files), checked after parsing.
void add_options(CLI::App& app, Options& o, cli::Files& files) {
  app.add_option("--engine", o.engine,
                 "model: the bit-accurate C++ model (hw/apu); rtl: the verilated RTL\n"
                 "(apu_rtl/fp24_units.sv; the three units run concurrently, each taking\n"
                 "its ops in input order); oracle: the MPFR oracle (tb/fp24_oracle.cpp)")
      ->check(CLI::IsMember({"model", "rtl", "oracle", "all"}));
  files.output(app.add_option("--trace", o.trace,
                              "rtl only: write an FST waveform of fp24_units to FILE, and beside it its\n"
                              "GTKWave save file FILE.gtkw (ops and flags by name through the filters\n"
                              "FILE.add_op.txt, FILE.func_op.txt, FILE.flags.txt)")
                   ->type_name("FILE"),
               trace_side_suffixes());
  files.input(app.add_option("--check", o.check, "check the golden file FILE (- for standard input) on --engine\n"
                                     "(model, rtl, oracle or all; default all)")
      ->type_name("FILE|-"), "the golden file");
}

// The options that do not fit together, as a usage message; empty if fine.
std::string conflicts(Options& o) {
  if (o.check.empty()) {
    if (o.engine.empty()) return "--engine is required";
    if (o.engine == "all") return "--engine all needs --check";
  } else if (o.engine.empty()) {
    o.engine = "all";
  }
  if (!o.trace.empty() && o.engine != "rtl") return "--trace needs --engine rtl";
  return "";
}

std::vector<Result> compute(const Options& o, const std::string& engine, const std::vector<Issue>& vectors) {
  std::vector<Result> results;
  results.reserve(vectors.size());
  if (engine == "rtl") return RtlUnits(o.fst).run(vectors);
  if (engine == "oracle") {
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

// The golden file named by --check; bad lines throw VectorError.
std::vector<Golden> read_check_file(const std::string& path) {
  if (path == "-") {
    cli::require_stdin_not_directory();
    std::vector<Golden> g = read_golden(std::cin, "<stdin>");
    if (std::cin.bad()) throw cli::UsageError("<stdin>: read error");
    return g;
  }
  std::ifstream in(path);
  if (!in) throw cli::UsageError("--check: " + path + ": " + std::strerror(errno));
  std::vector<Golden> g = read_golden(in, path);
  if (in.bad()) throw cli::UsageError("--check: " + path + ": read error");
  return g;
}

// The mismatch lines of golden vector g: one per wrong result, naming every
// engine that gave it ("model, rtl: ..."); "" when all agree with g.
std::string mismatch_lines(const std::string& source, const Golden& g, const std::vector<std::string>& engines,
                           const std::vector<Result>& got) {
  std::string out;
  std::vector<bool> said(engines.size());
  for (std::size_t e = 0; e < engines.size(); ++e) {
    if (said[e] || got[e] == g.expected) continue;
    std::string names;
    for (std::size_t f = e; f < engines.size(); ++f) {
      if (said[f] || !(got[f] == got[e])) continue;
      said[f] = true;
      names += (names.empty() ? "" : ", ") + engines[f];
    }
    out += mismatch_line(source, g, names, got[e]) + "\n";
  }
  return out;
}

// Runs the golden vectors on each engine; prints the mismatches and the
// summary. Returns the exit status. A mismatch is a vector that some engine
// gets wrong, counted once however many engines do (docs/fp24-verification.md);
// the summary's tables count per engine.
int check(const Options& o, const std::vector<Golden>& golden) {
  const std::vector<std::string> engines =
      o.engine == "all" ? std::vector<std::string>{"model", "rtl", "oracle"} : std::vector<std::string>{o.engine};
  const std::string source = o.check == "-" ? "<stdin>" : o.check;
  std::vector<Issue> vectors;
  for (const Golden& g : golden) vectors.push_back(g.vector);
  GoldenSummary summary(engines);
  for (const Golden& g : golden) summary.checked(g.vector.op);
  std::vector<std::vector<Result>> got;  // [engine][vector]
  for (const std::string& e : engines) got.push_back(compute(o, e, vectors));
  std::string out;
  std::uint64_t mismatches = 0;
  for (std::size_t i = 0; i < golden.size(); ++i) {
    std::vector<Result> mine;
    for (std::size_t e = 0; e < engines.size(); ++e) {
      mine.push_back(got[e][i]);
      if (!(got[e][i] == golden[i].expected)) summary.mismatch(e, golden[i], got[e][i]);
    }
    const std::string lines = mismatch_lines(source, golden[i], engines, mine);
    mismatches += !lines.empty();
    out += lines;
  }
  out += summary.text();
  out += source + ": " + std::to_string(golden.size()) + " vectors, " + std::to_string(mismatches) +
         (mismatches == 1 ? " mismatch" : " mismatches") + ": " + (mismatches == 0 ? "PASS" : "FAIL") + "\n";
  std::fwrite(out.data(), 1, out.size(), stdout);
  return mismatches == 0 ? cli::kExitOk : cli::kExitFailed;
}

// The staged waveform and its side files put in place (a failure throws)
// when the run passed: a failed check leaves none of them. Returns `status`.
int commit(const Options& o, std::optional<mc1::StagedFile>& fst, int status) {
  if (!fst || status != cli::kExitOk) return status;
  std::vector<mc1::StagedFile> sides;
  for (const auto& [path, text] : trace_side_files(o.trace)) sides.emplace_back(path, text);
  fst->commit();
  for (mc1::StagedFile& f : sides) f.commit();
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{kDescription, "fp24-run"};
  cli::conventions(app, "Exit status: 0 done (--check: every vector agrees); 1 a --check mismatch or an\n"
                        "RTL timing-contract violation; 2 usage or input error.");
  Options o;
  cli::Files files;
  add_options(app, o, files);
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
  if (const std::string why = conflicts(o); !why.empty()) return cli::usage_error(app, why);
  if (o.check.empty() || o.check == "-") files.reads_stdin();
  try {
    files.check();  // no output on an input; each writable
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  }
  std::ios::sync_with_stdio(false);
  std::vector<Issue> vectors;
  std::vector<Golden> golden;
  try {
    if (o.check.empty()) vectors = read_stdin();
    else golden = read_check_file(o.check);
  } catch (const VectorError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return cli::kExitUsage;
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  }
  // The waveform is staged: the RTL writes it under a temporary name, put in
  // place once the run is over.
  std::optional<mc1::StagedFile> fst;
  try {
    if (!o.trace.empty()) fst.emplace(cli::writer_output("--trace", o.trace));
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  }
  if (fst) o.fst = fst->temp();
  try {
    // What it prints is its output: the waveform stays only if that went out too.
    if (!o.check.empty()) return commit(o, fst, cli::flush_stdout("fp24-run", check(o, golden)));
    const std::vector<Result> results = compute(o, o.engine, vectors);
    std::string out;
    out.reserve(results.size() * 10);
    for (const Result& r : results) out += format_result(r) + '\n';
    std::fwrite(out.data(), 1, out.size(), stdout);
    return commit(o, fst, cli::flush_stdout("fp24-run", cli::kExitOk));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fp24-run: %s\n", e.what());
    return cli::kExitFailed;
  }
}
