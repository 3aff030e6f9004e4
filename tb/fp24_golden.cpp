// Golden-file reports. Host doubles are fine here: every FP24 value is exact
// in a double, and the decimal text is for a reader, never compared.
#include "fp24_golden.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "fp24_oracle.hpp"

namespace mc1::fp24::tb {
namespace {

// Bit i of the flags field, in docs/fp24.md's order (NX is bit 0).
constexpr std::array<const char*, 5> kFlagNames = {"NX", "UF", "OF", "DZ", "NV"};

std::string hex(Bits v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%0*x", digits, v);
  return buf;
}

int result_digits(Op op) { return op == Op::Cmp ? 1 : op == Op::Fix ? 4 : 6; }

std::string int16(Bits v) { return std::to_string(std::int16_t(std::uint16_t(v))); }

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = char(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

}  // namespace

std::string flag_names(std::uint8_t flags) {
  std::string s;
  for (int i = 4; i >= 0; --i)
    if (flags & (1u << i)) s += (s.empty() ? "" : "|") + std::string(kFlagNames[std::size_t(i)]);
  return s.empty() ? "-" : s;
}

std::optional<std::uint8_t> parse_flags(std::string_view text) {
  if (text == "-") return std::uint8_t(0);
  std::string t = upper(text);
  if (t.size() > 2 && t[0] == '0' && t[1] == 'X') t = t.substr(2);
  if (!t.empty() && t.size() <= 2 && t.find_first_not_of("0123456789ABCDEF") == std::string::npos) {
    const unsigned v = unsigned(std::stoul(t, nullptr, 16));
    return v <= kFlagMask ? std::optional<std::uint8_t>(std::uint8_t(v)) : std::nullopt;
  }
  std::uint8_t flags = 0;
  std::stringstream names(t);
  const char separator = t.find(',') != std::string::npos ? ',' : '|';  // NV,NX or NV|NX
  for (std::string name; std::getline(names, name, separator);) {
    std::size_t i = 0;
    while (i < kFlagNames.size() && name != kFlagNames[i]) ++i;
    if (i == kFlagNames.size()) return std::nullopt;
    flags = std::uint8_t(flags | (1u << i));
  }
  return flags;
}

std::string decimal(Bits a) {
  const double d = to_double(a);
  if (std::isnan(d)) return "nan";
  if (std::isinf(d)) return d < 0 ? "-inf" : "inf";
  if (d == 0) return std::string((a & kSignBit) ? "-0" : "0") + ((a & 0xFFFF) != 0 ? " (DAZ)" : "");
  // The fewest digits that round back to this encoding; 17 significant
  // bits never need more than 7.
  char buf[32];
  for (int digits = 1; digits <= 7; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, d);
    const std::optional<Result> back = from_decimal(buf);
    if (back && back->value == a) break;
  }
  return buf;
}

std::string describe_operand(Op op, Bits a) { return op == Op::Float ? int16(a) : decimal(a); }

std::string describe_result(Op op, Bits value) {
  if (op == Op::Fix) return int16(value);
  if (op != Op::Cmp) return decimal(value);
  static const char* const kConds[] = {"LT", "EQ", "GT", "UN"};
  std::string s;
  for (int i = 0; i < 4; ++i)
    if (value & (1u << i)) s += (s.empty() ? "" : "|") + std::string(kConds[i]);
  return s.empty() ? "none" : s;
}

std::string mismatch_line(const std::string& source, const Golden& g, const std::string& engine, Result got) {
  const Op op = g.vector.op;
  const int operands = info(op).operands;
  auto result = [&](Result r) {
    return hex(r.value, result_digits(op)) + " " + hex(r.flags, 2) + " (" + describe_result(op, r.value) + "; " +
           flag_names(r.flags) + ")";
  };
  std::string line = source + ":" + std::to_string(g.line) + ": " + engine + ": " + format_vector(g.vector) + " (" +
                     describe_operand(op, g.vector.a);
  if (operands == 2) line += ", " + describe_operand(op, g.vector.b);
  return line + "): expected " + result(g.expected) + ", got " + result(got);
}

GoldenSummary::GoldenSummary(std::vector<std::string> engines)
    : engines_(std::move(engines)), per_(engines_.size()) {}

void GoldenSummary::mismatch(std::size_t engine, const Golden& g, Result got) {
  PerEngine& p = per_[engine];
  ++total_;
  ++p.by_op[int(g.vector.op)];
  if (got.value != g.expected.value) ++p.value;
  for (std::size_t i = 0; i < 5; ++i) {
    const bool want = g.expected.flags & (1u << i), have = got.flags & (1u << i);
    if (want && !have) ++p.flag_missing[i];
    if (have && !want) ++p.flag_extra[i];
  }
}

std::string GoldenSummary::text() const {
  std::ostringstream t;
  char buf[64];
  t << "summary by op (mismatches per engine)\n";
  std::snprintf(buf, sizeof buf, "  %-6s %10s", "op", "vectors");
  t << buf;
  for (const std::string& e : engines_) t << " " << std::string(10 - std::min<std::size_t>(10, e.size()), ' ') << e;
  t << "\n";
  for (int op = 0; op < kOpCount; ++op) {
    if (vectors_[std::size_t(op)] == 0) continue;
    std::snprintf(buf, sizeof buf, "  %-6s %10llu", info(Op(op)).name.data(), (unsigned long long)vectors_[std::size_t(op)]);
    t << buf;
    for (const PerEngine& p : per_) {
      std::snprintf(buf, sizeof buf, " %10llu", (unsigned long long)p.by_op[std::size_t(op)]);
      t << buf;
    }
    t << "\n";
  }
  t << "summary by flag (expected set but clear / clear but set)\n";
  for (std::size_t e = 0; e < engines_.size(); ++e) {
    const PerEngine& p = per_[e];
    t << "  " << engines_[e] << ": result value " << p.value;
    for (int i = 4; i >= 0; --i)
      t << ", " << kFlagNames[std::size_t(i)] << " " << p.flag_missing[std::size_t(i)] << "/"
        << p.flag_extra[std::size_t(i)];
    t << "\n";
  }
  return t.str();
}

}  // namespace mc1::fp24::tb
