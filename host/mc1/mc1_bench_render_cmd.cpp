// mc1 bench-render: the speed of the rendered frame, simulated and on the
// host, against the reference renderer (docs/platform.md "Rendering
// benchmark").
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <sstream>

#include "apu_pool.hpp"
#include "cmdline.hpp"
#include "host_clock.hpp"
#include "image.hpp"
#include "json.hpp"
#include "mc1_cli.hpp"
#include "mc1_render.hpp"
#include "mc1_render_cmd.hpp"
#include "refrender.hpp"
#include "report_writers.hpp"
#include "scene.hpp"

namespace mc1::cli {

const char* const kBenchRenderDescription =
    "speed of the rendered frame: speedup, efficiency, lpt against static\n\n"
    "The rendering benchmark (docs/platform.md \"Rendering benchmark\"), on the Whitted scene:\n"
    "  1. --size (256x256) on each of --nodes (1,4,16,64) NCs, lpt: simulated frame time,\n"
    "     speedup over 1 NC, APU utilization, host seconds;\n"
    "  2. the same size on --static-nodes (16) NCs with the static split: lpt's gain;\n"
    "  3. --big (512x512) on 1 and --big-nodes (64) NCs, lpt and static: parallel efficiency\n"
    "     T1 / (N TN), the serial download's share, lpt's gain over static;\n"
    "  4. with --rtl: --size on --static-nodes NCs on the RTL engine, and with the RTL core on NC 1\n"
    "     only (--rtl-nodes 1; host times).\n"
    "Then the double-precision reference renderer (mc1-ref) on the same scene and size: the\n"
    "co-simulation's host time on --static-nodes NCs over the reference's, and with --rtl the RTL\n"
    "engine's over the ISS's, in wall-clock and in CPU time (the process's, every thread's), each\n"
    "the best of --repeat runs; under each, the frame's runs (best, worst, median), and a note if\n"
    "the host's load moved them by over 20 %. Every run's frame must equal the first run's of its\n"
    "size bit for bit.";

void add_bench_render_options(CLI::App& cmd) {
  files(cmd).input(value_option(cmd, "scene", "FILE", "(default: " + default_scene() + ")"), "the scene",
                   default_scene());
  value_option(cmd, "size", "WxH", "(default 256x256)");
  value_option(cmd, "nodes", "LIST", "(default 1,4,16,64)");
  value_option(cmd, "static-nodes", "N", "(default 16)");
  value_option(cmd, "block", "B", "(default 16)");
  value_option(cmd, "big", "WxH|0", "(default 512x512; 0 skips part 3)");
  value_option(cmd, "big-nodes", "N", "(default 64)");
  flag_option(cmd, "rtl", "also run part 4");
  value_option(cmd, "repeat", "N",
               "host times of the compared frames (the ISS's on --static-nodes NCs, the RTL engine's, the "
               "reference's): the best of N runs each (the reference's of at least 3), 1..100 (default 3; a shared "
               "host's load only ever adds)");
  add_threads_option(cmd);
  add_param_options(cmd);
  files(cmd).output(value_option(cmd, "json", "FILE", "also write the figures as JSON"));
}

namespace {

struct BenchRun {
  std::string label;
  unsigned nodes = 0, width = 0, height = 0;
  rc::Schedule schedule = rc::Schedule::Lpt;
  EngineKind engine = EngineKind::Iss;
  std::vector<unsigned> rtl_nodes;  // on the RTL engine beside `engine` (--rtl-nodes)
  FrameReport r;
};

// The host times of one frame's runs: the best is the figure compared (the
// least disturbed by other load); the median and the worst show how far
// the host's load moved the runs.
struct HostTimes {
  double best = 0, median = 0, worst = 0;
  unsigned runs = 0;

  explicit HostTimes(std::vector<double> t) : runs(static_cast<unsigned>(t.size())) {
    if (t.empty()) return;
    std::sort(t.begin(), t.end());
    best = t.front();
    worst = t.back();
    const std::size_t m = t.size() / 2;
    median = t.size() % 2 ? t[m] : (t[m - 1] + t[m]) / 2;
  }
  HostTimes() = default;
  // The worst run over the best, less one (0.2: the worst took 20 % longer);
  // 0 for frames under 20 ms, which vary more with caches and start-up than
  // with the host's load.
  double spread() const { return best >= 0.02 ? worst / best - 1 : 0; }
};

// The double-precision reference renderer's host times for the frame,
// `runs` of them (at least three: it is short).
// A frame's runs in wall-clock time and in the process's CPU time.
struct HostRuns {
  HostTimes wall, cpu;
  HostRuns() = default;
  HostRuns(std::vector<double> w, std::vector<double> c) : wall(std::move(w)), cpu(std::move(c)) {}
};

HostRuns reference_host_times(const std::string& scene, std::pair<unsigned, unsigned> size, unsigned runs) {
  const scene::Scene sc = scene::load_scene(scene);
  const refrender::Renderer ref(sc);
  std::vector<double> wall, cpu;
  for (unsigned i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = process_cpu_seconds();
    const imgcmp::Image img = ref.render(static_cast<int>(size.first), static_cast<int>(size.second));
    cpu.push_back(process_cpu_seconds() - c0);
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (img.width != static_cast<int>(size.first)) throw std::runtime_error("reference renderer: wrong size");
  }
  return HostRuns(std::move(wall), std::move(cpu));
}

void runs_json(std::ostream& json, const std::vector<BenchRun>& runs) {
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const BenchRun& b = runs[i];
    json << (i ? ", " : "") << "{\"label\": \"" << b.label << "\", \"nodes\": " << b.nodes << ", \"width\": " << b.width
         << ", \"height\": " << b.height << ", \"schedule\": \"" << rc::schedule_name(b.schedule)
         << "\", \"engine\": \"" << engine_name(b.engine) << "\", \"rtl_nodes\": [";
    for (std::size_t k = 0; k < b.rtl_nodes.size(); ++k) json << (k ? ", " : "") << b.rtl_nodes[k];
    json << "], \"simulated_time_s\": " << b.r.frame_time * 1e-12
         << ", \"host_seconds\": " << b.r.host_seconds << ", \"host_cpu_seconds\": " << b.r.host_cpu_seconds
         << ", \"apu_utilization\": " << apu_utilization_mean(b.r)
         << ", \"download_done_s\": " << milestone_time(b.r, "downloaded") * 1e-12 << "}";
  }
}

struct BenchOptions {
  std::string scene;
  std::pair<unsigned, unsigned> size, big;  // big {0, 0}: no efficiency runs
  std::vector<unsigned> nodes;
  unsigned static_nodes = 0, big_nodes = 0;
  unsigned repeat = 3;  // runs of each compared frame; its host time is their best
  bool rtl = false;
};

BenchOptions bench_options(const Parsed& a, SystemConfig& base) {
  BenchOptions o;
  o.scene = a.get("scene", default_scene());
  o.size = parse_size("--size", a.get("size", "256x256"), false);
  o.nodes = parse_list("--nodes", a.get("nodes", "1,4,16,64"), 1, 4096);
  o.static_nodes = parse_unsigned("--static-nodes", a.get("static-nodes", "16"), 1, 4096);
  if (a.has("block")) std::tie(base.block_w, base.block_h) = parse_size("--block", a.get("block"), true);
  const std::string big_text = a.get("big", "512x512");
  o.big = big_text == "0" ? std::pair<unsigned, unsigned>{0, 0} : parse_size("--big", big_text, false);
  o.big_nodes = parse_unsigned("--big-nodes", a.get("big-nodes", "64"), 1, 4096);
  o.rtl = a.has("rtl");
  o.repeat = parse_unsigned("--repeat", a.get("repeat", "3"), 1, 100);
  return o;
}

// The benchmark's frames, a table line each, and whether the frames of one
// size are the same in every run.
class BenchRuns {
 public:
  BenchRuns(const SystemConfig& base, std::string scene) : base_(base), scene_(std::move(scene)) {
    std::printf("%-26s %5s %9s %7s %13s %9s %9s %9s %9s %8s\n", "run", "NCs", "size", "sched", "simulated",
                "APU util", "download", "host", "CPU", "frame");
  }

  const FrameReport& run(const std::string& label, unsigned n, std::pair<unsigned, unsigned> wh, rc::Schedule s,
                         EngineKind e, const std::vector<unsigned>& rtl_nodes = {}) {
    if (!runs_.empty()) fresh_systemc_kernel();
    SystemConfig cfg = base_;
    cfg.nodes = n;
    cfg.schedule = s;
    cfg.engine = e;
    cfg.rtl_nodes = rtl_nodes;
    BenchRun b{label, n,         wh.first, wh.second, s,
               e,     rtl_nodes, run_render(RenderJob{scene_, wh.first, wh.second}, cfg).report};
    auto it = first_image_.find(wh);
    bool ok = true;
    if (it == first_image_.end())
      first_image_[wh] = b.r.rgb;
    else
      ok = it->second == b.r.rgb;
    same_ = same_ && ok;
    const Picos T = b.r.frame_time;
    std::printf("%-26s %5u %4ux%-4u %7s %10.3f ms %9s %9s %7.2f s %7.2f s %8s\n", label.c_str(), n, wh.first,
                wh.second, rc::schedule_name(s), T * 1e-9, pct(apu_utilization_mean(b.r)).c_str(),
                pct(T ? static_cast<double>(milestone_time(b.r, "downloaded")) / T : 0).c_str(), b.r.host_seconds,
                b.r.host_cpu_seconds, ok ? "same" : "DIFFERS");
    if (!b.r.timeouts.empty())
      std::printf("  (%zu deadlines missed: the timing table's rc_timeout_* figures are too short here)\n",
                  b.r.timeouts.size());
    std::fflush(stdout);
    runs_.push_back(std::move(b));
    return runs_.back().r;
  }

  const std::vector<BenchRun>& runs() const { return runs_; }
  bool same() const { return same_; }

 private:
  const SystemConfig& base_;
  std::string scene_;
  std::vector<BenchRun> runs_;
  std::map<std::pair<unsigned, unsigned>, std::vector<std::uint8_t>> first_image_;
  bool same_ = true;
};

// The figures the benchmark reports, from its runs.
struct BenchTimes {
  std::map<unsigned, Picos> t_size;  // --size, lpt, per node count
  Picos lpt_ref = 0, static_ref = 0;  // --size on --static-nodes
  Picos big1 = 0, bign = 0, bigs = 0, big_dl = 0;  // --big on 1 and --big-nodes NCs, static; the download
  HostRuns rtl, iss, ref;
  HostRuns rtl1;  // the RTL core on NC 1 only, the ISS on the others
};

// The host times of --repeat runs of --size on --static-nodes NCs (lpt) on
// `engine` (and the RTL engine on `rtl_nodes`): the benchmark's runs of that
// frame so far, and as many more as it takes.
HostRuns host_times(BenchRuns& b, const BenchOptions& o, EngineKind engine, const std::string& label,
                    const std::vector<unsigned>& rtl_nodes = {}) {
  std::vector<double> wall, cpu;
  const auto add = [&](const FrameReport& r) {
    wall.push_back(r.host_seconds);
    cpu.push_back(r.host_cpu_seconds);
  };
  for (const BenchRun& r : b.runs())
    if (r.engine == engine && r.rtl_nodes == rtl_nodes && r.nodes == o.static_nodes &&
        r.schedule == rc::Schedule::Lpt && r.width == o.size.first && r.height == o.size.second)
      add(r.r);
  while (wall.size() < o.repeat) add(b.run(label, o.static_nodes, o.size, rc::Schedule::Lpt, engine, rtl_nodes));
  return HostRuns(std::move(wall), std::move(cpu));
}

BenchTimes run_bench(BenchRuns& b, const BenchOptions& o) {
  BenchTimes t;
  for (unsigned n : o.nodes) t.t_size[n] = b.run("speedup", n, o.size, rc::Schedule::Lpt, EngineKind::Iss).frame_time;
  t.lpt_ref = t.t_size.count(o.static_nodes)
                  ? t.t_size[o.static_nodes]
                  : b.run("lpt", o.static_nodes, o.size, rc::Schedule::Lpt, EngineKind::Iss).frame_time;
  t.static_ref = b.run("static split", o.static_nodes, o.size, rc::Schedule::Static, EngineKind::Iss).frame_time;
  if (o.big.first) {
    t.big1 = b.run("efficiency, 1 NC", 1, o.big, rc::Schedule::Lpt, EngineKind::Iss).frame_time;
    const FrameReport& r = b.run("efficiency", o.big_nodes, o.big, rc::Schedule::Lpt, EngineKind::Iss);
    t.bign = r.frame_time;
    t.big_dl = milestone_time(r, "downloaded");
    t.bigs = b.run("static split", o.big_nodes, o.big, rc::Schedule::Static, EngineKind::Iss).frame_time;
  }
  // The co-simulation against the reference renderer on the same frame: the
  // ISS run on --static-nodes NCs (lpt), the best of --repeat (the runs above
  // count), over the reference's best; with --rtl the RTL engine's best over
  // the ISS's.
  t.iss = host_times(b, o, EngineKind::Iss, "lpt");
  if (o.rtl) {
    t.rtl = host_times(b, o, EngineKind::Rtl, "RTL engine");
    t.rtl1 = host_times(b, o, EngineKind::Iss, "RTL core on NC 1", {1});
  }
  t.ref = reference_host_times(o.scene, o.size, std::max(3u, o.repeat));
  return t;
}

// Speedup on --size and lpt over static: printed, and into the JSON.
void speedup_summary(std::ostream& json, const BenchOptions& o, BenchTimes& t) {
  json << "], \"speedup\": {";
  std::printf("\n%ux%u, lpt:", o.size.first, o.size.second);
  bool first = true;
  for (unsigned n : o.nodes) {
    if (!t.t_size.count(1)) break;
    const double sp = static_cast<double>(t.t_size[1]) / static_cast<double>(t.t_size[n]);
    std::printf("  %u NCs speedup %.2f (efficiency %s)", n, sp, pct(sp / n).c_str());
    json << (first ? "" : ", ") << "\"" << n << "\": " << sp;
    first = false;
  }
  const double gain = static_cast<double>(t.static_ref) / static_cast<double>(t.lpt_ref);
  std::printf("\n%ux%u on %u NCs: lpt %.3f ms, static %.3f ms: lpt gains %.2fx\n", o.size.first, o.size.second,
              o.static_nodes, t.lpt_ref * 1e-9, t.static_ref * 1e-9, gain);
  json << "}, \"lpt_over_static\": " << gain;
}

// Parallel efficiency on --big.
void efficiency_summary(std::ostream& json, const BenchOptions& o, const BenchTimes& t) {
  if (o.big.first) {
    const double eff = static_cast<double>(t.big1) / (static_cast<double>(o.big_nodes) * static_cast<double>(t.bign));
    const double big_gain = static_cast<double>(t.bigs) / static_cast<double>(t.bign);
    std::printf("%ux%u: 1 NC %.3f ms, %u NCs %.3f ms: parallel efficiency %s; the download (serial) is %s of the "
                "%u-NC frame; lpt gains %.2fx over static\n",
                o.big.first, o.big.second, t.big1 * 1e-9, o.big_nodes, t.bign * 1e-9, pct(eff).c_str(),
                pct(static_cast<double>(t.big_dl) / t.bign).c_str(), o.big_nodes, big_gain);
    json << ", \"big\": {\"width\": " << o.big.first << ", \"height\": " << o.big.second << ", \"nodes\": " << o.big_nodes
         << ", \"efficiency\": " << eff << ", \"download_share\": " << static_cast<double>(t.big_dl) / t.bign
         << ", \"lpt_over_static\": " << big_gain << "}";
  }
}

// "0.67-0.72 s (median 0.69)": a frame's runs, with `digits` decimals.
std::string runs_text(const HostTimes& h, int digits) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.*f-%.*f s (median %.*f)", digits, h.best, digits, h.worst, digits, h.median);
  return buf;
}

void host_times_json(std::ostream& json, const char* key, const HostTimes& h) {
  json << ", \"" << key << "\": " << h.best << ", \"" << key << "_median\": " << h.median << ", \"" << key
       << "_worst\": " << h.worst;
}

// One compared frame's line: its best run over the other's (wall clock and
// CPU time), then each frame's runs, so that a host whose load moved them
// shows it. Returns the larger spread of the two frames' runs.
double compare_line(std::ostream& json, const char* what, const char* key, const HostRuns& a, const char* a_key,
                    const HostRuns& b, const char* b_key) {
  const double wall = b.wall.best > 0 ? a.wall.best / b.wall.best : 0;
  const double cpu = b.cpu.best > 0 ? a.cpu.best / b.cpu.best : 0;
  const double medians = b.wall.median > 0 ? a.wall.median / b.wall.median : 0;
  std::printf("%s: %.3f s over %.3f s wall: %.1fx; CPU %.3f s over %.3f s: %.1fx (best of %u, %u)\n", what,
              a.wall.best, b.wall.best, wall, a.cpu.best, b.cpu.best, cpu, a.wall.runs, b.wall.runs);
  std::printf("  runs, wall: %s over %s: %.1fx of the medians; CPU: %s over %s\n", runs_text(a.wall, 3).c_str(),
              runs_text(b.wall, 3).c_str(), medians, runs_text(a.cpu, 3).c_str(), runs_text(b.cpu, 3).c_str());
  for (const auto& [k, h] : {std::pair<const char*, const HostRuns*>{a_key, &a}, {b_key, &b}}) {
    if (!k) continue;
    host_times_json(json, (std::string(k) + "_host_seconds").c_str(), h->wall);
    host_times_json(json, (std::string(k) + "_cpu_seconds").c_str(), h->cpu);
  }
  json << ", \"" << key << "\": " << wall << ", \"" << key << "_median\": " << medians << ", \"" << key
       << "_cpu\": " << cpu;
  return std::max({a.wall.spread(), b.wall.spread(), a.cpu.spread(), b.cpu.spread()});
}

// The host time of the co-simulation over the reference renderer's, and of
// the RTL engine over the ISS.
void host_summary(std::ostream& json, const BenchOptions& o, const BenchTimes& t) {
  json << ", \"repeat\": " << o.repeat;
  char what[160];
  std::snprintf(what, sizeof what, "%ux%u on %u NCs: co-simulation (ISS) over the reference renderer", o.size.first,
                o.size.second, o.static_nodes);
  double spread = compare_line(json, what, "cosim_over_reference", t.iss, "cosim", t.ref, "reference");
  if (o.rtl) {
    std::snprintf(what, sizeof what, "RTL engine, %u NCs, over the ISS", o.static_nodes);
    spread = std::max(spread, compare_line(json, what, "rtl_over_iss", t.rtl, "rtl", t.iss, nullptr));
    std::snprintf(what, sizeof what, "RTL core on NC 1 only (--rtl-nodes 1), the ISS on the other %u, over the ISS",
                  o.static_nodes - 1);
    spread = std::max(spread, compare_line(json, what, "rtl_nc1_over_iss", t.rtl1, "rtl_nc1", t.iss, nullptr));
  }
  // A quiet host repeats a frame within a few per cent.
  if (spread > 0.2)
    std::printf("The host's load moved the runs of one frame by up to %.0f %%: the ratios above are the best runs'; "
                "compare figures from a quiet host.\n",
                spread * 100);
}

}  // namespace

int cmd_bench_render(const CLI::App& cmd) {
  SystemConfig base = machine_config();
  apply_params(cmd, base.timing);
  const Parsed a(cmd);
  threads_option(a, base);
  const bool told = base.threads != 0;
  if (!told) base.threads = nc::ApuPool::default_threads();  // one count for every run, chosen now
  std::printf("host threads: %u (%s)\n", base.threads, told ? "--threads" : "the host's idle cores now");
  const BenchOptions o = bench_options(a, base);
  BenchRuns bench(base, o.scene);
  BenchTimes t = run_bench(bench, o);

  std::ostringstream json;
  json << "{\"schema\": \"mc1-bench-render/1\", \"scene\": " << mc1::json::quote(o.scene)
       << ", \"block\": " << base.block_w << ", \"threads\": " << base.threads << ", \"runs\": [";
  runs_json(json, bench.runs());
  speedup_summary(json, o, t);
  efficiency_summary(json, o, t);
  host_summary(json, o, t);
  const bool same = bench.same();
  json << ", \"frames_equal\": " << (same ? "true" : "false") << "}\n";
  if (a.has("json")) write_file_atomically(a.get("json"), json.str());
  if (!same) std::fprintf(stderr, "mc1 bench-render: frames of one size differ between runs\n");
  return same ? 0 : 1;
}

}  // namespace mc1::cli
