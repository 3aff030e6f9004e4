// The APU assembler (docs/apu-asm.md). Pass 1 reads lines, expands .include
// and macros, defines labels and constants and gives every instruction line
// its address; pass 2 encodes the lines, now that every label is known.
#include "apuasm.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "disasm.hpp"

namespace mc1::apuasm {

using apu::AddOp;
using apu::Encoded;
using apu::FuncOp;
using apu::IntOp;
using apu::MemOp;
using apu::MicroWord;
using apu::SeqOp;

std::string Diagnostic::str() const {
  if (loc.line <= 0) return loc.file + ": error: " + message;
  return loc.file + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.col) +
         ": error: " + message;
}

namespace {
std::string join(const std::vector<Diagnostic>& diags) {
  std::string out;
  for (const auto& d : diags) out += (out.empty() ? "" : "\n") + d.str();
  return out;
}
}  // namespace

AsmError::AsmError(std::vector<Diagnostic> diags)
    : std::runtime_error(join(diags)), diags_(std::move(diags)) {}

namespace {

constexpr int kMaxDepth = 32;

// A piece of a source line and the 1-based column of its first character.
struct Piece {
  std::string text;
  int col = 1;
};

// An error at a column of the line being assembled.
struct LineError {
  int col;
  std::string msg;
};

struct SrcLine {
  std::string text;
  Loc loc;              // col 1
  std::string context;  // appended to messages: macro expansion chain
};

bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool ident_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

Piece trim(const Piece& p) {
  size_t b = 0, e = p.text.size();
  while (b < e && std::isspace(static_cast<unsigned char>(p.text[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(p.text[e - 1]))) --e;
  return {p.text.substr(b, e - b), p.col + static_cast<int>(b)};
}

Piece sub(const Piece& p, size_t from, size_t n = std::string::npos) {
  return {p.text.substr(from, n), p.col + static_cast<int>(from)};
}

// Splits at `sep` outside brackets and parentheses; pieces are trimmed.
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

// The text before a `;` or `#` comment (none inside a "string").
std::string strip_comment(const std::string& s) {
  bool quoted = false;
  for (size_t k = 0; k < s.size(); ++k) {
    if (s[k] == '"') quoted = !quoted;
    if (!quoted && (s[k] == ';' || s[k] == '#')) return s.substr(0, k);
  }
  return s;
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

std::string dirname_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

std::optional<std::string> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// ---------------------------------------------------------------------------
// Integer expressions: C precedence for * / % + - << >> & ^, unary - + ~.

class ExprParser {
 public:
  using Lookup = std::function<std::optional<std::int64_t>(const std::string&)>;
  ExprParser(const Piece& p, const Lookup& lookup) : p_(p), lookup_(lookup) {}

  std::int64_t parse() {
    if (trim(p_).text.empty()) throw LineError{p_.col, "missing expression"};
    const auto v = xor_();
    skip();
    if (k_ < p_.text.size()) throw LineError{col(), "unexpected '" + std::string(1, p_.text[k_]) + "'"};
    return v;
  }

 private:
  int col() const { return p_.col + static_cast<int>(k_); }
  void skip() {
    while (k_ < p_.text.size() && std::isspace(static_cast<unsigned char>(p_.text[k_]))) ++k_;
  }
  bool eat(const char* op) {
    skip();
    const size_t n = std::char_traits<char>::length(op);
    if (p_.text.compare(k_, n, op) != 0) return false;
    // "<" alone is not an operator: keep "<<" whole.
    k_ += n;
    return true;
  }
  std::int64_t xor_() {
    auto v = and_();
    while (eat("^")) v ^= and_();
    return v;
  }
  std::int64_t and_() {
    auto v = shift();
    while (eat("&")) v &= shift();
    return v;
  }
  std::int64_t shift() {
    auto v = add();
    for (;;) {
      if (eat("<<")) {
        const auto s = add();
        v = (s < 0 || s > 62) ? 0 : static_cast<std::int64_t>(static_cast<std::uint64_t>(v) << s);
      } else if (eat(">>")) {
        const auto s = add();
        v = (s < 0 || s > 62) ? (v < 0 ? -1 : 0) : (v >> s);
      } else {
        return v;
      }
    }
  }
  std::int64_t add() {
    auto v = mul();
    for (;;) {
      if (eat("+")) v += mul();
      else if (eat("-")) v -= mul();
      else return v;
    }
  }
  std::int64_t mul() {
    auto v = unary();
    for (;;) {
      if (eat("*")) {
        v *= unary();
      } else if (eat("/") || eat("%")) {
        const bool div = p_.text[k_ - 1] == '/';
        const int at = col() - 1;
        const auto d = unary();
        if (d == 0) throw LineError{at, "division by zero"};
        v = div ? v / d : v % d;
      } else {
        return v;
      }
    }
  }
  std::int64_t unary() {
    if (eat("-")) return -unary();
    if (eat("+")) return unary();
    if (eat("~")) return ~unary();
    return primary();
  }
  std::int64_t primary() {
    skip();
    if (k_ >= p_.text.size()) throw LineError{col(), "missing operand in expression"};
    const char c = p_.text[k_];
    if (c == '(') {
      ++k_;
      const auto v = xor_();
      if (!eat(")")) throw LineError{col(), "expected ')'"};
      return v;
    }
    if (std::isdigit(static_cast<unsigned char>(c))) return number();
    if (ident_start(c)) {
      const int at = col();
      const size_t b = k_;
      while (k_ < p_.text.size() && ident_char(p_.text[k_])) ++k_;
      const std::string name = p_.text.substr(b, k_ - b);
      if (const auto v = lookup_(name)) return *v;
      throw LineError{at, "undefined symbol '" + name + "'"};
    }
    throw LineError{col(), "unexpected '" + std::string(1, c) + "'"};
  }
  std::int64_t number() {
    const int at = col();
    int base = 10;
    if (p_.text.compare(k_, 2, "0x") == 0 || p_.text.compare(k_, 2, "0X") == 0) base = 16;
    if (p_.text.compare(k_, 2, "0b") == 0 || p_.text.compare(k_, 2, "0B") == 0) base = 2;
    if (base != 10) k_ += 2;
    std::uint64_t v = 0;
    int digits = 0;
    while (k_ < p_.text.size()) {
      const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(p_.text[k_])));
      int d = -1;
      if (c >= '0' && c <= '9') d = c - '0';
      else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
      else if (c == '_') { ++k_; continue; }
      if (d < 0 || d >= base) break;
      if (v > (std::uint64_t{1} << 58)) throw LineError{at, "number too large"};
      v = v * base + d;
      ++digits;
      ++k_;
    }
    if (digits == 0) throw LineError{at, "malformed number"};
    if (k_ < p_.text.size() && (ident_char(p_.text[k_]) && p_.text[k_] != '_'))
      throw LineError{col(), "malformed number (a float is allowed only in lif)"};
    return static_cast<std::int64_t>(v);
  }

  Piece p_;
  const Lookup& lookup_;
  size_t k_ = 0;
};

// ---------------------------------------------------------------------------
// FP24 constants for LIF: F = imm << 8, so 1 sign, 7 exponent, 8 fraction bits.

// A decimal number as (negative, significant digits without leading or
// trailing zeros, exponent) so that value = 0.DIGITS * 10^exp.
struct Decimal {
  bool neg = false;
  std::string digits;
  int exp = 0;
  bool operator==(const Decimal& o) const {
    return digits == o.digits && (digits.empty() || (neg == o.neg && exp == o.exp));
  }
};

std::optional<Decimal> parse_decimal(const std::string& s) {
  Decimal d;
  size_t k = 0;
  if (k < s.size() && (s[k] == '+' || s[k] == '-')) d.neg = s[k++] == '-';
  std::string digits;
  int point = -1, mant_digits = 0;
  for (; k < s.size(); ++k) {
    if (std::isdigit(static_cast<unsigned char>(s[k]))) {
      digits += s[k];
      ++mant_digits;
    } else if (s[k] == '.' && point < 0) {
      point = static_cast<int>(digits.size());
    } else {
      break;
    }
  }
  if (mant_digits == 0) return std::nullopt;
  if (point < 0) point = static_cast<int>(digits.size());
  long e10 = 0;
  if (k < s.size() && (s[k] == 'e' || s[k] == 'E')) {
    ++k;
    bool eneg = false;
    if (k < s.size() && (s[k] == '+' || s[k] == '-')) eneg = s[k++] == '-';
    if (k >= s.size()) return std::nullopt;
    for (; k < s.size() && std::isdigit(static_cast<unsigned char>(s[k])); ++k)
      e10 = std::min(e10 * 10 + (s[k] - '0'), 100000L);
    if (eneg) e10 = -e10;
  }
  if (k != s.size()) return std::nullopt;
  size_t lead = 0;
  while (lead < digits.size() && digits[lead] == '0') ++lead;
  d.digits = digits.substr(lead);
  d.exp = point - static_cast<int>(lead) + static_cast<int>(e10);
  while (!d.digits.empty() && d.digits.back() == '0') d.digits.pop_back();
  return d;
}

std::string hex4(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04x", v);
  return buf;
}

// The LIF immediate of v (finite, nonzero), rounded to 9 significant bits;
// nullopt when the exponent does not fit.
std::optional<std::uint16_t> nearest_lif(double v) {
  int e2;
  const double m = std::frexp(std::fabs(v), &e2);  // [0.5, 1)
  double frac = std::nearbyint((m * 2 - 1) * 256);
  int e = e2 - 1 + 63;
  if (frac == 256) {
    frac = 0;
    ++e;
  }
  if (e < 1 || e > 126) return std::nullopt;
  return static_cast<std::uint16_t>((v < 0 ? 0x8000 : 0) | (e << 8) | static_cast<int>(frac));
}

std::uint16_t lif_immediate(const Piece& p) {
  const std::string s = lower(p.text);
  if (s.size() > 2 && s.compare(0, 2, "0x") == 0 &&
      s.find_first_not_of("0123456789abcdef_", 2) == std::string::npos) {
    std::uint64_t v = 0;
    for (size_t k = 2; k < s.size(); ++k) {
      if (s[k] == '_') continue;
      v = v * 16 + static_cast<unsigned>(std::isdigit(static_cast<unsigned char>(s[k])) ? s[k] - '0' : s[k] - 'a' + 10);
      if (v > 0xFFFF) throw LineError{p.col, "raw LIF immediate " + p.text + " is wider than 16 bits"};
    }
    return static_cast<std::uint16_t>(v);
  }
  if (s == "inf" || s == "+inf") return 0x7F00;
  if (s == "-inf") return 0xFF00;
  if (s == "nan") return 0x7F80;
  const auto lit = parse_decimal(s);
  if (!lit)
    throw LineError{p.col, "expected an FP24 constant (a decimal like 1.5 or -2e3, inf, nan, or raw 0xHHHH), got '" +
                               p.text + "'"};
  const double v = std::strtod(s.c_str(), nullptr);
  if (lit->digits.empty()) return lit->neg ? 0x8000 : 0;
  const std::string what = p.text + " is not exactly representable as an FP24 constant with an 8-bit fraction";
  if (!std::isfinite(v) || v == 0) throw LineError{p.col, what + " (out of range)"};
  const auto imm = nearest_lif(v);
  if (!imm) throw LineError{p.col, what + " (out of range)"};
  char buf[200];
  std::snprintf(buf, sizeof buf, "%.120e", std::ldexp(1.0 + (*imm & 0xFF) / 256.0, ((*imm >> 8) & 0x7F) - 63));
  auto exact = parse_decimal(buf);
  exact->neg = lit->neg;
  if (!(*exact == *lit))
    throw LineError{p.col, what + " (nearest: " + apu::lif_literal_text(*imm) + " = " + hex4(*imm) + ")"};
  return *imm;
}

// ".word" operand: 0x and up to 32 hex digits (underscores allowed), bit 127 first.
std::optional<Encoded> parse_raw_word(const std::string& text) {
  const std::string s = lower(text);
  if (s.size() < 3 || s.compare(0, 2, "0x") != 0) return std::nullopt;
  unsigned __int128 v = 0;
  int digits = 0;
  for (size_t k = 2; k < s.size(); ++k) {
    if (s[k] == '_') continue;
    const char c = s[k];
    int d;
    if (c >= '0' && c <= '9') d = c - '0';
    else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
    else return std::nullopt;
    if (++digits > 32) return std::nullopt;
    v = (v << 4) | static_cast<unsigned>(d);
  }
  if (digits == 0) return std::nullopt;
  Encoded e;
  e.lo = static_cast<std::uint64_t>(v);
  e.hi = static_cast<std::uint64_t>(v >> 64);
  return e;
}

// ---------------------------------------------------------------------------
// Mnemonics.

enum Slot { kSlotM, kSlotA, kSlotF, kSlotD, kSlotI, kSlotS, kSlots };
const char* const kSlotNames[kSlots] = {"M (multiplier)", "A (adder)", "F (function)", "D (data move)",
                                        "I (integer)", "S (sequencer)"};

const std::set<std::string>& mnemonics() {
  static const std::set<std::string> names = {
      "nop",  "mul",   "fmul",  "add",   "fadd",  "sub",   "fsub", "cmp",  "float", "fix",
      "neg",  "abs",   "recip", "sqrt",  "sin",   "cos",   "ld",   "st",   "li",    "addi",
      "muli", "shl",   "shr",   "sra",   "andi",  "ori",   "xor",  "movaf", "movfa", "lif",
      "jmp",  "bcc",   "bncc",  "dbnz",  "bz",    "bnz",   "bltz", "call", "ret",   "swapd",
      "swapp", "halt", "beq",   "bne",   "blt",   "ble",   "bgt",  "bge",  "bun",   "bord"};
  return names;
}

// Where the slots of one word are taken and which registers it writes.
struct WordState {
  int slot_col[kSlots] = {0, 0, 0, 0, 0, 0};
  std::vector<std::pair<int, int>> fwrites;  // F register, column
  int iwrite_areg = -1, iwrite_col = 0;
  int dbnz_areg = -1, dbnz_col = 0;
};

class WordEncoder {
 public:
  using Lookup = ExprParser::Lookup;
  explicit WordEncoder(const Lookup& lookup) : lookup_(lookup) {}

  // Adds one slot instruction to `w`.
  void add(const Piece& ins, MicroWord& w, WordState& st) {
    size_t k = 0;
    while (k < ins.text.size() && ident_char(ins.text[k])) ++k;
    if (k == 0) throw LineError{ins.col, "expected a mnemonic, got '" + ins.text + "'"};
    const std::string mn = lower(ins.text.substr(0, k));
    const Piece rest = trim(sub(ins, k));
    std::vector<Piece> ops;
    if (!rest.text.empty()) ops = split(rest, ',');
    for (const auto& o : ops)
      if (o.text.empty()) throw LineError{o.col, "missing operand"};
    mn_ = mn;
    mn_col_ = ins.col;
    ops_ = &ops;
    dispatch(w, st);
  }

 private:
  void need(size_t n, const char* usage) {
    if (ops_->size() != n)
      throw LineError{mn_col_, "'" + mn_ + "' takes " + std::to_string(n) + " operand" + (n == 1 ? "" : "s") +
                                   ": " + usage};
  }
  const Piece& op(size_t k) const { return (*ops_)[k]; }

  void take(WordState& st, Slot s) {
    if (st.slot_col[s])
      throw LineError{mn_col_, std::string("two instructions for the ") + kSlotNames[s] +
                                   " slot in one word (the other at column " + std::to_string(st.slot_col[s]) + ")"};
    st.slot_col[s] = mn_col_;
  }

  static std::optional<int> reg_number(const std::string& text, char kind) {
    if (text.size() < 2 || std::tolower(static_cast<unsigned char>(text[0])) != kind) return std::nullopt;
    if (text.find_first_not_of("0123456789", 1) != std::string::npos) return std::nullopt;
    if (text.size() > 4) return 9999;
    return std::stoi(text.substr(1));
  }
  static bool is_freg(const Piece& p) { return reg_number(p.text, 'f').has_value(); }

  int freg(const Piece& p) {
    const auto n = reg_number(p.text, 'f');
    if (!n) throw LineError{p.col, "expected an F register (f0..f63), got '" + p.text + "'"};
    if (*n > 63) throw LineError{p.col, "no such F register '" + p.text + "' (f0..f63)"};
    return *n;
  }
  int fdest(const Piece& p, WordState& st) {
    const int r = freg(p);
    st.fwrites.emplace_back(r, p.col);
    return r;
  }
  int areg(const Piece& p) {
    const auto n = reg_number(p.text, 'a');
    if (!n) throw LineError{p.col, "expected an A register (a0..a15), got '" + p.text + "'"};
    if (*n > 15) throw LineError{p.col, "no such A register '" + p.text + "' (a0..a15)"};
    return *n;
  }
  std::int64_t value(const Piece& p, bool cc_names = false) {
    if (!cc_names) return ExprParser(p, lookup_).parse();
    const Lookup cc = [this](const std::string& name) -> std::optional<std::int64_t> {
      const std::string l = lower(name);
      if (l == "lt") return 1;
      if (l == "eq") return 2;
      if (l == "gt") return 4;
      if (l == "un") return 8;
      return lookup_(name);
    };
    return ExprParser(p, cc).parse();
  }
  std::int64_t ranged(const Piece& p, std::int64_t lo, std::int64_t hi, const char* what) {
    const auto v = value(p);
    if (v < lo || v > hi)
      throw LineError{p.col, std::string(what) + " " + std::to_string(v) + " out of range " + std::to_string(lo) +
                                 ".." + std::to_string(hi)};
    return v;
  }
  std::uint16_t imm16(const Piece& p) {
    return static_cast<std::uint16_t>(ranged(p, -32768, 65535, "immediate"));
  }
  std::uint16_t target(const Piece& p) { return static_cast<std::uint16_t>(ranged(p, 0, 1023, "branch target")); }
  std::uint8_t mask(const Piece& p) {
    const auto v = value(p, true);
    if (v < 0 || v > 15) throw LineError{p.col, "CC mask " + std::to_string(v) + " out of range 0..15"};
    return static_cast<std::uint8_t>(v);
  }
  void mem(const Piece& p, apu::MemSlot& d) {
    if (p.text.size() < 2 || p.text.front() != '[' || p.text.back() != ']')
      throw LineError{p.col, "expected a data address [aN], [aN+disp] or [aN-disp], got '" + p.text + "'"};
    const Piece in = trim(sub(p, 1, p.text.size() - 2));
    size_t k = 0;
    while (k < in.text.size() && ident_char(in.text[k])) ++k;
    d.base = static_cast<std::uint8_t>(areg(trim(sub(in, 0, k))));
    const Piece rest = trim(sub(in, k));
    std::int64_t disp = 0;
    if (!rest.text.empty()) {
      if (rest.text[0] != '+' && rest.text[0] != '-')
        throw LineError{rest.col, "expected '+' or '-' after the base register"};
      disp = value(trim(sub(rest, 1)));
      if (rest.text[0] == '-') disp = -disp;
      if (disp < -128 || disp > 127)
        throw LineError{rest.col, "displacement " + std::to_string(disp) + " out of range -128..127"};
    }
    d.disp = static_cast<std::int8_t>(disp);
  }
  void iwrite(WordState& st, int a, int col) {
    st.iwrite_areg = a;
    st.iwrite_col = col;
  }

  void dispatch(MicroWord& w, WordState& st) {
    const std::string& m = mn_;
    if (m == "nop") return need(0, "nop");
    // M slot.
    if (m == "mul" || m == "fmul") {
      need(3, "mul fd, fa, fb");
      take(st, kSlotM);
      w.m = {true, u8(fdest(op(0), st)), u8(freg(op(1))), u8(freg(op(2)))};
      return;
    }
    // A slot; add and sub with F operands are the adder's.
    const bool fp_addsub = (m == "add" || m == "sub") && !ops_->empty() && is_freg(op(0));
    if (fp_addsub || m == "fadd" || m == "fsub") {
      need(3, "add fd, fa, fb");
      take(st, kSlotA);
      const auto aop = (m == "add" || m == "fadd") ? AddOp::Add : AddOp::Sub;
      w.a = {true, aop, u8(fdest(op(0), st)), u8(freg(op(1))), u8(freg(op(2)))};
      return;
    }
    if (m == "cmp") {
      need(2, "cmp fa, fb");
      take(st, kSlotA);
      w.a = {true, AddOp::Cmp, 0, u8(freg(op(0))), u8(freg(op(1)))};
      return;
    }
    static const std::pair<const char*, AddOp> kUnaryAdd[] = {
        {"float", AddOp::Float}, {"fix", AddOp::Fix}, {"neg", AddOp::Neg}, {"abs", AddOp::Abs}};
    for (const auto& [name, aop] : kUnaryAdd) {
      if (m != name) continue;
      need(2, "fd, fa");
      take(st, kSlotA);
      w.a = {true, aop, u8(fdest(op(0), st)), u8(freg(op(1))), 0};
      return;
    }
    // F slot.
    static const std::pair<const char*, FuncOp> kFunc[] = {
        {"recip", FuncOp::Recip}, {"sqrt", FuncOp::Sqrt}, {"sin", FuncOp::Sin}, {"cos", FuncOp::Cos}};
    for (const auto& [name, fop] : kFunc) {
      if (m != name) continue;
      need(2, "fd, fa");
      take(st, kSlotF);
      w.f = {true, fop, u8(fdest(op(0), st)), u8(freg(op(1)))};
      return;
    }
    // D slot.
    if (m == "ld" || m == "st") {
      need(2, m == "ld" ? "ld fd, [aN+disp]" : "st fs, [aN+disp]");
      take(st, kSlotD);
      w.d.op = m == "ld" ? MemOp::Ld : MemOp::St;
      w.d.f = u8(m == "ld" ? fdest(op(0), st) : freg(op(0)));
      mem(op(1), w.d);
      return;
    }
    if (int_slot(w, st)) return;
    if (seq_slot(w, st)) return;
    throw LineError{mn_col_, "unknown mnemonic '" + m + "'"};
  }

  bool int_slot(MicroWord& w, WordState& st) {
    const std::string& m = mn_;
    auto& i = w.i;
    if (m == "li") {
      need(2, "li ad, imm");
      take(st, kSlotI);
      i.op = IntOp::Li;
      i.d = u8(areg(op(0)));
      i.imm = imm16(op(1));
      iwrite(st, i.d, op(0).col);
      return true;
    }
    static const std::pair<const char*, IntOp> kImmOps[] = {
        {"addi", IntOp::Addi}, {"muli", IntOp::Muli}, {"andi", IntOp::Andi}, {"ori", IntOp::Ori},
        {"shl", IntOp::Shl},   {"shr", IntOp::Shr},   {"sra", IntOp::Sra}};
    for (const auto& [name, iop] : kImmOps) {
      if (m != name) continue;
      need(3, "ad, as, imm");
      take(st, kSlotI);
      i.op = iop;
      i.d = u8(areg(op(0)));
      i.s = u8(areg(op(1)));
      const bool shift = iop == IntOp::Shl || iop == IntOp::Shr || iop == IntOp::Sra;
      i.imm = shift ? static_cast<std::uint16_t>(ranged(op(2), 0, 15, "shift amount")) : imm16(op(2));
      iwrite(st, i.d, op(0).col);
      return true;
    }
    static const std::pair<const char*, IntOp> kRegOps[] = {
        {"add", IntOp::Add}, {"sub", IntOp::Sub}, {"xor", IntOp::Xor}};
    for (const auto& [name, iop] : kRegOps) {
      if (m != name) continue;
      need(3, "ad, as, at");
      take(st, kSlotI);
      i.op = iop;
      i.d = u8(areg(op(0)));
      i.s = u8(areg(op(1)));
      i.t = u8(areg(op(2)));
      iwrite(st, i.d, op(0).col);
      return true;
    }
    if (m == "movaf") {
      need(2, "movaf fd, as");
      take(st, kSlotI);
      i.op = IntOp::Movaf;
      i.d = u8(fdest(op(0), st));
      i.s = u8(areg(op(1)));
      return true;
    }
    if (m == "movfa") {
      need(2, "movfa ad, fs");
      take(st, kSlotI);
      i.op = IntOp::Movfa;
      i.d = u8(areg(op(0)));
      i.imm = static_cast<std::uint16_t>(freg(op(1)));
      iwrite(st, i.d, op(0).col);
      return true;
    }
    if (m == "lif") {
      need(2, "lif fd, constant");
      take(st, kSlotI);
      i.op = IntOp::Lif;
      i.d = u8(fdest(op(0), st));
      i.imm = lif_immediate(op(1));
      return true;
    }
    return false;
  }

  bool seq_slot(MicroWord& w, WordState& st) {
    const std::string& m = mn_;
    auto& s = w.s;
    static const std::pair<const char*, SeqOp> kTargetOps[] = {
        {"jmp", SeqOp::Jmp}, {"call", SeqOp::Call}, {"swapp", SeqOp::Swapp}};
    for (const auto& [name, sop] : kTargetOps) {
      if (m != name) continue;
      need(1, "target");
      take(st, kSlotS);
      s.op = sop;
      s.target = target(op(0));
      return true;
    }
    static const std::pair<const char*, SeqOp> kBare[] = {
        {"ret", SeqOp::Ret}, {"swapd", SeqOp::Swapd}, {"halt", SeqOp::Halt}};
    for (const auto& [name, sop] : kBare) {
      if (m != name) continue;
      need(0, name);
      take(st, kSlotS);
      s.op = sop;
      return true;
    }
    if (m == "bcc" || m == "bncc") {
      need(2, "mask, target");
      take(st, kSlotS);
      s.op = m == "bcc" ? SeqOp::Bcc : SeqOp::Bncc;
      s.r = mask(op(0));
      s.target = target(op(1));
      return true;
    }
    // Aliases: IEEE-style comparisons after "cmp fa, fb".
    static const struct { const char* name; SeqOp op; std::uint8_t mask; } kAliases[] = {
        {"beq", SeqOp::Bcc, 2},  {"bne", SeqOp::Bncc, 2}, {"blt", SeqOp::Bcc, 1},  {"ble", SeqOp::Bcc, 3},
        {"bgt", SeqOp::Bcc, 4},  {"bge", SeqOp::Bcc, 6},  {"bun", SeqOp::Bcc, 8},  {"bord", SeqOp::Bncc, 8}};
    for (const auto& a : kAliases) {
      if (m != a.name) continue;
      need(1, "target");
      take(st, kSlotS);
      s.op = a.op;
      s.r = a.mask;
      s.target = target(op(0));
      return true;
    }
    static const std::pair<const char*, SeqOp> kRegOps[] = {
        {"dbnz", SeqOp::Dbnz}, {"bz", SeqOp::Bz}, {"bnz", SeqOp::Bnz}, {"bltz", SeqOp::Bltz}};
    for (const auto& [name, sop] : kRegOps) {
      if (m != name) continue;
      need(2, "ar, target");
      take(st, kSlotS);
      s.op = sop;
      s.r = u8(areg(op(0)));
      s.target = target(op(1));
      if (sop == SeqOp::Dbnz) {
        st.dbnz_areg = s.r;
        st.dbnz_col = op(0).col;
      }
      return true;
    }
    return false;
  }

  static std::uint8_t u8(int v) { return static_cast<std::uint8_t>(v); }

  const Lookup& lookup_;
  std::string mn_;
  int mn_col_ = 1;
  const std::vector<Piece>* ops_ = nullptr;
};

// ---------------------------------------------------------------------------

struct Symbol {
  std::int64_t value;
  Loc loc;
};

struct Macro {
  std::vector<std::string> params;
  std::vector<SrcLine> body;
  Loc loc;
};

// An instruction line waiting for pass 2.
struct Stmt {
  SrcLine line;
  Piece body;
  int addr;
  size_t listing_index;
  std::optional<Encoded> raw;  // .word
};

bool is_register_name(const std::string& s) {
  const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(s.empty() ? ' ' : s[0])));
  return s.size() >= 2 && (c == 'f' || c == 'a') && s.find_first_not_of("0123456789", 1) == std::string::npos;
}

std::string where(const Loc& l) {
  return l.file + ":" + std::to_string(l.line) + ":" + std::to_string(l.col);
}

class Assembler {
 public:
  Program run(const std::string& source, const std::string& filename) {
    process(split_lines(source, filename), 0);
    pass2();
    if (!diags_.empty()) {
      std::vector<size_t> order(diags_.size());
      for (size_t k = 0; k < order.size(); ++k) order[k] = k;
      std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return keys_[x] < keys_[y]; });
      std::vector<Diagnostic> sorted;
      for (const auto k : order) sorted.push_back(diags_[k]);
      throw AsmError(std::move(sorted));
    }
    Program p;
    p.words = std::move(words_);
    for (const auto& [name, sym] : syms_) p.symbols[name] = sym.value;
    p.listing = std::move(listing_);
    return p;
  }

 private:
  void error(const SrcLine& l, int col, const std::string& msg, size_t key) {
    diags_.push_back({{l.loc.file, l.loc.line, col}, msg + l.context});
    keys_.push_back(key);
  }
  void error(const SrcLine& l, int col, const std::string& msg) { error(l, col, msg, listing_.size() - 1); }

  std::optional<std::int64_t> lookup(const std::string& name) const {
    const auto it = syms_.find(name);
    if (it == syms_.end()) return std::nullopt;
    return it->second.value;
  }

  void define(const SrcLine& l, const std::string& name, int col, std::int64_t v) {
    const auto it = syms_.find(name);
    if (it != syms_.end())
      return error(l, col, "duplicate symbol '" + name + "' (first defined at " + where(it->second.loc) + ")");
    if (mnemonics().count(lower(name)) || is_register_name(name))
      return error(l, col, "'" + name + "' is a mnemonic or register name");
    syms_[name] = {v, {l.loc.file, l.loc.line, col}};
  }

  void process(const std::vector<SrcLine>& lines, int depth) {
    for (size_t k = 0; k < lines.size(); ++k) {
      const SrcLine& l = lines[k];
      listing_.push_back({l.loc, l.text, -1, depth});
      const Piece code{strip_comment(l.text), 1};
      size_t pos = 0;
      // Labels: "name:" at the start of the line, any number of them.
      for (;;) {
        while (pos < code.text.size() && std::isspace(static_cast<unsigned char>(code.text[pos]))) ++pos;
        if (pos >= code.text.size() || !ident_start(code.text[pos])) break;
        size_t e = pos;
        while (e < code.text.size() && ident_char(code.text[e])) ++e;
        size_t c = e;
        while (c < code.text.size() && std::isspace(static_cast<unsigned char>(code.text[c]))) ++c;
        if (c >= code.text.size() || code.text[c] != ':') break;
        define(l, code.text.substr(pos, e - pos), static_cast<int>(pos) + 1, pc_);
        pos = c + 1;
      }
      const Piece rest = trim(sub(code, pos));
      if (rest.text.empty()) continue;
      if (rest.text[0] == '.') {
        k = directive(lines, k, rest, depth);
        continue;
      }
      size_t e = 0;
      while (e < rest.text.size() && ident_char(rest.text[e])) ++e;
      const auto mac = macros_.find(rest.text.substr(0, e));
      if (e > 0 && mac != macros_.end()) {
        expand(l, mac->first, mac->second, rest, e, depth);
        continue;
      }
      emit(l, rest, std::nullopt);
    }
  }

  void emit(const SrcLine& l, const Piece& body, std::optional<Encoded> raw) {
    if (pc_ >= apu::kProgramWords) {
      if (!too_big_) error(l, body.col, "program larger than 1024 words");
      too_big_ = true;
      return;
    }
    const auto used = used_.find(pc_);
    if (used != used_.end()) {
      error(l, body.col, "address " + hex4(pc_) + " already holds the word of " + where(used->second));
      return;
    }
    used_[pc_] = {l.loc.file, l.loc.line, body.col};
    listing_.back().addr = pc_;
    stmts_.push_back({l, body, pc_, listing_.size() - 1, raw});
    ++pc_;
  }

  // Returns the index of the last line the directive consumed.
  size_t directive(const std::vector<SrcLine>& lines, size_t k, const Piece& rest, int depth) {
    const SrcLine& l = lines[k];
    size_t e = 1;
    while (e < rest.text.size() && ident_char(rest.text[e])) ++e;
    const std::string name = lower(rest.text.substr(0, e));
    const Piece args = trim(sub(rest, e));
    const ExprParser::Lookup look = [this](const std::string& s) { return lookup(s); };
    try {
      if (name == ".equ") {
        const auto a = split(args, ',');
        if (a.size() != 2 || a[0].text.empty())
          throw LineError{rest.col, ".equ takes a name and a value: .equ NAME, expr"};
        const auto& n = a[0].text;
        if (!ident_start(n[0]) || !std::all_of(n.begin(), n.end(), ident_char))
          throw LineError{a[0].col, "'" + n + "' is not a valid symbol name"};
        define(l, n, a[0].col, ExprParser(a[1], look).parse());
      } else if (name == ".org") {
        const auto v = ExprParser(args, look).parse();
        if (v < 0 || v >= apu::kProgramWords)
          throw LineError{args.col, ".org address " + std::to_string(v) + " out of range 0..1023"};
        pc_ = static_cast<int>(v);
      } else if (name == ".word") {
        const auto w = parse_raw_word(args.text);
        if (!w) throw LineError{args.col, ".word takes one hex literal of up to 32 digits: .word 0x<hi>_<lo>"};
        emit(l, rest, w);
      } else if (name == ".include") {
        include(l, args, depth);
      } else if (name == ".macro") {
        return define_macro(lines, k, args);
      } else if (name == ".endm") {
        throw LineError{rest.col, ".endm without .macro"};
      } else {
        throw LineError{rest.col, "unknown directive '" + name + "'"};
      }
    } catch (const LineError& err) {
      error(l, err.col, err.msg);
    }
    return k;
  }

  void include(const SrcLine& l, const Piece& args, int depth) {
    if (args.text.size() < 2 || args.text.front() != '"' || args.text.back() != '"')
      throw LineError{args.col, ".include takes a quoted file name"};
    const std::string name = args.text.substr(1, args.text.size() - 2);
    const std::string path = name[0] == '/' ? name : dirname_of(l.loc.file) + name;
    if (depth >= kMaxDepth) throw LineError{args.col, ".include nested deeper than 32"};
    const auto text = read_file(path);
    if (!text) throw LineError{args.col, "cannot read include file '" + path + "'"};
    auto lines = split_lines(*text, path);
    for (auto& x : lines) x.context = l.context;
    process(lines, depth + 1);
  }

  size_t define_macro(const std::vector<SrcLine>& lines, size_t k, const Piece& args) {
    const SrcLine& l = lines[k];
    Piece spec = args;
    for (auto& c : spec.text)
      if (c == ',') c = ' ';
    std::istringstream words(spec.text);
    std::string mname, param;
    words >> mname;
    Macro mac;
    mac.loc = {l.loc.file, l.loc.line, args.col};
    while (words >> param) mac.params.push_back(param);
    // The body runs to the matching .endm.
    int nest = 1;
    size_t j = k + 1;
    for (; j < lines.size(); ++j) {
      const std::string t = lower(trim({strip_comment(lines[j].text), 1}).text);
      if (t.compare(0, 6, ".macro") == 0) ++nest;
      if (t.compare(0, 5, ".endm") == 0 && --nest == 0) break;
      mac.body.push_back(lines[j]);
    }
    for (size_t b = k + 1; b < j && b < lines.size(); ++b) listing_.push_back({lines[b].loc, lines[b].text, -1, 1});
    if (j < lines.size()) listing_.push_back({lines[j].loc, lines[j].text, -1, 1});
    if (j >= lines.size()) error(l, args.col, ".macro without .endm");
    if (mname.empty() || !ident_start(mname[0]) || !std::all_of(mname.begin(), mname.end(), ident_char)) {
      error(l, args.col, ".macro needs a name: .macro NAME [param, ...]");
    } else if (mnemonics().count(lower(mname))) {
      error(l, args.col, "macro name '" + mname + "' is an instruction mnemonic");
    } else if (macros_.count(mname)) {
      error(l, args.col, "duplicate macro '" + mname + "' (first defined at " + where(macros_[mname].loc) + ")");
    } else {
      macros_[mname] = std::move(mac);
    }
    return j;
  }

  void expand(const SrcLine& l, const std::string& name, const Macro& mac, const Piece& rest, size_t name_end,
              int depth) {
    if (depth >= kMaxDepth) return error(l, rest.col, "macro expansion nested deeper than 32");
    const Piece argtext = trim(sub(rest, name_end));
    std::vector<Piece> args;
    if (!argtext.text.empty()) args = split(argtext, ',');
    if (args.size() != mac.params.size())
      return error(l, rest.col, "macro '" + name + "' takes " + std::to_string(mac.params.size()) +
                                    " argument(s), got " + std::to_string(args.size()));
    const std::string id = std::to_string(expansions_++);
    const std::string ctx = " (in macro '" + name + "' invoked at " + where({l.loc.file, l.loc.line, rest.col}) + ")" +
                            l.context;
    std::vector<SrcLine> out;
    for (const auto& b : mac.body) {
      SrcLine x = b;
      x.context = ctx;
      std::string t;
      for (size_t c = 0; c < b.text.size(); ++c) {
        if (b.text[c] != '\\') {
          t += b.text[c];
          continue;
        }
        if (c + 1 < b.text.size() && b.text[c + 1] == '@') {
          t += id;
          ++c;
          continue;
        }
        size_t e = c + 1;
        while (e < b.text.size() && ident_char(b.text[e])) ++e;
        const std::string p = b.text.substr(c + 1, e - c - 1);
        const auto it = std::find(mac.params.begin(), mac.params.end(), p);
        if (it == mac.params.end()) {
          error(x, static_cast<int>(c) + 1, "unknown macro parameter '\\" + p + "'");
          t += b.text.substr(c, e - c);
        } else {
          t += args[static_cast<size_t>(it - mac.params.begin())].text;
        }
        c = e - 1;
      }
      x.text = t;
      out.push_back(std::move(x));
    }
    process(out, depth + 1);
  }

  void pass2() {
    int top = -1;
    for (const auto& s : stmts_) top = std::max(top, s.addr);
    words_.assign(static_cast<size_t>(top + 1), Encoded{});
    const ExprParser::Lookup look = [this](const std::string& s) { return lookup(s); };
    WordEncoder enc(look);
    for (const auto& s : stmts_) {
      if (s.raw) {
        words_[static_cast<size_t>(s.addr)] = *s.raw;
        continue;
      }
      MicroWord w;
      WordState st;
      bool ok = true;
      for (const auto& slot : split(s.body, '|')) {
        try {
          if (slot.text.empty()) throw LineError{slot.col, "empty slot between '|'"};
          enc.add(slot, w, st);
        } catch (const LineError& err) {
          error(s.line, err.col, err.msg, s.listing_index);
          ok = false;
        }
      }
      if (ok) check_writes(s, st);
      words_[static_cast<size_t>(s.addr)] = w.encode();
    }
  }

  // docs/apu-isa.md: no register may be written twice by one word.
  void check_writes(const Stmt& s, const WordState& st) {
    for (size_t x = 0; x < st.fwrites.size(); ++x) {
      for (size_t y = 0; y < x; ++y) {
        if (st.fwrites[x].first != st.fwrites[y].first) continue;
        error(s.line, st.fwrites[x].second,
              "f" + std::to_string(st.fwrites[x].first) + " is written twice in one word (also at column " +
                  std::to_string(st.fwrites[y].second) + ")",
              s.listing_index);
        break;
      }
    }
    if (st.dbnz_areg >= 0 && st.dbnz_areg == st.iwrite_areg) {
      error(s.line, st.dbnz_col,
            "a" + std::to_string(st.dbnz_areg) + " is written twice in one word (DBNZ and the I slot at column " +
                std::to_string(st.iwrite_col) + ")",
            s.listing_index);
    }
  }

  std::vector<Diagnostic> diags_;
  std::vector<size_t> keys_;  // listing index of each diagnostic, to sort them by source order
  std::map<std::string, Symbol> syms_;
  std::map<std::string, Macro> macros_;
  std::vector<Stmt> stmts_;
  std::vector<ListingLine> listing_;
  std::map<int, Loc> used_;
  std::vector<Encoded> words_;
  int pc_ = 0;
  int expansions_ = 0;
  bool too_big_ = false;
};

}  // namespace

Program assemble(const std::string& source, const std::string& filename) {
  return Assembler().run(source, filename);
}

Program assemble_file(const std::string& path) {
  const auto text = read_file(path);
  if (!text) {
    Diagnostic d;
    d.loc.file = path;
    d.message = "cannot read file";
    throw AsmError({d});
  }
  return assemble(*text, path);
}

}  // namespace mc1::apuasm
