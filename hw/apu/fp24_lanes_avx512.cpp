// The AVX-512 kernels of fp24_lanes.hpp: eight FP24 MULs or ADD/SUBs at a
// time, one op per 64-bit lane, each lane the arithmetic of
// fp24_arith_inline.hpp's mul24() and add_normal() and of fp24_bits.hpp's
// round_sig() (the one rounding rule) on the plain normal case. A lane where
// that case does not hold (an operand zero, infinite or NaN; a rounded result
// that overflows or is tiny; an exact zero sum) is left to the scalar op
// through finish_mul() or finish_add().
//
// Compiled with -mavx512{f,vl,bw,dq,cd} (hw/apu/CMakeLists.txt), so nothing
// here may be an inline function that other files also define: only
// intrinsics and this file's own static functions (fp24_lanes_avx512.hpp).
#include "fp24_lanes_avx512.hpp"

// GCC 12.1 and 12.2 warn of the deliberately undefined register in the
// intrinsics' own code (_mm512_undefined_epi32, GCC bug 105593, fixed in 12.3).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>

namespace mc1::fp24::lanes::detail {
namespace {

// FP24 fields (fp24.hpp), repeated here because fp24.hpp's neighbours are
// inline functions this file must not instantiate.
constexpr long long kSignBit = 0x800000;
constexpr long long kMagMask = 0x7FFFFF;
constexpr long long kFracMask = 0xFFFF;
constexpr long long kHidden = 0x10000;
constexpr long long kMinNormal = 0x10000;  // encoding of 2^-62
constexpr long long kPosInf = 0x7F0000;
constexpr int kFracBits = 16;
constexpr int kBias = 63;

__m512i set1(long long v) { return _mm512_set1_epi64(v); }

// V[idx[0..7]], eight 32-bit words.
__m256i load_operands(const std::uint32_t* V, const std::uint16_t* idx) {
  const __m256i i = _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(idx)));
  return _mm256_i32gather_epi32(reinterpret_cast<const int*>(V), i, 4);
}

__m512i exp_of(__m512i x) { return _mm512_and_si512(_mm512_srli_epi64(x, kFracBits), set1(0x7F)); }
__m512i sig_of(__m512i x) { return _mm512_or_si512(_mm512_and_si512(x, set1(kFracMask)), set1(kHidden)); }

// Lanes whose biased exponent is 1..126 (a normal number), one unsigned
// compare as bits::is_normal().
__mmask8 normal(__m512i e) { return _mm512_cmplt_epu64_mask(_mm512_sub_epi64(e, set1(1)), set1(126)); }

// round_sig<kDrop>() on eight lanes: q holds the significand, its leading one
// at bit kDrop + 16, the tail below bit kDrop; e1 is the biased exponent
// minus one. The encoding of the magnitude, (e1 << 16) + the rounded
// significand (a carry out of it moves the exponent up), to *mag; the lanes
// whose magnitude is not a normal number's (overflow, tininess after
// rounding) to *out_of_range; the return is the lanes with a nonzero tail.
template <int kDrop>
__mmask8 round_lanes(__m512i q, __m512i e1, __m512i* mag, __mmask8* out_of_range) {
  const __m512i lsb = _mm512_and_si512(_mm512_srli_epi64(q, kDrop), set1(1));
  const __m512i up = _mm512_add_epi64(_mm512_add_epi64(q, set1((1ll << (kDrop - 1)) - 1)), lsb);
  *mag = _mm512_add_epi64(_mm512_slli_epi64(e1, kFracBits), _mm512_srli_epi64(up, kDrop));
  // mag < kMinNormal (negative ones too, as unsigned) or mag >= kPosInf.
  *out_of_range = _mm512_cmpge_epu64_mask(_mm512_sub_epi64(*mag, set1(kMinNormal)), set1(kPosInf - kMinNormal));
  return _mm512_test_epi64_mask(q, set1((1ll << kDrop) - 1));
}

// The lanes in use, 0..n-1.
__mmask8 in_use(const Batch& b) { return static_cast<__mmask8>((1u << b.n) - 1); }

// Writes the eight values, then lets the scalar op redo the special lanes in
// use from the operands as read (out may alias V). Returns the flags: NX if
// a vector-computed lane in use is inexact, or'ed with the scalar lanes'.
std::uint32_t store_and_finish(bool is_mul, const Batch& b, __m512i value, __mmask8 nx, __mmask8 special, __m256i x,
                               __m256i y, std::uint32_t* out) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm512_cvtepi64_epi32(value));
  const __mmask8 used = in_use(b);
  special &= used;
  std::uint32_t flags = (nx & used & ~special) != 0 ? 1u : 0u;  // kNX
  if (__builtin_expect(special != 0, 0)) {
    alignas(32) std::uint32_t xs[kLanes], ys[kLanes];
    _mm256_store_si256(reinterpret_cast<__m256i*>(xs), x);
    _mm256_store_si256(reinterpret_cast<__m256i*>(ys), y);
    flags |= is_mul ? finish_mul(special, xs, ys, out) : finish_add(special, b.neg, xs, ys, out);
  }
  return flags;
}

}  // namespace

// mul24(): the 17 x 17-bit significand product p in [2^32, 2^34), q = p at
// [2^33, 2^34), biased exponent ea + eb - kBias + hi, its 17 low bits the
// tail of round_sig<17>.
std::uint32_t mul_avx512(const std::uint32_t* V, const Batch& b, std::uint32_t* out) {
  const __m256i x32 = load_operands(V, b.a), y32 = load_operands(V, b.b);
  const __m512i x = _mm512_cvtepu32_epi64(x32), y = _mm512_cvtepu32_epi64(y32);
  const __m512i ex = exp_of(x), ey = exp_of(y);
  const __mmask8 both_normal = normal(ex) & normal(ey);
  const __m512i p = _mm512_mul_epu32(sig_of(x), sig_of(y));
  const __m512i hi = _mm512_srli_epi64(p, 2 * kFracBits + 1);
  const __m512i q = _mm512_sllv_epi64(p, _mm512_xor_si512(hi, set1(1)));
  const __m512i e1 = _mm512_add_epi64(_mm512_add_epi64(ex, ey), _mm512_sub_epi64(hi, set1(kBias + 1)));
  __m512i mag;
  __mmask8 out_of_range;
  const __mmask8 nx = round_lanes<kFracBits + 1>(q, e1, &mag, &out_of_range);
  const __m512i sign = _mm512_and_si512(_mm512_xor_si512(x, y), set1(kSignBit));
  const __mmask8 special = static_cast<__mmask8>(~both_normal | out_of_range);
  return store_and_finish(true, b, _mm512_or_si512(sign, mag), nx, special, x32, y32, out);
}

// add_normal(): ordered by magnitude (|x| >= |y|), y's significand aligned
// by the exponent difference clamped to 24 (no bit is lost: see
// add_normal()), added or subtracted at bit 40, normalized so the leading
// one is at bit 62, round_sig<46>.
std::uint32_t add_avx512(const std::uint32_t* V, const Batch& b, std::uint32_t* out) {
  constexpr int kPos = 40, kMaxShift = 24, kDrop = 46;
  const __m256i a32 = load_operands(V, b.a), b32 = load_operands(V, b.b);
  const __m512i a = _mm512_cvtepu32_epi64(a32);
  const __m512i c = _mm512_mask_xor_epi64(_mm512_cvtepu32_epi64(b32), b.neg, _mm512_cvtepu32_epi64(b32), set1(kSignBit));
  const __mmask8 both_normal = normal(exp_of(a)) & normal(exp_of(c));
  const __mmask8 swap = _mm512_cmpgt_epu64_mask(_mm512_and_si512(c, set1(kMagMask)), _mm512_and_si512(a, set1(kMagMask)));
  const __m512i x = _mm512_mask_blend_epi64(swap, a, c), y = _mm512_mask_blend_epi64(swap, c, a);
  const __m512i ex = exp_of(x);
  const __m512i d = _mm512_min_epu64(_mm512_sub_epi64(ex, exp_of(y)), set1(kMaxShift));
  const __m512i big = _mm512_slli_epi64(sig_of(x), kPos);
  const __m512i small = _mm512_srlv_epi64(_mm512_slli_epi64(sig_of(y), kPos), d);
  const __mmask8 differ = _mm512_test_epi64_mask(_mm512_xor_si512(a, c), set1(kSignBit));
  const __m512i m = _mm512_mask_sub_epi64(_mm512_add_epi64(big, small), differ, big, small);
  const __mmask8 zero = _mm512_testn_epi64_mask(m, m);
  // The leading one of m at bit 63 - lz; the biased exponent of m is
  // ex + 7 - lz, q = m << (lz - 1) has it at bit 62.
  const __m512i lz = _mm512_lzcnt_epi64(m);
  const __m512i q = _mm512_sllv_epi64(m, _mm512_sub_epi64(lz, set1(1)));
  const __m512i e1 = _mm512_sub_epi64(_mm512_add_epi64(ex, set1(6)), lz);
  __m512i mag;
  __mmask8 out_of_range;
  const __mmask8 nx = round_lanes<kDrop>(q, e1, &mag, &out_of_range);
  const __m512i sign = _mm512_and_si512(x, set1(kSignBit));
  const __mmask8 special = static_cast<__mmask8>(~both_normal | zero | out_of_range);
  return store_and_finish(false, b, _mm512_or_si512(sign, mag), nx, special, a32, b32, out);
}

}  // namespace mc1::fp24::lanes::detail

#pragma GCC diagnostic pop
