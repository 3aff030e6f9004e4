// MPFR oracle for FP24. Deliberately written from docs/fp24.md alone: it
// decodes operands into MPFR numbers, lets MPFR round the exact result to 17
// bits, and encodes that rounded value with the spec's overflow/underflow
// rule. The special-case table of the spec is spelled out per op.
#include "fp24_oracle.hpp"

#include <mpfr.h>

#include <cmath>
#include <cctype>
#include <cstdint>
#include <limits>
#include <string>

namespace mc1::fp24::tb {
namespace {

constexpr mpfr_prec_t kPrec = 17;  // 1.f: 17 significant bits
// SIN/COS are first computed to 64 bits: enough to round to 17 bits in all
// but (astronomically rare) near-midpoint cases, and to measure ulp errors.
constexpr mpfr_prec_t kWide = 64;
constexpr Bits kOne = 0x3F0000;

struct Fields {
  bool neg;
  int exp;
  unsigned frac;
};

Fields fields(Bits a) { return {(a & kSignBit) != 0, int((a >> 16) & 0x7F), unsigned(a & 0xFFFF)}; }
bool is_nan(Bits a) { return fields(a).exp == 127 && fields(a).frac != 0; }
bool is_inf(Bits a) { return fields(a).exp == 127 && fields(a).frac == 0; }
bool is_zero(Bits a) { return fields(a).exp == 0; }  // DAZ: e = 0 reads as zero
bool is_neg(Bits a) { return (a & kSignBit) != 0; }
Bits signed_zero(bool neg) { return neg ? kSignBit : 0; }
Bits signed_inf(bool neg) { return (neg ? kSignBit : 0) | kPosInf; }

constexpr Result kNaN{kCanonicalNaN, 0};
constexpr Result kInvalid{kCanonicalNaN, kNV};

// Loads an FP24 value (finite, zero included, DAZ applied) exactly.
void load(mpfr_t x, Bits a) {
  const Fields f = fields(a);
  if (f.exp == 0) {
    mpfr_set_zero(x, f.neg ? -1 : 1);
    return;
  }
  mpfr_set_ui_2exp(x, 0x10000u | f.frac, f.exp - kBias - kFracBits, MPFR_RNDN);
  if (f.neg) mpfr_neg(x, x, MPFR_RNDN);
}

// Encodes a value MPFR has already rounded to 17 bits (with MPFR's default,
// far wider exponent range), applying steps 3-5 of the spec's rounding rule.
Result encode(mpfr_srcptr r, int ternary) {
  const bool neg = mpfr_signbit(r) != 0;
  if (mpfr_zero_p(r)) return {signed_zero(neg), 0};  // an exact zero
  const long k = mpfr_get_exp(r) - 1;                // |r| in [2^k, 2^(k+1))
  if (k + kBias > 126) return {signed_inf(neg), kOF | kNX};
  if (k + kBias < 1) return {signed_zero(neg), kUF | kNX};
  // |r| * 2^(16-k) is the 17-bit integer significand; doubles hold it exactly.
  const double sig = std::ldexp(std::fabs(mpfr_get_d(r, MPFR_RNDN)), int(kFracBits - k));
  const Bits frac = Bits(sig) & 0xFFFF;
  const Bits exp = Bits(k + kBias) << 16;
  return {(neg ? kSignBit : 0) | exp | frac, std::uint8_t(ternary != 0 ? kNX : 0)};
}

}  // namespace

double to_double(Bits a) {
  const Fields f = fields(a);
  if (f.exp == 127) {
    if (f.frac != 0) return std::numeric_limits<double>::quiet_NaN();
    return f.neg ? -HUGE_VAL : HUGE_VAL;
  }
  const double mag = f.exp == 0 ? 0.0 : std::ldexp(double(0x10000u | f.frac), f.exp - kBias - kFracBits);
  return f.neg ? -mag : mag;
}

// MPFR's default exponent range (about +-2^30) is already "unbounded" for
// FP24, whose exact results stay within 2^+-300, so no emin/emax is changed.
struct Oracle::Vars {
  mpfr_t x, y, r, wide, diff;
  Vars() {
    mpfr_inits2(kPrec, x, y, r, static_cast<mpfr_ptr>(nullptr));
    mpfr_inits2(kWide, wide, diff, static_cast<mpfr_ptr>(nullptr));
  }
  // The thread's MPFR caches (pi and the like, filled by sin and cos) go with
  // the last variables: LeakSanitizer reports them otherwise.
  ~Vars() {
    mpfr_clears(x, y, r, wide, diff, static_cast<mpfr_ptr>(nullptr));
    mpfr_free_cache();
  }
};

namespace {

Result add(Oracle::Vars& v, Bits a, Bits b, bool subtract) {
  if (is_nan(a) || is_nan(b)) return kNaN;
  const bool na = is_neg(a), nb = is_neg(b) != subtract;
  if (is_inf(a) && is_inf(b) && na != nb) return kInvalid;
  if (is_inf(a)) return {signed_inf(na), 0};
  if (is_inf(b)) return {signed_inf(nb), 0};
  load(v.x, a);
  load(v.y, b);
  // IEEE signed-zero rules (MPFR's) are the spec's: x + -x = +0, -0 + -0 = -0.
  const int t = subtract ? mpfr_sub(v.r, v.x, v.y, MPFR_RNDN) : mpfr_add(v.r, v.x, v.y, MPFR_RNDN);
  return encode(v.r, t);
}

Result mul(Oracle::Vars& v, Bits a, Bits b) {
  if (is_nan(a) || is_nan(b)) return kNaN;
  const bool neg = is_neg(a) != is_neg(b);
  if ((is_inf(a) && is_zero(b)) || (is_zero(a) && is_inf(b))) return kInvalid;
  if (is_inf(a) || is_inf(b)) return {signed_inf(neg), 0};
  load(v.x, a);
  load(v.y, b);
  return encode(v.r, mpfr_mul(v.r, v.x, v.y, MPFR_RNDN));
}

Result recip(Oracle::Vars& v, Bits a) {
  if (is_nan(a)) return kNaN;
  if (is_zero(a)) return {signed_inf(is_neg(a)), kDZ};
  if (is_inf(a)) return {signed_zero(is_neg(a)), 0};
  load(v.x, a);
  return encode(v.r, mpfr_ui_div(v.r, 1, v.x, MPFR_RNDN));
}

Result sqrt(Oracle::Vars& v, Bits a) {
  if (is_nan(a)) return kNaN;
  if (is_zero(a)) return {signed_zero(is_neg(a)), 0};
  if (is_neg(a)) return kInvalid;
  if (is_inf(a)) return {kPosInf, 0};
  load(v.x, a);
  return encode(v.r, mpfr_sqrt(v.r, v.x, MPFR_RNDN));
}

// Special operands of SIN/COS, or nullopt-like {false} for a finite nonzero a.
bool trig_special(Op op, Bits a, Result* out) {
  if (is_nan(a)) *out = kNaN;
  else if (is_inf(a)) *out = kInvalid;
  else if (is_zero(a)) *out = op == Op::Sin ? Result{signed_zero(is_neg(a)), 0} : Result{kOne, 0};
  else return false;
  return true;
}

int trig(Op op, mpfr_ptr out, mpfr_srcptr x) {
  return op == Op::Sin ? mpfr_sin(out, x, MPFR_RNDN) : mpfr_cos(out, x, MPFR_RNDN);
}

// Correctly rounded SIN/COS of a finite nonzero a, leaving the 64-bit value
// in v.wide. Rounding the 64-bit value again is safe when mpfr_can_round
// says so (the RNDZ, prec + 1 form decides ties for RNDN); otherwise MPFR
// computes the 17-bit result directly.
Result trig_rounded(Oracle::Vars& v, Op op, Bits a) {
  load(v.x, a);
  const int t_wide = trig(op, v.wide, v.x);
  if (mpfr_can_round(v.wide, kWide - 1, MPFR_RNDN, MPFR_RNDZ, kPrec + 1)) {
    const int t = mpfr_set(v.r, v.wide, MPFR_RNDN);
    return encode(v.r, (t_wide != 0 || t != 0) ? 1 : 0);
  }
  return encode(v.r, trig(op, v.r, v.x));
}

Result cmp(Bits a, Bits b) {
  if (is_nan(a) || is_nan(b)) return {kUN, kNV};
  const double x = to_double(a), y = to_double(b);  // -0.0 == +0.0, as the spec wants
  if (x < y) return {kLT, 0};
  if (x == y) return {kEQ, 0};
  return {kGT, 0};
}

Result from_int(Oracle::Vars& v, Bits a) {
  mpfr_set_si(v.r, std::int16_t(a & 0xFFFF), MPFR_RNDN);  // 16 bits fit 17: exact
  return encode(v.r, 0);
}

Result to_int(Bits a) {
  if (is_nan(a)) return {0x7FFF, kNV};
  const double x = to_double(a);
  const double t = std::trunc(x);
  if (t > 32767.0 || t < -32768.0) return {is_neg(a) ? Bits(0x8000) : Bits(0x7FFF), kNV};
  const Bits value = Bits(std::uint16_t(std::int16_t(t)));
  return {value, std::uint8_t(t != x ? kNX : 0)};
}

Result neg(Bits a) {
  if (is_nan(a)) return kNaN;
  if (is_zero(a)) return {signed_zero(!is_neg(a)), 0};
  return {a ^ kSignBit, 0};
}

Result abs(Bits a) {
  if (is_nan(a)) return kNaN;
  if (is_zero(a)) return {0, 0};
  return {a & ~kSignBit, 0};
}

}  // namespace

Oracle::Oracle() : v_(std::make_unique<Vars>()) {}
Oracle::~Oracle() = default;

Result Oracle::run(Op op, Bits a, Bits b) {
  a &= 0xFFFFFF;
  b &= 0xFFFFFF;
  switch (op) {
    case Op::Add: return add(*v_, a, b, false);
    case Op::Sub: return add(*v_, a, b, true);
    case Op::Mul: return mul(*v_, a, b);
    case Op::Recip: return recip(*v_, a);
    case Op::Sqrt: return sqrt(*v_, a);
    case Op::Sin:
    case Op::Cos: {
      Result special;
      return trig_special(op, a, &special) ? special : trig_rounded(*v_, op, a);
    }
    case Op::Cmp: return cmp(a, b);
    case Op::Float: return from_int(*v_, a);
    case Op::Fix: return to_int(a);
    case Op::Neg: return neg(a);
    case Op::Abs: return abs(a);
  }
  return kInvalid;
}

Oracle::Measured Oracle::measure(Op op, Bits a, Bits candidate) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  a &= 0xFFFFFF;
  Result special;
  if (trig_special(op, a, &special)) return {special, candidate == special.value ? 0.0 : kInf};
  const Result rounded = trig_rounded(*v_, op, a);  // exact value now in v_->wide
  if (is_nan(candidate) || is_inf(candidate) || is_zero(candidate)) return {rounded, kInf};
  load(v_->x, candidate);
  mpfr_sub(v_->diff, v_->x, v_->wide, MPFR_RNDN);
  // ulp(y) = 2^(k-16) for |y| in [2^k, 2^(k+1)), and mpfr_get_exp(y) = k + 1.
  mpfr_mul_2si(v_->diff, v_->diff, kFracBits + 1 - mpfr_get_exp(v_->wide), MPFR_RNDN);
  return {rounded, std::fabs(mpfr_get_d(v_->diff, MPFR_RNDN))};
}

std::optional<Result> from_decimal(std::string_view text) {
  std::string t(text);
  std::string lower;
  for (char c : t) lower += char(std::tolower(static_cast<unsigned char>(c)));
  if (lower == "nan" || lower == "+nan" || lower == "-nan") return Result{kCanonicalNaN, 0};
  if (lower == "inf" || lower == "+inf" || lower == "infinity") return Result{kPosInf, 0};
  if (lower == "-inf" || lower == "-infinity") return Result{kSignBit | kPosInf, 0};
  if (t.empty() || t.find_first_not_of("+-.0123456789eE") != std::string::npos) return std::nullopt;
  mpfr_t x;
  mpfr_init2(x, kPrec);
  char* end = nullptr;
  const int ternary = mpfr_strtofr(x, t.c_str(), &end, 10, MPFR_RNDN);
  std::optional<Result> r;
  if (end == t.c_str() + t.size()) {
    // Beyond even MPFR's exponent range: overflow or underflow all the same.
    if (mpfr_inf_p(x)) r = Result{signed_inf(mpfr_signbit(x) != 0), kOF | kNX};
    else if (mpfr_zero_p(x) && ternary != 0) r = Result{signed_zero(mpfr_signbit(x) != 0), kUF | kNX};
    else r = encode(x, ternary);
  }
  mpfr_clear(x);
  return r;
}

}  // namespace mc1::fp24::tb
