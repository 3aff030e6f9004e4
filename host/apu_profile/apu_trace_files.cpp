// The files beside an FST trace of the RTL core (apu_trace_files.hpp).
#include "apu_trace_files.hpp"

#include <unistd.h>

#include <algorithm>
#include <sstream>

namespace mc1::apu {

extern const char* const kApuCoreGtkw;  // docs/apu-core.gtkw (apu_core_gtkw.cpp, generated)

namespace {

// Where docs/apu-core.gtkw finds the enum filters and the FP24 process
// filter (relative to the source tree).
const std::string kFilterDir = "build/generated/gtkwave/";
const std::string kFp24Filter = "build/bin/apu-gtkw-fp24";

// The FP24 process filter beside the running program (build/bin, or the
// installed bin directory); the source tree's path if there is none.
std::string fp24_filter() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return kFp24Filter;
  std::string dir(buf, static_cast<std::size_t>(n));
  dir.erase(dir.rfind('/') + 1);
  return access((dir + "apu-gtkw-fp24").c_str(), X_OK) == 0 ? dir + "apu-gtkw-fp24" : kFp24Filter;
}

std::string absolute(const std::string& path) {
  if (!path.empty() && path[0] == '/') return path;
  char buf[4096];
  if (!getcwd(buf, sizeof buf)) return path;
  return std::string(buf) + "/" + path;
}

// The first marker's time in a gtkw_markers() text ("*-zoom A B ..."), or -1.
long long first_marker(const std::string& markers) {
  const auto star = markers.find("\n*-");
  if (star == std::string::npos) return -1;
  std::istringstream f(markers.substr(star + 1));
  std::string zoom;
  long long t = -1;
  f >> zoom >> t;
  return t;
}

// The MPU's side (TOP.mc1.*, hw/apu_rtl_engine/apu_trace_top.sv) as a group:
// the NC's processor in mc1 render, in apu-run the tool that loads the
// banks. Its title is short: GTKWave sizes the signal pane's name column to
// the longest label, and a long one leaves no room for the values.
std::string mpu_group(const std::string& filter_prefix) {
  const std::string title = "-MPU";
  return "@800200\n" + title + "\n@2022\n^17 " + filter_prefix + "mpu_doing.txt\nTOP.mc1.mpu_doing[3:0]\n" +
         "@2022\n^18 " + filter_prefix + "mpu_step.txt\nTOP.mc1.mpu_step[15:0]\n" +
         "@24\nTOP.mc1.mpu_detail[31:0]\nTOP.mc1.mpu_words_left[15:0]\nTOP.mc1.mpu_block[31:0]\n" +
         "@28\nTOP.mc1.bank_req\nTOP.mc1.bank_grant\nTOP.mc1.swap_wait\nTOP.mc1.hdlc_wait\nTOP.mc1.bus_wait\n" +
         "@1000200\n" + title + "\n";
}

}  // namespace

std::string trace_save_file(const std::string& trace, const std::string& kpc_filter,
                            const std::string& kernel_filter, const std::string& markers,
                            const std::string& writer, const std::string& enum_filter_prefix) {
  std::string out = "[*] GTKWave save file written by " + writer + " for " + trace + "\n[dumpfile] \"" + trace + "\"\n";
  out += markers;
  // The view opens 1 us (4 cycles) before the first marker (the top stall site).
  const long long marker = first_marker(markers);
  const long long start = marker < 0 ? 0 : std::max(0LL, marker - 1000000);
  std::istringstream lines(kApuCoreGtkw);
  std::string line, flags;  // flags: the last "@..." line, which holds for the signals after it
  bool restore = false;     // a signal was added: the next signal needs `flags` again
  const std::string rel = kFilterDir;
  const auto add_signal = [&](int filter_no, const std::string& filter, const std::string& name) {
    out += "@2022\n^" + std::to_string(filter_no) + " " + filter + "\n" + name + "\n";  // hex, filtered
    restore = true;
  };
  int sequencer = 0;  // "-Sequencer" lines seen: the second closes its group
  const std::string fp24 = fp24_filter();
  while (std::getline(lines, line)) {
    if (marker >= 0 && line.rfind("*-", 0) == 0) continue;  // the markers' line replaces the zoom line
    if (line.rfind("[timestart]", 0) == 0) line = "[timestart] " + std::to_string(start);
    if (line.size() > 1 && line[0] == '^' && line.find(rel) != std::string::npos)
      line.replace(line.find(rel), rel.size(), enum_filter_prefix);
    if (line.rfind("^>", 0) == 0 && line.find(kFp24Filter) != std::string::npos)
      line.replace(line.find(kFp24Filter), kFp24Filter.size(), fp24);
    if (line.rfind("@", 0) == 0) flags = line;
    else if (restore && !flags.empty()) out += flags + "\n";
    restore = false;
    out += line + "\n";
    if (line == "-Sequencer" && out.find("TOP.mc1.kernel_id") == std::string::npos)
      add_signal(16, kernel_filter, "TOP.mc1.kernel_id[15:0]");
    if (line == "-Sequencer" && ++sequencer == 2) {
      out += mpu_group(enum_filter_prefix);
      restore = true;
    }
    if (line == "TOP.apu_core.pc[9:0]") add_signal(15, kpc_filter, "TOP.mc1.kpc[27:0]");
  }
  return out;
}

std::vector<std::string> trace_side_suffixes() {
  std::vector<std::string> suffixes = {".kernel.txt", ".kpc.txt"};
  const std::string base = kApuCoreGtkw;
  for (const auto& [name, text] : enum_filters())  // the ones the save file names
    if (base.find(kFilterDir + name + ".txt") != std::string::npos) suffixes.push_back("." + name + ".txt");
  suffixes.push_back(".mpu_doing.txt");
  suffixes.push_back(".mpu_step.txt");
  suffixes.push_back(".gtkw");
  return suffixes;
}

std::vector<std::pair<std::string, std::string>> trace_side_files(const std::string& trace, const KernelTable& kernels,
                                                                  const std::string& markers,
                                                                  const std::string& writer, const MpuFilters& mpu) {
  const std::string abs = absolute(trace);
  std::vector<std::pair<std::string, std::string>> files;
  for (const std::string& suffix : trace_side_suffixes()) {  // each suffix's text
    std::string text;
    if (suffix == ".kernel.txt") text = kernels.id_filter();
    else if (suffix == ".kpc.txt") text = kernels.kpc_filter();
    else if (suffix == ".mpu_doing.txt") text = mpu.doing.empty() ? "# no MPU side traced\n" : mpu.doing;
    else if (suffix == ".mpu_step.txt") text = mpu.step.empty() ? "# no MPU side traced\n" : mpu.step;
    else if (suffix == ".gtkw") text = trace_save_file(abs, abs + ".kpc.txt", abs + ".kernel.txt", markers, writer, abs + ".");
    else
      for (const auto& [name, filter] : enum_filters())
        if (suffix == "." + name + ".txt") text = filter;
    files.emplace_back(trace + suffix, std::move(text));
  }
  return files;
}

}  // namespace mc1::apu
