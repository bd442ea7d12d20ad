// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatExponential.h
 * @brief exp(-x) for the rasterizers' per-pixel loops: inline and branch-free, so that the
 * compiler vectorizes the loops that call it, where a call to the C library's expf (or a table
 * lookup) keeps them scalar.
 *
 * 2^t = 2^n 2^f with n = round(t) and |f| <= 1/2; 2^f by its Taylor polynomial of degree 6,
 * whose remainder (ln 2 / 2)^7 / 7! is 1.2e-7 relative, within one float rounding; the rounding
 * of t = x log2(e) adds an error that grows with x (measured: 6e-7 relative below x = 10, 4e-6
 * up to 87). The result is exactly 0 beyond x = 87 (below the smallest normal float) and for
 * x = +inf; the caller passes x >= 0 or x = NaN-free negatives down to -87.
 *
 * NegativeExponential2, 2^-x, is the capture compositing's: its alphas end in 8 bits, so a
 * degree-4 polynomial (3e-6 relative) serves where float precision would take degree 6, and
 * the capture footprints are kept in base 2, which saves the change of base per pixel.
 */
#ifndef SplatExponential_h
#define SplatExponential_h

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace splat
{

/// p = e^g for |g| <= 0.347 (g = f ln 2), by its Taylor polynomial of degree 6: for a float,
/// or per lane for a vector of floats (splat::Float8; by reference, as vectors are passed
/// there, so that no AVX vector is returned by value where AVX is not enabled).
template <typename T>
inline void ExponentialPolynomial(const T& g, T& p)
{
  p = g * (1.0f / 720.0f) + 1.0f / 120.0f;
  p = p * g + 1.0f / 24.0f;
  p = p * g + 1.0f / 6.0f;
  p = p * g + 0.5f;
  p = p * g + 1.0f;
  p = p * g + 1.0f;
}

/// p = 2^-g for |g| <= 1/2 by a degree-4 minimax polynomial, 2.7e-6 relative (fitted to the
/// relative error on Chebyshev nodes; the odd coefficients negated for the argument's sign).
template <typename T>
inline void NegativeExponential2Polynomial(const T& g, T& p)
{
  p = g * 0.00957009662f - 0.0559178591f;
  p = p * g + 0.240247443f;
  p = p * g - 0.693121791f;
  p = p * g + 0.999999285f;
}

/// The rounding to an integer shared by both exponentials: (t + Shifter) - Shifter rounds t to
/// nearest for |t| < 2^22, with no conversion instruction, and t + Shifter holds that integer
/// in its low bits, over ShifterBits.
constexpr float Shifter = 12582912.0f; // 1.5 * 2^23
constexpr std::int32_t ShifterBits = 0x4b400000;

/// 2^-x for x >= 0 within 3e-6 relative, 2^-126 beyond 126 and for NaN.
inline float NegativeExponential2(float x)
{
  const float t = x < 126.0f ? x : 126.0f;
  const float shifted = Shifter - t;
  const float g = t + (shifted - Shifter); // -t's fraction, negated
  float p;
  NegativeExponential2Polynomial(g, p);
  std::int32_t bits;
  std::memcpy(&bits, &shifted, sizeof(bits));
  const std::int32_t exponent = (bits - ShifterBits + 127) * (1 << 23);
  float scale;
  std::memcpy(&scale, &exponent, sizeof(scale));
  return p * scale;
}

/// exp(-x) for x in [-87, +inf], to the precision the file comment gives.
inline float NegativeExponential(float x)
{
  constexpr float Log2E = 1.44269504088896341f;
  constexpr float Largest = 87.0f;
  const float clamped = std::min(std::max(x, -Largest), Largest);
  const float t = -clamped * Log2E;
  const float n = (t + Shifter) - Shifter;
  const float f = (t - n) * 0.693147180559945309f; // 2^f = e^(f ln 2), |f ln 2| <= 0.347
  float p;
  ExponentialPolynomial(f, p);
  const std::int32_t exponent = (static_cast<std::int32_t>(n) + 127) << 23;
  float scale;
  std::memcpy(&scale, &exponent, sizeof(scale));
  return x < Largest ? p * scale : 0.0f;
}

} // namespace splat

#endif
