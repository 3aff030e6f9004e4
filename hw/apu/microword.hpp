// The APU's 128-bit horizontal microword (docs/apu-isa.md): its fields as a
// value type, and the bit packing shared by the assembler, the ISS, the RTL
// harness and the co-simulator.
//
// The fields, op codes, sizes and latencies come from the instruction-set
// table apu_rtl/isa/apu_isa.tbl, through the generated apu_isa.hpp (the RTL's
// apu_pkg.sv is generated from the same table); only the packing is here.
#pragma once

#include <cstdint>
#include <type_traits>

#include "apu_isa.hpp"

namespace mc1::apu {

struct Encoded {
  std::uint64_t lo = 0, hi = 0;  // bits 0..63, bits 64..127
  bool operator==(const Encoded& o) const { return lo == o.lo && hi == o.hi; }
  bool operator!=(const Encoded& o) const { return !(*this == o); }
};

namespace detail {
inline std::uint64_t get(const Encoded& e, Field f) {
  // A field may straddle the 64-bit boundary.
  unsigned __int128 all = (static_cast<unsigned __int128>(e.hi) << 64) | e.lo;
  return static_cast<std::uint64_t>(all >> f.lsb) & ((std::uint64_t{1} << f.width) - 1);
}
inline void put(Encoded& e, Field f, std::uint64_t v) {
  unsigned __int128 all = (static_cast<unsigned __int128>(e.hi) << 64) | e.lo;
  const unsigned __int128 mask = static_cast<unsigned __int128>((std::uint64_t{1} << f.width) - 1) << f.lsb;
  all = (all & ~mask) | ((static_cast<unsigned __int128>(v) << f.lsb) & mask);
  e.lo = static_cast<std::uint64_t>(all);
  e.hi = static_cast<std::uint64_t>(all >> 64);
}

// A field member's bits (a signed one in two's complement), and back.
template <class T>
std::uint64_t to_bits(T v) {
  if constexpr (std::is_same_v<T, bool>) {
    return v ? 1 : 0;
  } else if constexpr (std::is_enum_v<T>) {
    return static_cast<std::underlying_type_t<T>>(v);
  } else {
    return static_cast<std::make_unsigned_t<T>>(v);
  }
}
template <class T>
T from_bits(std::uint64_t bits, Field f) {
  if constexpr (std::is_same_v<T, bool>) {
    return bits != 0;
  } else if constexpr (std::is_enum_v<T>) {
    return static_cast<T>(bits);
  } else {
    if (std::is_signed_v<T> && (bits >> (f.width - 1)) & 1) bits |= ~std::uint64_t{0} << f.width;
    return static_cast<T>(bits);
  }
}
}  // namespace detail

inline Encoded MicroWord::encode() const {
  Encoded e;
  for_each_field(*this, [&e](Field f, auto v) { detail::put(e, f, detail::to_bits(v)); });
  return e;
}

inline MicroWord MicroWord::decode(const Encoded& e) {
  MicroWord w;
  for_each_field(w, [&e](Field f, auto& v) {
    v = detail::from_bits<std::decay_t<decltype(v)>>(detail::get(e, f), f);
  });
  return w;
}

}  // namespace mc1::apu
