// Command-line parsing of `mc1` (docs/platform.md "Running it"), on CLI11
// with the project's conventions (host/common/cmdline.hpp): the commands'
// options, and the values CLI11 cannot read alone (sizes, times, dead-link
// windows, fault lists). Errors are CliError (exit 2) naming the option and
// the offending text.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "atomic_file.hpp"
#include "cmdline.hpp"
#include "mc1_system.hpp"

namespace mc1::cli {

using CliError = cmdline::UsageError;

// Declaring a command's options. Values are kept as text and read after
// parsing by the parse_* functions below, which name the option in errors.
// --name VALUE (or --name=VALUE); given twice, the last counts.
CLI::Option* value_option(CLI::App& cmd, const std::string& name, const std::string& type, const std::string& help);
// --name VALUE, repeatable: every value, in the order given.
CLI::Option* list_option(CLI::App& cmd, const std::string& name, const std::string& type, const std::string& help);
CLI::Option* flag_option(CLI::App& cmd, const std::string& name, const std::string& help);
// The files a command reads and writes (cmdline::Files), declared with its
// options: files(cmd).input(value_option(...)), .output(...). run_command
// checks them all before the command runs (an output on an input or on
// another output, an output given twice, one that cannot be written); a
// command that learns more paths later (mc1 sweep's points) adds them and
// checks again.
cmdline::Files& files(const CLI::App& cmd);
// --params FILE and --param key=value, both repeatable.
void add_param_options(CLI::App& cmd);
// The default scene of bench-render and sweep, scenes/whitted.json: the
// installed copy beside this program (<prefix>/bin/mc1 reads
// <prefix>/share/mc1/scenes) where there is one, else the source tree's.
std::string default_scene();
// The timing table: --params and --param applied in the order given, as one
// sequence, then validated.
void apply_params(const CLI::App& cmd, TimingParams& t);
// A share as the printouts give it: 0.765 -> "76.5 %".
std::string pct(double x);

// The options of a parsed command, by name without the dashes.
class Parsed {
 public:
  explicit Parsed(const CLI::App& cmd) : cmd_(cmd) {}
  bool has(const std::string& name) const { return cmd_.count("--" + name) != 0; }
  std::string get(const std::string& name, const std::string& fallback = "") const;
  std::vector<std::string> all(const std::string& name) const;  // repeated options

 private:
  const CLI::App& cmd_;
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
// The faults of a frame command: --ber, --seed, --dead-link, --kill-node,
// --cut-line (the last three repeatable).
void add_fault_options(CLI::App& cmd);
// Reads them into cfg, the NCs named checked against cfg.nodes.
void fault_options(const Parsed& a, SystemConfig& cfg);
// The files a frame command writes: --out, --stats, --gantt, --vcd (outputs in files(cmd)).
void add_report_options(CLI::App& cmd);
// --threads N (SystemConfig::threads).
void add_threads_option(CLI::App& cmd);
void threads_option(const Parsed& a, SystemConfig& cfg);
// "iss" or "rtl".
EngineKind parse_engine(const std::string& text);
// A machine of the default configuration whose NCs can run either engine
// (SystemConfig::engines = make_engine).
SystemConfig machine_config();

// Helpers of the commands.
// The files one run writes, whole or not at all (docs/reliability.md): each
// is staged beside its target as it is made, and commit() renames them all
// into place. A run that fails before commit(), a write that fails included,
// leaves none of them.
class Outputs {
 public:
  void add(const std::string& path, std::string_view bytes);
  void add(const std::string& path, const std::vector<std::uint8_t>& bytes);
  void add(StagedFile&& written);  // a writer's file (writer_output)
  void commit();

 private:
  std::vector<StagedFile> staged_;
};
// --trace's FST and --vcd's VCD: staged before the run (a CliError for a
// path they cannot take), written by their writers under a temporary name.
using cmdline::writer_output;
// --vcd's file, if given, staged in `out`: the path SystemC is to write
// during the run, or "".
std::string stage_vcd(const Parsed& a, Outputs& out);

// The summary's lines on injected faults and the links the RC found down.
void print_faults(const FrameReport& r);

}  // namespace mc1::cli
