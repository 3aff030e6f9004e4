// FP24 unit coverage (fp24_coverage.hpp). The exact values come from MPFR
// at a precision that holds every sum and product of two FP24 values
// exactly; RECIP, SQRT, SIN and COS are compared with a 200-bit value (their
// exact value is never halfway between two FP24 values, so 200 bits decide).
#include "fp24_coverage.hpp"

#include <mpfr.h>

#include <string>

namespace mc1::cov {

namespace {

using fp24::Bits;
using fp24::Op;

constexpr mpfr_prec_t kExactBits = 400;  // |exponent difference| <= 126, 17-bit significands
constexpr mpfr_prec_t kFuncBits = 200;

int exp_field(Bits x) { return static_cast<int>(x >> 16) & 0x7F; }
bool is_normal(Bits x) { return exp_field(x) != 0 && exp_field(x) != 0x7F; }
bool is_special(Bits x) { return exp_field(x) == 0x7F; }

std::string op_name(Op op) { return std::string(fp24::info(op).name); }
bool two_operands(Op op) { return fp24::info(op).operands == 2; }

const char* const kFpClasses[] = {"zero", "sub", "norm", "max", "inf", "nan"};
const char* const kResultClasses[] = {"zero", "flushed", "norm", "max", "inf", "nan"};
const char* const kIntClasses[] = {"zero", "pos", "neg", "max", "min"};
const char* const kCmpClasses[] = {"lt", "eq", "gt", "un"};
const char* const kFlagNames[] = {"nx", "uf", "of", "dz", "nv"};
const char* const kExpDiff[] = {"0", "1", "2-16", "17", "18", "19-63", "64+"};

// The rounding outcomes an op can have at all (FLOAT: every 16-bit
// integer fits 17 bits; FIX truncates toward zero; a tie needs an exact
// value with one more bit than FP24 holds, which only a sum or product has).
std::vector<const char*> roundings(Op op) {
  switch (op) {
    case Op::Add:
    case Op::Sub:
    case Op::Mul: return {"exact", "down", "up", "tie"};
    case Op::Recip:
    case Op::Sqrt:
    case Op::Sin:
    case Op::Cos: return {"exact", "down", "up"};
    case Op::Fix: return {"exact", "down"};
    case Op::Float: return {"exact"};
    default: return {};
  }
}

std::vector<std::string> result_classes(Op op) {
  std::vector<std::string> out;
  if (op == Op::Cmp) {
    for (const char* c : kCmpClasses) out.push_back(c);
  } else if (op == Op::Fix) {
    for (const char* c : {"zero", "pos", "neg", "max", "min"}) out.push_back(c);
  } else {
    for (const char* s : {"+", "-"})
      for (const char* c : kResultClasses) out.push_back(std::string(s) + c);
  }
  return out;
}

std::vector<std::string> operand_classes(Op op) {
  std::vector<std::string> out;
  if (op == Op::Float) {
    for (const char* c : kIntClasses) out.push_back(c);
  } else {
    for (const char* s : {"+", "-"})
      for (const char* c : kFpClasses) out.push_back(std::string(s) + c);
  }
  return out;
}

}  // namespace

const char* fp24_operand_class(Bits x) {
  static const char* const kNames[2][6] = {{"+zero", "+sub", "+norm", "+max", "+inf", "+nan"},
                                           {"-zero", "-sub", "-norm", "-max", "-inf", "-nan"}};
  const int sign = (x >> 23) & 1, e = exp_field(x), f = static_cast<int>(x & 0xFFFF);
  int c = 2;
  if (e == 0) c = f == 0 ? 0 : 1;
  else if (e == 0x7F) c = f == 0 ? 4 : 5;
  else if ((x & 0x7FFFFF) == fp24::kMaxFinite) c = 3;
  return kNames[sign][c];
}

const char* fp24_int_class(Bits x) {
  const auto i = static_cast<std::int16_t>(x & 0xFFFF);
  if (i == 0) return "zero";
  if (i == 32767) return "max";
  if (i == -32768) return "min";
  return i > 0 ? "pos" : "neg";
}

const char* fp24_result_class(Op op, const fp24::Result& r) {
  if (op == Op::Cmp) {
    if (r.value & fp24::kLT) return "lt";
    if (r.value & fp24::kEQ) return "eq";
    if (r.value & fp24::kGT) return "gt";
    return "un";
  }
  if (op == Op::Fix) return fp24_int_class(r.value);
  static const char* const kNames[2][6] = {{"+zero", "+flushed", "+norm", "+max", "+inf", "+nan"},
                                           {"-zero", "-flushed", "-norm", "-max", "-inf", "-nan"}};
  const int sign = (r.value >> 23) & 1;
  const char* c = fp24_operand_class(r.value);
  int k = 2;
  if (c[1] == 'z') k = (r.flags & fp24::kUF) ? 1 : 0;
  else if (c[1] == 'm') k = 3;
  else if (c[1] == 'i') k = 4;
  else if (c[1] == 'n' && c[2] == 'a') k = 5;
  return kNames[sign][k];
}

const char* fp24_expdiff_class(Bits a, Bits b) {
  if (!is_normal(a) || !is_normal(b)) return nullptr;
  const int d = exp_field(a) > exp_field(b) ? exp_field(a) - exp_field(b) : exp_field(b) - exp_field(a);
  if (d <= 1) return kExpDiff[d];
  if (d <= 16) return kExpDiff[2];
  if (d <= 18) return kExpDiff[d - 14];
  return d <= 63 ? kExpDiff[5] : kExpDiff[6];
}

struct Fp24Coverage::Mpfr {
  mpfr_t a, b, exact, r, other, mid;
  Mpfr() {
    for (mpfr_ptr v : {a, b, exact, r, other, mid}) mpfr_init2(v, kExactBits);
  }
  ~Mpfr() {
    for (mpfr_ptr v : {a, b, exact, r, other, mid}) mpfr_clear(v);
  }
  // A finite FP24 value, denormal encodings read as zero (DAZ).
  static void set(mpfr_ptr v, Bits x) {
    const int e = exp_field(x);
    if (e == 0) mpfr_set_zero(v, 1);
    else mpfr_set_ui_2exp(v, 0x10000u | (x & 0xFFFF), e - 63 - 16, MPFR_RNDN);
    if (x & fp24::kSignBit) mpfr_neg(v, v, MPFR_RNDN);
  }
};

Fp24Coverage::Fp24Coverage(Bins& bins) : bins_(bins), m_(std::make_unique<Mpfr>()) {
  for (int k = 0; k < fp24::kOpCount; ++k) {
    const Op op = static_cast<Op>(k);
    const std::string p = "fp24." + op_name(op) + ".";
    for (const auto& c : operand_classes(op)) {
      bins_.declare(p + "a." + c);
      if (two_operands(op)) bins_.declare(p + "b." + c);
    }
    for (const auto& c : result_classes(op)) bins_.declare(p + "result." + c);
    for (const char* c : roundings(op)) bins_.declare(p + "round." + c);
    bins_.declare(p + "flag.none");
    for (const char* f : kFlagNames) bins_.declare(p + "flag." + f);
    if (op == Op::Add || op == Op::Sub)
      for (const char* c : kExpDiff) bins_.declare(p + "expdiff." + c);
  }
}

Fp24Coverage::~Fp24Coverage() = default;

const char* Fp24Coverage::rounding(Op op, Bits a, Bits b, const fp24::Result& r) {
  if (op == Op::Cmp || op == Op::Neg || op == Op::Abs) return nullptr;
  Mpfr& m = *m_;
  if (op == Op::Float) {
    mpfr_set_si(m.exact, static_cast<std::int16_t>(a & 0xFFFF), MPFR_RNDN);
  } else {
    if (is_special(a) || (two_operands(op) && is_special(b))) return nullptr;
    Mpfr::set(m.a, a);
    Mpfr::set(m.b, b);
    switch (op) {
      case Op::Add: mpfr_add(m.exact, m.a, m.b, MPFR_RNDN); break;
      case Op::Sub: mpfr_sub(m.exact, m.a, m.b, MPFR_RNDN); break;
      case Op::Mul: mpfr_mul(m.exact, m.a, m.b, MPFR_RNDN); break;
      case Op::Fix: mpfr_set(m.exact, m.a, MPFR_RNDN); break;
      default: {
        if ((op == Op::Recip && mpfr_zero_p(m.a)) || (op == Op::Sqrt && mpfr_sgn(m.a) < 0)) return nullptr;  // inf, NaN
        mpfr_set_prec(m.exact, kFuncBits);
        if (op == Op::Recip) mpfr_ui_div(m.exact, 1, m.a, MPFR_RNDN);
        else if (op == Op::Sqrt) mpfr_sqrt(m.exact, m.a, MPFR_RNDN);
        else if (op == Op::Sin) mpfr_sin(m.exact, m.a, MPFR_RNDN);
        else mpfr_cos(m.exact, m.a, MPFR_RNDN);
        mpfr_prec_round(m.exact, kExactBits, MPFR_RNDN);
      }
    }
  }
  if (op == Op::Fix) {
    if (r.flags & fp24::kNV) return nullptr;  // saturated or NaN: no rounding
    mpfr_set_si(m.r, static_cast<std::int16_t>(r.value & 0xFFFF), MPFR_RNDN);
    return mpfr_cmpabs(m.r, m.exact) == 0 ? "exact" : "down";
  }
  if (exp_field(r.value) == 0x7F) return (r.flags & fp24::kOF) ? "up" : nullptr;  // overflow, or NaN
  Mpfr::set(m.r, r.value);
  const int c = mpfr_cmpabs(m.r, m.exact);
  if (c == 0) return "exact";
  if (mpfr_zero_p(m.r)) return "down";  // flushed
  // The FP24 neighbour on the exact value's other side; halfway between: a tie.
  const Bits mag = r.value & 0x7FFFFF;
  const Bits other = (r.value & fp24::kSignBit) | (c > 0 ? mag - 1 : mag + 1);
  if (exp_field(other) != 0x7F && !(exp_field(other) == 0 && (other & 0xFFFF))) {
    Mpfr::set(m.other, other);
    mpfr_add(m.mid, m.r, m.other, MPFR_RNDN);
    mpfr_div_2ui(m.mid, m.mid, 1, MPFR_RNDN);
    if (mpfr_cmp(m.mid, m.exact) == 0) return "tie";
  }
  return c > 0 ? "up" : "down";
}

void Fp24Coverage::sample(Op op, Bits a, Bits b) {
  const fp24::Result r = fp24::execute(op, a, b);
  const std::string p = "fp24." + op_name(op) + ".";
  bins_.hit(p + "a." + (op == Op::Float ? fp24_int_class(a) : fp24_operand_class(a)));
  if (two_operands(op)) bins_.hit(p + "b." + fp24_operand_class(b));
  bins_.hit(p + "result." + fp24_result_class(op, r));
  if (const char* c = rounding(op, a, b, r)) bins_.hit(p + "round." + c);
  if (r.flags == 0) bins_.hit(p + "flag.none");
  for (int f = 0; f < 5; ++f)
    if (r.flags >> f & 1) bins_.hit(p + "flag." + kFlagNames[f]);
  if (op == Op::Add || op == Op::Sub)
    if (const char* d = fp24_expdiff_class(a, b)) bins_.hit(p + "expdiff." + d);
}

}  // namespace mc1::cov
