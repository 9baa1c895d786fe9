#pragma once
// Exact, associative per-pixel sample sums.
//
// Each sample value (a float: path values are floats, and double values such
// as 1 - camera transmittance are rounded to float first) is turned into a
// signed 128-bit fixed-point number with 64 fractional bits and added with
// integer arithmetic. Integer addition is associative, so the sum over any
// partition of a pixel's sample range is the same integer: renders of sample
// ranges [0,a), [a,b), [b,n) merged by adding their sums give exactly the
// bits of a single [0,n) render, because the mean is formed from (sum, count)
// by the one function exact_mean() both paths call.
//
// Conversion (to_fixed) shifts the float's 24-bit mantissa into place:
// - exact for |v| >= 2^-41 (the mantissa's last bit is still >= 2^-64);
// - smaller magnitudes are truncated toward zero, deterministically (below
//   2^-64 they become 0; subnormals are 0);
// - |v| >= 2^40 (about 1.1e12) is clamped to ±2^40: one sample brighter than
//   that is clamped (no radiance in a sane scene comes near it);
// - NaN gives 0 and ±Inf clamps (callers drop non-finite samples before).
// Overflow: a clamped sample is at most 2^(40+64) = 2^104 in fixed point, and
// the sum has 127 bits of magnitude, so 2^22 samples (sum <= 2^126) can never
// overflow, whatever their values. render() and merge_partials() refuse sample
// ranges longer than kMaxExactSamples = 2^22 = 4,194,304 samples per pixel.
#include <bit>
#include <cstdint>

namespace vesper {

// Signed 128-bit fixed point, value = sum * 2^-64.
#if defined(__GNUC__) || defined(__clang__)
__extension__ typedef __int128 ExactSum;  // __extension__: no -Wpedantic noise
#else
#error "ExactSum needs a compiler with __int128 (GCC or Clang)"
#endif

inline constexpr int kExactFractionBits = 64;
inline constexpr int kExactClampExponent = 40;  // |sample| <= 2^40
// Most samples one sum may hold: 2^22 * 2^104 = 2^126 < 2^127 (one bit of margin).
inline constexpr int64_t kMaxExactSamples = int64_t(1) << 22;  // 4,194,304

// v * 2^64 as an integer, by shifting the mantissa (no libgcc __fixsfti).
inline ExactSum to_fixed(float v) {
  const uint32_t bits = std::bit_cast<uint32_t>(v);
  const int exp = int((bits >> 23) & 0xffu);
  if (exp == 0) return 0;  // zero and subnormals (< 2^-126): truncated to 0
  if (exp == 0xff && (bits & 0x7fffffu) != 0) return 0;  // NaN
  ExactSum mag;
  // v = m * 2^(exp - 150) with the 24-bit mantissa m; v * 2^64 = m << (exp - 86).
  if (exp >= 127 + kExactClampExponent) {
    mag = ExactSum(1) << (kExactClampExponent + kExactFractionBits);  // clamp (and ±Inf)
  } else {
    const uint64_t m = uint64_t((bits & 0x7fffffu) | 0x800000u);
    const int shift = exp - 86;  // in [-85, 80]
    if (shift >= 40)
      mag = ExactSum(m << 40) << (shift - 40);  // m < 2^24: m << 40 fits in 64 bits
    else if (shift >= 0)
      mag = ExactSum(m << shift);
    else if (shift > -24)
      mag = ExactSum(m >> -shift);  // truncation toward zero
    else
      mag = 0;
  }
  return (bits >> 31) ? -mag : mag;
}

// The sum as a double (rounded to nearest).
inline double fixed_to_double(ExactSum s) { return double(s) * 0x1p-64; }

// THE output value of a pixel channel: the mean of `count` samples whose
// fixed-point sum is `sum`. render() and merge_partials() both call this, so
// a merged frame rounds exactly like a single render.
inline float exact_mean(ExactSum sum, int64_t count) {
  if (count <= 0) return 0.f;
  return float(fixed_to_double(sum) / double(count));
}

}  // namespace vesper
