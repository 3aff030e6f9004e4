// The assembler's view of source text (docs/apu-asm.md, "Lines"): lines with
// their place, pieces of a line with their column, names, comments.
// Internal to apuasm_lib.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "apuasm.hpp"

namespace mc1::apuasm::detail {

// A piece of a source line and the 1-based column of its first character.
struct Piece {
  std::string text;
  int col = 1;
};

// An error at a column of the line being assembled; the pass that catches it
// adds the file and line.
struct LineError {
  int col;
  std::string msg;
};

// One macro invocation in the chain a line was expanded from, innermost
// first; shared by the lines of one expansion.
struct Expansion {
  std::string note;                        // " (in macro 'm' invoked at file:line:col)"
  std::shared_ptr<const Expansion> outer;  // the expansion the invocation is in, or null
  int depth = 1;                           // the invocations in the chain, this one included
};

struct SrcLine {
  std::string text;
  Loc loc;  // col 1
  // The macro expansion chain, for messages (context_text); null outside a macro.
  std::shared_ptr<const Expansion> context;
};

bool ident_start(char c);
bool ident_char(char c);
bool is_space(char c);
bool is_name(const std::string& s);           // ident_start, then ident_char
bool is_register_name(const std::string& s);  // f3, A12, ... (any number)
std::string lower(std::string s);

Piece trim(const Piece& p);
Piece sub(const Piece& p, size_t from, size_t n = std::string::npos);
// Splits at `sep` outside brackets and parentheses; pieces are trimmed.
std::vector<Piece> split(const Piece& p, char sep);
// The end of the run of name characters (ident_char) that starts at `from`.
size_t name_end(const std::string& s, size_t from = 0);

// The text before a `;` or `#` comment (none inside a "string").
std::string strip_comment(const std::string& s);
// `text` as numbered lines of `file` (a trailing '\r' dropped).
std::vector<SrcLine> split_lines(const std::string& text, const std::string& file);
// How many lines split_lines makes of `text`, counted without making them.
size_t line_count(const std::string& text);

// "file:line:col", for messages that point at a second place.
std::string where(const Loc& l);
std::string hex4(unsigned v);  // "0x%04x"

}  // namespace mc1::apuasm::detail
