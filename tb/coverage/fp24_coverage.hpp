// Functional coverage of the FP24 units (docs/fp24-verification.md
// "Coverage"): for every op, the class of each operand (zero, denormal
// encoding, normal, max, inf, NaN, each sign; FLOAT: its integer's), the
// class of the result (a "flushed" result is one in the subnormal range,
// flushed to zero), the rounding outcome against the exact value (exact,
// down, up, tie: toward or away from zero in magnitude, a tie going to even),
// each flag raised (or none), and for ADD and SUB the exponent difference
// of two normal operands. Bins: fp24.<op>.{a,b,result,round,flag,expdiff}.<class>.
#pragma once

#include <memory>

#include "coverage_bins.hpp"
#include "fp24.hpp"

namespace mc1::cov {

// The class names the bins use.
const char* fp24_operand_class(fp24::Bits x);       // "+zero", "-sub", "+norm", "-max", "+inf", "-nan", ...
const char* fp24_int_class(fp24::Bits x);           // FLOAT's operand: "zero", "pos", "neg", "max", "min"
const char* fp24_result_class(fp24::Op op, const fp24::Result& r);  // also "+flushed"; CMP "lt".."un"; FIX
const char* fp24_expdiff_class(fp24::Bits a, fp24::Bits b);  // nullptr unless both are normal

class Fp24Coverage {
 public:
  explicit Fp24Coverage(Bins& bins);  // declares the fp24.* bins in `bins`
  ~Fp24Coverage();
  Fp24Coverage(const Fp24Coverage&) = delete;
  Fp24Coverage& operator=(const Fp24Coverage&) = delete;

  // One op as a unit executed it (b ignored by one-operand ops; FLOAT reads
  // the integer in a's low 16 bits); the result is the model's (the same
  // bits as the RTL's in a lockstep run).
  void sample(fp24::Op op, fp24::Bits a, fp24::Bits b = 0);
  // The rounding outcome of op on (a, b): "exact", "down", "up", "tie", or
  // nullptr when it does not apply (NaN or inf involved, CMP, NEG, ABS).
  const char* rounding(fp24::Op op, fp24::Bits a, fp24::Bits b, const fp24::Result& r);

 private:
  Bins& bins_;
  struct Mpfr;  // the MPFR variables, reused
  std::unique_ptr<Mpfr> m_;
};

}  // namespace mc1::cov
