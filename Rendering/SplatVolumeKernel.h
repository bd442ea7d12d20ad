// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatVolumeKernel.h
 * @brief EWA volume splatting of one 3D Gaussian kernel (Zwicker et al., EWA Volume Splatting,
 * 2002): its footprint, the integral along each pixel's ray under the local affine approximation
 * of the perspective projection, band-limited by the screen low-pass filter.
 *
 * VTK-free (GLM only) so that the CPU rasterizer, the filters, the tests and the GLSL of the
 * OpenGL backend share one formulation.
 *
 * Conventions
 * - A kernel is a normalized 3D Gaussian r(x) = G_V(x - p) with covariance V (model units^2).
 * - Ray space: u = (pixel x, pixel y, distance along the pixel's ray), distance measured from the
 *   eye for perspective views and from the eye plane for parallel ones. J = du/de is its Jacobian
 *   with respect to eye coordinates at the kernel center.
 * - Footprint (the integral of r along the ray through pixel position x):
 *     int r dt = |J| G_{V'}(x - m), V' = (J W V W^T J^T) restricted to (x, y),
 *   with W the linear part of the model-to-eye map. Convolved with the unit screen low-pass
 *   filter it becomes |J| G_{V' + I}(x - m): splat::ResamplingKernel with
 *   Amplitude = |J| / (2 pi sqrt|V' + I|). The band limit instead raises V''s eigenvalues to
 *   at least 1 (FilteredCovariance). A parallel view with s model units per pixel gives
 *   J = diag(1/s, 1/s, 1) and the footprint s^-2 G_{V'}(x/s) = G_{V_xy}(world offset): the
 *   orthographic projection of the Gaussian, as it must.
 * - The footprint is evaluated while the exponent 1/2 d^T (V' + I)^-1 d is below the cutoff c,
 *   which keeps a share 1 - e^-c of its mass; TruncationCompensation(c) restores the total.
 * - Pixel (i, j) has its center at (i + 0.5, j + 0.5), origin at the viewport's lower left.
 */
#ifndef SplatVolumeKernel_h
#define SplatVolumeKernel_h

#include "SplatSurfelKernel.h" // For splat::ResamplingKernel, splat::InverseTwoPi

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace splat
{

/**
 * Standard deviation of a voxel's kernel per unit of grid spacing along each index axis.
 * Gaussians of standard deviation 0.6 h on a grid of spacing h, each weighted by the voxel
 * volume, sum to 1 within 2 exp(-2 pi^2 0.36) = 0.16% per axis, 0.5% in 3D (Poisson summation;
 * measured in SplatVolumeKernelTest): the voxels' extinctions reconstruct a constant field
 * without ripples. Narrower kernels ripple (0.5 h: 1.4% per axis), wider ones blur.
 */
constexpr double VoxelKernelSigma = 0.6;

/**
 * Default cutoff of volume footprints: 4.5 keeps 98.9% of each footprint's mass (support radius
 * 3 sigma). The surface mapper's cutoff 1 suits surfels, whose kernels are normalized per pixel;
 * volume footprints are summed as optical depth, so a cutoff of 1 would drop 37% of it.
 */
constexpr double DefaultVolumeCutoff = 4.5;

/// (2 pi)^(3/2): the integral of exp(-1/2 x^T V^-1 x) is (2 pi)^(3/2) sqrt|V|.
constexpr double TwoPiToThreeHalves = 15.749609945722419;

/// The symmetric matrix of the six components (xx, xy, xz, yy, yz, zz).
template <typename T>
inline glm::dmat3 SymmetricFromComponents(const T* c)
{
  return glm::dmat3(c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5]);
}

/**
 * The covariance R diag(scale^2) R^T of a Gaussian with standard deviations `scale` along the
 * axes of the rotation given by the quaternion (w, x, y, z) (not necessarily normalized; it must
 * not be zero). This is the convention of 3D Gaussian Splatting files once their log-scales are
 * exponentiated, and of VTK 9.4's anisotropic point gaussians.
 */
inline glm::dmat3 CovarianceFromScaleRotation(const glm::dvec3& scale, const glm::dvec4& wxyz)
{
  // Divided by its largest component first, so that the length of a quaternion of huge or tiny
  // norm (1e200, 1e-200) neither overflows nor underflows.
  const double largest = std::max(
    std::max(std::abs(wxyz[0]), std::abs(wxyz[1])), std::max(std::abs(wxyz[2]), std::abs(wxyz[3])));
  const glm::dvec4 u = wxyz / largest;
  const glm::dvec4 q = u / glm::length(u);
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  // Columns of the rotation matrix.
  const glm::dmat3 R(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y),
    2.0 * (x * y - w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z + w * x),
    2.0 * (x * z + w * y), 2.0 * (y * z - w * x), 1.0 - 2.0 * (x * x + y * y));
  const glm::dmat3 S(scale.x * scale.x, 0.0, 0.0, 0.0, scale.y * scale.y, 0.0, 0.0, 0.0,
    scale.z * scale.z);
  return R * S * glm::transpose(R);
}

/**
 * The covariance of a voxel's kernel: indexToModel has the grid's index axes as columns (the
 * image's direction matrix times its spacing); sigma = VoxelKernelSigma along each of them.
 */
inline glm::dmat3 VoxelCovariance(const glm::dmat3& indexToModel)
{
  return (VoxelKernelSigma * VoxelKernelSigma) * (indexToModel * glm::transpose(indexToModel));
}

/// Restores the footprint mass beyond the cutoff c: 1 / (1 - e^-c).
inline double TruncationCompensation(double cutoff)
{
  return 1.0 / -std::expm1(-cutoff);
}

/**
 * Distance of the near clipping plane in front of the eye, from an OpenGL projection matrix
 * (NDC z = -1 there), for perspective and parallel projections.
 */
inline double NearPlaneDistance(const glm::dmat4& eyeToClip)
{
  const glm::dmat4& P = eyeToClip;
  return (P[3][2] + P[3][3]) / (P[2][2] + P[2][3]);
}

/// The same for the far plane (NDC z = +1).
inline double FarPlaneDistance(const glm::dmat4& eyeToClip)
{
  const glm::dmat4& P = eyeToClip;
  return (P[3][2] - P[3][3]) / (P[2][2] - P[2][3]);
}

/**
 * Whether the kernel's cutoff ellipsoid 1/2 x^T V^-1 x < c reaches the near plane or lies
 * behind it, where the projected conic is not an ellipse (paper 003, figure 3): it extends
 * sqrt(2 c V_zz) along the eye's z axis.
 */
inline bool CrossesNearPlane(
  const glm::dvec3& eyeCenter, const glm::dmat3& eyeCovariance, double nearDistance, double cutoff)
{
  const double extent = std::sqrt(2.0 * cutoff * std::max(eyeCovariance[2][2], 0.0));
  return !(-eyeCenter.z - extent > nearDistance);
}

/**
 * A kernel center through the projection, linearized: the projected center in pixels and the
 * Jacobian of ray space (pixel x, pixel y, distance along the ray) with respect to eye
 * coordinates.
 */
struct VolumeProjection
{
  glm::dvec2 Center{ 0.0 };
  glm::dmat3 Jacobian{ 1.0 }; ///< J[column][row]: rows are d(pixel x), d(pixel y), d(distance)
};

/**
 * Projects the eye-space point e through eyeToClip and the viewport mapping. Returns false when
 * the point is not strictly in front of the eye (clip w <= 0), where the linearization does not
 * exist.
 */
inline bool ProjectVolumeKernel(const glm::dmat4& eyeToClip, const glm::dvec2& viewportSize,
  const glm::dvec3& e, VolumeProjection& out)
{
  PointProjection center;
  if (!ProjectPoint(eyeToClip, viewportSize, e, center))
  {
    return false;
  }
  out.Center = center.Center;
  const bool perspective = eyeToClip[3][3] == 0.0;
  // The distance along the ray: |e| from the eye (perspective) or -z from the eye plane.
  const glm::dvec3 distanceGradient =
    perspective ? e / glm::length(e) : glm::dvec3(0.0, 0.0, -1.0);
  for (int axis = 0; axis < 3; ++axis)
  {
    out.Jacobian[axis] =
      glm::dvec3(center.PixelDerivative(eyeToClip[axis]), distanceGradient[axis]);
  }
  return true;
}

/**
 * A footprint's 2D covariance c (px^2) under a screen filter of variance `variance`: convolved
 * with it (c + variance I), or with bandLimit each eigenvalue raised to at least `variance`
 * (Botsch et al. 2005 take the larger of the splat's and the low-pass's radius as their
 * approximation of EWA). Both band-limit minified footprints alike; the floor leaves footprints
 * already wider than the filter as they are, where the sum blurs them by a pixel more. Written
 * with the projector onto the smaller eigenvalue's direction, (c - l1 I) / (l2 - l1), as the
 * GLSL does.
 */
inline glm::dmat2 FilteredCovariance(const glm::dmat2& c, double variance, bool bandLimit)
{
  const glm::dmat2 identity(1.0);
  if (!bandLimit)
  {
    return c + variance * identity;
  }
  const double mean = 0.5 * (c[0][0] + c[1][1]);
  const double half = 0.5 * (c[0][0] - c[1][1]);
  const double radius = std::sqrt(half * half + c[0][1] * c[0][1]);
  const double l1 = mean + radius, l2 = mean - radius;
  if (!(l2 < variance))
  {
    return c;
  }
  if (!(l1 > variance))
  {
    return variance * identity;
  }
  return c + ((variance - l2) / (l2 - l1)) * (c - l1 * identity);
}

/**
 * The footprint of a normalized Gaussian of eye-space covariance eyeCovariance (see the file
 * comment): Amplitude * exp(-beta) is its integral along the ray, screen-filtered, per unit of
 * kernel mass. The filter (the unit low-pass, 1 px^2 convolved, unless another screen filter is
 * asked for: splat::FilterVariance, FilteredCovariance) keeps the 2x2 covariance invertible for
 * degenerate kernels (zero scales, eigenvalue ratios of 1e12).
 */
inline ResamplingKernel MakeVolumeFootprint(const VolumeProjection& projection,
  const glm::dmat3& eyeCovariance, double cutoff, double filterVariance = 1.0,
  bool bandLimit = false)
{
  const glm::dmat3& J = projection.Jacobian;
  const glm::dmat3 rayCovariance = J * eyeCovariance * glm::transpose(J);
  ResamplingKernel k;
  k.Center = projection.Center;
  k.Cutoff = cutoff;
  k.Covariance = FilteredCovariance(glm::dmat2(rayCovariance), filterVariance, bandLimit);
  const double detM = glm::determinant(k.Covariance);
  k.Conic = glm::inverse(k.Covariance);
  k.Amplitude = std::abs(glm::determinant(J)) * InverseTwoPi / std::sqrt(detM);
  k.HalfExtent = glm::dvec2(std::sqrt(2.0 * cutoff * k.Covariance[0][0]),
    std::sqrt(2.0 * cutoff * k.Covariance[1][1]));
  return k;
}

/**
 * Exact integral along the line o + t d (t over all reals, d a unit vector) of the normalized
 * Gaussian G_V(x - p): the reference the affine approximation is tested against.
 */
inline double GaussianLineIntegral(
  const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& p, const glm::dmat3& V)
{
  const glm::dmat3 A = glm::inverse(V);
  const glm::dvec3 r = o - p;
  const double a = glm::dot(d, A * d);
  const double b = glm::dot(d, A * r);
  const double c = glm::dot(r, A * r);
  return std::exp(-0.5 * (c - b * b / a)) * std::sqrt(2.0 * 3.14159265358979323846 / a) /
    (TwoPiToThreeHalves * std::sqrt(glm::determinant(V)));
}

} // namespace splat

#endif
