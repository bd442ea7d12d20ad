// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatFloat8.h
 * @brief Eight floats as one value, for the short per-kernel loops of
 * splat::VolumeLayerCompositor: one group of lanes per row of a footprint, and the layer's
 * opacities eight pixels at a time.
 *
 * Written as loops over eight floats, GCC vectorizes those loops only partly (a vector of four,
 * then a scalar remainder with a scalar exponential each) or unrolls them into scalar code. With
 * GCC's and Clang's vector extension a Float8 is one AVX register where the code is built for
 * AVX2 (SPLAT_VECTOR_CLONES) and two SSE registers otherwise; other compilers get the same
 * operations as plain loops.
 */
#ifndef SplatFloat8_h
#define SplatFloat8_h

#include "SplatExponential.h"

#include <cstdint>
#include <cstring>

namespace splat
{
#if defined(__GNUC__)
// Inlined also into the AVX2 clones, whatever their size.
#define SPLAT_FLOAT8 __attribute__((always_inline))
struct Float8
{
  typedef float Vector __attribute__((vector_size(32)));
  typedef std::int32_t Integers __attribute__((vector_size(32)));
  Vector V;

  Float8() = default;
  SPLAT_FLOAT8 Float8(float x)
    : V(Vector{} + x)
  {
  }
  SPLAT_FLOAT8 explicit Float8(const Vector& v)
    : V(v)
  {
  }
  SPLAT_FLOAT8 static Float8 Iota()
  {
    return Float8(Vector{ 0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f });
  }
  SPLAT_FLOAT8 static Float8 Load(const float* p)
  {
    Vector v;
    std::memcpy(&v, p, sizeof(v));
    return Float8(v);
  }
  SPLAT_FLOAT8 void Store(float* p) const { std::memcpy(p, &this->V, sizeof(this->V)); }
  SPLAT_FLOAT8 friend Float8 operator+(const Float8& a, const Float8& b)
  {
    return Float8(a.V + b.V);
  }
  SPLAT_FLOAT8 friend Float8 operator-(const Float8& a, const Float8& b)
  {
    return Float8(a.V - b.V);
  }
  SPLAT_FLOAT8 friend Float8 operator*(const Float8& a, const Float8& b)
  {
    return Float8(a.V * b.V);
  }
  SPLAT_FLOAT8 friend Float8 operator/(const Float8& a, const Float8& b)
  {
    return Float8(a.V / b.V);
  }

  /// Per lane: a where the lane of `less` is below the one of `than`, b elsewhere.
  SPLAT_FLOAT8 static Float8 SelectLess(
    const Float8& less, const Float8& than, const Float8& a, const Float8& b)
  {
    return Float8(less.V < than.V ? a.V : b.V);
  }

  /// splat::NegativeExponential per lane, step by step.
  SPLAT_FLOAT8 static Float8 NegativeExponential(const Float8& x)
  {
    constexpr float Log2E = 1.44269504088896341f;
    constexpr float Largest = 87.0f;
    const Vector clamped =
      x.V < -Largest ? Vector{} - Largest : (x.V > Largest ? Vector{} + Largest : x.V);
    const Vector t = -clamped * Log2E;
    constexpr float Shifter = 12582912.0f;
    const Vector n = (t + Shifter) - Shifter;
    const Vector f = (t - n) * 0.693147180559945309f;
    Vector p;
    ExponentialPolynomial(f, p);
    const Integers exponent = (__builtin_convertvector(n, Integers) + 127) << 23;
    Vector scale;
    std::memcpy(&scale, &exponent, sizeof(scale));
    return Float8(x.V < Largest ? p * scale : Vector{});
  }
};
#undef SPLAT_FLOAT8
#else
struct Float8
{
  float V[8];

  Float8() = default;
  Float8(float x)
  {
    for (float& v : this->V)
    {
      v = x;
    }
  }
  static Float8 Iota()
  {
    Float8 r;
    for (int i = 0; i < 8; ++i)
    {
      r.V[i] = static_cast<float>(i);
    }
    return r;
  }
  static Float8 Load(const float* p)
  {
    Float8 r;
    std::memcpy(r.V, p, sizeof(r.V));
    return r;
  }
  void Store(float* p) const { std::memcpy(p, this->V, sizeof(this->V)); }
  friend Float8 operator+(Float8 a, Float8 b)
  {
    for (int i = 0; i < 8; ++i)
    {
      a.V[i] += b.V[i];
    }
    return a;
  }
  friend Float8 operator-(Float8 a, Float8 b)
  {
    for (int i = 0; i < 8; ++i)
    {
      a.V[i] -= b.V[i];
    }
    return a;
  }
  friend Float8 operator*(Float8 a, Float8 b)
  {
    for (int i = 0; i < 8; ++i)
    {
      a.V[i] *= b.V[i];
    }
    return a;
  }
  friend Float8 operator/(Float8 a, Float8 b)
  {
    for (int i = 0; i < 8; ++i)
    {
      a.V[i] /= b.V[i];
    }
    return a;
  }
  static Float8 SelectLess(Float8 less, Float8 than, Float8 a, Float8 b)
  {
    for (int i = 0; i < 8; ++i)
    {
      a.V[i] = less.V[i] < than.V[i] ? a.V[i] : b.V[i];
    }
    return a;
  }
  static Float8 NegativeExponential(Float8 x)
  {
    for (float& v : x.V)
    {
      v = splat::NegativeExponential(v);
    }
    return x;
  }
};
#endif
}

#endif
