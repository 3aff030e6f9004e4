#include "mc1_cli.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <system_error>

#include "mc1_engines.hpp"

namespace mc1::cli {

CLI::Option* value_option(CLI::App& cmd, const std::string& name, const std::string& type, const std::string& help) {
  return cmd.add_option("--" + name, help)
      ->type_name(type)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

std::string default_scene() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path() / MC1_DATA_FROM_BIN / "scenes" / "whitted.json";
    if (fs::is_regular_file(installed, ec)) return installed.lexically_normal().string();
  }
  return MC1_SOURCE_DIR "/scenes/whitted.json";
}

CLI::Option* list_option(CLI::App& cmd, const std::string& name, const std::string& type, const std::string& help) {
  // One value per occurrence: `--dead-link A SCENE` must not take SCENE too.
  return value_option(cmd, name, type, help)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
}

CLI::Option* flag_option(CLI::App& cmd, const std::string& name, const std::string& help) {
  return cmd.add_flag("--" + name, help);
}

cmdline::Files& files(const CLI::App& cmd) {
  static std::map<const CLI::App*, cmdline::Files> commands;  // the main thread's, while parsing and before the run
  return commands[&cmd];
}

void add_param_options(CLI::App& cmd) {
  files(cmd).input(
      list_option(cmd, "params", "FILE", "timing table file (docs/timing.md); repeatable, in order with --param"),
      "the timing table");
  list_option(cmd, "param", "key=value", "one timing figure; repeatable, in order with --params");
}

std::string pct(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f %%", 100 * x);
  return b;
}

void apply_params(const CLI::App& cmd, TimingParams& t) {
  // CLI11 keeps each option's values apart; its parse order interleaves them
  // again, so that a later --param overrides an earlier --params file and
  // vice versa.
  const CLI::Option* files = cmd.get_option("--params");
  const CLI::Option* figures = cmd.get_option("--param");
  std::size_t next_file = 0, next_figure = 0;
  try {
    for (const CLI::Option* o : cmd.parse_order()) {
      if (o == files) load_params_file(t, files->results().at(next_file++));
      if (o == figures) apply_param_override(t, figures->results().at(next_figure++));
    }
    t.validate();
  } catch (const ParamError& e) {
    throw CliError(e.what());
  }
}

std::string Parsed::get(const std::string& name, const std::string& fallback) const {
  const CLI::results_t& r = cmd_.get_option("--" + name)->results();
  return r.empty() ? fallback : r.back();
}

std::vector<std::string> Parsed::all(const std::string& name) const {
  return cmd_.get_option("--" + name)->results();
}

// The project's strict numbers (decimal or 0x hex, no octal, no wrapping).
unsigned parse_unsigned(const std::string& opt, const std::string& text, unsigned min, unsigned max) {
  return static_cast<unsigned>(cmdline::parse_unsigned(opt, text, min, max));
}

double parse_double(const std::string& opt, const std::string& text, double min, double max) {
  return cmdline::parse_real(opt, text, min, max);
}

std::pair<unsigned, unsigned> parse_size(const std::string& opt, const std::string& text, bool square_ok) {
  const auto x = text.find('x');
  if (x != std::string::npos && text.find('x', x + 1) != std::string::npos)
    throw CliError(opt + ": bad size '" + text + "' (expected WxH, e.g. 256x256)");
  if (x == std::string::npos) {
    if (!square_ok) throw CliError(opt + ": bad size '" + text + "' (expected WxH, e.g. 256x256)");
    const unsigned n = parse_unsigned(opt, text, 1, 4096);
    return {n, n};
  }
  return {parse_unsigned(opt, text.substr(0, x), 1, 4096), parse_unsigned(opt, text.substr(x + 1), 1, 4096)};
}

Picos parse_time(const std::string& opt, const std::string& text) {
  static const std::pair<const char*, double> units[] = {
      {"ps", 1.0}, {"ns", 1e3}, {"us", 1e6}, {"ms", 1e9}, {"s", 1e12}};
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  const std::string unit(end);
  double scale = 0;
  if (unit.empty()) scale = 1e9;
  for (const auto& u : units)
    if (unit == u.first) scale = u.second;
  if (text.empty() || end == text.c_str() || scale == 0 || !std::isfinite(v) || v < 0 || v * scale > 9e18)
    throw CliError(opt + ": bad time '" + text + "' (expected e.g. 2ms, 350us, 1.5s)");
  return static_cast<Picos>(std::llround(v * scale));
}

DeadLink parse_dead_link(const std::string& text) {
  const std::string opt = "--dead-link";
  const auto at = text.find('@');
  const auto dash = text.find('-', at == std::string::npos ? 0 : at);
  if (at == std::string::npos || dash == std::string::npos)
    throw CliError(opt + ": bad window '" + text + "' (expected NC@T0-T1, e.g. 3@1ms-4ms)");
  DeadLink d;
  d.nc = parse_unsigned(opt + " (NC)", text.substr(0, at), 1, 1u << 20);
  d.begin = parse_time(opt, text.substr(at + 1, dash - at - 1));
  d.end = parse_time(opt, text.substr(dash + 1));
  if (d.end <= d.begin) throw CliError(opt + ": window '" + text + "' ends before it begins");
  return d;
}

std::vector<unsigned> parse_list(const std::string& opt, const std::string& text, unsigned min, unsigned max) {
  std::vector<unsigned> out;
  std::size_t from = 0;
  for (;;) {
    const auto comma = text.find(',', from);
    out.push_back(parse_unsigned(opt, text.substr(from, comma - from), min, max));
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  return out;
}

namespace {

// K@TIME, the NC and the time of a --kill-node or --cut-line.
template <class Event>
Event parse_nc_at(const std::string& opt, const std::string& text) {
  const auto at = text.find('@');
  if (at == std::string::npos) throw CliError(opt + ": bad value '" + text + "' (expected K@TIME, e.g. 3@20ms)");
  Event e;
  e.nc = parse_unsigned(opt + " (NC)", text.substr(0, at), 1, 1u << 20);
  e.time = parse_time(opt, text.substr(at + 1));
  return e;
}

}  // namespace

NodeKill parse_kill(const std::string& text) { return parse_nc_at<NodeKill>("--kill-node", text); }

CutLine parse_cut_line(const std::string& text) { return parse_nc_at<CutLine>("--cut-line", text); }

void add_fault_options(CLI::App& cmd) {
  value_option(cmd, "ber", "X", "HDLC bit error rate on every line end, both directions (default 0)");
  value_option(cmd, "seed", "S", "seed of the bit-error streams (default 1)");
  list_option(cmd, "dead-link", "NC@T0-T1",
              "NC's link dead in both directions from T0 to T1 (e.g. 3@1ms-4ms; units ps ns us ms s, bare numbers "
              "are ms); repeatable");
  list_option(cmd, "kill-node", "K@TIME",
              "NC K's processor, and with it its HDLC station, stops at TIME (e.g. 3@20ms); the RC's link "
              "supervision finds it and hands its work to the others; repeatable");
  list_option(cmd, "cut-line", "K@TIME",
              "NC K's HDLC line carries nothing either way from TIME on; the NC is lost to the frame like a "
              "killed one; repeatable");
}

void fault_options(const Parsed& a, SystemConfig& cfg) {
  if (a.has("ber")) cfg.ber = parse_double("--ber", a.get("ber"), 0.0, 0.01);
  if (a.has("seed")) cfg.seed = parse_unsigned("--seed", a.get("seed"), 0, 0xFFFFFFFFu);
  const std::string machine = ": the machine has NC 1.." + std::to_string(cfg.nodes);
  for (const std::string& d : a.all("dead-link")) {
    cfg.dead_links.push_back(parse_dead_link(d));
    if (cfg.dead_links.back().nc > cfg.nodes) throw CliError("--dead-link " + d + machine);
  }
  for (const std::string& k : a.all("kill-node")) {
    cfg.kills.push_back(parse_kill(k));
    if (cfg.kills.back().nc > cfg.nodes) throw CliError("--kill-node " + k + machine);
  }
  for (const std::string& c : a.all("cut-line")) {
    cfg.cut_lines.push_back(parse_cut_line(c));
    if (cfg.cut_lines.back().nc > cfg.nodes) throw CliError("--cut-line " + c + machine);
  }
}

void add_report_options(CLI::App& cmd) {
  cmdline::Files& f = files(cmd);
  f.output(value_option(cmd, "out", "FILE.png", "write the frame memory as PNG"));
  f.output(value_option(cmd, "stats", "FILE.json", "write statistics (docs/platform.md \"Statistics\")"));
  f.output(value_option(cmd, "gantt", "FILE.svg", "write the activity chart of every NC and the RC's dispatches"));
  f.output(value_option(cmd, "vcd", "FILE.vcd", "trace platform signals (HDLC line busy, image-bus grant/owner)"));
}

void add_threads_option(CLI::App& cmd) {
  value_option(cmd, "threads", "N",
               "host threads clocking the NCs' APUs, 1..1024 (default: the host's idle cores now, at least 1); the frame, the "
               "statistics and every simulated time are the same for any N");
}

void threads_option(const Parsed& a, SystemConfig& cfg) {
  if (a.has("threads")) cfg.threads = parse_unsigned("--threads", a.get("threads"), 1, 1024);
}

EngineKind parse_engine(const std::string& s) {
  if (s == "iss") return EngineKind::Iss;
  if (s == "rtl") return EngineKind::Rtl;
  throw CliError("--engine: bad value '" + s + "' (expected iss or rtl)");
}

SystemConfig machine_config() {
  SystemConfig cfg;
  cfg.engines = make_engine;
  return cfg;
}

void Outputs::add(const std::string& path, std::string_view bytes) { staged_.emplace_back(path, bytes); }

void Outputs::add(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  add(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void Outputs::add(StagedFile&& written) { staged_.push_back(std::move(written)); }

std::string stage_vcd(const Parsed& a, Outputs& out) {
  if (!a.has("vcd")) return "";
  StagedFile f = writer_output("--vcd", a.get("vcd"), ".vcd");
  std::string temp = f.temp();
  out.add(std::move(f));
  return temp;
}

void Outputs::commit() {
  for (StagedFile& f : staged_) f.commit();
  staged_.clear();
}

void print_faults(const FrameReport& r) {
  auto ms = [](Picos t) { return t * 1e-9; };
  for (const KillReport& k : r.kills) std::printf("  NC %u killed at %.3f ms\n", k.nc, ms(k.time));
  for (const NcReport& n : r.ncs)
    if (n.watchdog) std::printf("  NC %u stopped at %.3f ms: %s\n", n.id, ms(n.killed_at), n.fault.c_str());
  for (const CutLineReport& c : r.cut_lines) std::printf("  NC %u's line cut at %.3f ms\n", c.nc, ms(c.time));
  for (const rc::LinkDown& d : r.link_downs)
    std::printf("  %.3f ms: NC %u's link is down (%s); %u pieces handed out again\n", ms(d.time), d.nc,
                hdlc::link_down_reason_name(d.reason), d.requeued);
}

}  // namespace mc1::cli
