// FP24: the APU's 24-bit floating-point format and its operations.
// Bit-accurate C++ model of docs/fp24.md (s1 e7 f16, bias 63, RNE, DAZ/FTZ).
// Integer arithmetic only: no host float, no long double, no MPFR.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace mc1::fp24 {

// An FP24 encoding lives in the low 24 bits; the upper 8 bits are always zero.
using Bits = std::uint32_t;

constexpr Bits kSignBit = 0x800000;
constexpr Bits kCanonicalNaN = 0x7F8000;
constexpr Bits kPosInf = 0x7F0000;
constexpr Bits kMaxFinite = 0x7EFFFF;
constexpr int kBias = 63;
constexpr int kFracBits = 16;

// Exception flags, RISC-V fflags order (docs/fp24.md).
enum Flag : std::uint8_t {
  kNX = 0x01,  // inexact
  kUF = 0x02,  // underflow (tiny after rounding)
  kOF = 0x04,  // overflow
  kDZ = 0x08,  // divide by zero
  kNV = 0x10,  // invalid
};

// CMP condition code, returned in Result::value by cmp().
enum Cond : std::uint8_t { kLT = 0x1, kEQ = 0x2, kGT = 0x4, kUN = 0x8 };

struct Result {
  Bits value;          // FP24 encoding; CMP: condition; FIX: 16-bit integer
  std::uint8_t flags;  // Flag bits
  bool operator==(const Result& o) const { return value == o.value && flags == o.flags; }
  bool operator!=(const Result& o) const { return !(*this == o); }
};

enum class Op : std::uint8_t { Add, Sub, Mul, Recip, Sqrt, Sin, Cos, Cmp, Float, Fix, Neg, Abs };
constexpr int kOpCount = 12;

enum class Unit : std::uint8_t { Mul, Adder, Func };

// Static facts about an op: its spelling in the vector interface, the unit
// that executes it, its operand count and its pipeline timing (identical in
// RTL, model and ISS), and its op code on the unit's RTL `op` port.
struct OpInfo {
  std::string_view name;
  Unit unit;
  int operands;
  int latency;   // cycles from issue until the result is usable
  int interval;  // cycles from issue until the unit accepts its next op
  std::uint8_t rtl_code;
};

const OpInfo& info(Op op);
std::optional<Op> op_from_name(std::string_view name);

// Multiplier.
Result mul(Bits a, Bits b);
// Adder unit.
Result add(Bits a, Bits b);
Result sub(Bits a, Bits b);
Result cmp(Bits a, Bits b);
Result from_int(std::uint16_t i);  // FLOAT: two's-complement 16-bit integer
Result to_int(Bits a);             // FIX: toward zero, saturating, 16-bit result
Result neg(Bits a);
Result abs(Bits a);
// Function unit.
Result recip(Bits a);
Result sqrt(Bits a);
Result sin(Bits a);
Result cos(Bits a);

// Dispatch by op; b is ignored by one-operand ops.
Result execute(Op op, Bits a, Bits b = 0);

}  // namespace mc1::fp24
