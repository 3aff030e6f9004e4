// The command-line conventions every MC-1 program shares, on CLI11:
// --help and --version print on stdout and exit 0; a usage or input error is
// "PROGRAM: what" on stderr, naming the option or the file, and exit 2; a
// failed check or simulation is exit 1. Numbers are read strictly: decimal or
// 0x hex, inside the option's range, never saturated, wrapped or truncated.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "atomic_file.hpp"

namespace mc1::cmdline {

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;  // a check or a simulation failed
constexpr int kExitUsage = 2;   // bad option, missing or bad input file

// A usage or input error found after parsing; main reports it with exit 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The project's version, from project(... VERSION) in the top CMakeLists.txt.
const char* version();

// --version, and the exit statuses (the program's own words for them, or
// the general rule) as the help's footer.
void conventions(CLI::App& app,
                 const std::string& exit_statuses = "Exit status: 0 done; 1 a check or simulation failed; "
                                                    "2 usage or input error.");

// Parses the command line. Returns the exit status when the program is
// done already (0 after --help or --version, 2 after a usage error, printed),
// nullopt when it should run. Installs mc1::remove_staged_files_on_signals.
std::optional<int> parse(CLI::App& app, int argc, char** argv);

// Prints "PROGRAM: message" and the --help hint on stderr; returns 2.
int usage_error(const CLI::App& app, const std::string& message);

// `text` as an unsigned integer, decimal or 0x hex, in [min, max]; throws
// UsageError "what: ..." otherwise. A leading 0 (C's octal) is refused.
std::uint64_t parse_unsigned(const std::string& what, const std::string& text, std::uint64_t min,
                             std::uint64_t max);
// `text` as a finite decimal number in [min, max].
double parse_real(const std::string& what, const std::string& text, double min, double max);

// Validators for add_option(...)->transform(...): they rewrite the value in
// the form CLI11's own conversion reads exactly (plain decimal), so the
// bound variable gets what parse_unsigned / parse_real read.
CLI::Validator unsigned_in(std::uint64_t min, std::uint64_t max);
CLI::Validator real_in(double min, double max);
// A file that exists, is not a directory and can be read.
CLI::Validator input_file();

// A progress bar's time part, the same in every program: host time elapsed
// and, from the fraction done so far, an estimate of what is left:
// "12 s elapsed, ~30 s left" ("~? left" before anything is done).
std::string progress_times(double elapsed_seconds, double fraction_done);

// Throws UsageError when standard input is a directory (`prog < docs`),
// which a stream would otherwise read as empty.
void require_stdin_not_directory();

// An output that a library writes by name (an FST or VCD writer), staged
// beside `path` before the run (mc1::StagedFile::for_writer): the writer
// writes temp(), and commit() puts it in place once the writer has closed
// it; without commit() it is removed. A path it cannot take (a directory, a
// device, a missing directory, "") is a UsageError naming `option`.
StagedFile writer_output(const std::string& option, const std::string& path, const std::string& suffix = "");

using mc1::NamedPaths;
// mc1::check_distinct_files, its error a UsageError.
void check_distinct(const NamedPaths& inputs, const NamedPaths& outputs);
// mc1::check_writable of each output, its error a UsageError naming the
// option: before a run that writes its outputs at its end.
void check_writable(const NamedPaths& outputs);

// The files a program reads and writes, declared once, where its options are
// added, and checked all together by one call after parsing (docs/reliability.md
// "Output files"): every program uses it.
//   cmdline::Files files;
//   files.input(app.add_option("--vectors", o.vectors, ...), "the vectors");
//   files.output(app.add_option("--json", o.json, ...));
//   files.output(app.add_option("--trace", o.trace, ...), {".gtkw"});  // and TRACE.gtkw
//   ... cmdline::parse(app, argc, argv) ...
//   files.check();  // before anything is read or written
// check() throws UsageError, before the run, when
// - an output option is given more than once (the first file would be lost;
//   outputs_each's options excepted);
// - two outputs name one file, a side file an output implies (an FST's
//   TRACE.gtkw) included, or an output names an input (standard input
//   redirected from a file included, with reads_stdin()): through symbolic
//   and hard links (mc1::check_distinct_files);
// - an output cannot be written (mc1::check_writable): a missing directory
//   is found before the run, not after it.
// An input given as "-" is standard input. Paths known only after parsing
// (an assembly's included files, the files a sweep writes into --out-dir)
// are added with add_input / add_output before check().
class Files {
 public:
  // An option whose values name files the program reads; `role` names them
  // in messages ("--out x.json would replace the scene x.json"); the option's
  // name when empty. `fallback`: the file read when the option is not given.
  CLI::Option* input(CLI::Option* option, const std::string& role = "", const std::string& fallback = "");
  // An option whose value names a file the program writes, and the side
  // files it implies: the value followed by each of `side_suffixes`.
  CLI::Option* output(CLI::Option* option, std::vector<std::string> side_suffixes = {});
  // An output option that may be given more than once, each value a file
  // of its own that the program writes (mc1 render --profile p.md --profile
  // p.json): not refused as repeated; the files are still checked against
  // each other, the inputs and the other outputs.
  CLI::Option* outputs_each(CLI::Option* option, std::vector<std::string> side_suffixes = {});
  void add_input(const std::string& role, const std::string& path);
  void add_output(const std::string& name, const std::string& path);
  // Standard input is read: a regular file redirected to it is an input.
  void reads_stdin() { stdin_ = true; }

  // The files given, after parsing: (role, path) and (option, path) pairs.
  NamedPaths inputs() const;
  NamedPaths outputs() const;
  // The checks above; `writable` false skips the last (a program whose
  // outputs are made before its work, so that a bad path costs nothing).
  void check(bool writable = true) const;

 private:
  struct Declared {
    CLI::Option* option;
    std::string role;
    std::vector<std::string> sides;  // outputs: the side files' suffixes; inputs: {fallback} or {}
    bool each = false;               // outputs: repeatable, a file per value (outputs_each)
  };
  std::vector<Declared> inputs_, outputs_;
  NamedPaths more_inputs_, more_outputs_;
  bool stdin_ = false;
};

// The exit status once standard output is flushed: `status`, or
// kExitFailed, said on stderr as "PROGRAM: standard output: reason", when a
// write to it failed (`> /dev/full`): a report printed there is the output.
int flush_stdout(const std::string& program, int status);

}  // namespace mc1::cmdline
