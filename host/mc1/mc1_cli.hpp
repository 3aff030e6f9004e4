// Command-line parsing of `mc1` (docs/platform.md "Running it"): option
// values, sizes, times, dead-link windows. Errors are CliError naming the
// option and the offending text.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "mc1_system.hpp"

namespace mc1::cli {

class CliError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `--name value` or `--name=value`; flags without a value. Anything not
// declared is an error naming it.
class Args {
 public:
  Args(const std::vector<std::string>& args, const std::vector<std::string>& with_value,
       const std::vector<std::string>& flags);
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  std::string get(const std::string& name, const std::string& fallback = "") const;
  const std::vector<std::string>& all(const std::string& name) const;  // repeated options

 private:
  std::map<std::string, std::vector<std::string>> values_;
};

unsigned parse_unsigned(const std::string& opt, const std::string& text, unsigned min, unsigned max);
double parse_double(const std::string& opt, const std::string& text, double min, double max);
// "WxH" (or "N" for N x N when square_ok).
std::pair<unsigned, unsigned> parse_size(const std::string& opt, const std::string& text, bool square_ok);
// "12.5ms", "300us", "2s", "1500ns", "7ps"; a bare number is milliseconds.
Picos parse_time(const std::string& opt, const std::string& text);
// "NC@T0-T1", e.g. "3@1ms-4ms".
DeadLink parse_dead_link(const std::string& text);
// A list "16,256".
std::vector<unsigned> parse_list(const std::string& opt, const std::string& text, unsigned min, unsigned max);
// "K@TIME", e.g. "3@20ms": NC K's processor stops at TIME.
NodeKill parse_kill(const std::string& text);
// "K@TIME", e.g. "3@20ms": both directions of NC K's line carry nothing from TIME on.
CutLine parse_cut_line(const std::string& text);
// The --kill-node and --cut-line options of a frame command, checked against cfg.nodes.
void fault_options(const std::vector<std::string>& kills, const std::vector<std::string>& cuts, SystemConfig& cfg);
// "iss" or "rtl".
EngineKind parse_engine(const std::string& text);
// A machine of the default configuration whose NCs can run either engine
// (SystemConfig::engines = make_engine).
SystemConfig machine_config();

// Helpers of the commands.
bool wants_help(const std::vector<std::string>& args);
// The timing table first (it consumes --param/--params); returns the rest.
std::vector<std::string> take_params(TimingParams& t, const std::vector<std::string>& args);
void write_text(const std::string& path, const std::string& text);
// The summary's lines on injected faults and the links the RC found down.
void print_faults(const FrameReport& r);

}  // namespace mc1::cli
