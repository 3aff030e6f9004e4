// FP24's range as the scene loader checks the values it converts (docs/fp24.md):
// shared by the JSON loader and the patch-file reader.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include <glm/glm.hpp>

namespace mc1::scene {

// FP24's magnitudes (docs/fp24.md): largest finite (2 - 2^-16) 2^63, smallest
// normal 2^-62. A scene value outside them would become inf or 0 on the NC.
inline const double kFp24Max = std::ldexp(2.0 - std::ldexp(1.0, -16), 63);
inline const double kFp24MinNormal = std::ldexp(1.0, -62);
inline const char* const kFp24Range = "0 or a magnitude in [2.168e-19, 1.8447e19], FP24's range";

inline bool in_fp24_range(double d) {
  double a = std::abs(d);
  return a == 0 || (a >= kFp24MinNormal && a <= kFp24Max);
}
inline bool below_fp24_max(const glm::dvec3& v) {
  return std::abs(v.x) <= kFp24Max && std::abs(v.y) <= kFp24Max && std::abs(v.z) <= kFp24Max;
}

inline std::string shortest(double d) {
  std::ostringstream o;
  o << d;
  return o.str();
}

}  // namespace mc1::scene
