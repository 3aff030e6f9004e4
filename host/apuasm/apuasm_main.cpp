// apuasm: the APU assembler and image disassembler (docs/apu-asm.md).
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

#include "apu_image.hpp"
#include "apuasm.hpp"

namespace {

const char kUsage[] =
    "usage: apuasm [-o image.bin] [-l listing.lst] [-x image.hex] source.apu\n"
    "       apuasm -d image.bin\n"
    "\n"
    "Assembles APU microcode (docs/apu-asm.md) into a binary image.\n"
    "  -o FILE   image to write (default: the source name with .bin)\n"
    "  -l FILE   also write a listing: address, 128-bit encoding, source line\n"
    "  -x FILE   also write the image as Verilog $readmemh text (32 hex digits a word)\n"
    "  -d FILE   disassemble a binary image to standard output instead\n"
    "  --help    show this text\n"
    "Errors go to standard error as file:line:col: error: message; exit status 1.\n";

bool write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) std::cerr << "apuasm: " << path << ": cannot write\n";
  return static_cast<bool>(out);
}

int usage_error(const std::string& msg) {
  std::cerr << "apuasm: " << msg << "\n" << kUsage;
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::string source, image, listing, hex, disasm;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    auto value = [&](std::string& dst) {
      if (k + 1 >= argc) return false;
      dst = argv[++k];
      return true;
    };
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return 0;
    } else if (a == "-o") {
      if (!value(image)) return usage_error("-o needs a file name");
    } else if (a == "-l") {
      if (!value(listing)) return usage_error("-l needs a file name");
    } else if (a == "-x") {
      if (!value(hex)) return usage_error("-x needs a file name");
    } else if (a == "-d") {
      if (!value(disasm)) return usage_error("-d needs a file name");
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + a + "'");
    } else if (source.empty()) {
      source = a;
    } else {
      return usage_error("more than one source file");
    }
  }

  try {
    if (!disasm.empty()) {
      if (!source.empty()) return usage_error("-d takes no source file");
      std::cout << mc1::apuasm::disassembly_text(mc1::apu::load_image(disasm));
      return 0;
    }
    if (source.empty()) return usage_error("no source file");
    if (image.empty()) {
      const auto dot = source.find_last_of('.');
      const auto slash = source.find_last_of('/');
      const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
      image = (has_ext ? source.substr(0, dot) : source) + ".bin";
    }
    const auto program = mc1::apuasm::assemble_file(source);
    mc1::apu::write_image(image, program.words);
    if (!listing.empty() && !write_text(listing, mc1::apuasm::listing_text(program))) return 1;
    if (!hex.empty() && !write_text(hex, mc1::apuasm::readmemh_text(program.words))) return 1;
    return 0;
  } catch (const mc1::apuasm::AsmError& e) {
    for (const auto& d : e.diagnostics()) std::cerr << d.str() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "apuasm: " << e.what() << "\n";
    return 1;
  }
}
