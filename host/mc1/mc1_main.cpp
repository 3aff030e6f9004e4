// mc1: the MC-1 machine model from the command line (docs/platform.md).
//   mc1 render, mc1 bench-render   the rendered frame of fig. 3 (mc1_render_cmd.cpp)
//   mc1 diag   the machine's self-test frame, checked against the FP24 model
//   mc1 bench  host time and simulated time of the diagnostic frame
//   mc1 params the timing table in effect
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <systemc>
#include <vector>

#include "apu_image.hpp"
#include "diag.hpp"
#include "mc1_cli.hpp"
#include "mc1_diag.hpp"
#include "mc1_render_cmd.hpp"
#include "mc1_sweep_cmd.hpp"
#include "mc1_system.hpp"
#include "png_writer.hpp"
#include "report_writers.hpp"
#include "scene.hpp"

namespace {

using namespace mc1;
using cli::CliError;

[[maybe_unused]] const int no_banner = setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);

const char* kDescription =
    "The MC-1 multicomputer (RC + N node computers over HDLC, image bus, frame memory)\n"
    "as a loosely-timed SystemC/TLM-2.0 model. `mc1 COMMAND --help` for a command's options.";

const char* kDiagDescription =
    "run the self-test frame and check it bit for bit against the FP24 model\n\n"
    "The machine's self-test frame: the RC broadcasts the diag APU kernel over HDLC,\n"
    "hands out blocks of the screen dynamically, each NC computes its blocks on its APU\n"
    "and sends the pixels over the image bus to the frame memory. The frame is compared\n"
    "with the host's FP24-model computation; the exit status is 0 only if they are equal.";

const char* kBenchDescription =
    "host seconds and simulated time of the self-test frame at 16 and 256 NCs\n\n"
    "Runs the self-test frame on the ISS engine for each node count and prints host\n"
    "seconds, simulated time, APU cycles and the share of host time spent in the APU\n"
    "engine (the rest is SystemC, HDLC, bus and firmware model).";

const char* kParamsDescription =
    "print the timing table (after --params/--param)\n\n"
    "Prints the timing table in effect, in the --params file format (docs/timing.md).";

void add_frame_options(CLI::App& cmd, const std::string& block_help) {
  cli::value_option(cmd, "engine", "iss|rtl", "APU engine: C++ ISS or verilated RTL core (default iss)");
  cli::value_option(cmd, "size", "WxH", "frame size (default 256x256)");
  cli::value_option(cmd, "block", "B|WxH", block_help);
  cli::add_threads_option(cmd);
  cli::add_param_options(cmd);
}

void add_diag_options(CLI::App& cmd) {
  cli::value_option(cmd, "nodes", "N", "node computers, 1..4096 (default 4)");
  add_frame_options(cmd, "block size (default 16; rows of at most 1024 pixels)");
  cli::add_fault_options(cmd);
  cli::files(cmd).input(
      cli::value_option(cmd, "kernel", "FILE", "APU image to broadcast instead of the built-in diag.bin"), "the kernel");
  cli::add_report_options(cmd);
  cli::flag_option(cmd, "quiet", "print nothing but errors");
}

void add_bench_options(CLI::App& cmd) {
  cli::value_option(cmd, "nodes", "LIST", "node counts (default 16,256)");
  add_frame_options(cmd, "block size (default 16)");
  cli::files(cmd).output(cli::value_option(cmd, "json", "FILE", "also write the figures as JSON"));
}

using cli::parse_engine;

void frame_options(const cli::Parsed& a, SystemConfig& cfg) {
  cli::threads_option(a, cfg);
  if (a.has("engine")) cfg.engine = parse_engine(a.get("engine"));
  if (a.has("size")) std::tie(cfg.width, cfg.height) = cli::parse_size("--size", a.get("size"), false);
  if (a.has("block")) std::tie(cfg.block_w, cfg.block_h) = cli::parse_size("--block", a.get("block"), true);
  if (cfg.block_w > diag::kMaxRunPixels)
    throw CliError("--block: rows of " + std::to_string(cfg.block_w) + " pixels (at most " +
                   std::to_string(diag::kMaxRunPixels) + ")");
}

struct Check {
  std::uint64_t mismatches = 0;
  unsigned first_x = 0, first_y = 0;
};

Check compare(const FrameReport& r) {
  const std::vector<std::uint8_t> want = diag::expected_image(r.width, r.height);
  Check c;
  for (std::size_t i = 0; i < want.size(); i += 3)
    if (want[i] != r.rgb[i] || want[i + 1] != r.rgb[i + 1] || want[i + 2] != r.rgb[i + 2]) {
      if (c.mismatches++ == 0) {
        c.first_x = static_cast<unsigned>((i / 3) % r.width);
        c.first_y = static_cast<unsigned>((i / 3) / r.width);
      }
    }
  return c;
}

double apu_share(const FrameReport& r) {
  double apu = 0;
  for (const NcReport& n : r.ncs) apu += n.apu_host_seconds;
  return r.host_seconds > 0 ? apu / r.host_seconds : 0;
}

std::uint64_t apu_cycles(const FrameReport& r) {
  std::uint64_t c = 0;
  for (const NcReport& n : r.ncs) c += n.apu_cycles;
  return c;
}

// --kernel: a bad or unreadable image is bad input (exit 2), named.
std::vector<apu::Encoded> kernel_image(const std::string& path) {
  try {
    return apu::load_image(path);
  } catch (const std::runtime_error& e) {
    throw CliError(std::string("--kernel: ") + e.what());
  }
}

int cmd_diag(const CLI::App& cmd) {
  SystemConfig cfg = cli::machine_config();
  cli::apply_params(cmd, cfg.timing);
  const cli::Parsed a(cmd);
  if (a.has("nodes")) cfg.nodes = cli::parse_unsigned("--nodes", a.get("nodes"), 1, 4096);
  frame_options(a, cfg);
  cli::fault_options(a, cfg);
  const bool quiet = a.has("quiet");
  const std::vector<apu::Encoded> program =
      a.has("kernel") ? kernel_image(a.get("kernel")) : diag::kernel();

  // The outputs were checked before the command ran (run_command).
  cli::Outputs out;  // the VCD's writer writes under a temporary name during the run
  const std::string vcd = cli::stage_vcd(a, out);

  const FrameReport r = run_frame(cfg, program, diag::nc_main, vcd);
  const Check c = compare(r);
  if (a.has("out")) out.add(a.get("out"), encode_png_rgb8(r.width, r.height, r.rgb.data()));
  if (a.has("stats")) out.add(a.get("stats"), stats_json(r));
  if (a.has("gantt")) out.add(a.get("gantt"), gantt_svg(r));
  out.commit();
  if (!quiet) {
    std::printf("mc1 diag: %u NCs (%s engine), %ux%u pixels, %u blocks of %ux%u\n", r.nodes, r.engine.c_str(),
                r.width, r.height, r.blocks, r.block_w, r.block_h);
    std::printf("  simulated %.6f ms, host %.3f s (APU engine %.0f%%), %llu APU cycles\n", r.frame_time * 1e-9,
                r.host_seconds, 100 * apu_share(r), static_cast<unsigned long long>(apu_cycles(r)));
    std::printf("  HDLC: %llu retransmissions, %llu timeouts, %llu FCS errors; image bus %.1f%% busy\n",
                static_cast<unsigned long long>([&] {
                  std::uint64_t n = 0;
                  for (const auto& l : r.hdlc.down) n += l.retransmissions;
                  for (const auto& l : r.hdlc.up) n += l.retransmissions;
                  return n;
                }()),
                static_cast<unsigned long long>(r.hdlc.timeouts), static_cast<unsigned long long>(r.hdlc.fcs_errors),
                r.frame_time ? 100.0 * r.bus.busy / r.frame_time : 0.0);
    cli::print_faults(r);
    if (c.mismatches == 0)
      std::printf("  frame OK: equal bit for bit to the FP24 model\n");
  }
  if (c.mismatches) {
    std::fprintf(stderr, "mc1 diag: frame differs from the FP24 model in %llu pixels (first at x=%u y=%u)\n",
                 static_cast<unsigned long long>(c.mismatches), c.first_x, c.first_y);
    return 1;
  }
  return 0;
}

int cmd_bench(const CLI::App& cmd) {
  SystemConfig base = cli::machine_config();
  cli::apply_params(cmd, base.timing);
  const cli::Parsed a(cmd);
  frame_options(a, base);
  const std::vector<unsigned> nodes = cli::parse_list("--nodes", a.get("nodes", "16,256"), 1, 4096);
  std::ostringstream json;
  json << "{\"schema\": \"mc1-bench/1\", \"engine\": \"" << engine_name(base.engine) << "\", \"width\": " << base.width
       << ", \"height\": " << base.height << ", \"block_width\": " << base.block_w
       << ", \"block_height\": " << base.block_h << ", \"runs\": [";
  std::printf("%6s %12s %10s %14s %12s %12s %6s\n", "NCs", "simulated", "host", "APU cycles", "cycles/s",
              "APU engine", "frame");
  bool all_ok = true;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (i) fresh_systemc_kernel();
    SystemConfig cfg = base;
    cfg.nodes = nodes[i];
    const FrameReport r = run_diag(cfg);
    const bool ok = compare(r).mismatches == 0;
    all_ok = all_ok && ok;
    const std::uint64_t cycles = apu_cycles(r);
    std::printf("%6u %9.3f ms %8.3f s %14llu %12.3g %11.0f%% %6s\n", cfg.nodes, r.frame_time * 1e-9, r.host_seconds,
                static_cast<unsigned long long>(cycles), cycles / r.host_seconds, 100 * apu_share(r),
                ok ? "OK" : "WRONG");
    json << (i ? ", " : "") << "{\"nodes\": " << cfg.nodes << ", \"simulated_time_s\": " << r.frame_time * 1e-12
         << ", \"host_seconds\": " << r.host_seconds << ", \"apu_cycles\": " << cycles
         << ", \"apu_engine_share\": " << apu_share(r) << ", \"frame_ok\": " << (ok ? "true" : "false") << "}";
    std::fflush(stdout);
  }
  json << "]}\n";
  if (a.has("json")) write_file_atomically(a.get("json"), json.str());
  return all_ok ? 0 : 1;
}

int cmd_params(const CLI::App& cmd) {
  TimingParams t;
  cli::apply_params(cmd, t);
  std::cout << t.to_text();
  return 0;
}

// `mc1 --help` lists each command by the first line of its description; the
// rest is for `mc1 COMMAND --help`.
class Formatter : public CLI::Formatter {
 public:
  std::string make_subcommand(const CLI::App* sub) const override {
    const std::string& d = sub->get_description();
    std::stringstream out;
    CLI::detail::format_help(out, sub->get_display_name(), d.substr(0, d.find('\n')), column_width_);
    return out.str();
  }
};

// The command line: one subcommand, and `mc1 help` as `mc1 --help`.
void add_commands(CLI::App& app) {
  app.formatter(std::make_shared<Formatter>());
  cmdline::conventions(app);
  app.get_formatter()->label("Usage", "usage");
  app.require_subcommand(1);
  app.add_subcommand("help", "this text; `mc1 help COMMAND` or `mc1 COMMAND --help` for a command's options")
      ->add_option("COMMAND", "a command whose options to show");
  cli::add_render_options(*app.add_subcommand("render", cli::kRenderDescription));
  cli::add_bench_render_options(*app.add_subcommand("bench-render", cli::kBenchRenderDescription));
  cli::add_sweep_options(*app.add_subcommand("sweep", cli::kSweepDescription));
  add_diag_options(*app.add_subcommand("diag", kDiagDescription));
  add_bench_options(*app.add_subcommand("bench", kBenchDescription));
  cli::add_param_options(*app.add_subcommand("params", kParamsDescription));
}

int run_command(const CLI::App& app, const CLI::App& cmd) {
  const std::string name = cmd.get_name();
  if (name == "help") {
    // app.help() would describe the selected subcommand, `help` itself.
    const CLI::results_t& what = cmd.get_option("COMMAND")->results();
    if (what.empty()) {
      std::cout << app.get_formatter()->make_help(&app, app.get_name(), CLI::AppFormatMode::Normal);
      return cmdline::kExitOk;
    }
    const auto named = [&](const CLI::App* sub) { return sub->check_name(what.front()) && sub != &cmd; };
    const auto subs = app.get_subcommands(named);
    if (subs.empty()) throw CliError("unknown command '" + what.front() + "'");
    std::cout << subs.front()->help();
    return cmdline::kExitOk;
  }
  // Every file option of the command at once: no output on an input or on
  // another output, none given twice, each writable (cmdline::Files).
  cli::files(cmd).check();
  if (name == "diag") return cmd_diag(cmd);
  if (name == "render") return cli::cmd_render(cmd);
  if (name == "bench-render") return cli::cmd_bench_render(cmd);
  if (name == "bench") return cmd_bench(cmd);
  if (name == "sweep") return cli::cmd_sweep(cmd);
  return cmd_params(cmd);
}

}  // namespace

int sc_main(int argc, char** argv) {
  // SystemC's notes (trace timescale, ...) would mix with the report.
  sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  CLI::App app(kDescription, "mc1");
  add_commands(app);
  // CLI11 would only say that a command is required.
  const auto named = [&](const CLI::App* sub) { return sub->check_name(argv[1]); };
  if (argc > 1 && argv[1][0] != '-' && app.get_subcommands(named).empty())
    return cmdline::usage_error(app, std::string("unknown command '") + argv[1] + "'");
  if (const auto done = cmdline::parse(app, argc, argv)) return *done;
  const CLI::App& cmd = *app.get_subcommands().front();
  const std::string name = cmd.get_name();
  try {
    return cmdline::flush_stdout("mc1 " + name, run_command(app, cmd));
  } catch (const CliError& e) {
    std::fprintf(stderr, "mc1 %s: %s\n", name.c_str(), e.what());
    return cmdline::kExitUsage;
  } catch (const scene::SceneError& e) {  // a missing or bad scene is bad input
    std::fprintf(stderr, "mc1 %s: %s\n", name.c_str(), e.what());
    return cmdline::kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mc1 %s: %s\n", name.c_str(), e.what());
    return cmdline::kExitFailed;
  }
}
