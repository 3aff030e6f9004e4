// mc1 render / mc1 bench-render: the rendered frame of fig. 3 on the machine
// (docs/platform.md "The rendered frame", "Rendering benchmark").
#include "mc1_render_cmd.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "apu_trace_files.hpp"
#include "image.hpp"
#include "json.hpp"
#include "cmdline.hpp"
#include "mc1_cli.hpp"
#include "mc1_render.hpp"
#include "png_writer.hpp"
#include "refrender.hpp"
#include "frame_profile.hpp"
#include "apu_pool.hpp"
#include "frame_steps.hpp"
#include "host_clock.hpp"
#include "report_profile.hpp"
#include "report_writers.hpp"
#include "scene.hpp"

namespace mc1::cli {

const char* const kRenderDescription =
    "render a scene (fig. 3): broadcast, block lists, blocks by schedule; PNG, stats, Gantt\n\n"
    "Renders a scene (docs/scene-format.md) on the machine as the paper's fig. 3 does: the RC\n"
    "broadcasts the renderer's kernels and the scene in FP24 over HDLC; every NC transforms it\n"
    "to view coordinates on its APU (step 1); the NCs build the block lists (step 2); the RC\n"
    "hands the blocks out by its schedule and the NCs render them and send the pixels over the\n"
    "image bus to the frame memory (step 3). The frame does not depend on the node count, the\n"
    "schedule, the engine or the faults.";

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
    "engine's over the ISS's, each the best of --repeat runs; under each, the frame's runs (best,\n"
    "worst, median), and a note if the host's load moved them by over 20 %. Every run's frame\n"
    "must equal the first run's of its size bit for bit.";

void add_render_options(CLI::App& cmd) {
  cmdline::Files& f = files(cmd);
  f.input(cmd.add_option("SCENE", "the scene file (or --scene FILE)")->type_name("FILE"), "the scene");
  f.input(value_option(cmd, "scene", "FILE", "the scene file, instead of SCENE"), "the scene");
  value_option(cmd, "nodes", "N", "node computers, 1..4096 (default 16)");
  value_option(cmd, "size", "WxH", "frame size (default: the scene's camera size)");
  value_option(cmd, "block", "B|WxH", "block size (default 16)");
  value_option(cmd, "engine", "iss|rtl", "APU engine: C++ ISS or verilated RTL core (default iss)");
  value_option(cmd, "rtl-nodes", "K,...",
               "these NCs run the verilated RTL core, the others the ISS (with --engine iss): the RTL in a whole "
               "frame at a fraction of its host time; the frame and every statistic are the same");
  value_option(cmd, "schedule", "S",
               "lpt: heaviest predicted load first (the paper's, default); fifo: screen order as NCs ask; "
               "static: block i to NC (i mod N) + 1");
  add_threads_option(cmd);
  add_fault_options(cmd);
  add_param_options(cmd);
  add_report_options(cmd);
  f.outputs_each(list_option(cmd, "profile", "FILE.md|FILE.json",
                             "FILE.md: the timing evaluation, per step and per kernel APU cycles, issue, bank stalls, "
                             "MPU cycles (docs/renderer.md \"Timing\"); FILE.json: the stall profile per kernel and "
                             "pc, over NCs and per NC (schema apu-profile/2, docs/apu-tools.md), its summary on "
                             "stdout; repeatable: every file written, each by its name's ending"));
  f.output(value_option(cmd, "trace", "FILE.fst",
                        "APU waveform of NC --trace-node (that NC runs the RTL core) on simulated time; also "
                        "FILE.fst.gtkw (the save file), .kpc.txt, .kernel.txt and .<enum>.txt (translate filters)"),
           apu::trace_side_suffixes());
  value_option(cmd, "trace-node", "K", "the NC to trace (default 1)");
  value_option(cmd, "trace-from", "TIME", "the waveform starts at simulated TIME (12.5ms, 300us, ...; bare: ms)");
  value_option(cmd, "trace-to", "TIME", "the waveform ends at simulated TIME");
  flag_option(cmd, "ref",
              "also render the double-precision reference (mc1-ref) at the same size and print the PSNR of the "
              "frame against it");
  f.output(value_option(cmd, "diff", "FILE.png", "with --ref: the difference image, |frame - reference| x 8"));
  value_option(cmd, "min-psnr", "DB", "with --ref: exit status 1 when the PSNR is below DB");
  flag_option(cmd, "quiet", "print nothing but errors (no progress bar)");
}

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

std::string pct(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f %%", 100 * x);
  return b;
}

std::string ms(Picos t) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f ms", t * 1e-9);
  return b;
}

// A progress bar on the terminal: blocks done of the total, simulated time,
// host time elapsed and an estimate of what is left (from blocks done).
// The simulation draws it as blocks complete; a ticker thread redraws it
// each second meanwhile, so that the broadcast and the block lists before
// the first block, or a slow block, still show the time going by.
class ProgressBar {
 public:
  explicit ProgressBar(bool on) : on_(on) {
    if (on_) ticker_ = std::thread([this] { tick(); });
  }
  ~ProgressBar() { done(); }
  void update(const rc::Progress& p) {
    if (!on_) return;
    const std::lock_guard<std::mutex> lock(m_);
    last_progress_ = p;
    const auto now = std::chrono::steady_clock::now();
    if (p.blocks_done != p.blocks && drawn_ && now - last_ < std::chrono::milliseconds(100)) return;
    draw(now);
  }
  void done() {
    if (!on_) return;
    {
      const std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    if (ticker_.joinable()) ticker_.join();
    if (drawn_) std::fputc('\n', stderr);
    drawn_ = false;
  }

 private:
  void tick() {
    std::unique_lock<std::mutex> lock(m_);
    while (!cv_.wait_for(lock, std::chrono::seconds(1), [this] { return stop_; })) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last_ >= std::chrono::seconds(1)) draw(now);
    }
  }
  void draw(std::chrono::steady_clock::time_point now) {  // m_ held
    last_ = now;
    drawn_ = true;
    const rc::Progress& p = last_progress_;
    constexpr int kWidth = 30;
    const double fraction = p.blocks ? static_cast<double>(p.blocks_done) / p.blocks : 0.0;
    const int fill = static_cast<int>(kWidth * fraction);
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (p.blocks)
      std::fprintf(stderr, "\r  [%s%s] %u/%u blocks, %.3f ms simulated, %s   ", std::string(fill, '#').c_str(),
                   std::string(kWidth - fill, '.').c_str(), p.blocks_done, p.blocks, p.time * 1e-9,
                   mc1::cmdline::progress_times(elapsed, fraction).c_str());
    else
      std::fprintf(stderr, "\r  [%s] no block done yet (broadcast, block lists), %.0f s elapsed   ",
                   std::string(kWidth, '.').c_str(), elapsed);
    std::fflush(stderr);
  }

  bool on_;
  std::mutex m_;  // the fields below, and stderr while drawing
  std::condition_variable cv_;
  bool stop_ = false;
  bool drawn_ = false;
  rc::Progress last_progress_;
  std::chrono::steady_clock::time_point last_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::thread ticker_;
};

void frame_options(const Parsed& a, SystemConfig& cfg, RenderJob& job) {
  if (a.has("nodes")) cfg.nodes = parse_unsigned("--nodes", a.get("nodes"), 1, 4096);
  if (a.has("engine")) cfg.engine = parse_engine(a.get("engine"));
  if (a.has("rtl-nodes")) {
    if (cfg.engine == EngineKind::Rtl) throw CliError("--rtl-nodes: with --engine rtl every NC runs the RTL core");
    cfg.rtl_nodes = parse_list("--rtl-nodes", a.get("rtl-nodes"), 1, cfg.nodes);
    std::vector<unsigned> sorted = cfg.rtl_nodes;
    std::sort(sorted.begin(), sorted.end());
    if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
      throw CliError("--rtl-nodes: NC " + std::to_string(*twice) + " is given twice");
  }
  if (a.has("size")) std::tie(job.width, job.height) = parse_size("--size", a.get("size"), false);
  if (a.has("block")) std::tie(cfg.block_w, cfg.block_h) = parse_size("--block", a.get("block"), true);
  if (a.has("schedule")) {
    const auto s = rc::parse_schedule(a.get("schedule"));
    if (!s) throw CliError("--schedule: bad value '" + a.get("schedule") + "' (expected lpt, fifo or static)");
    cfg.schedule = *s;
  }
}

imgcmp::Image frame_image(const FrameReport& r) {
  imgcmp::Image img(static_cast<int>(r.width), static_cast<int>(r.height));
  img.rgb = r.rgb;
  return img;
}

void print_summary(const RenderRun& run) {
  const FrameReport& r = run.report;
  const Picos T = r.frame_time;
  const std::string engine = engine_text(r);
  std::printf("mc1 render: %s, %u NCs (%s, %s), %ux%u pixels, %u blocks of %ux%u\n", r.scene.c_str(), r.nodes,
              engine.c_str(), r.schedule.c_str(), r.width, r.height, r.blocks, r.block_w, r.block_h);
  const Picos dl = milestone_time(r, "downloaded"), s1 = milestone_time(r, "step1");
  std::printf("  simulated %s: download done %s (%s), step 1 done %s, block lists done %s; host %.2f s (CPU %.2f s)\n",
              ms(T).c_str(), ms(dl).c_str(), pct(T ? static_cast<double>(dl) / T : 0).c_str(), ms(s1).c_str(),
              ms(r.rc.lists_done).c_str(), r.host_seconds, r.host_cpu_seconds);
  std::uint64_t retx = 0;
  for (const LineReport& l : r.hdlc.down) retx += l.retransmissions;
  for (const LineReport& l : r.hdlc.up) retx += l.retransmissions;
  std::printf("  APU utilization %s (mean over NCs); HDLC %llu bytes broadcast, %llu retransmissions, %llu FCS "
              "errors; image bus %s busy\n",
              pct(apu_utilization_mean(r)).c_str(), static_cast<unsigned long long>(r.rc.download_bytes),
              static_cast<unsigned long long>(retx), static_cast<unsigned long long>(r.hdlc.fcs_errors),
              pct(T ? static_cast<double>(r.bus.busy) / T : 0).c_str());
  print_faults(r);
  for (const rc::Timeout& x : r.timeouts)
    std::printf("  %s: NC %u missed its deadline (%s %u); %u pieces handed out again\n", ms(x.time).c_str(), x.nc,
                x.list_job ? "list job" : "block", x.block, x.requeued);
  if (r.bus.duplicate_runs || r.rc.late_reports)
    std::printf("  %llu late reports ignored, %llu duplicate pixel runs dropped by the DC\n",
                static_cast<unsigned long long>(r.rc.late_reports),
                static_cast<unsigned long long>(r.bus.duplicate_runs));
}

// --trace's window [from, to) when the traced NC's APU does not run in it:
// the waveform would show an idle core and the save file no stall site, so
// say so on stderr, with when that APU did run (its first start to its last
// HALT, and the run nearest the window). Returns true if it warned.
bool warn_idle_trace_window(const FrameReport& r, unsigned nc, Picos from, Picos to) {
  if (nc == 0 || nc > r.ncs.size()) return false;
  const std::vector<nc::ApuSpan>& runs = r.ncs[nc - 1].apu;
  const Picos end = std::min(to, r.frame_time);
  for (const nc::ApuSpan& a : runs)
    if (a.begin < end && a.end > from) return false;
  const std::string window = ms(from) + " to " + (to == ~Picos{0} ? "the end" : ms(to));
  std::fprintf(stderr, "mc1 render: warning: --trace: NC %u's APU does not run in the window %s: the waveform shows "
               "an idle core and the save file marks no stall site\n", nc, window.c_str());
  if (from >= r.frame_time)
    std::fprintf(stderr, "  the frame ends at %s, before the window starts\n", ms(r.frame_time).c_str());
  if (runs.empty()) {
    std::fprintf(stderr, "  NC %u's APU did not run in this frame\n", nc);
    return true;
  }
  const nc::ApuSpan* near = &runs.front();
  auto gap = [&](const nc::ApuSpan& a) { return a.end <= from ? from - a.end : a.begin - end; };
  for (const nc::ApuSpan& a : runs)
    if (gap(a) < gap(*near)) near = &a;
  std::fprintf(stderr, "  NC %u's APU runs from %s to %s (%zu runs); the nearest run: %s to %s\n", nc,
               ms(runs.front().begin).c_str(), ms(runs.back().end).c_str(), runs.size(), ms(near->begin).c_str(),
               ms(near->end).c_str());
  return true;
}

// --trace's side files into `out`, after the warning of a window the traced
// NC's APU does not run in.
void trace_files(const std::string& trace, const FrameReport& r, const SystemConfig& cfg, FrameProfiler& profiler,
                 Outputs& out) {
  warn_idle_trace_window(r, cfg.trace_node, cfg.trace_from, cfg.trace_to);
  for (const auto& [path, text] : trace_side_files(trace, profiler, cfg.trace_node)) out.add(path, text);
}

// --ref: the double-precision reference at the same size, its PSNR, and with
// --diff the difference image (staged with the other outputs). Returns 1 when
// the PSNR is below min_psnr.
int compare_to_reference(const RenderJob& job, const FrameReport& r, const std::string& diff, double min_psnr,
                         bool quiet, Outputs& out) {
  scene::Scene s = scene::load_scene(job.scene);
  const imgcmp::Image ref = refrender::Renderer(s).render(static_cast<int>(r.width), static_cast<int>(r.height));
  const imgcmp::Image got = frame_image(r);
  const double p = imgcmp::psnr(got, ref);
  if (!quiet)
    std::printf("  against the reference renderer: PSNR %.2f dB, largest difference %d\n", p,
                imgcmp::max_abs_diff(got, ref));
  if (!diff.empty()) {
    const imgcmp::Image d = imgcmp::difference(got, ref, 8);
    out.add(diff, encode_png_rgb8(static_cast<unsigned>(d.width), static_cast<unsigned>(d.height), d.rgb.data()));
  }
  if (p < min_psnr) {
    std::fprintf(stderr, "mc1 render: PSNR %.2f dB against the reference is below --min-psnr %.2f\n", p, min_psnr);
    return 1;
  }
  return 0;
}

// Before the run (the outputs were checked against the inputs and each
// other before the command ran: run_command): --trace's FST and --vcd's VCD
// staged in `out` (their writers write the temporary files: cfg.trace_path,
// and the VCD path returned, "" without --vcd).
std::string stage_writers(const Parsed& a, SystemConfig& cfg, Outputs& out) {
  if (a.has("trace")) {
    StagedFile fst = writer_output("--trace", a.get("trace"));
    cfg.trace_path = fst.temp();
    out.add(std::move(fst));
  }
  return stage_vcd(a, out);
}

}  // namespace

int cmd_render(const CLI::App& cmd) {
  RenderJob job;
  if (cmd.count("SCENE")) job.scene = cmd.get_option("SCENE")->results().back();
  SystemConfig cfg = machine_config();
  cfg.nodes = 16;
  apply_params(cmd, cfg.timing);
  const Parsed a(cmd);
  if (a.has("scene") && !job.scene.empty()) throw CliError("SCENE and --scene are both given: name the scene once");
  if (a.has("scene")) job.scene = a.get("scene");
  if (job.scene.empty()) throw CliError("missing SCENE (see --help)");
  frame_options(a, cfg, job);
  threads_option(a, cfg);
  fault_options(a, cfg);
  if (a.has("trace")) {
    cfg.trace_node = a.has("trace-node") ? parse_unsigned("--trace-node", a.get("trace-node"), 1, cfg.nodes) : 1;
    if (a.has("trace-from")) cfg.trace_from = parse_time("--trace-from", a.get("trace-from"));
    if (a.has("trace-to")) cfg.trace_to = parse_time("--trace-to", a.get("trace-to"));
    if (cfg.trace_to <= cfg.trace_from) throw CliError("--trace-to must be later than --trace-from");
  } else if (a.has("trace-node") || a.has("trace-from") || a.has("trace-to")) {
    throw CliError("--trace-node, --trace-from and --trace-to need --trace FILE.fst");
  }
  const std::vector<std::string> profiles = a.all("profile");
  auto is_json = [](const std::string& p) { return p.size() > 5 && p.compare(p.size() - 5, 5, ".json") == 0; };
  const bool stall_profile = std::any_of(profiles.begin(), profiles.end(), is_json);
  FrameProfiler profiler(stall_profile, cfg.trace_node, cfg.trace_from, cfg.trace_to);
  if (stall_profile || cfg.trace_node) cfg.attach = [&profiler](nc::NodeComputer& n) { profiler.attach(n); };
  if ((a.has("diff") || a.has("min-psnr")) && !a.has("ref")) throw CliError("--diff and --min-psnr need --ref");
  const double min_psnr = a.has("min-psnr") ? parse_double("--min-psnr", a.get("min-psnr"), 0, 200) : 0;
  const bool quiet = a.has("quiet");
  // Every output is staged first and renamed into place together, so that a
  // write that fails leaves none of them; a failed check still leaves them.
  // The waveforms' writers write under a temporary name during the run.
  Outputs out;
  const std::string vcd = stage_writers(a, cfg, out);

  RenderRun run;
  {
    ProgressBar bar(!quiet && isatty(fileno(stderr)));
    run = run_render(job, cfg, vcd, [&bar](const rc::Progress& p) { bar.update(p); });
  }
  const FrameReport& r = run.report;
  if (a.has("out")) out.add(a.get("out"), encode_png_rgb8(r.width, r.height, r.rgb.data()));
  if (a.has("stats")) out.add(a.get("stats"), stats_json(r));
  if (a.has("gantt")) out.add(a.get("gantt"), gantt_svg(r));
  for (const std::string& p : profiles)
    if (!is_json(p)) out.add(p, profile_tables(r));
  if (!quiet) print_summary(run);
  if (stall_profile) {
    profiler.profile().finish();
    const std::string json_profile = profiler.profile().json(profiler.kernels(), "mc1 render",
                                             ", \"scene\": " + json::quote(r.scene) + ", \"engine\": \"" + r.engine +
                                                 "\", \"nodes\": " + std::to_string(r.nodes) +
                                                 ", \"frame_time_ps\": " + std::to_string(r.frame_time));
    for (const std::string& p : profiles)
      if (is_json(p)) out.add(p, json_profile);
    if (!quiet) std::fputs(profiler.profile().text(profiler.kernels(), 10).c_str(), stdout);
  }
  if (cfg.trace_node) trace_files(a.get("trace"), r, cfg, profiler, out);
  int status = 0;
  if (r.fm_pixels_written != std::uint64_t{r.width} * r.height) {
    std::fprintf(stderr, "mc1 render: the frame memory got %llu pixel writes for %u pixels\n",
                 static_cast<unsigned long long>(r.fm_pixels_written), r.width * r.height);
    status = 1;
  } else if (a.has("ref")) {
    status = compare_to_reference(job, r, a.get("diff"), min_psnr, quiet, out);
  }
  out.commit();
  return status;
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
