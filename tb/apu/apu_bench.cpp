// apu-bench: the paper's step 1 kernel (firmware/kernels/xform4.apu, a 4x4
// transform of a vertex stream, double buffered) on the ISS and the RTL core:
// APU cycles, unit utilization, host cycles per second and the ISS/RTL speed
// ratio (docs/apu-tools.md). The results of one block are checked against
// FP24 model arithmetic first, on every engine. With the ISS, the stream's
// arithmetic alone is timed too (arithmetic_floor).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "apu_driver.hpp"
#include "apu_image.hpp"
#include "apu_lockstep.hpp"
#include "apu_profile.hpp"
#include "apu_random.hpp"
#include "apu_tools.hpp"
#include "fp24.hpp"
#include "fp24_arith_inline.hpp"

// firmware/kernels/xform4.apu, assembled at build time (tb/apu/CMakeLists.txt).
extern const unsigned char mc1_xform4_kernel_image[];
extern const unsigned long mc1_xform4_kernel_image_size;

namespace {

using namespace mc1::apu;
namespace fp = mc1::fp24;
namespace cli = mc1::cmdline;

constexpr const char* kDescription =
    "apu-bench: the xform4 vertex-transform stream (blocks of 1000 vertices; the built-in\n"
    "firmware/kernels/xform4.apu, or --kernel's .apu/.bin with its interface) on each engine through\n"
    "the MPU driver, the MPU polling every 64 cycles. Prints APU cycles, cycles per vertex, unit\n"
    "utilization and host speed; with the ISS, also the speed of the stream's FP24 arithmetic alone\n"
    "(no engine), which bounds the ISS's.";

constexpr int kVertices = 1000;  // per block (the kernel allows up to 1015)
constexpr int kCount = 0, kMatrix = 16, kVerts = 32;
constexpr double kIssTarget = 20e6, kRtlTarget = 2e6;

// FP24 values of moderate size: sign, exponent 60..66, random fraction.
std::uint32_t moderate(Rng& rng) {
  return (rng.below(2) << 23) | static_cast<std::uint32_t>(rng.range(60, 66)) << 16 | rng.below(0x10000);
}

struct Block {
  std::vector<std::uint32_t> words;  // [0, 32 + 4n)
};

Block make_block(Rng& rng, int n) {
  Block b;
  b.words.assign(kVerts + 4 * n, 0);
  b.words[kCount] = static_cast<std::uint32_t>(n);
  for (int i = 0; i < 16; ++i) b.words[kMatrix + i] = moderate(rng);
  for (int i = 0; i < 4 * n; ++i) b.words[kVerts + i] = moderate(rng);
  return b;
}

// What the kernel computes (its header): ((m0 x + m1 y) + (m2 z + m3 w)).
std::vector<std::uint32_t> reference(const Block& b) {
  const int n = static_cast<int>(b.words[kCount]);
  std::vector<std::uint32_t> out(4 * n);
  const std::uint32_t* m = &b.words[kMatrix];
  for (int i = 0; i < n; ++i) {
    const std::uint32_t* v = &b.words[kVerts + 4 * i];
    for (int r = 0; r < 4; ++r) {
      auto p = [&](int c) { return fp::mul(m[4 * r + c], v[c]).value; };
      out[4 * i + r] = fp::add(fp::add(p(0), p(1)).value, fp::add(p(2), p(3)).value).value;
    }
  }
  return out;
}

struct Stream {
  std::vector<Block> blocks;  // the last has count 0
  std::size_t next = 0;
};

// Runs a stream to its HALT; returns APU cycles. The MPU hands the next
// block over whenever the APU has taken the last, polling every 64 cycles.
std::uint64_t run_stream(ApuDriver& drv, const std::vector<Encoded>& kernel, Stream& s) {
  drv.load_program(kernel);
  drv.hand_over_program();
  auto give = [&] {
    const Block& b = s.blocks[s.next++];
    drv.load_data(0, b.words);
    drv.hand_over_data();
  };
  give();
  drv.start(0);
  const auto mpu = [&] {
    if (s.next < s.blocks.size() && !drv.data_ready()) give();
  };
  return drv.run_until_done(~0ull >> 1, mpu, 64);
}

// The blocks of a timed run of about `cycles_wanted` APU cycles (16 a vertex).
int timed_blocks(std::uint64_t cycles_wanted) {
  return static_cast<int>(std::max<std::uint64_t>(1, cycles_wanted / (16 * kVertices + 64)));
}

Stream make_stream(std::uint64_t seed, int blocks) {
  Rng rng(seed);
  Stream s;
  for (int i = 0; i < blocks; ++i) s.blocks.push_back(make_block(rng, kVertices));
  s.blocks.push_back(make_block(rng, 0));
  return s;
}

// CPU time of this thread: on a shared machine the wall clock also counts
// the time other jobs had the core.
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Result {
  std::string engine;
  std::uint64_t cycles = 0;
  double seconds = 0, cpu_seconds = 0, util[kFpUnits] = {}, mflops = 0;
  std::uint64_t vertices = 0;
  std::uint64_t stalls[kStallKinds] = {};
  bool correct = false;
};

Result bench(const std::string& name, const std::vector<Encoded>& kernel, std::uint64_t cycles_wanted) {
  Result r;
  r.engine = name;
  // 1. Correctness and profile: two blocks, every cycle recorded.
  {
    auto engine = tools::make_engine(name);
    ApuDriver drv(*engine);
    Profile prof([&drv](int bank, std::uint16_t pc) { return drv.program_word(bank, pc); });
    drv.set_observer([&](const CycleRecord& rec) { prof.add(rec); });
    Stream s = make_stream(7, 2);
    run_stream(drv, kernel, s);
    // After the end block the MPU holds the last real block, in place.
    const Block& last = s.blocks[1];
    r.correct = drv.read_results(kVerts, 4 * kVertices) == reference(last);
    for (int u = 0; u < kFpUnits; ++u) r.util[u] = prof.utilization(u);
    r.mflops = prof.mflops();
    for (int k = 0; k < kStallKinds; ++k) r.stalls[k] = prof.stalls(static_cast<Stall>(k));
  }
  // 2. Speed: the fast path, no records.
  const int blocks = timed_blocks(cycles_wanted);
  Stream s = make_stream(11, blocks);
  auto engine = tools::make_engine(name);
  ApuDriver drv(*engine);
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = thread_cpu_seconds();
  r.cycles = run_stream(drv, kernel, s);
  r.cpu_seconds = thread_cpu_seconds() - c0;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.vertices = static_cast<std::uint64_t>(blocks) * kVertices;
  return r;
}

// The timed stream's arithmetic alone: each vertex's 16 MULs and 12 ADDs
// by the FP24 model's inline ops (the ones the ISS calls), in a plain loop,
// no engine. An engine that clocked the kernel could cost no less than
// this if the arithmetic were all it did; the ISS against it shows what
// its own work adds (docs/apu-tools.md "apu-bench").
struct Floor {
  std::uint64_t vertices = 0;
  double cpu_seconds = 0;
  bool correct = false;
};

Floor arithmetic_floor(std::uint64_t cycles_wanted) {
  const Stream s = make_stream(11, timed_blocks(cycles_wanted));
  Floor f;
  std::vector<std::uint32_t> out(4 * kVertices);
  std::uint32_t flags = 0, sum = 0;
  const double c0 = thread_cpu_seconds();
  for (const Block& b : s.blocks) {
    const int n = static_cast<int>(b.words[kCount]);
    const std::uint32_t* m = &b.words[kMatrix];
    for (int i = 0; i < n; ++i) {
      const std::uint32_t* v = &b.words[kVerts + 4 * i];
      for (int r = 0; r < 4; ++r) {
        const fp::Result p0 = fp::inl::mul24(m[4 * r], v[0]), p1 = fp::inl::mul24(m[4 * r + 1], v[1]);
        const fp::Result p2 = fp::inl::mul24(m[4 * r + 2], v[2]), p3 = fp::inl::mul24(m[4 * r + 3], v[3]);
        const fp::Result s01 = fp::inl::add24(p0.value, p1.value), s23 = fp::inl::add24(p2.value, p3.value);
        const fp::Result y = fp::inl::add24(s01.value, s23.value);
        out[static_cast<std::size_t>(4 * i + r)] = y.value;
        sum += y.value;
        flags |= p0.flags | p1.flags | p2.flags | p3.flags | s01.flags | s23.flags | y.flags;
      }
    }
    f.vertices += static_cast<std::uint64_t>(n);
  }
  f.cpu_seconds = thread_cpu_seconds() - c0;
  // out holds the last real block's results (the end block has none).
  f.correct = out == reference(s.blocks[s.blocks.size() - 2]);
  static volatile std::uint32_t sink;
  sink = sink + (sum ^ flags);  // every block's results are used
  return f;
}

struct Options {
  std::string kernel_path;  // empty: the embedded xform4.apu
  std::vector<std::string> engines = {"iss", "rtl"};
  std::uint64_t iss_cycles = 40'000'000, rtl_cycles = 4'000'000;
  bool check = false;
};

void add_options(CLI::App& app, Options& o) {
  app.add_option("--kernel", o.kernel_path, "another kernel with xform4's interface (.apu or .bin)")
      ->check(cli::input_file());
  app.add_option("--engines", o.engines, "the engines to run, in order")
      ->delimiter(',')
      // Not icarus (tools::engine_names()): at about 1000 cycles a second a
      // timed run of the kernel would take hours.
      ->check(CLI::IsMember(std::vector<std::string>{"iss", "rtl"}))
      ->allow_extra_args(false)
      ->type_name("E,...")
      ->capture_default_str();
  app.add_option("--iss-cycles", o.iss_cycles, "APU cycles of the ISS's timed run")
      ->transform(cli::unsigned_in(1, UINT64_MAX >> 2))
      ->capture_default_str();
  app.add_option("--rtl-cycles", o.rtl_cycles, "APU cycles of the RTL's timed run")
      ->transform(cli::unsigned_in(1, UINT64_MAX >> 2))
      ->capture_default_str();
  app.add_flag("--check", o.check, "exit 1 if the ISS is below 20 M cycles/s or the RTL below 2 M");
}

// --kernel's program: a file that cannot be read or assembled is bad input
// (exit 2); a kernel that then faults or runs wrong is a failed run (exit 1).
std::vector<Encoded> load_kernel(const std::string& path) {
  try {
    return tools::load_program_file(path);
  } catch (const std::exception& e) {
    throw cli::UsageError(e.what());
  }
}

int run(Options o) {
  try {
    const std::vector<Encoded> kernel =
        o.kernel_path.empty()
            ? mc1::apu::parse_image(std::string(reinterpret_cast<const char*>(mc1_xform4_kernel_image),
                                              mc1_xform4_kernel_image_size),
                                  "xform4.bin (embedded)")
            : load_kernel(o.kernel_path);
    if (o.kernel_path.empty()) o.kernel_path = "xform4.apu (built in)";
    std::vector<Result> results;
    for (const auto& e : o.engines)
      results.push_back(bench(e, kernel, e == "rtl" ? o.rtl_cycles : o.iss_cycles));

    std::printf("apu-bench: %s, blocks of %d vertices, MPU polling every 64 cycles\n", o.kernel_path.c_str(),
                kVertices);
    std::printf("engine  result  APU cycles  vertices  cyc/vertex  mul%%   add%%   func%%  MFLOPS  host s   cycles/s  "
                "cpu s    cycles/cpu s\n");
    bool ok = true;
    for (const Result& r : results) {
      const double rate = r.cycles / r.seconds;
      std::printf("%-6s  %-6s  %-10llu  %-8llu  %-10.2f  %5.1f  %5.1f  %5.1f  %6.2f  %-7.3f  %-8.3g  %-7.3f  %.3g\n",
                  r.engine.c_str(), r.correct ? "ok" : "WRONG", static_cast<unsigned long long>(r.cycles),
                  static_cast<unsigned long long>(r.vertices), double(r.cycles) / r.vertices, 100 * r.util[0],
                  100 * r.util[1], 100 * r.util[2], r.mflops, r.seconds, rate, r.cpu_seconds,
                  r.cpu_seconds > 0 ? r.cycles / r.cpu_seconds : 0.0);
      const double target = r.engine == "rtl" ? kRtlTarget : kIssTarget;
      if (!r.correct) ok = false;
      if (rate < target) {
        std::printf("  %s below its target of %.0f M cycles/s\n", r.engine.c_str(), target / 1e6);
        if (o.check) ok = false;
      }
      std::printf("  stall cycles (2-block profile):");
      for (int k = 1; k < kStallKinds; ++k)
        std::printf(" %s %llu", stall_name(static_cast<Stall>(k)), static_cast<unsigned long long>(r.stalls[k]));
      std::printf("\n");
    }
    for (const Result& r : results) {
      if (r.engine != "iss") continue;
      const Floor f = arithmetic_floor(o.iss_cycles);
      const double per_vertex = double(r.cycles) / r.vertices;
      const double floor_rate = f.cpu_seconds > 0 ? f.vertices / f.cpu_seconds * per_vertex : 0.0;
      std::printf("arithmetic alone (no engine: 16 MUL, 12 ADD a vertex, the FP24 inline ops): %s, %llu vertices, "
                  "%.3f cpu s, %.3g cycles/cpu s at %.2f cycles a vertex; the ISS %.2f of it\n",
                  f.correct ? "ok" : "WRONG", static_cast<unsigned long long>(f.vertices), f.cpu_seconds, floor_rate,
                  per_vertex, r.cpu_seconds > 0 && floor_rate > 0 ? (r.cycles / r.cpu_seconds) / floor_rate : 0.0);
      if (!f.correct) ok = false;
      break;
    }
    if (results.size() == 2)
      std::printf("speed ratio %s/%s: %.1f\n", results[0].engine.c_str(), results[1].engine.c_str(),
                  (results[0].cycles / results[0].seconds) / (results[1].cycles / results[1].seconds));
    return ok ? 0 : 1;
  } catch (const cli::UsageError& ex) {
    std::cerr << "apu-bench: " << ex.what() << "\n";
    return cli::kExitUsage;
  } catch (const std::exception& ex) {  // the kernel faulted or stopped short
    std::cerr << "apu-bench: " << ex.what() << "\n";
    return cli::kExitFailed;
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{kDescription, "apu-bench"};
  cli::conventions(app, "Exit status: 0 done; 1 a wrong result or a kernel that faults (always) or, with --check,\n"
                        "an engine below its target speed; 2 usage or input error.");
  Options o;
  add_options(app, o);
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
  return cli::flush_stdout("apu-bench", run(o));  // the table is the output
}
