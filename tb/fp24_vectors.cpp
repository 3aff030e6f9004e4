// Vector-line parsing: strict, because a silently mis-read operand would
// make every engine "agree" on the wrong question.
#include "fp24_vectors.hpp"

#include <cctype>
#include <cstdint>
#include <cstdio>

namespace mc1::fp24::tb {
namespace {

// A vector or golden line is a few dozen bytes; these bound what a stream
// that never ends (/dev/zero, a FIFO) can make a reader hold before it
// starts: the limits of fp24-regress --vectors.
constexpr std::size_t kMaxLineBytes = 4096;                        // the newline not counted
constexpr std::uint64_t kMaxStreamBytes = std::uint64_t{1} << 30;  // 1 GiB

// Calls each(line, line_no) for every line of `in`, each at most
// kMaxLineBytes and all together at most kMaxStreamBytes: past either a
// VectorError SOURCE:LINE, nothing read beyond that line (a line too long
// is read to its byte past the limit).
template <class Each>
void for_each_line(std::istream& in, const std::string& source, Each each) {
  std::vector<char> line(kMaxLineBytes + 1);
  std::uint64_t bytes = 0;
  long line_no = 1;
  for (; in.getline(line.data(), std::streamsize(line.size())); ++line_no) {
    const std::size_t length = std::size_t(in.gcount()) - (in.eof() ? 0 : 1);  // without the newline
    if ((bytes += std::uint64_t(in.gcount())) > kMaxStreamBytes)
      throw VectorError(source + ":" + std::to_string(line_no) + ": over " + std::to_string(kMaxStreamBytes >> 30) +
                        " GiB read, the limit of a vector file");
    each(std::string_view(line.data(), length), line_no);
  }
  if (!in.eof() && !in.bad())  // getline stopped at the limit, not at a newline
    throw VectorError(source + ":" + std::to_string(line_no) + ": line longer than " +
                      std::to_string(kMaxLineBytes) + " bytes (not a vector file?)");
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

[[noreturn]] void fail(const std::string& source, long line_no, const std::string& what) {
  throw VectorError(source + ":" + std::to_string(line_no) + ": " + what);
}

// A hex operand no larger than `max`; more than 8 digits is out of range
// whatever they are, which also keeps the accumulation from overflowing.
Bits parse_hex(std::string_view token, Bits max, const char* what, const std::string& source, long line_no) {
  const std::string quoted = "'" + std::string(token) + "'";
  std::uint64_t v = 0;
  for (char c : token) {
    if (!std::isxdigit(static_cast<unsigned char>(c))) fail(source, line_no, std::string(what) + " " + quoted + " is not hex");
    const int digit = std::isdigit(static_cast<unsigned char>(c)) ? c - '0' : std::tolower(c) - 'a' + 10;
    v = v * 16 + std::uint64_t(digit);
    if (v > max) break;
  }
  if (v > max) {
    char limit[16];
    std::snprintf(limit, sizeof limit, "%x", max);
    fail(source, line_no, std::string(what) + " " + quoted + " is out of range (max " + limit + ")");
  }
  return Bits(v);
}

std::string lower(std::string_view text) {
  std::string s(text);
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// `text` without a 0x/0X prefix: golden files may carry one.
std::string_view strip_0x(std::string_view text) {
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) return text.substr(2);
  return text;
}

// The tokens before a `#` that starts a token (a golden file's trailing comment).
std::vector<std::string_view> before_comment(std::vector<std::string_view> tokens) {
  for (std::size_t i = 0; i < tokens.size(); ++i)
    if (tokens[i][0] == '#') return {tokens.begin(), tokens.begin() + std::ptrdiff_t(i)};
  return tokens;
}

// `op a [b]` and `trailing` more tokens (0: the vector interface, 2: a
// golden line's result and flags); the operands of tokens[1..].
Issue parse_issue(const std::vector<std::string_view>& tokens, bool golden, int trailing, const std::string& source,
                  long line_no) {
  const std::optional<Op> op = op_from_name(golden ? lower(tokens[0]) : std::string(tokens[0]));
  if (!op) fail(source, line_no, "unknown op '" + std::string(tokens[0]) + "'");
  const OpInfo& info = fp24::info(*op);
  const int operands = int(tokens.size()) - 1 - trailing;
  if (golden && operands != info.operands) {
    fail(source, line_no, std::string(info.name) + " wants " + std::to_string(info.operands) +
                              " operand(s), a result and flags: " + std::to_string(1 + info.operands + 2) +
                              " fields, got " + std::to_string(tokens.size()));
  }
  if (operands < info.operands) {
    fail(source, line_no, std::string(info.name) + " needs " + std::to_string(info.operands) + " operand(s), got " +
                              std::to_string(operands));
  }
  if (operands > info.operands) {
    fail(source, line_no, "extra operand '" + std::string(tokens[1 + info.operands]) + "' after " +
                              std::string(info.name) + " (takes " + std::to_string(info.operands) + ")");
  }
  auto hex = [&](std::string_view t, Bits max, const char* what) {
    return parse_hex(golden ? strip_0x(t) : t, max, what, source, line_no);
  };
  const Bits max_a = *op == Op::Float ? 0xFFFF : 0xFFFFFF;
  Issue v{*op, hex(tokens[1], max_a, "operand"), 0};
  if (info.operands == 2) v.b = hex(tokens[2], 0xFFFFFF, "operand");
  return v;
}

}  // namespace

Bits result_max(Op op) {
  if (op == Op::Cmp) return 0xF;
  if (op == Op::Fix) return 0xFFFF;
  return 0xFFFFFF;
}

std::optional<Issue> parse_vector(std::string_view line, const std::string& source, long line_no) {
  const std::vector<std::string_view> tokens = split(line);
  if (tokens.empty() || tokens[0][0] == '#') return std::nullopt;
  return parse_issue(tokens, false, 0, source, line_no);
}

std::optional<Golden> parse_golden(std::string_view line, const std::string& source, long line_no,
                                   bool expected_optional) {
  const std::vector<std::string_view> tokens = before_comment(split(line));
  if (tokens.empty()) return std::nullopt;
  const std::optional<Op> op = op_from_name(lower(tokens[0]));
  const bool bare = expected_optional && op && int(tokens.size()) == 1 + info(*op).operands;
  Golden g{parse_issue(tokens, true, bare ? 0 : 2, source, line_no), {0, 0}, line_no, !bare};
  if (bare) return g;
  const std::size_t n = tokens.size();
  g.expected.value = parse_hex(strip_0x(tokens[n - 2]), result_max(g.vector.op), "result", source, line_no);
  g.expected.flags = std::uint8_t(parse_hex(strip_0x(tokens[n - 1]), kFlagMask, "flags", source, line_no));
  return g;
}

std::vector<Golden> read_golden(std::istream& in, const std::string& source, bool expected_optional) {
  std::vector<Golden> vectors;
  for_each_line(in, source, [&](std::string_view line, long line_no) {
    if (std::optional<Golden> g = parse_golden(line, source, line_no, expected_optional)) vectors.push_back(*g);
  });
  return vectors;
}

std::vector<Issue> read_vectors(std::istream& in, const std::string& source) {
  std::vector<Issue> vectors;
  for_each_line(in, source, [&](std::string_view line, long line_no) {
    if (std::optional<Issue> v = parse_vector(line, source, line_no)) vectors.push_back(*v);
  });
  return vectors;
}

std::string format_vector(const Issue& v) {
  const OpInfo& info = fp24::info(v.op);
  char buf[48];
  if (v.op == Op::Float) std::snprintf(buf, sizeof buf, "%s %04x", info.name.data(), v.a);
  else if (info.operands == 1) std::snprintf(buf, sizeof buf, "%s %06x", info.name.data(), v.a);
  else std::snprintf(buf, sizeof buf, "%s %06x %06x", info.name.data(), v.a, v.b);
  return buf;
}

std::string format_result(const Result& r) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%06x %02x", r.value, unsigned(r.flags));
  return buf;
}

}  // namespace mc1::fp24::tb
