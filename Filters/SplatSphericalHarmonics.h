// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatSphericalHarmonics.h
 * @brief View-dependent kernel colors from real spherical harmonics of degree 0 to 3, in the
 * convention of 3D Gaussian Splatting: the basis order, signs and constants of eval_sh in
 * graphdeco-inria/gaussian-splatting, utils/sh_utils.py, and color = max(0, 0.5 + sum_k
 * Y_k(d) c_k) per channel, d the unit direction from the eye to the kernel's center in model
 * coordinates. VTK-free (GLM only); Rendering/glsl/vtkSplatSphericalHarmonics.glsl mirrors it
 * line by line. It lives in SplatFilters because the capture readers turn coefficients with it.
 *
 * Coefficients are stored coefficient-major with RGB interleaved, 3 (degree + 1)^2 floats per
 * kernel: k0.r, k0.g, k0.b, k1.r, ... (the array contract of vtkVolumeSplatMapper's
 * SphericalHarmonics array).
 */
#ifndef SplatSphericalHarmonics_h
#define SplatSphericalHarmonics_h

#include <glm/glm.hpp>

#include <cstring>

namespace splat
{

/// The highest degree evaluated, and its number of basis functions.
constexpr int MaximumSphericalHarmonicsDegree = 3;
constexpr int MaximumSphericalHarmonicsCoefficients = 16;

/// (degree + 1)^2: the basis functions (coefficients per channel) up to `degree`.
constexpr int SphericalHarmonicsCoefficients(int degree)
{
  return (degree + 1) * (degree + 1);
}

/// The degree whose RGB coefficients take `components` floats (3, 12, 27, 48), or -1.
constexpr int SphericalHarmonicsDegreeOf(int components)
{
  for (int degree = 0; degree <= MaximumSphericalHarmonicsDegree; ++degree)
  {
    if (3 * SphericalHarmonicsCoefficients(degree) == components)
    {
      return degree;
    }
  }
  return -1;
}

// The constants of eval_sh (graphdeco-inria/gaussian-splatting, utils/sh_utils.py).
constexpr float ShC0 = 0.28209479177387814f;
constexpr float ShC1 = 0.4886025119029199f;
constexpr float ShC2[5] = { 1.0925484305920792f, -1.0925484305920792f, 0.31539156525252005f,
  -1.0925484305920792f, 0.5462742152960396f };
constexpr float ShC3[7] = { -0.5900435899266435f, 2.890611442640554f, -0.4570457994644658f,
  0.3731763325901154f, -0.4570457994644658f, 1.445305721320277f, -0.5900435899266435f };

/**
 * The basis functions up to `degree` (0 to 3) at the unit direction (x, y, z), in eval_sh's
 * order: basis[0 .. (degree + 1)^2 - 1]. For floats, or per lane for splat::Float8.
 */
template <typename T>
inline void SphericalHarmonicsBasis(const T& x, const T& y, const T& z, int degree, T* basis)
{
  basis[0] = T(ShC0);
  if (degree < 1)
  {
    return;
  }
  basis[1] = -ShC1 * y;
  basis[2] = ShC1 * z;
  basis[3] = -ShC1 * x;
  if (degree < 2)
  {
    return;
  }
  const T xx = x * x, yy = y * y, zz = z * z;
  const T xy = x * y, yz = y * z, xz = x * z;
  basis[4] = ShC2[0] * xy;
  basis[5] = ShC2[1] * yz;
  basis[6] = ShC2[2] * (2.0f * zz - xx - yy);
  basis[7] = ShC2[3] * xz;
  basis[8] = ShC2[4] * (xx - yy);
  if (degree < 3)
  {
    return;
  }
  basis[9] = ShC3[0] * y * (3.0f * xx - yy);
  basis[10] = ShC3[1] * xy * z;
  basis[11] = ShC3[2] * y * (4.0f * zz - xx - yy);
  basis[12] = ShC3[3] * z * (2.0f * zz - 3.0f * xx - 3.0f * yy);
  basis[13] = ShC3[4] * x * (4.0f * zz - xx - yy);
  basis[14] = ShC3[5] * z * (xx - yy);
  basis[15] = ShC3[6] * x * (xx - 3.0f * yy);
}

/// The same at the unit direction d, for floats.
inline void SphericalHarmonicsBasis(const glm::vec3& d, int degree, float* basis)
{
  SphericalHarmonicsBasis(d.x, d.y, d.z, degree, basis);
}

/**
 * The color of a kernel with RGB coefficients `coefficients` (at least 3 (degree + 1)^2) seen
 * along `direction` (eye to kernel center, any length), clamped to [0, 1] as the mapper's
 * colors are. A zero direction keeps the degree-0 term only.
 */
inline glm::vec3 SphericalHarmonicsColor(
  const float* coefficients, int degree, const glm::vec3& direction)
{
  const float length = glm::length(direction);
  const glm::vec3 d = length > 0.0f ? direction / length : glm::vec3(0.0f);
  float basis[MaximumSphericalHarmonicsCoefficients];
  SphericalHarmonicsBasis(d, degree, basis);
  const int count = SphericalHarmonicsCoefficients(degree);
  // Four sums over every fourth coefficient, so that a long degree's additions overlap rather
  // than wait on one another. With GCC's and Clang's vector extension each sum is one register
  // (an RGB triple and, unused, the next red): for 1 M kernels of degree 3, 30 ms on one thread
  // instead of 51 for one scalar sum per channel.
#if defined(__GNUC__)
  typedef float Quad __attribute__((vector_size(16)));
  Quad sums[4] = { { 0.5f, 0.5f, 0.5f, 0.0f }, {}, {}, {} };
  int k = 0;
  for (; k + 4 < count; k += 4) // short of the last triple, whose fourth float is not the kernel's
  {
    for (int j = 0; j < 4; ++j)
    {
      Quad triple;
      std::memcpy(&triple, coefficients + 3 * (k + j), sizeof(triple));
      sums[j] += basis[k + j] * triple;
    }
  }
  for (; k < count; ++k)
  {
    const Quad triple = { coefficients[3 * k], coefficients[3 * k + 1], coefficients[3 * k + 2],
      0.0f };
    sums[0] += basis[k] * triple;
  }
  const Quad sum = (sums[0] + sums[1]) + (sums[2] + sums[3]);
  const glm::vec3 color(sum[0], sum[1], sum[2]);
#else
  glm::vec3 sums[4] = { glm::vec3(0.5f), glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f) };
  for (int k = 0; k < count; ++k)
  {
    sums[k % 4] += basis[k] *
      glm::vec3(coefficients[3 * k], coefficients[3 * k + 1], coefficients[3 * k + 2]);
  }
  const glm::vec3 color = (sums[0] + sums[1]) + (sums[2] + sums[3]);
#endif
  return glm::clamp(color, 0.0f, 1.0f);
}

} // namespace splat

#endif
