// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatExponential.h
 * @brief exp(-x) for the rasterizers' per-pixel loops: inline and branch-free, so that the
 * compiler vectorizes the loops that call it, where a call to the C library's expf (or a table
 * lookup) keeps them scalar.
 *
 * 2^t = 2^n 2^f with n = round(t) and |f| <= 1/2; 2^f by its Taylor polynomial of degree 6,
 * whose remainder (ln 2 / 2)^7 / 7! is 1.2e-7 relative, within one float rounding. The result
 * is exactly 0 beyond x = 87 (below the smallest normal float) and for x = +inf; the caller
 * passes x >= 0 or x = NaN-free negatives down to -87.
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

/// exp(-x) for x in [-87, +inf] within 2e-7 relative (see the file comment).
inline float NegativeExponential(float x)
{
  constexpr float Log2E = 1.44269504088896341f;
  constexpr float Largest = 87.0f;
  const float clamped = std::min(std::max(x, -Largest), Largest);
  const float t = -clamped * Log2E;
  // Round to nearest by the 1.5 * 2^23 trick: no conversion instruction needed to vectorize.
  constexpr float Shifter = 12582912.0f;
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
