// Code coverage of the verilated models (docs/fp24-verification.md
// "Coverage"). In a build configured with -DMC1_RTL_COVERAGE=ON every
// verilate() call adds Verilator's line, branch and toggle coverage
// (apu_rtl/CMakeLists.txt), and each model counts in its VerilatedContext.
// A program run with MC1_COVERAGE_DAT=FILE adds the counts of a context to
// the process's total with collect(), called while the context's models are
// still alive (they own the counters), and writes the total when it exits
// to FILE, "%p" in its name replaced by the process id, in Verilator's
// coverage format (verilator_coverage reads and merges it; tools/coverage.py).
// In any other build, or without the variable, collect() does nothing.
#pragma once

#include "verilated.h"

#if MC1_RTL_COVERAGE
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include "verilated_cov.h"
#endif

namespace mc1::rtl_coverage {

#if MC1_RTL_COVERAGE
namespace detail {

// The process's total: coverage point (Verilator's key) -> count.
class Totals {
 public:
  static Totals& get() {
    static Totals totals;
    return totals;
  }
  bool on() const { return !path_.empty(); }

  void add(VerilatedContext& ctx) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const std::string tmp = path_ + ".part" + std::to_string(parts_++);
    ctx.coveragep()->write(tmp.c_str());
    std::ifstream in(tmp);
    std::string line;
    while (std::getline(in, line)) {
      // C '<key>' <count>
      const auto end = line.rfind("' ");
      if (line.compare(0, 3, "C '") != 0 || end == std::string::npos || end < 3) continue;
      counts_[line.substr(3, end - 3)] += std::strtoull(line.c_str() + end + 2, nullptr, 10);
    }
    in.close();
    std::remove(tmp.c_str());
  }

  ~Totals() {
    if (!on() || counts_.empty()) return;
    const std::string tmp = path_ + ".tmp";
    {
      std::ofstream out(tmp);
      out << "# SystemC::Coverage-3\n";
      for (const auto& [key, n] : counts_) out << "C '" << key << "' " << n << "\n";
      if (!out) {
        std::fprintf(stderr, "rtl_coverage: cannot write %s\n", tmp.c_str());
        return;
      }
    }
    std::rename(tmp.c_str(), path_.c_str());
  }

 private:
  Totals() {
    const char* env = std::getenv("MC1_COVERAGE_DAT");
    if (!env || !*env) return;
    path_ = env;
    const auto p = path_.find("%p");
    if (p != std::string::npos) path_.replace(p, 2, std::to_string(::getpid()));
  }

  std::mutex mutex_;
  std::string path_;
  unsigned parts_ = 0;
  std::map<std::string, unsigned long long> counts_;
};

}  // namespace detail
#endif

// Whether this build counts coverage (MC1_RTL_COVERAGE=ON).
constexpr bool kBuilt = MC1_RTL_COVERAGE != 0;

// Adds the counts of ctx's models to the process's total (see above).
inline void collect(VerilatedContext& ctx) {
#if MC1_RTL_COVERAGE
  auto& totals = detail::Totals::get();
  if (totals.on()) totals.add(ctx);
#else
  (void)ctx;
#endif
}

}  // namespace mc1::rtl_coverage
