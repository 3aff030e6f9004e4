// Integer expressions: C precedence for * / % + - << >> & ^, unary - + ~.
// Every operation is checked: an assembler that wraps silently turns a typo
// into a wrong word (`li a1, (1<<62)*4+5` would load 5).
#include "apuasm_expr.hpp"

#include <cctype>
#include <limits>

namespace mc1::apuasm::detail {
namespace {

constexpr int kMaxShift = 63;

LineError overflow(int col, const std::string& what) {
  return {col, "integer overflow: " + what + " does not fit in 64 bits"};
}

std::string show(std::int64_t a, const char* op, std::int64_t b) {
  return std::to_string(a) + " " + op + " " + std::to_string(b);
}

// a OP b for the binary operators; `col` is the operator's column.
std::int64_t apply(char op, std::int64_t a, std::int64_t b, int col) {
  std::int64_t r = 0;
  switch (op) {
    case '+':
      if (__builtin_add_overflow(a, b, &r)) throw overflow(col, show(a, "+", b));
      return r;
    case '-':
      if (__builtin_sub_overflow(a, b, &r)) throw overflow(col, show(a, "-", b));
      return r;
    case '*':
      if (__builtin_mul_overflow(a, b, &r)) throw overflow(col, show(a, "*", b));
      return r;
    case '/':
    case '%':
      if (b == 0) throw LineError{col, op == '/' ? "division by zero" : "modulo by zero"};
      // INT64_MIN / -1 traps on x86 (SIGFPE); INT64_MIN % -1 is 0.
      if (b == -1 && a == std::numeric_limits<std::int64_t>::min()) {
        if (op == '%') return 0;
        throw overflow(col, show(a, "/", b));
      }
      return op == '/' ? a / b : a % b;
  }
  throw LineError{col, std::string("unknown operator '") + op + "'"};
}

std::int64_t shift(bool left, std::int64_t v, std::int64_t s, int col) {
  if (s < 0 || s > kMaxShift)
    throw LineError{col, "shift count " + std::to_string(s) + " out of range 0..63"};
  if (!left) return v >> s;  // arithmetic (GCC defines >> of a negative value so)
  const auto r = static_cast<std::int64_t>(static_cast<std::uint64_t>(v) << s);
  if ((r >> s) != v) throw overflow(col, show(v, "<<", s));
  return r;
}

class ExprParser {
 public:
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
    while (k_ < p_.text.size() && is_space(p_.text[k_])) ++k_;
  }
  // Consumes `op` if it comes next; "<<" is matched whole, never as "<".
  bool eat(const char* op) {
    skip();
    const size_t n = std::char_traits<char>::length(op);
    if (p_.text.compare(k_, n, op) != 0) return false;
    k_ += n;
    return true;
  }
  // The column of the operator eat() just consumed (one or two characters).
  int op_col(const char* op) const { return col() - static_cast<int>(std::char_traits<char>::length(op)); }

  std::int64_t xor_() {
    auto v = and_();
    while (eat("^")) v ^= and_();
    return v;
  }
  std::int64_t and_() {
    auto v = shifts();
    while (eat("&")) v &= shifts();
    return v;
  }
  std::int64_t shifts() {
    auto v = add();
    for (;;) {
      const bool left = eat("<<");
      if (!left && !eat(">>")) return v;
      const int at = op_col("<<");
      v = shift(left, v, add(), at);
    }
  }
  std::int64_t add() { return binary_level("+-", &ExprParser::mul); }
  std::int64_t mul() { return binary_level("*/%", &ExprParser::unary); }

  // One precedence level of left-associative one-character operators.
  std::int64_t binary_level(const char* ops, std::int64_t (ExprParser::*next)()) {
    auto v = (this->*next)();
    for (;;) {
      skip();
      if (k_ >= p_.text.size() || !std::char_traits<char>::find(ops, std::char_traits<char>::length(ops), p_.text[k_]))
        return v;
      const char op = p_.text[k_++];
      const int at = col() - 1;
      v = apply(op, v, (this->*next)(), at);
    }
  }

  std::int64_t unary() {
    skip();
    const char c = k_ < p_.text.size() ? p_.text[k_] : '\0';
    if (c != '-' && c != '+' && c != '~') return primary();
    const int at = col();
    ++k_;
    nest(at);
    const auto v = unary();
    --depth_;
    if (c == '-') return negate(v, at);
    return c == '~' ? ~v : v;
  }
  std::int64_t primary() {
    skip();
    if (k_ >= p_.text.size()) throw LineError{col(), "missing operand in expression"};
    const char c = p_.text[k_];
    if (c == '(') {
      nest(col());
      ++k_;
      const auto v = xor_();
      if (!eat(")")) throw LineError{col(), "expected ')'"};
      --depth_;
      return v;
    }
    if (std::isdigit(static_cast<unsigned char>(c))) return number();
    if (ident_start(c)) return symbol();
    throw LineError{col(), "unexpected '" + std::string(1, c) + "'"};
  }
  // One more level of parentheses or unary operators, opened at `at`.
  void nest(int at) {
    if (++depth_ > kMaxExprNesting)
      throw LineError{at, "expression nested deeper than " + std::to_string(kMaxExprNesting) +
                              " levels of parentheses and unary operators"};
  }
  std::int64_t symbol() {
    const int at = col();
    const size_t b = k_;
    k_ = name_end(p_.text, k_);
    const std::string name = p_.text.substr(b, k_ - b);
    if (const auto v = lookup_(name)) return *v;
    throw LineError{at, "undefined symbol '" + name + "'"};
  }
  int base_prefix() {
    int base = 10;
    if (p_.text.compare(k_, 2, "0x") == 0 || p_.text.compare(k_, 2, "0X") == 0) base = 16;
    if (p_.text.compare(k_, 2, "0b") == 0 || p_.text.compare(k_, 2, "0B") == 0) base = 2;
    if (base != 10) k_ += 2;
    return base;
  }
  static int digit_value(char c) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
  }
  std::int64_t number() {
    const int at = col();
    const int base = base_prefix();
    std::int64_t v = 0;
    int digits = 0;
    for (; k_ < p_.text.size(); ++k_) {
      if (p_.text[k_] == '_') continue;
      const int d = digit_value(p_.text[k_]);
      if (d < 0 || d >= base) break;
      if (__builtin_mul_overflow(v, base, &v) || __builtin_add_overflow(v, d, &v))
        throw LineError{at, "number too large (the largest is 9223372036854775807)"};
      ++digits;
    }
    if (digits == 0) throw LineError{at, "malformed number"};
    if (k_ < p_.text.size() && (ident_char(p_.text[k_]) && p_.text[k_] != '_'))
      throw LineError{col(), "malformed number (a float is allowed only in lif)"};
    return v;
  }

  Piece p_;
  const Lookup& lookup_;
  size_t k_ = 0;
  int depth_ = 0;  // open parentheses and unary operators
};

}  // namespace

std::int64_t eval_expr(const Piece& p, const Lookup& lookup) { return ExprParser(p, lookup).parse(); }

std::int64_t negate(std::int64_t v, int col) {
  std::int64_t r = 0;
  if (__builtin_sub_overflow(std::int64_t{0}, v, &r)) throw overflow(col, "-(" + std::to_string(v) + ")");
  return r;
}

}  // namespace mc1::apuasm::detail
