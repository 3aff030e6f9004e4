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

struct SrcLine {
  std::string text;
  Loc loc;  // col 1
  // Appended to messages: the macro expansion chain, shared by the lines of
  // one expansion (its length grows with the nesting depth).
  std::shared_ptr<const std::string> context;
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

// "file:line:col", for messages that point at a second place.
std::string where(const Loc& l);
std::string hex4(unsigned v);  // "0x%04x"

}  // namespace mc1::apuasm::detail
