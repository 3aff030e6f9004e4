// apu-gtkw-fp24: a GTKWave process filter that shows FP24 words as decimal
// numbers (docs/apu-tools.md "Waveforms"): GTKWave writes each value as it
// prints it (hex, one line each) and reads one line back. A trace's save
// file (apu_trace_files.cpp) names the one beside the program that wrote
// it; docs/apu-core.gtkw names build/bin/apu-gtkw-fp24 (run GTKWave in the
// source tree). A value that is not 1 to 6 hex digits (x, z) comes back as
// it is.
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include "fp24_convert.hpp"

namespace {

std::string translate(const std::string& value) {
  if (value.empty() || value.size() > 6) return value;
  for (char c : value)
    if (!std::isxdigit(static_cast<unsigned char>(c))) return value;
  return mc1::fp24::fp24_decimal(static_cast<std::uint32_t>(std::strtoul(value.c_str(), nullptr, 16)));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1) {
    const bool help = std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0;
    std::fputs("usage: apu-gtkw-fp24 (no arguments)\n"
               "A GTKWave process filter: reads FP24 words in hex, one a line, and writes each as\n"
               "its decimal value (the fewest digits that read back to it), one a line.\n",
               help ? stdout : stderr);
    return help ? 0 : 2;
  }
  std::string line;
  while (std::getline(std::cin, line)) {
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    std::cout << translate(line) << std::endl;  // GTKWave waits for each line
  }
  return 0;
}
