// FP24 oracle: every operation of docs/fp24.md computed with MPFR, sharing no
// arithmetic with the integer model in hw/apu (only its Result/Op types).
// Rounding follows the spec literally: MPFR rounds to 17 bits (RNDN) with an
// unbounded exponent, then the spec's overflow/underflow rule is applied to
// that rounded value; NX comes from MPFR's ternary value.
#pragma once

#include <memory>
#include <optional>
#include <string_view>

#include "fp24.hpp"

namespace mc1::fp24::tb {

// An oracle owns its MPFR variables and is therefore not shareable between
// threads: give each worker thread its own.
class Oracle {
 public:
  Oracle();
  ~Oracle();
  Oracle(const Oracle&) = delete;
  Oracle& operator=(const Oracle&) = delete;

  // The correctly rounded result and flags of op; b is ignored by
  // one-operand ops (FLOAT reads its integer from the low 16 bits of a).
  Result run(Op op, Bits a, Bits b = 0);

  // SIN/COS: the correctly rounded result, and the error of `candidate`
  // (another engine's answer) in ulps of the exact value sin(a)/cos(a),
  // measured against a 64-bit approximation (relative error < 2^-63).
  // The error is 0 when both are the same special value, +inf when the
  // candidate is NaN/inf/zero but the exact value is not (or vice versa).
  struct Measured {
    Result rounded;
    double ulp_error;
  };
  Measured measure(Op op, Bits a, Bits candidate);

  struct Vars;  // the reused MPFR variables (opaque; defined in the .cpp)

 private:
  std::unique_ptr<Vars> v_;
};

// Exact value of an FP24 encoding as a double (DAZ applied; NaN and inf map
// to the double NaN/inf). Every FP24 value is exactly representable.
double to_double(Bits a);

// A decimal number ("1.5", "-2.5e-3", "inf", "nan") rounded to FP24 by the
// spec's one rule (17 bits RNE, then overflow to inf / tininess after
// rounding to zero), with the flags that rounding raises; nullopt if `text`
// is not a number.
std::optional<Result> from_decimal(std::string_view text);

}  // namespace mc1::fp24::tb
