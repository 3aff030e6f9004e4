// Batched FP24 MUL and ADD/SUB: up to eight independent ops of one kind in
// one call, for the ISS's batched path through a straight-line body. Each
// lane is bit-exact, value and flags, to the scalar op it stands for,
// fp24::inl::mul24, add24 or sub24 (fp24_arith_inline.hpp), which stay the
// reference.
//
// Two variants: an AVX-512 kernel (fp24_lanes_avx512.cpp) that computes the
// plain normal lanes eight at a time and hands the others (an operand not
// normal, a result that overflows or is tiny, an exact zero sum) to the
// scalar ops; and a generic one, the scalar ops in a loop, for any x86-64.
// mul() and add() use the best one the host runs, chosen on the first call.
#pragma once

#include <cstdint>

namespace mc1::fp24::lanes {

constexpr unsigned kLanes = 8;

// One batch of up to kLanes ops of one kind. Lanes n..7 are padding: their
// indices must still name valid entries of V (they are read and computed,
// their results are not meaningful and their flags do not count).
struct Batch {
  std::uint16_t a[kLanes];  // operand indices into V
  std::uint16_t b[kLanes];
  std::uint8_t neg = 0;  // add only: bit i set = lane i subtracts (b's sign flipped first, as sub24)
  std::uint8_t n = 0;    // lanes in use, 1..kLanes
};

// out[i] = op(V[a[i]], V[b[i]]).value for all kLanes lanes (lanes >= n may
// hold anything); returns the OR of the flags of lanes 0..n-1. V's values
// are within 24 bits. Every operand is read before any result is written,
// so out may point into V.
std::uint32_t mul(const std::uint32_t* V, const Batch& b, std::uint32_t* out);
std::uint32_t add(const std::uint32_t* V, const Batch& b, std::uint32_t* out);

enum class Variant : std::uint8_t { Generic, Avx512 };
constexpr Variant kVariants[] = {Variant::Generic, Variant::Avx512};

const char* name(Variant v);
// Whether the host CPU runs v (Generic: always).
bool supported(Variant v);
// The variant mul() and add() use: the best supported one.
Variant active();

// mul() and add() by a given variant, for tests and benchmarks; v must be
// supported (std::invalid_argument if not).
std::uint32_t mul(Variant v, const std::uint32_t* V, const Batch& b, std::uint32_t* out);
std::uint32_t add(Variant v, const std::uint32_t* V, const Batch& b, std::uint32_t* out);

}  // namespace mc1::fp24::lanes
