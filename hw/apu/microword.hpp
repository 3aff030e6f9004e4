// The APU's 128-bit horizontal microword (docs/apu-isa.md): its fields as a
// value type, and the bit packing shared by the assembler, the ISS, the RTL
// harness and the co-simulator.
#pragma once

#include <cstdint>

namespace mc1::apu {

constexpr int kNumFRegs = 64;
constexpr int kNumARegs = 16;
constexpr int kProgramWords = 1024;  // per bank
constexpr int kDataWords = 4096;     // per bank
constexpr int kCallDepth = 8;

enum class AddOp : std::uint8_t { Add = 0, Sub, Cmp, Float, Fix, Neg, Abs };
enum class FuncOp : std::uint8_t { Recip = 0, Sqrt, Sin, Cos };
enum class MemOp : std::uint8_t { None = 0, Ld, St };
enum class IntOp : std::uint8_t {
  None = 0, Li, Addi, Add, Sub, Muli, Shl, Shr, Sra, Andi, Ori, Xor, Movaf, Movfa, Lif, Reserved
};
enum class SeqOp : std::uint8_t {
  Next = 0, Jmp, Bcc, Bncc, Dbnz, Bz, Bnz, Bltz, Call, Ret, Swapd, Swapp, Halt,
  Reserved13, Reserved14, Reserved15
};

struct MulSlot { bool en = false; std::uint8_t d = 0, a = 0, b = 0; };
struct AddSlot { bool en = false; AddOp op = AddOp::Add; std::uint8_t d = 0, a = 0, b = 0; };
struct FuncSlot { bool en = false; FuncOp op = FuncOp::Recip; std::uint8_t d = 0, a = 0; };
struct MemSlot { MemOp op = MemOp::None; std::uint8_t f = 0, base = 0; std::int8_t disp = 0; };
struct IntSlot { IntOp op = IntOp::None; std::uint8_t d = 0, s = 0, t = 0; std::uint16_t imm = 0; };
struct SeqSlot { SeqOp op = SeqOp::Next; std::uint8_t r = 0; std::uint16_t target = 0; };

// A microword as two 64-bit halves: lo holds bits 0..63, hi bits 64..127.
struct Encoded {
  std::uint64_t lo = 0, hi = 0;
  bool operator==(const Encoded& o) const { return lo == o.lo && hi == o.hi; }
  bool operator!=(const Encoded& o) const { return !(*this == o); }
};

struct MicroWord {
  MulSlot m;
  AddSlot a;
  FuncSlot f;
  MemSlot d;
  IntSlot i;
  SeqSlot s;

  Encoded encode() const;
  static MicroWord decode(const Encoded& e);
};

namespace field {
// Bit positions of docs/apu-isa.md's microword table.
constexpr int kM = 0, kA = 19, kF = 41, kD = 56, kI = 76, kS = 110;
}  // namespace field

namespace detail {
inline std::uint64_t get(const Encoded& e, int pos, int width) {
  // A field may straddle the 64-bit boundary.
  unsigned __int128 all = (static_cast<unsigned __int128>(e.hi) << 64) | e.lo;
  return static_cast<std::uint64_t>(all >> pos) & ((std::uint64_t{1} << width) - 1);
}
inline void put(Encoded& e, int pos, int width, std::uint64_t v) {
  unsigned __int128 all = (static_cast<unsigned __int128>(e.hi) << 64) | e.lo;
  const unsigned __int128 mask = static_cast<unsigned __int128>((std::uint64_t{1} << width) - 1) << pos;
  all = (all & ~mask) | ((static_cast<unsigned __int128>(v) << pos) & mask);
  e.lo = static_cast<std::uint64_t>(all);
  e.hi = static_cast<std::uint64_t>(all >> 64);
}
}  // namespace detail

inline Encoded MicroWord::encode() const {
  using detail::put;
  using namespace field;
  Encoded e;
  put(e, kM, 1, m.en); put(e, kM + 1, 6, m.d); put(e, kM + 7, 6, m.a); put(e, kM + 13, 6, m.b);
  put(e, kA, 1, a.en); put(e, kA + 1, 3, static_cast<unsigned>(a.op));
  put(e, kA + 4, 6, a.d); put(e, kA + 10, 6, a.a); put(e, kA + 16, 6, a.b);
  put(e, kF, 1, f.en); put(e, kF + 1, 2, static_cast<unsigned>(f.op));
  put(e, kF + 3, 6, f.d); put(e, kF + 9, 6, f.a);
  put(e, kD, 2, static_cast<unsigned>(d.op)); put(e, kD + 2, 6, d.f);
  put(e, kD + 8, 4, d.base); put(e, kD + 12, 8, static_cast<std::uint8_t>(d.disp));
  put(e, kI, 4, static_cast<unsigned>(i.op)); put(e, kI + 4, 6, i.d);
  put(e, kI + 10, 4, i.s); put(e, kI + 14, 4, i.t); put(e, kI + 18, 16, i.imm);
  put(e, kS, 4, static_cast<unsigned>(s.op)); put(e, kS + 4, 4, s.r); put(e, kS + 8, 10, s.target);
  return e;
}

inline MicroWord MicroWord::decode(const Encoded& e) {
  using detail::get;
  using namespace field;
  MicroWord w;
  w.m = {get(e, kM, 1) != 0, std::uint8_t(get(e, kM + 1, 6)), std::uint8_t(get(e, kM + 7, 6)),
         std::uint8_t(get(e, kM + 13, 6))};
  w.a = {get(e, kA, 1) != 0, AddOp(get(e, kA + 1, 3)), std::uint8_t(get(e, kA + 4, 6)),
         std::uint8_t(get(e, kA + 10, 6)), std::uint8_t(get(e, kA + 16, 6))};
  w.f = {get(e, kF, 1) != 0, FuncOp(get(e, kF + 1, 2)), std::uint8_t(get(e, kF + 3, 6)),
         std::uint8_t(get(e, kF + 9, 6))};
  w.d = {MemOp(get(e, kD, 2)), std::uint8_t(get(e, kD + 2, 6)), std::uint8_t(get(e, kD + 8, 4)),
         static_cast<std::int8_t>(get(e, kD + 12, 8))};
  w.i = {IntOp(get(e, kI, 4)), std::uint8_t(get(e, kI + 4, 6)), std::uint8_t(get(e, kI + 10, 4)),
         std::uint8_t(get(e, kI + 14, 4)), std::uint16_t(get(e, kI + 18, 16))};
  w.s = {SeqOp(get(e, kS, 4)), std::uint8_t(get(e, kS + 4, 4)), std::uint16_t(get(e, kS + 8, 10))};
  return w;
}

}  // namespace mc1::apu
