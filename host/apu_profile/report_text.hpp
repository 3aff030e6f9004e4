// Text helpers of the APU reports (apu_profile, apu_stall_profile, and mc1's
// timing tables in host/mc1/report_profile.cpp): printf into
// a string, and a JSON string's body with quotes, backslashes and control
// characters escaped.
#pragma once

#include <cstdarg>
#include <cstdio>
#include <string>

namespace mc1::apu::report_text {

inline std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
inline std::string format(const char* fmt, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  return buf;
}

inline std::string json_escape(const std::string& text) {
  std::string o;
  for (unsigned char c : text) {
    if (c == '"' || c == '\\') o += '\\';
    if (c < 0x20) o += format("\\u%04x", c);
    else o += static_cast<char>(c);
  }
  return o;
}

}  // namespace mc1::apu::report_text
