// fp24-conv: FP24 values and flags by hand, for writing golden files.
//   fp24-conv 1.5 0.1 1e30     decimal -> FP24 hex, with the flags rounding raises
//   fp24-conv 0x3f8000         FP24 hex -> decimal and fields
//   fp24-conv --flags 0x11 NV,NX
#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

#include "cmdline.hpp"
#include "fp24_golden.hpp"
#include "fp24_oracle.hpp"

namespace {

using namespace mc1::fp24;
using namespace mc1::fp24::tb;
namespace cli = mc1::cmdline;

constexpr const char* kDescription =
    "fp24-conv: FP24 values and flags by hand (docs/fp24-verification.md).\n"
    "Each VALUE with a 0x prefix is an FP24 encoding: printed as its decimal value\n"
    "and its fields. Any other VALUE is a decimal number (or inf, -inf, nan):\n"
    "printed as the FP24 encoding that docs/fp24.md's rounding rule gives (17 bits,\n"
    "ties to even, overflow to inf, tininess after rounding to zero) with the flags\n"
    "that rounding raises and the value read back. With --flags each VALUE is a\n"
    "flags field, hex (0x11) or names (NV|NX, nv,nx, -), printed both ways.\n"
    "Flags: NV 10 invalid, DZ 08 divide by zero, OF 04 overflow, UF 02 underflow,\n"
    "NX 01 inexact.";

std::string hex6(Bits v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%06x", v);
  return buf;
}

std::string flags_text(std::uint8_t f) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%02x", unsigned(f));
  return std::string(buf) + " (" + flag_names(f) + ")";
}

// One VALUE's line, or a UsageError naming it.
std::string convert(const std::string& value, bool flags) {
  if (flags) {
    const std::optional<std::uint8_t> f = parse_flags(value);
    if (!f) throw cli::UsageError("VALUE '" + value + "': not flags (hex 00..1f or names NV DZ OF UF NX)");
    return value + ": " + flags_text(*f);
  }
  if (value.size() > 2 && value[0] == '0' && (value[1] == 'x' || value[1] == 'X')) {
    const Bits a = Bits(cli::parse_unsigned("VALUE", value, 0, 0xFFFFFF));
    char fields[64];
    std::snprintf(fields, sizeof fields, "s %u e %u f %04x", a >> 23, (a >> 16) & 0x7F, a & 0xFFFF);
    return hex6(a) + ": " + decimal(a) + " (" + fields + ")";
  }
  const std::optional<Result> r = from_decimal(value);
  if (!r) throw cli::UsageError("VALUE '" + value + "': not a decimal number, inf, nan or 0x encoding");
  return value + ": " + hex6(r->value) + " flags " + flags_text(r->flags) + ", reads back " + decimal(r->value);
}

// A VALUE such as -inf or -nan starts with '-' but is no number to CLI11,
// which would read it as short options (-i -n -f). When one is given, the
// command line is parsed as: the options, "--", then every VALUE in its
// order ("--" stays where the user put one).
std::vector<std::string> with_values_last(int argc, char** argv) {
  const auto negative_special = [](std::string v) {
    for (char& c : v) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return v == "-inf" || v == "-infinity" || v == "-nan";
  };
  std::vector<std::string> options, values;
  bool special = false, rest = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (rest || a == "--") {
      if (rest) values.push_back(a);
      rest = true;
      continue;
    }
    special = special || negative_special(a);
    (a.size() > 1 && a[0] == '-' && !negative_special(a) && !std::isdigit(static_cast<unsigned char>(a[1])) &&
             a[1] != '.'
         ? options
         : values)
        .push_back(a);
  }
  std::vector<std::string> out{argv[0]};
  if (!special) out.assign(argv, argv + argc);
  else {
    out.insert(out.end(), options.begin(), options.end());
    out.push_back("--");
    out.insert(out.end(), values.begin(), values.end());
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{kDescription, "fp24-conv"};
  cli::conventions(app, "Exit status: 0 done; 1 standard output could not be written; 2 usage error (a VALUE\n"
                        "that is not a number).");
  std::vector<std::string> values;
  bool flags = false;
  app.add_option("VALUE", values, "decimal numbers, 0x encodings, or (--flags) flags")->required();
  app.add_flag("--flags", flags, "read each VALUE as a flags field");
  std::vector<std::string> args = with_values_last(argc, argv);
  std::vector<char*> arg_ptrs;
  for (std::string& a : args) arg_ptrs.push_back(a.data());
  if (auto rc = cli::parse(app, static_cast<int>(arg_ptrs.size()), arg_ptrs.data())) return *rc;
  std::string out;
  try {
    for (const std::string& v : values) out += convert(v, flags) + "\n";
  } catch (const cli::UsageError& e) {
    return cli::usage_error(app, e.what());
  }
  std::fputs(out.c_str(), stdout);
  return cli::flush_stdout("fp24-conv", cli::kExitOk);
}
