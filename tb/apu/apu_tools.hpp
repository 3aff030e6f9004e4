// What apu-run, apu-cosim and apu-bench share: making an engine by name and
// reading a program file (.apu source through the assembler library, or an
// "APU1" binary image, docs/apu-asm.md).
#pragma once

#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "apu_engine.hpp"
#include "apu_iss.hpp"
#include "microword.hpp"
#ifdef MC1_HAVE_RTL_ENGINE
#include "apu_rtl_engine.hpp"
#endif
#ifdef MC1_HAVE_APUASM
#include "apuasm.hpp"
#endif

namespace mc1::apu::tools {

inline bool rtl_available() {
#ifdef MC1_HAVE_RTL_ENGINE
  return true;
#else
  return false;
#endif
}

// "iss" or "rtl"; `trace` (an FST path) only means something to the RTL.
inline std::unique_ptr<ApuEngine> make_engine(const std::string& name, const char* trace = nullptr) {
  if (name == "iss") return std::make_unique<Iss>();
  if (name == "rtl") {
#ifdef MC1_HAVE_RTL_ENGINE
    return std::make_unique<RtlEngine>(trace);
#else
    (void)trace;
    throw std::runtime_error("engine 'rtl': this build has no RTL engine (apu_rtl_engine was not built)");
#endif
  }
  throw std::runtime_error("unknown engine '" + name + "' (iss or rtl)");
}

inline bool ends_with(const std::string& s, const char* suffix) {
  const std::size_t n = std::strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

// An "APU1" image: magic, word count (u32 LE), then lo and hi (u64 LE) per word.
inline std::vector<Encoded> parse_apu1(const std::string& bytes, const std::string& name) {
  auto u64 = [&](std::size_t at) {
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  if (bytes.size() < 8 || bytes.compare(0, 4, "APU1") != 0)
    throw std::runtime_error(name + ": not an APU1 program image");
  std::uint32_t n = 0;
  for (int i = 3; i >= 0; --i) n = n << 8 | static_cast<unsigned char>(bytes[4 + i]);
  if (n > static_cast<std::uint32_t>(kProgramWords) || bytes.size() != 8 + 16ull * n)
    throw std::runtime_error(name + ": image of " + std::to_string(n) + " words has " +
                             std::to_string(bytes.size()) + " bytes");
  std::vector<Encoded> words(n);
  for (std::uint32_t i = 0; i < n; ++i) words[i] = {u64(8 + 16 * i), u64(16 + 16 * i)};
  return words;
}

inline std::vector<Encoded> load_program_file(const std::string& path) {
#ifdef MC1_HAVE_APUASM
  if (ends_with(path, ".apu")) return apuasm::assemble_file(path).words;
  return apuasm::load_image(path);
#else
  if (ends_with(path, ".apu"))
    throw std::runtime_error(path + ": this build has no assembler library (apuasm_lib) to read .apu sources");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_apu1(bytes, path);
#endif
}

}  // namespace mc1::apu::tools
