// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatCaptureKernel.h
 * @brief The footprint of a 3D Gaussian Splatting kernel (a kernel with a peak opacity) under
 * the rules of the published rasterizer its capture was optimized against (Kerbl et al. 2023,
 * graphdeco-inria diff-gaussian-rasterization, forward pass), and the screen filters of volume
 * footprints.
 *
 * The rules, per kernel of center e and covariance V in eye coordinates:
 * - left out when its center is less than the near distance in front of the eye (kernels that
 *   only reach across the near plane are drawn);
 * - the 2D covariance J V J^T of the linearized projection, the Jacobian taken at the center
 *   with its normalized device coordinates clamped to +-1.3 (the reference clamps x/z and y/z
 *   to 1.3 times the half field of view's tangent: the same for a centered frustum), plus the
 *   filter's variance on the diagonal;
 * - alpha(x) = min(0.99, opacity exp(-1/2 d^T Conic d)), d = x - center, contributions below
 *   1/255 skipped, evaluated within a square of half-size ceil(3 sqrt(lambda_max)) pixels;
 * - front to back in the order of the centers' depths (DepthOrderKey), each pixel stopping before the kernel
 *   that would take its transmittance below 1e-4.
 *
 * Pixel (i, j) has its center at (i + 0.5, j + 0.5), as in SplatVolumeKernel.h; the reference's
 * integer pixel coordinates are these minus one half.
 *
 * VTK-free (GLM only): the CPU rasterizers and the GLSL share it.
 */
#ifndef SplatCaptureKernel_h
#define SplatCaptureKernel_h

#include "SplatVolumeKernel.h" // For splat::VolumeProjection

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace splat
{

/**
 * The screen filter a footprint's 2D covariance is convolved with.
 * - LowPass: EWA's unit screen low-pass (1 px^2), the band limit of density kernels;
 * - Dilation: the 0.3 px^2 that captures were trained with, peak opacity unchanged;
 * - Antialiased: the dilation with the peak opacity scaled by sqrt(|V'| / |V' + 0.3 I|), which
 *   keeps each kernel's integral (gsplat's antialiased mode, Mip-Splatting's 2D filter) for
 *   views far from the training range.
 */
enum class FootprintFilter
{
  LowPass = 0,
  Dilation = 1,
  Antialiased = 2
};

/// The variance the reference rasterizer adds to every projected covariance, px^2.
constexpr double CaptureDilation = 0.3;
/// The reference's largest alpha of one kernel at one pixel.
constexpr float CaptureMaximumAlpha = 0.99f;
/// The reference's smallest alpha that contributes.
constexpr float CaptureMinimumAlpha = 1.0f / 255.0f;
/// A pixel stops before the kernel that would take its transmittance below this.
constexpr float CaptureMinimumTransmittance = 1e-4f;
/// The reference's clamp of the projected center's normalized device coordinates.
constexpr double CaptureJacobianClamp = 1.3;

/// The variance the filter adds to a footprint's 2D covariance, px^2.
inline double FilterVariance(FootprintFilter filter)
{
  return filter == FootprintFilter::LowPass ? 1.0 : CaptureDilation;
}

/**
 * The factor on a peak opacity under `filter` for a footprint whose 2D covariance before the
 * filter is `covariance`: sqrt(|V'| / |V' + 0.3 I|) for Antialiased, 1 otherwise.
 */
inline double PeakOpacityCompensation(FootprintFilter filter, const glm::dmat2& covariance)
{
  if (filter != FootprintFilter::Antialiased)
  {
    return 1.0;
  }
  const double filtered = glm::determinant(covariance + glm::dmat2(CaptureDilation));
  return std::sqrt(std::max(glm::determinant(covariance), 0.0) / filtered);
}

/**
 * A capture kernel on the screen: alpha(x) = min(0.99, Opacity exp(-q(x - Center))) with
 * q(d) = ConicXX d.x^2 + ConicXY d.x d.y + ConicYY d.y^2 (half the conic's quadratic form),
 * nonzero only inside Box.
 */
struct CaptureFootprint
{
  glm::dvec2 Center{ 0.0 };
  double ConicXX = 0.0;
  double ConicXY = 0.0;
  double ConicYY = 0.0;
  double Opacity = 0.0;
  double Depth = 0.0; ///< -z of the center in eye coordinates: the sort key
  /// The largest q(d) where alpha can reach 1/255 (a little more, for float rounding).
  double Level = 0.0;
  /// The pixels (inclusive x0, x1, y0, y1) whose centers lie in the reference's square and
  /// where alpha can reach 1/255, clipped to the viewport.
  glm::ivec4 Box{ 0 };
};

/// Why a capture kernel is not drawn.
enum class CaptureSkip
{
  Kept = 0,
  NearPlane,     ///< center less than the near distance in front of the eye
  OutsideView,   ///< no pixel where its alpha reaches 1/255
};

/**
 * The footprint of a kernel of peak opacity `opacity`, center e in eye coordinates and
 * covariance V in coordinates that the linear map toEye takes to eye coordinates (the model's,
 * so that the 3 x 3 products are done once as 2 x 3 ones), under eyeToClip and a viewport of
 * the given size (see the file comment).
 */
inline CaptureSkip MakeCaptureFootprint(const glm::dmat4& eyeToClip, const glm::dvec2& viewport,
  double nearDistance, const glm::dvec3& e, const glm::dmat3& toEye, const glm::dmat3& V,
  double opacity, FootprintFilter filter, CaptureFootprint& out)
{
  out.Depth = -e.z;
  PointProjection center;
  if (!(out.Depth >= nearDistance) || !ProjectPoint(eyeToClip, viewport, e, center))
  {
    return CaptureSkip::NearPlane;
  }
  out.Center = center.Center;
  // The Jacobian's rows d(pixel)/d(eye) at the center with its NDC clamped (no effect for a
  // parallel projection, whose clip w does not depend on the position).
  PointProjection clamped = center;
  clamped.Ndc = glm::clamp(center.Ndc, -CaptureJacobianClamp, CaptureJacobianClamp);
  glm::dmat3x2 J;
  for (int axis = 0; axis < 3; ++axis)
  {
    J[axis] = clamped.PixelDerivative(eyeToClip[axis]);
  }
  const glm::dmat3x2 T = J * toEye;
  const glm::dmat2 projected = T * V * glm::transpose(T);
  const glm::dmat2 covariance = projected + glm::dmat2(FilterVariance(filter));
  const double det = glm::determinant(covariance);
  out.Opacity = opacity * PeakOpacityCompensation(filter, projected);
  if (!(det > 0.0) || !(out.Opacity >= CaptureMinimumAlpha))
  {
    return CaptureSkip::OutsideView;
  }
  const glm::dmat2 conic = glm::inverse(covariance);
  out.ConicXX = 0.5 * conic[0][0];
  out.ConicXY = conic[1][0];
  out.ConicYY = 0.5 * conic[1][1];
  // The reference's square: 3 standard deviations along the larger eigenvalue, rounded up.
  const double mid = 0.5 * (covariance[0][0] + covariance[1][1]);
  const double largest = mid + std::sqrt(std::max(0.1, mid * mid - det));
  const double radius = std::ceil(3.0 * std::sqrt(largest));
  // Within it, alpha reaches 1/255 only inside the ellipse d^T Conic d <= 2 ln(255 opacity),
  // whose bounding box is sqrt(level V'_xx) by sqrt(level V'_yy); a little wider, so that float
  // rounding at its edge stays inside.
  out.Level = std::log(std::min(out.Opacity, 1.0) / CaptureMinimumAlpha) * 1.001;
  const double level = 2.0 * out.Level;
  const glm::dvec2 halfExtent(std::min(radius, std::sqrt(level * covariance[0][0]) + 1e-3),
    std::min(radius, std::sqrt(level * covariance[1][1]) + 1e-3));
  return CoveredPixels(out.Center, halfExtent, static_cast<int>(viewport.x),
           static_cast<int>(viewport.y), out.Box)
    ? CaptureSkip::Kept
    : CaptureSkip::OutsideView;
}

/**
 * A float's bits as an unsigned key of the same order (negative floats included).
 */
inline std::uint32_t SortKey(float value)
{
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof(bits));
  return bits & 0x80000000u ? ~bits : bits | 0x80000000u;
}

/**
 * A kernel's depth as a sort key in the high half and its index in the low half: sorting such
 * keys orders the kernels front to back, equal depths by index (std::stable_sort's order by
 * depth, from integer comparisons that parallel and radix sorts can use).
 */
inline std::uint64_t DepthOrderKey(float depth, std::uint32_t index)
{
  return static_cast<std::uint64_t>(SortKey(depth)) << 32 | index;
}

} // namespace splat

#endif
