// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatDifferentialPointNormal.h
 * @brief The normal a differential point predicts around itself (Kalaiah and Varshney, eq. 10).
 *
 * Plain C++ (no VTK, GLM or Eigen) so that vtkDifferentialPointGenerator's simplification, the
 * CPU rasterizer of vtkSurfaceSplatMapper and, line by line, the GLSL of its OpenGL backend
 * (vtkSurfaceSplatFS.glsl) share one formulation.
 *
 * A differential point has a unit normal N, unit principal directions U and V, and signed
 * principal curvatures lambda_u, lambda_v (dN(U) = -lambda_u U). At (u, v) on its tangent plane
 * (in the input's units along U and V) the normal moved along the osculating circle of the
 * direction (u, v) by its arc length is, unnormalized,
 *
 *   n(u, v) = N - g(u, v) (lambda_u u U + lambda_v v V),   g = arcsin(x) / x,
 *   x = (lambda_u u^2 + lambda_v v^2) / sqrt(u^2 + v^2),
 *
 * x being the normal curvature of the direction times the distance. Where |x| > 1 the point
 * lies beyond the osculating circle's reach and arcsin is taken at 1. The renderer computes it
 * exactly per pixel, where the paper's 2003 hardware looked it up in 256 normal maps.
 */
#ifndef SplatDifferentialPointNormal_h
#define SplatDifferentialPointNormal_h

#include <algorithm>
#include <cmath>

namespace splat
{

/// g(u, v) of the file comment: 1 at the point itself and wherever the surface is flat.
template <typename Real>
inline Real DifferentialNormalScale(Real curvatureU, Real curvatureV, Real u, Real v)
{
  const Real r2 = u * u + v * v;
  if (!(r2 > Real(0)))
  {
    return Real(1);
  }
  const Real k = curvatureU * u * u + curvatureV * v * v; // x sqrt(u^2 + v^2)
  const Real x2 = k * k / r2;
  // arcsin(x) / x = 1 + x^2/6 + 3 x^4/40 + 5 x^6/112 + 35 x^8/1152 + ...: the series, within
  // 5e-7 of it, where the error bound keeps most points (x^2 < 1/16: |x| < 1/4, and
  // sqrt(2 eps - eps^2) is 0.14 at the default eps), without an arcsin or a square root.
  if (x2 < Real(0.0625))
  {
    return Real(1) + x2 * (Real(1) / Real(6) + x2 * (Real(3) / Real(40) + x2 * Real(5) / Real(112)));
  }
  const Real x = std::sqrt(x2);
  return std::asin(std::min(x, Real(1))) / x;
}

} // namespace splat

#endif
