// fp24_lanes.hpp: the generic variant (the scalar ops in a loop), the scalar
// finish of the AVX-512 kernels' special lanes, and the dispatch. Ordinary
// code: compiled for any x86-64, the only file of the two that may use the
// fp24 inline ops (fp24_lanes_avx512.hpp says why).
#include "fp24_lanes.hpp"

#include <atomic>
#include <stdexcept>
#include <string>

#include "fp24_arith_inline.hpp"
#include "fp24_lanes_avx512.hpp"

namespace mc1::fp24::lanes {
namespace detail {

std::uint32_t finish_mul(unsigned mask, const std::uint32_t* x, const std::uint32_t* y, std::uint32_t* out) {
  std::uint32_t flags = 0;
  for (; mask != 0; mask &= mask - 1) {
    const int i = __builtin_ctz(mask);
    const Result r = inl::mul24(x[i], y[i]);
    out[i] = r.value;
    flags |= r.flags;
  }
  return flags;
}

std::uint32_t finish_add(unsigned mask, unsigned neg, const std::uint32_t* x, const std::uint32_t* y,
                         std::uint32_t* out) {
  std::uint32_t flags = 0;
  for (; mask != 0; mask &= mask - 1) {
    const int i = __builtin_ctz(mask);
    const Result r = (neg >> i) & 1 ? inl::sub24(x[i], y[i]) : inl::add24(x[i], y[i]);
    out[i] = r.value;
    flags |= r.flags;
  }
  return flags;
}

}  // namespace detail

namespace {

using Kernel = std::uint32_t (*)(const std::uint32_t*, const Batch&, std::uint32_t*);

// Lanes 0..n-1 by the scalar ops, every operand read first (out may alias
// V); lanes n..7 are written as zeros, which is cheaper than computing the
// padding.
std::uint32_t mul_generic(const std::uint32_t* V, const Batch& b, std::uint32_t* out) {
  std::uint32_t x[kLanes], y[kLanes];
  for (unsigned i = 0; i < b.n; ++i) x[i] = V[b.a[i]], y[i] = V[b.b[i]];
  for (unsigned i = b.n; i < kLanes; ++i) out[i] = 0;
  return detail::finish_mul((1u << b.n) - 1, x, y, out);
}

std::uint32_t add_generic(const std::uint32_t* V, const Batch& b, std::uint32_t* out) {
  std::uint32_t x[kLanes], y[kLanes];
  for (unsigned i = 0; i < b.n; ++i) x[i] = V[b.a[i]], y[i] = V[b.b[i]];
  for (unsigned i = b.n; i < kLanes; ++i) out[i] = 0;
  return detail::finish_add((1u << b.n) - 1, b.neg, x, y, out);
}

bool host_has_avx512() {
#ifdef MC1_FP24_LANES_AVX512
  // libgcc's check also asks the OS (XGETBV) whether it saves the ZMM state.
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
         __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
         __builtin_cpu_supports("avx512cd");
#else
  return false;  // the kernel is not built for this target
#endif
}

struct Kernels {
  Kernel mul, add;
};

Kernels kernels_of(Variant v) {
  if (!supported(v)) throw std::invalid_argument(std::string("fp24 lanes: variant not supported here: ") + name(v));
#ifdef MC1_FP24_LANES_AVX512
  if (v == Variant::Avx512) return {detail::mul_avx512, detail::add_avx512};
#endif
  return {mul_generic, add_generic};
}

// mul() and add() call through these: the first call finds the variant and
// replaces the pointer, so later calls pay one indirect call and nothing
// else. Constant-initialized, so a call during another file's static
// initialization is safe too; a race of two first calls stores the same.
std::uint32_t mul_first(const std::uint32_t* V, const Batch& b, std::uint32_t* out);
std::uint32_t add_first(const std::uint32_t* V, const Batch& b, std::uint32_t* out);
std::atomic<Kernel> g_mul{mul_first};
std::atomic<Kernel> g_add{add_first};

std::uint32_t mul_first(const std::uint32_t* V, const Batch& b, std::uint32_t* out) {
  const Kernel k = kernels_of(active()).mul;
  g_mul.store(k, std::memory_order_relaxed);
  return k(V, b, out);
}

std::uint32_t add_first(const std::uint32_t* V, const Batch& b, std::uint32_t* out) {
  const Kernel k = kernels_of(active()).add;
  g_add.store(k, std::memory_order_relaxed);
  return k(V, b, out);
}

}  // namespace

std::uint32_t mul(const std::uint32_t* V, const Batch& b, std::uint32_t* out) {
  return g_mul.load(std::memory_order_relaxed)(V, b, out);
}

std::uint32_t add(const std::uint32_t* V, const Batch& b, std::uint32_t* out) {
  return g_add.load(std::memory_order_relaxed)(V, b, out);
}

const char* name(Variant v) { return v == Variant::Avx512 ? "avx512" : "generic"; }

bool supported(Variant v) {
  static const bool avx512 = host_has_avx512();
  return v == Variant::Generic || avx512;
}

Variant active() { return supported(Variant::Avx512) ? Variant::Avx512 : Variant::Generic; }

std::uint32_t mul(Variant v, const std::uint32_t* V, const Batch& b, std::uint32_t* out) {
  return kernels_of(v).mul(V, b, out);
}

std::uint32_t add(Variant v, const std::uint32_t* V, const Batch& b, std::uint32_t* out) {
  return kernels_of(v).add(V, b, out);
}

}  // namespace mc1::fp24::lanes
