// The seam between fp24_lanes.cpp (ordinary code) and fp24_lanes_avx512.cpp
// (compiled with -mavx512*). Only declarations cross it: the AVX-512 file
// must define no inline function that another file also uses (the fp24 inline
// ops, std:: templates), or the linker could keep its AVX-512 copy for every
// caller and the program would die of SIGILL on a CPU without AVX-512. So the
// AVX-512 kernels leave the lanes that need the scalar ops to finish_mul()
// and finish_add(), out-of-line functions of fp24_lanes.cpp.
#pragma once

#include <cstdint>

#include "fp24_lanes.hpp"

namespace mc1::fp24::lanes::detail {

// fp24_lanes_avx512.cpp; call only on a CPU with AVX-512 F, VL, BW, DQ, CD.
// mul() and add() of fp24_lanes.hpp.
std::uint32_t mul_avx512(const std::uint32_t* V, const Batch& b, std::uint32_t* out);
std::uint32_t add_avx512(const std::uint32_t* V, const Batch& b, std::uint32_t* out);

// fp24_lanes.cpp: lane i of `mask` (bit i) by the scalar op, its operands
// x[i] and y[i] as read from V (add: y[i] before the SUB lanes' sign flip,
// `neg` as in Batch), its value into out[i]; returns the OR of their flags.
std::uint32_t finish_mul(unsigned mask, const std::uint32_t* x, const std::uint32_t* y, std::uint32_t* out);
std::uint32_t finish_add(unsigned mask, unsigned neg, const std::uint32_t* x, const std::uint32_t* y,
                         std::uint32_t* out);

}  // namespace mc1::fp24::lanes::detail
