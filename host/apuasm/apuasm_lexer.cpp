// Source lines and the pieces of a line (docs/apu-asm.md, "Lines").
#include "apuasm_lexer.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <sstream>

namespace mc1::apuasm::detail {

bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }

bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; }

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)); }

bool is_name(const std::string& s) {
  return !s.empty() && ident_start(s[0]) && std::all_of(s.begin(), s.end(), ident_char);
}

bool is_register_name(const std::string& s) {
  const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(s.empty() ? ' ' : s[0])));
  return s.size() >= 2 && (c == 'f' || c == 'a') && s.find_first_not_of("0123456789", 1) == std::string::npos;
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

Piece trim(const Piece& p) {
  size_t b = 0, e = p.text.size();
  while (b < e && is_space(p.text[b])) ++b;
  while (e > b && is_space(p.text[e - 1])) --e;
  return {p.text.substr(b, e - b), p.col + static_cast<int>(b)};
}

Piece sub(const Piece& p, size_t from, size_t n) { return {p.text.substr(from, n), p.col + static_cast<int>(from)}; }

std::vector<Piece> split(const Piece& p, char sep) {
  std::vector<Piece> out;
  int depth = 0;
  size_t start = 0;
  for (size_t k = 0; k <= p.text.size(); ++k) {
    const char c = k < p.text.size() ? p.text[k] : sep;
    if (c == '[' || c == '(') ++depth;
    if (c == ']' || c == ')') --depth;
    if (c == sep && (depth <= 0 || k == p.text.size())) {
      out.push_back(trim(sub(p, start, k - start)));
      start = k + 1;
    }
  }
  return out;
}

size_t name_end(const std::string& s, size_t from) {
  while (from < s.size() && ident_char(s[from])) ++from;
  return from;
}

std::string strip_comment(const std::string& s) {
  bool quoted = false;
  for (size_t k = 0; k < s.size(); ++k) {
    if (s[k] == '"') quoted = !quoted;
    if (!quoted && (s[k] == ';' || s[k] == '#')) return s.substr(0, k);
  }
  return s;
}

size_t line_count(const std::string& text) {
  const auto newlines = static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
  return newlines + (!text.empty() && text.back() != '\n' ? 1 : 0);
}

std::vector<SrcLine> split_lines(const std::string& text, const std::string& file) {
  std::vector<SrcLine> out;
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    SrcLine l;
    l.text = line;
    l.loc.file = file;
    l.loc.line = ++n;
    l.loc.col = 1;
    out.push_back(std::move(l));
  }
  return out;
}

std::string where(const Loc& l) { return l.file + ":" + std::to_string(l.line) + ":" + std::to_string(l.col); }

std::string hex4(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04x", v);
  return buf;
}

}  // namespace mc1::apuasm::detail
