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

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

// Where GCC can dispatch on the running CPU (ifunc, x86-64 glibc), the per-pixel loops are also
// built for AVX2 and FMA: twice the lanes of the SSE2 baseline, and the exponential's polynomial
// in fused steps.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define SPLAT_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define SPLAT_VECTOR_CLONES
#endif

// For the small helpers of those loops, which GCC otherwise leaves out of line in the clones,
// and for their visitors (lambdas), which GCC otherwise builds once for the baseline only.
#if defined(__GNUC__)
#define SPLAT_ALWAYS_INLINE inline __attribute__((always_inline))
#define SPLAT_INLINE_LAMBDA __attribute__((always_inline))
#else
#define SPLAT_ALWAYS_INLINE inline
#define SPLAT_INLINE_LAMBDA
#endif

// For a per-kernel loop over the math of the VTK-free headers (the capture footprints): the
// clones with that math inlined, so that the AVX2 one has its rounding as instructions rather
// than calls and its products fused.
#if defined(__GNUC__)
#define SPLAT_VECTOR_CLONES_INLINED SPLAT_VECTOR_CLONES __attribute__((flatten))
#else
#define SPLAT_VECTOR_CLONES_INLINED SPLAT_VECTOR_CLONES
#endif

namespace splat
{
/// Asks for the cache lines of bytes [p, p + bytes) ahead of their use: a hint, which never
/// faults, also for addresses past an array's end.
SPLAT_ALWAYS_INLINE void PrefetchBytes(const void* p, std::size_t bytes)
{
#if defined(__GNUC__)
  const char* first = static_cast<const char*>(p);
  for (std::size_t offset = 0; offset < bytes; offset += 64)
  {
    __builtin_prefetch(first + offset);
  }
  __builtin_prefetch(first + bytes - 1); // the last line, where p is not at a line's start
#else
  (void)p;
  (void)bytes;
#endif
}

#if defined(__GNUC__)
// Inlined also into the AVX2 clones, whatever their size.
#define SPLAT_FLOAT8 __attribute__((always_inline))
struct Float8
{
  typedef float Vector __attribute__((vector_size(32)));
  typedef std::int32_t Integers __attribute__((vector_size(32)));
  typedef float Quad __attribute__((vector_size(16)));
  Vector V;
  // The exponentials' argument range: exp(87) is near the largest float.
  static constexpr float Largest = 87.0f;

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

  /// The lanes where `less` is below `than`, as the bits of an int (lane i in bit i).
  SPLAT_FLOAT8 static int LessMask(const Float8& less, const Float8& than)
  {
    const Integers mask = less.V < than.V;
#if defined(__SSE__)
    // The sign bits of each half, by SSE's instruction (so also in the baseline clone).
    Quad halves[2];
    std::memcpy(halves, &mask, sizeof(halves));
    return __builtin_ia32_movmskps(halves[0]) | __builtin_ia32_movmskps(halves[1]) << 4;
#else
    int bits = 0;
    for (int i = 0; i < 8; ++i)
    {
      bits |= (mask[i] & 1) << i;
    }
    return bits;
#endif
  }

  /// Whether any lane of `less` is below the one of `than`.
  SPLAT_FLOAT8 static bool AnyLess(const Float8& less, const Float8& than)
  {
    return LessMask(less, than) != 0;
  }

  /// The square root per lane, by SSE's instruction on each half (so also in the baseline
  /// clone, where a loop of std::sqrt would be calls that set errno).
  SPLAT_FLOAT8 static Float8 Sqrt(const Float8& x)
  {
#if defined(__SSE__)
    Quad halves[2];
    std::memcpy(halves, &x.V, sizeof(halves));
    halves[0] = __builtin_ia32_sqrtps(halves[0]);
    halves[1] = __builtin_ia32_sqrtps(halves[1]);
    Vector r;
    std::memcpy(&r, halves, sizeof(r));
    return Float8(r);
#else
    Vector r;
    for (int i = 0; i < 8; ++i)
    {
      r[i] = std::sqrt(x.V[i]);
    }
    return Float8(r);
#endif
  }

  /// Rounded toward zero per lane, for lanes of magnitude below 2^31; any other lane (NaN and
  /// infinities included) gets an unspecified value, for the caller not to read.
  SPLAT_FLOAT8 static Float8 Truncated(const Float8& x)
  {
    return Float8(__builtin_convertvector(__builtin_convertvector(x.V, Integers), Vector));
  }

  /// -|x| per lane: the sign bit set.
  SPLAT_FLOAT8 Float8 NegatedMagnitude() const
  {
    Integers bits;
    std::memcpy(&bits, &this->V, sizeof(bits));
    bits |= std::int32_t(0x80000000u);
    Vector v;
    std::memcpy(&v, &bits, sizeof(v));
    return Float8(v);
  }

  /// The channels of eight consecutive four-float pixels from p, a Float8 each: pixel i in lane
  /// i. Each pixel is read as one 16-byte load, so that a load of a pixel stored by an earlier
  /// StoreChannels (or a glm::vec4 store) at another group's offset is forwarded from the store.
  SPLAT_FLOAT8 static void LoadChannels(const float* p, Float8 (&channels)[4])
  {
    Quad q[8];
    std::memcpy(q, p, sizeof(q));
    // Rows of pixels i and i + 4, then a 4 x 4 transpose in each half.
    Vector r[4];
    for (int i = 0; i < 4; ++i)
    {
      r[i] = __builtin_shufflevector(q[i], q[i + 4], 0, 1, 2, 3, 4, 5, 6, 7);
    }
    Transpose(r, channels);
  }

  /// Stores channels as eight consecutive four-float pixels from p (see LoadChannels).
  SPLAT_FLOAT8 static void StoreChannels(float* p, const Float8 (&channels)[4])
  {
    Float8 r[4];
    const Vector c[4] = { channels[0].V, channels[1].V, channels[2].V, channels[3].V };
    Transpose(c, r);
    Quad q[8];
    for (int i = 0; i < 4; ++i)
    {
      q[i] = __builtin_shufflevector(r[i].V, r[i].V, 0, 1, 2, 3);
      q[i + 4] = __builtin_shufflevector(r[i].V, r[i].V, 4, 5, 6, 7);
    }
    std::memcpy(p, q, sizeof(q));
  }

  /// The columns of eight rows of eight floats, row r at p + r stride: lane r of columns[i]
  /// (i < 8) is float i of row r (two 4 x 4 transposes in each half, then the halves
  /// exchanged).
  SPLAT_FLOAT8 static void LoadColumns(const float* p, std::ptrdiff_t stride, Float8* columns)
  {
    // Each row loaded into a register (a loop of copies into an array went through the stack,
    // a store of two halves and a load of the whole that waited for them).
    const auto load = [p, stride](int r, Vector& v) SPLAT_INLINE_LAMBDA
    { std::memcpy(&v, p + r * stride, sizeof(v)); };
    Vector upperRows[4], lowerRows[4];
    load(0, upperRows[0]);
    load(1, upperRows[1]);
    load(2, upperRows[2]);
    load(3, upperRows[3]);
    load(4, lowerRows[0]);
    load(5, lowerRows[1]);
    load(6, lowerRows[2]);
    load(7, lowerRows[3]);
    Float8 upper[4], lower[4];
    Transpose(upperRows, upper);
    Transpose(lowerRows, lower);
    for (int i = 0; i < 4; ++i)
    {
      columns[i] =
        Float8(__builtin_shufflevector(upper[i].V, lower[i].V, 0, 1, 2, 3, 8, 9, 10, 11));
      columns[i + 4] =
        Float8(__builtin_shufflevector(upper[i].V, lower[i].V, 4, 5, 6, 7, 12, 13, 14, 15));
    }
  }

  /// splat::NegativeExponential per lane, step by step.
  SPLAT_FLOAT8 static Float8 NegativeExponential(const Float8& x)
  {
    const Vector above = x.V < -Largest ? Vector{} - Largest : x.V;
    return Float8(x.V < Largest ? NegativeExponentialAbove(Float8(above)).V : Vector{});
  }

  /// NegativeExponential of lanes that are at least -Largest (the caller's bound: there is no
  /// clamp from below), except that lanes above Largest give exp(-Largest), about 1.6e-38,
  /// rather than zero. Two comparisons and blends less than NegativeExponential.
  SPLAT_FLOAT8 static Float8 NegativeExponentialAbove(const Float8& x)
  {
    constexpr float Log2E = 1.44269504088896341f;
    const Vector t = -(x.V > Largest ? Vector{} + Largest : x.V) * Log2E;
    const Vector n = (t + Shifter) - Shifter;
    const Vector f = (t - n) * 0.693147180559945309f;
    Vector p;
    ExponentialPolynomial(f, p);
    const Integers exponent = (__builtin_convertvector(n, Integers) + 127) << 23;
    Vector scale;
    std::memcpy(&scale, &exponent, sizeof(scale));
    return Float8(p * scale);
  }

  /// splat::NegativeExponential2 per lane: 2^-x for x >= 0 (2^-126 past 126 and for NaN).
  SPLAT_FLOAT8 static Float8 NegativeExponential2(const Float8& x)
  {
    const Vector t = x.V < 126.0f ? x.V : Vector{} + 126.0f;
    const Vector shifted = Shifter - t;
    const Vector g = t + (shifted - Shifter);
    Vector p;
    NegativeExponential2Polynomial(g, p);
    Integers bits;
    std::memcpy(&bits, &shifted, sizeof(bits));
    const Integers exponent = (bits - (ShifterBits - 127)) << 23;
    Vector scale;
    std::memcpy(&scale, &exponent, sizeof(scale));
    return Float8(p * scale);
  }

private:
  /// The 4 x 4 transposes of the halves of four vectors: lane j of out[i] is lane i of in[j]
  /// within each half.
  SPLAT_FLOAT8 static void Transpose(const Vector (&in)[4], Float8 (&out)[4])
  {
    const Vector t0 = __builtin_shufflevector(in[0], in[1], 0, 8, 1, 9, 4, 12, 5, 13);
    const Vector t1 = __builtin_shufflevector(in[0], in[1], 2, 10, 3, 11, 6, 14, 7, 15);
    const Vector t2 = __builtin_shufflevector(in[2], in[3], 0, 8, 1, 9, 4, 12, 5, 13);
    const Vector t3 = __builtin_shufflevector(in[2], in[3], 2, 10, 3, 11, 6, 14, 7, 15);
    out[0] = Float8(__builtin_shufflevector(t0, t2, 0, 1, 8, 9, 4, 5, 12, 13));
    out[1] = Float8(__builtin_shufflevector(t0, t2, 2, 3, 10, 11, 6, 7, 14, 15));
    out[2] = Float8(__builtin_shufflevector(t1, t3, 0, 1, 8, 9, 4, 5, 12, 13));
    out[3] = Float8(__builtin_shufflevector(t1, t3, 2, 3, 10, 11, 6, 7, 14, 15));
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
  static int LessMask(const Float8& less, const Float8& than)
  {
    int bits = 0;
    for (int i = 0; i < 8; ++i)
    {
      bits |= (less.V[i] < than.V[i]) << i;
    }
    return bits;
  }
  static bool AnyLess(const Float8& less, const Float8& than)
  {
    return LessMask(less, than) != 0;
  }
  static Float8 Sqrt(Float8 x)
  {
    for (float& v : x.V)
    {
      v = std::sqrt(v);
    }
    return x;
  }
  static Float8 Truncated(Float8 x)
  {
    for (float& v : x.V)
    {
      v = std::trunc(v);
    }
    return x;
  }
  Float8 NegatedMagnitude() const
  {
    Float8 r;
    for (int i = 0; i < 8; ++i)
    {
      r.V[i] = -std::fabs(this->V[i]);
    }
    return r;
  }
  static Float8 NegativeExponential(Float8 x)
  {
    for (float& v : x.V)
    {
      v = splat::NegativeExponential(v);
    }
    return x;
  }
  static Float8 NegativeExponentialAbove(const Float8& x) { return NegativeExponential(x); }
  static Float8 NegativeExponential2(Float8 x)
  {
    for (float& v : x.V)
    {
      v = splat::NegativeExponential2(v);
    }
    return x;
  }
  static void LoadChannels(const float* p, Float8 (&channels)[4])
  {
    for (int i = 0; i < 8; ++i)
    {
      for (int c = 0; c < 4; ++c)
      {
        channels[c].V[i] = p[4 * i + c];
      }
    }
  }
  static void StoreChannels(float* p, const Float8 (&channels)[4])
  {
    for (int i = 0; i < 8; ++i)
    {
      for (int c = 0; c < 4; ++c)
      {
        p[4 * i + c] = channels[c].V[i];
      }
    }
  }
  static void LoadColumns(const float* p, std::ptrdiff_t stride, Float8* columns)
  {
    for (int r = 0; r < 8; ++r)
    {
      for (int i = 0; i < 8; ++i)
      {
        columns[i].V[r] = p[r * stride + i];
      }
    }
  }
};
#endif
}

#endif
