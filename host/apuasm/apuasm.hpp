// The APU assembler as a library (docs/apu-asm.md): source text to microwords,
// listings, $readmemh text, disassembly. The `apuasm` program and the
// co-simulator go through this interface; the binary image format is the
// APU's own (hw/apu/apu_image.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "microword.hpp"

namespace mc1::apuasm {

// A place in a source file; line and col count from 1 (col in bytes).
struct Loc {
  std::string file;
  int line = 0;
  int col = 0;
};

struct Diagnostic {
  Loc loc;
  std::string message;
  std::string str() const;  // "file:line:col: error: message" (GNU style)
};

// Every error of one assembly run; what() is their str() lines joined by '\n'.
class AsmError : public std::runtime_error {
 public:
  explicit AsmError(std::vector<Diagnostic> diags);
  const std::vector<Diagnostic>& diagnostics() const { return diags_; }

 private:
  std::vector<Diagnostic> diags_;
};

// One source line as the assembler saw it (after .include and macro
// expansion), for the listing.
struct ListingLine {
  Loc loc;            // col unused
  std::string text;   // the line as written (macro lines after substitution)
  int addr = -1;      // the word this line emits, or -1
  int depth = 0;      // 0: top file; >0: inside .include or macro expansion
};

struct Program {
  std::vector<apu::Encoded> words;           // address 0 .. highest emitted address
  std::map<std::string, std::int64_t> symbols;  // labels and .equ constants
  std::vector<ListingLine> listing;
};

// An assembly stops at this many errors (and says so in one more): a macro
// expanded thousands of times would otherwise repeat one error per expansion,
// megabytes of diagnostics that each carry the whole chain of invocations.
constexpr std::size_t kMaxErrors = 100;

// A source file (the one assembled, or one it includes) is read up to this
// size and refused beyond it ("cannot read file: larger than 16 MiB"): the
// largest kernel is 20 kB, and reading /dev/zero would otherwise never end.
constexpr std::size_t kMaxSourceBytes = std::size_t{16} << 20;
// And the text assembled has at most this many lines ("FILE: error: more
// than 65536 lines"), 64 for each word a program can hold: the assembler
// keeps some 170 bytes a line: 16 MiB of empty lines took 2.8 GB.
// An included file's lines count against the limit of expansions instead
// (kMaxExpandedLines, docs/apu-asm.md "Limits").
constexpr std::size_t kMaxSourceLines = 65536;

// Assembles `source`; `filename` names it in diagnostics, and .include paths
// are relative to its directory. Throws AsmError listing every error found
// (the first kMaxErrors).
Program assemble(const std::string& source, const std::string& filename = "<input>");
// Reads the file `path` (at most kMaxSourceBytes) and assembles it.
Program assemble_file(const std::string& path);

// The listing: "AAAA  hhhhhhhhhhhhhhhh_llllllllllllllll  source" per emitting
// line, blank address and encoding columns for the others.
std::string listing_text(const Program& p);

// Verilog $readmemh text: one word per line, 32 hex digits, bit 127 first.
std::string readmemh_text(const std::vector<apu::Encoded>& words);

// "AAAA  hhhhhhhhhhhhhhhh_llllllllllllllll  disassembly" per word.
std::string disassembly_text(const std::vector<apu::Encoded>& words);

}  // namespace mc1::apuasm
