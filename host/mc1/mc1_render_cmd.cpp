// mc1 render: the rendered frame of fig. 3 on the machine (docs/platform.md
// "The rendered frame"); mc1 bench-render is mc1_bench_render_cmd.cpp.
#include "mc1_render_cmd.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <sstream>
#include <system_error>
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
#include "frame_steps.hpp"
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

namespace {

std::string ms(Picos t) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f ms", t * 1e-9);
  return b;
}

// A progress bar on the terminal: blocks done of the total, simulated time,
// host time elapsed and an estimate of what is left (from blocks done).
// The simulation draws it as blocks complete; a ticker thread redraws it
// each second meanwhile, so that the broadcast and the block lists before
// the first block, or a slow block, still show the time going by. A ticker
// the host will not start (a process limit) is done without: the bar is
// then drawn only as blocks complete, and the frame is rendered all the
// same (tests/thread_limit_test.sh).
class ProgressBar {
 public:
  explicit ProgressBar(bool on) : on_(on) {
    if (!on_) return;
    try {
      ticker_ = std::thread([this] { tick(); });
    } catch (const std::system_error&) {
    }
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

}  // namespace mc1::cli
