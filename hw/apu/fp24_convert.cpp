#include "fp24_convert.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "fp24_bits.hpp"

namespace mc1::fp24 {

std::uint32_t fp24_from_double(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  const std::uint32_t sign = (u >> 63) ? 0x800000u : 0u;
  const int e = static_cast<int>((u >> 52) & 0x7FF);
  const std::uint64_t f = u & ((std::uint64_t{1} << 52) - 1);
  if (e == 0x7FF) return f ? 0x7F8000u : (sign | 0x7F0000u);  // NaN, inf
  if (e == 0) return sign;                                     // zero, subnormal: far below 2^-62
  // 53-bit significand, leading one at bit 52: 17 bits kept, the 36 below
  // are the guard and the sticky of the one rounding rule.
  const std::uint64_t sig = (std::uint64_t{1} << 52) | f;
  return bits::round_sig<36>(sign, e - 1023 + kBias, sig).value;
}

double fp24_to_double(std::uint32_t bits) {
  const int e = static_cast<int>((bits >> 16) & 0x7F);
  const bool neg = (bits & 0x800000u) != 0;
  if (e == 0) return neg ? -0.0 : 0.0;
  // Assemble the binary64 encoding: same value, exponent rebiased.
  std::uint64_t u = neg ? (std::uint64_t{1} << 63) : 0;
  if (e == 127) {
    u |= std::uint64_t{0x7FF} << 52;
    if (bits & 0xFFFF) u |= std::uint64_t{1} << 51;
  } else {
    u |= static_cast<std::uint64_t>(e - 63 + 1023) << 52;
    u |= static_cast<std::uint64_t>(bits & 0xFFFF) << 36;
  }
  double x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}

std::string fp24_decimal(std::uint32_t w) {
  const double d = fp24_to_double(w);
  if (std::isnan(d)) return "nan";
  if (std::isinf(d)) return d < 0 ? "-inf" : "inf";
  if (d == 0) return std::string((w & 0x800000) ? "-0" : "0") + ((w & 0xFFFF) ? " (DAZ)" : "");
  char buf[32];
  for (int digits = 1; digits <= 7; ++digits) {  // 17 bits: 7 digits always read back
    std::snprintf(buf, sizeof buf, "%.*g", digits, d);
    if (fp24_from_double(std::strtod(buf, nullptr)) == w) break;
  }
  return buf;
}

}  // namespace mc1::fp24
