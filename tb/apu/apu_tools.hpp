// What apu-run, apu-cosim and apu-bench share: their common options, making
// an engine by name and reading a program file (.apu source through the
// assembler library, or an "APU1" binary image, docs/apu-asm.md).
#pragma once

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "apu_engine.hpp"
#include "apu_icarus_engine.hpp"
#include "apu_iss.hpp"
#include "apu_rtl_engine.hpp"
#include "apu_image.hpp"
#include "apuasm.hpp"
#include "cmdline.hpp"
#include "microword.hpp"

namespace mc1::apu::tools {

inline const std::vector<std::string>& engine_names() {
  static const std::vector<std::string> names = {"iss", "rtl", "icarus"};
  return names;
}

inline CLI::Option* add_program_option(CLI::App& app, std::string& path) {
  return app.add_option("PROGRAM", path, "the program: .apu source, or an APU1 image (apuasm -o)")
      ->check(cmdline::input_file());
}

inline CLI::Option* add_data_option(CLI::App& app, std::vector<std::string>& files) {
  return app
      .add_option("--data", files,
                  "data file (hex words, @ADDR); several form a stream, the next handed over\n"
                  "when the APU has taken the last (SWAPD)")
      ->check(cmdline::input_file())
      ->allow_extra_args(false);
}

inline CLI::Option* add_max_cycles_option(CLI::App& app, std::uint64_t& cycles, const std::string& what) {
  return app.add_option("--max-cycles", cycles, what)->transform(cmdline::unsigned_in(1, UINT64_MAX));
}

// "iss", "rtl" or "icarus" (the core under Icarus Verilog, a vvp child:
// apu_icarus_engine.hpp); `trace` (an FST path) only means something to the
// RTL, `icarus_vvp` (the bench's vvp file; empty: $MC1_ICARUS_VVP, else the
// build's) to Icarus.
inline std::unique_ptr<ApuEngine> make_engine(const std::string& name, const char* trace = nullptr,
                                              const std::string& icarus_vvp = "") {
  if (name == "iss") return std::make_unique<Iss>();
  if (name == "rtl") return std::make_unique<RtlEngine>(trace);
  if (name == "icarus") {
    IcarusEngine::Options o;
    o.vvp_file = icarus_vvp;
    return std::make_unique<IcarusEngine>(o);
  }
  throw std::runtime_error("unknown engine '" + name + "' (iss, rtl or icarus)");
}

inline bool ends_with(const std::string& s, const char* suffix) {
  const std::size_t n = std::strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

inline std::vector<Encoded> load_program_file(const std::string& path) {
  if (ends_with(path, ".apu")) return apuasm::assemble_file(path).words;
  return apu::load_image(path);
}

// A program in .apu source: the files it .includes (each with a line in its
// listing) added to `files` as inputs, so that no output replaces one
// (cmdline::Files). An image includes nothing.
inline void add_included_files(const std::string& path, cmdline::Files& files) {
  if (!ends_with(path, ".apu")) return;
  std::vector<std::string> seen{path};
  for (const auto& line : apuasm::assemble_file(path).listing)
    if (std::find(seen.begin(), seen.end(), line.loc.file) == seen.end()) {
      seen.push_back(line.loc.file);
      files.add_input("the include file", line.loc.file);
    }
}

}  // namespace mc1::apu::tools
