#include "mc1_cli.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "mc1_engines.hpp"

namespace mc1::cli {

Args::Args(const std::vector<std::string>& args, const std::vector<std::string>& with_value,
           const std::vector<std::string>& flags) {
  auto known = [](const std::vector<std::string>& v, const std::string& n) {
    return std::find(v.begin(), v.end(), n) != v.end();
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string a = args[i];
    if (a.rfind("--", 0) != 0) throw CliError("unexpected argument '" + a + "'");
    std::string name = a.substr(2), value;
    const auto eq = name.find('=');
    const bool inline_value = eq != std::string::npos;
    if (inline_value) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    if (known(flags, name)) {
      if (inline_value) throw CliError("--" + name + " takes no value (got '" + value + "')");
      values_[name].push_back("");
    } else if (known(with_value, name)) {
      if (!inline_value) {
        if (i + 1 >= args.size()) throw CliError("--" + name + ": missing value");
        value = args[++i];
      }
      values_[name].push_back(value);
    } else {
      throw CliError("unknown option '" + a + "' (see --help)");
    }
  }
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
  const auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second.back();
}

const std::vector<std::string>& Args::all(const std::string& name) const {
  static const std::vector<std::string> none;
  const auto it = values_.find(name);
  return it == values_.end() ? none : it->second;
}

unsigned parse_unsigned(const std::string& opt, const std::string& text, unsigned min, unsigned max) {
  char* end = nullptr;
  const unsigned long v = std::strtoul(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || text[0] == '-' || v < min || v > max)
    throw CliError(opt + ": bad value '" + text + "' (expected an integer " + std::to_string(min) + ".." +
                   std::to_string(max) + ")");
  return static_cast<unsigned>(v);
}

double parse_double(const std::string& opt, const std::string& text, double min, double max) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v < min || v > max)
    throw CliError(opt + ": bad value '" + text + "' (expected a number in [" + std::to_string(min) + ", " +
                   std::to_string(max) + "])");
  return v;
}

std::pair<unsigned, unsigned> parse_size(const std::string& opt, const std::string& text, bool square_ok) {
  const auto x = text.find('x');
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

NodeKill parse_kill(const std::string& text) {
  const std::string opt = "--kill-node";
  const auto at = text.find('@');
  if (at == std::string::npos) throw CliError(opt + ": bad value '" + text + "' (expected K@TIME, e.g. 3@20ms)");
  NodeKill k;
  k.nc = parse_unsigned(opt + " (NC)", text.substr(0, at), 1, 1u << 20);
  k.time = parse_time(opt, text.substr(at + 1));
  return k;
}

CutLine parse_cut_line(const std::string& text) {
  const std::string opt = "--cut-line";
  const auto at = text.find('@');
  if (at == std::string::npos) throw CliError(opt + ": bad value '" + text + "' (expected K@TIME, e.g. 3@20ms)");
  CutLine c;
  c.nc = parse_unsigned(opt + " (NC)", text.substr(0, at), 1, 1u << 20);
  c.time = parse_time(opt, text.substr(at + 1));
  return c;
}

void fault_options(const std::vector<std::string>& kills, const std::vector<std::string>& cuts, SystemConfig& cfg) {
  for (const std::string& k : kills) {
    cfg.kills.push_back(parse_kill(k));
    if (cfg.kills.back().nc > cfg.nodes)
      throw CliError("--kill-node " + k + ": the machine has NC 1.." + std::to_string(cfg.nodes));
  }
  for (const std::string& c : cuts) {
    cfg.cut_lines.push_back(parse_cut_line(c));
    if (cfg.cut_lines.back().nc > cfg.nodes)
      throw CliError("--cut-line " + c + ": the machine has NC 1.." + std::to_string(cfg.nodes));
  }
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

bool wants_help(const std::vector<std::string>& args) {
  for (const std::string& a : args)
    if (a == "--help" || a == "-h") return true;
  return false;
}

std::vector<std::string> take_params(TimingParams& t, const std::vector<std::string>& args) {
  try {
    return apply_param_args(t, args);
  } catch (const ParamError& e) {
    throw CliError(e.what());
  }
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out << text;
  if (!out) throw std::runtime_error(path + ": write failed");
}

void print_faults(const FrameReport& r) {
  auto ms = [](Picos t) { return t * 1e-9; };
  for (const KillReport& k : r.kills) std::printf("  NC %u killed at %.3f ms\n", k.nc, ms(k.time));
  for (const CutLineReport& c : r.cut_lines) std::printf("  NC %u's line cut at %.3f ms\n", c.nc, ms(c.time));
  for (const rc::LinkDown& d : r.link_downs)
    std::printf("  %.3f ms: NC %u's link is down (%s); %u pieces handed out again\n", ms(d.time), d.nc,
                hdlc::link_down_reason_name(d.reason), d.requeued);
}

}  // namespace mc1::cli
