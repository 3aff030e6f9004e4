// FP24 constants for LIF (F = imm << 8: 1 sign, 7 exponent, 8 fraction bits)
// and raw 128-bit words.
#include "apuasm_literals.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "disasm.hpp"

namespace mc1::apuasm::detail {
namespace {

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

// The decimal exponent "e[+-]DDD" from s[k] on (saturated, to stay an int);
// nullopt when the sign is not followed by anything.
std::optional<long> decimal_exponent(const std::string& s, size_t& k) {
  long e10 = 0;
  if (k >= s.size() || (s[k] != 'e' && s[k] != 'E')) return e10;
  ++k;
  bool eneg = false;
  if (k < s.size() && (s[k] == '+' || s[k] == '-')) eneg = s[k++] == '-';
  if (k >= s.size()) return std::nullopt;
  for (; k < s.size() && std::isdigit(static_cast<unsigned char>(s[k])); ++k)
    e10 = std::min(e10 * 10 + (s[k] - '0'), 100000L);
  return eneg ? -e10 : e10;
}

std::optional<Decimal> parse_decimal(const std::string& s) {
  Decimal d;
  size_t k = 0;
  if (k < s.size() && (s[k] == '+' || s[k] == '-')) d.neg = s[k++] == '-';
  std::string digits;
  int point = -1;
  for (; k < s.size(); ++k) {
    if (std::isdigit(static_cast<unsigned char>(s[k]))) {
      digits += s[k];
    } else if (s[k] == '.' && point < 0) {
      point = static_cast<int>(digits.size());
    } else {
      break;
    }
  }
  if (digits.empty()) return std::nullopt;
  if (point < 0) point = static_cast<int>(digits.size());
  const auto e10 = decimal_exponent(s, k);
  if (!e10 || k != s.size()) return std::nullopt;
  size_t lead = 0;
  while (lead < digits.size() && digits[lead] == '0') ++lead;
  d.digits = digits.substr(lead);
  d.exp = point - static_cast<int>(lead) + static_cast<int>(*e10);
  while (!d.digits.empty() && d.digits.back() == '0') d.digits.pop_back();
  return d;
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

// "0xHHHH" as the raw immediate; nullopt when `s` (lower case) is not hex.
std::optional<std::uint16_t> raw_lif(const std::string& s, const Piece& p) {
  if (s.size() <= 2 || s.compare(0, 2, "0x") != 0 || s.find_first_not_of("0123456789abcdef_", 2) != std::string::npos)
    return std::nullopt;
  std::uint64_t v = 0;
  for (size_t k = 2; k < s.size(); ++k) {
    if (s[k] == '_') continue;
    v = v * 16 + static_cast<unsigned>(std::isdigit(static_cast<unsigned char>(s[k])) ? s[k] - '0' : s[k] - 'a' + 10);
    if (v > 0xFFFF) throw LineError{p.col, "raw LIF immediate " + p.text + " is wider than 16 bits"};
  }
  return static_cast<std::uint16_t>(v);
}

// The immediate of a nonzero decimal, if it is exactly an FP24 constant.
std::uint16_t exact_lif(const Decimal& lit, const std::string& s, const Piece& p) {
  const double v = std::strtod(s.c_str(), nullptr);
  const std::string what = p.text + " is not exactly representable as an FP24 constant with an 8-bit fraction";
  if (!std::isfinite(v) || v == 0) throw LineError{p.col, what + " (out of range)"};
  const auto imm = nearest_lif(v);
  if (!imm) throw LineError{p.col, what + " (out of range)"};
  // Compare digit strings, not doubles: 1.30078125000001 is not 1.30078125.
  char buf[200];
  std::snprintf(buf, sizeof buf, "%.120e", std::ldexp(1.0 + (*imm & 0xFF) / 256.0, ((*imm >> 8) & 0x7F) - 63));
  auto exact = parse_decimal(buf);
  exact->neg = lit.neg;
  if (!(*exact == lit))
    throw LineError{p.col, what + " (nearest: " + apu::lif_literal_text(*imm) + " = " + hex4(*imm) + ")"};
  return *imm;
}

}  // namespace

std::uint16_t lif_immediate(const Piece& p) {
  const std::string s = lower(p.text);
  if (const auto raw = raw_lif(s, p)) return *raw;
  if (s == "inf" || s == "+inf") return 0x7F00;
  if (s == "-inf") return 0xFF00;
  if (s == "nan") return 0x7F80;
  const auto lit = parse_decimal(s);
  if (!lit)
    throw LineError{p.col, "expected an FP24 constant (a decimal like 1.5 or -2e3, inf, nan, or raw 0xHHHH), got '" +
                               p.text + "'"};
  if (lit->digits.empty()) return lit->neg ? 0x8000 : 0;
  return exact_lif(*lit, s, p);
}

std::optional<apu::Encoded> parse_raw_word(const std::string& text) {
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
  apu::Encoded e;
  e.lo = static_cast<std::uint64_t>(v);
  e.hi = static_cast<std::uint64_t>(v >> 64);
  return e;
}

}  // namespace mc1::apuasm::detail
