// The op table: spelling, unit, operand count, timing and RTL op code of
// every FP24 operation. RTL, model, ISS and assembler all read timing here
// (docs/fp24-rtl.md restates it for the Verilog side).
#include "fp24.hpp"

#include <array>

#include "apu_isa.hpp"

namespace mc1::fp24 {
namespace {

// The latencies are the instruction-set table's (apu_rtl/isa/apu_isa.tbl):
// the multiplier and the adder are the paper's 2-stage pipes; the function
// unit's RECIP/SQRT (seed ROM, interpolation, remainder check) and SIN/COS
// take more stages, still one issue per cycle (docs/fp24-func.md).
constexpr int kAdd = apu::kAddLatency;
constexpr int kMul = apu::kMulLatency;
constexpr int kFunc = apu::kFuncLatency;
constexpr int kTrig = apu::kTrigLatency;
constexpr std::array<OpInfo, kOpCount> kOps = {{
    {"add", Unit::Adder, 2, kAdd, 1, 0},   {"sub", Unit::Adder, 2, kAdd, 1, 1},
    {"mul", Unit::Mul, 2, kMul, 1, 0},     {"recip", Unit::Func, 1, kFunc, 1, 0},
    {"sqrt", Unit::Func, 1, kFunc, 1, 1},  {"sin", Unit::Func, 1, kTrig, 1, 2},
    {"cos", Unit::Func, 1, kTrig, 1, 3},   {"cmp", Unit::Adder, 2, kAdd, 1, 2},
    {"float", Unit::Adder, 1, kAdd, 1, 3}, {"fix", Unit::Adder, 1, kAdd, 1, 4},
    {"neg", Unit::Adder, 1, kAdd, 1, 5},   {"abs", Unit::Adder, 1, kAdd, 1, 6},
}};

}  // namespace

const OpInfo& info(Op op) { return kOps[static_cast<int>(op)]; }

std::optional<Op> op_from_name(std::string_view name) {
  for (int i = 0; i < kOpCount; ++i)
    if (kOps[i].name == name) return static_cast<Op>(i);
  return std::nullopt;
}

Result execute(Op op, Bits a, Bits b) {
  switch (op) {
    case Op::Add: return add(a, b);
    case Op::Sub: return sub(a, b);
    case Op::Mul: return mul(a, b);
    case Op::Recip: return recip(a);
    case Op::Sqrt: return sqrt(a);
    case Op::Sin: return sin(a);
    case Op::Cos: return cos(a);
    case Op::Cmp: return cmp(a, b);
    case Op::Float: return from_int(static_cast<std::uint16_t>(a));
    case Op::Fix: return to_int(a);
    case Op::Neg: return neg(a);
    case Op::Abs: return abs(a);
  }
  return {kCanonicalNaN, kNV};
}

}  // namespace mc1::fp24
