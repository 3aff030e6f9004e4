// The assembler's text outputs (docs/apu-asm.md, "Output"): the listing,
// Verilog $readmemh text and the disassembly of an image.
#include <cstdio>

#include "apuasm.hpp"
#include "disasm.hpp"

namespace mc1::apuasm {
namespace {

std::string address_column(int addr) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%04x", static_cast<unsigned>(addr));
  return buf;
}

}  // namespace

std::string readmemh_text(const std::vector<apu::Encoded>& words) {
  std::string out;
  for (const auto& w : words) {
    std::string h = apu::encoding_hex(w);
    h.erase(16, 1);  // the '_' between hi and lo
    out += h + "\n";
  }
  return out;
}

std::string listing_text(const Program& p) {
  const std::string blank(4 + 2 + 33, ' ');
  std::string out;
  for (const auto& l : p.listing) {
    if (l.addr >= 0) {
      out += address_column(l.addr) + "  " + apu::encoding_hex(p.words[static_cast<size_t>(l.addr)]) + "  ";
    } else {
      out += blank + "  ";
    }
    out += l.text + "\n";
  }
  return out;
}

std::string disassembly_text(const std::vector<apu::Encoded>& words) {
  std::string out;
  for (size_t k = 0; k < words.size(); ++k)
    out += address_column(static_cast<int>(k)) + "  " + apu::encoding_hex(words[k]) + "  " +
           apu::disassemble(words[k]) + "\n";
  return out;
}

}  // namespace mc1::apuasm
