#include "cmdline.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>

namespace mc1::cmdline {
namespace {

std::string quoted(const std::string& s) { return "'" + s + "'"; }

std::string range_text(std::uint64_t min, std::uint64_t max) {
  return "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
}

std::string real_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

int digit_value(char c, int base) {
  int d = -1;
  if (c >= '0' && c <= '9') d = c - '0';
  else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
  else if (c >= 'A' && c <= 'F') d = c - 'A' + 10;
  return d < base ? d : -1;
}

// Empty on success (value in `out`), else why `text` is not acceptable.
std::string read_unsigned(const std::string& text, std::uint64_t min, std::uint64_t max, std::uint64_t& out) {
  const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
  const int base = hex ? 16 : 10;
  const std::size_t from = hex ? 2 : 0;
  if (text.size() == from) return quoted(text) + " is not a number";
  if (!hex && text.size() > 1 && text[0] == '0')
    return quoted(text) + ": a leading 0 is not read (C would read octal); write decimal or 0x hex";
  std::uint64_t v = 0;
  bool overflow = false;
  for (std::size_t i = from; i < text.size(); ++i) {
    const int d = digit_value(text[i], base);
    if (d < 0) return quoted(text) + " is not a number (decimal, or hex with 0x)";
    if (v > (UINT64_MAX - static_cast<std::uint64_t>(d)) / base) overflow = true;
    v = v * base + static_cast<std::uint64_t>(d);
  }
  if (overflow || v < min || v > max) return quoted(text) + " is out of range " + range_text(min, max);
  out = v;
  return "";
}

std::string read_real(const std::string& text, double min, double max, double& out) {
  char* end = nullptr;
  errno = 0;
  const double v = text.empty() ? 0 : std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || std::isspace(static_cast<unsigned char>(text[0])))
    return quoted(text) + " is not a number";
  if (!std::isfinite(v) || errno == ERANGE || v < min || v > max)
    return quoted(text) + " is out of range [" + real_text(min) + ", " + real_text(max) + "]";
  out = v;
  return "";
}

}  // namespace

const char* version() { return MC1_VERSION; }

void conventions(CLI::App& app, const std::string& exit_statuses) {
  app.set_version_flag("--version", app.get_name() + " (MC-1 virtual platform) " + version(),
                       "print the version and exit");
  app.footer(exit_statuses);
  app.get_formatter()->column_width(24);
}

std::optional<int> parse(CLI::App& app, int argc, char** argv) {
  remove_staged_files_on_signals();  // a program: Ctrl-C leaves no temporary file
  try {
    app.parse(argc, argv);
    return std::nullopt;
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return usage_error(app, e.what());
  }
}

int usage_error(const CLI::App& app, const std::string& message) {
  std::cerr << app.get_name() << ": " << message << "\nRun with --help for more information.\n";
  return kExitUsage;
}

std::uint64_t parse_unsigned(const std::string& what, const std::string& text, std::uint64_t min,
                             std::uint64_t max) {
  std::uint64_t v = 0;
  const std::string err = read_unsigned(text, min, max, v);
  if (!err.empty()) throw UsageError(what + ": " + err);
  return v;
}

double parse_real(const std::string& what, const std::string& text, double min, double max) {
  double v = 0;
  const std::string err = read_real(text, min, max, v);
  if (!err.empty()) throw UsageError(what + ": " + err);
  return v;
}

CLI::Validator unsigned_in(std::uint64_t min, std::uint64_t max) {
  return CLI::Validator(
      [min, max](std::string& text) {
        std::uint64_t v = 0;
        std::string err = read_unsigned(text, min, max, v);
        if (err.empty()) text = std::to_string(v);
        return err;
      },
      range_text(min, max));  // help: UINT:[min, max]
}

CLI::Validator real_in(double min, double max) {
  return CLI::Validator(
      [min, max](std::string& text) {
        double v = 0;
        return read_real(text, min, max, v);
      },
      "[" + real_text(min) + ", " + real_text(max) + "]");  // help: FLOAT:[min, max]
}

CLI::Validator input_file() {
  return CLI::Validator(
      [](std::string& path) -> std::string {
        struct stat st {};
        if (::stat(path.c_str(), &st) != 0) return path + ": " + std::strerror(errno);
        if (S_ISDIR(st.st_mode)) return path + ": is a directory, not a file";
        if (::access(path.c_str(), R_OK) != 0) return path + ": " + std::strerror(errno);
        return "";
      },
      "FILE");
}

void require_stdin_not_directory() {
  struct stat st {};
  if (::fstat(0, &st) == 0 && S_ISDIR(st.st_mode))
    throw UsageError("standard input is a directory, not a file");
}

std::string progress_times(double elapsed_seconds, double fraction_done) {
  auto span = [](double s) {
    char b[32];
    if (s < 60) std::snprintf(b, sizeof b, "%.0f s", s);
    else if (s < 3600) std::snprintf(b, sizeof b, "%d min %02d s", int(s) / 60, int(s) % 60);
    else std::snprintf(b, sizeof b, "%d h %02d min", int(s) / 3600, int(s) / 60 % 60);
    return std::string(b);
  };
  std::string t = span(elapsed_seconds) + " elapsed, ";
  if (fraction_done <= 0 || !std::isfinite(fraction_done)) return t + "~? left";
  const double left = fraction_done >= 1 ? 0 : elapsed_seconds * (1 - fraction_done) / fraction_done;
  return t + "~" + span(left) + " left";
}

StagedFile writer_output(const std::string& option, const std::string& path, const std::string& suffix) {
  if (path.empty()) throw UsageError(option + " needs a file name");
  try {
    return StagedFile::for_writer(path, suffix);
  } catch (const std::runtime_error& e) {
    throw UsageError(option + ": " + e.what());
  }
}

void check_distinct(const NamedPaths& inputs, const NamedPaths& outputs) {
  try {
    check_distinct_files(inputs, outputs);
  } catch (const std::runtime_error& e) {
    throw UsageError(e.what());
  }
}

void check_writable(const NamedPaths& outputs) {
  for (const auto& [option, path] : outputs) {
    if (path.empty()) throw UsageError(option + " needs a file name");
    try {
      mc1::check_writable(path);
    } catch (const std::runtime_error& e) {
      throw UsageError(option + ": " + e.what());
    }
  }
}

CLI::Option* Files::input(CLI::Option* option, const std::string& role, const std::string& fallback) {
  std::vector<std::string> fallbacks;
  if (!fallback.empty()) fallbacks.push_back(fallback);
  inputs_.push_back({option, role.empty() ? option->get_name() : role, fallbacks});
  return option;
}

CLI::Option* Files::output(CLI::Option* option, std::vector<std::string> side_suffixes) {
  outputs_.push_back({option, option->get_name(), std::move(side_suffixes)});
  return option;
}

CLI::Option* Files::outputs_each(CLI::Option* option, std::vector<std::string> side_suffixes) {
  outputs_.push_back({option, option->get_name(), std::move(side_suffixes), true});
  return option;
}

void Files::add_input(const std::string& role, const std::string& path) { more_inputs_.emplace_back(role, path); }

void Files::add_output(const std::string& name, const std::string& path) { more_outputs_.emplace_back(name, path); }

NamedPaths Files::inputs() const {
  NamedPaths in;
  for (const Declared& d : inputs_)
    for (const std::string& path : d.option->count() ? d.option->results() : d.sides)
      if (!path.empty() && path != "-") in.emplace_back(d.role, path);
  in.insert(in.end(), more_inputs_.begin(), more_inputs_.end());
  // A regular file redirected to standard input (a pipe or a terminal is
  // never one): /dev/stdin stats as that file.
  if (stdin_) in.emplace_back("standard input", "/dev/stdin");
  return in;
}

NamedPaths Files::outputs() const {
  NamedPaths out;
  for (const Declared& d : outputs_)
    for (const std::string& path : d.option->results()) {
      out.emplace_back(d.role, path);
      for (const std::string& suffix : d.sides) out.emplace_back(d.role + "'s side file", path + suffix);
    }
  out.insert(out.end(), more_outputs_.begin(), more_outputs_.end());
  return out;
}

void Files::check(bool writable) const {
  for (const Declared& d : outputs_) {
    const std::vector<std::string>& given = d.option->results();
    if (given.size() < 2 || d.each) continue;
    std::string list;
    for (const std::string& path : given) list += (list.empty() ? "" : ", ") + path;
    throw UsageError(d.role + " is given " + std::to_string(given.size()) + " times (" + list +
                     "): the last would replace the others; name one file");
  }
  const NamedPaths out = outputs();
  check_distinct(inputs(), out);
  if (writable) check_writable(out);
}

int flush_stdout(const std::string& program, int status) {
  errno = 0;
  std::cout.flush();
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout;
  if (!failed) return status;
  std::fprintf(stderr, "%s: standard output: %s\n", program.c_str(), errno ? std::strerror(errno) : "write error");
  return kExitFailed;
}

}  // namespace mc1::cmdline
