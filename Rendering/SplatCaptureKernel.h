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
 * The CPU computes the footprints eight kernels at a time, in float as the reference does
 * (MakeCaptureFootprints); the GLSL mirrors the same steps per kernel. VTK-free (GLM and
 * SplatFloat8.h only).
 */
#ifndef SplatCaptureKernel_h
#define SplatCaptureKernel_h

#include "SplatFloat8.h"       // For splat::Float8
#include "SplatSortKey.h"      // For splat::DepthOrderKey
#include "SplatVolumeKernel.h" // For splat::NearPlaneDistance

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace splat
{

/**
 * The screen filter a footprint's 2D covariance is convolved with.
 * - LowPass: EWA's unit screen low-pass (1 px^2), the band limit of density kernels;
 * - Dilation: the 0.3 px^2 that captures were trained with, peak opacity unchanged;
 * - Antialiased: the dilation with the peak opacity scaled by sqrt(|V'| / |V' + 0.3 I|), which
 *   keeps each kernel's integral (gsplat's antialiased mode, Mip-Splatting's 2D filter) for
 *   views far from the training range;
 * - BandLimit: LowPass's 1 px^2 as a floor of the covariance's eigenvalues instead of a sum
 *   (FilteredCovariance), for density kernels: magnified ones keep their width.
 */
enum class FootprintFilter
{
  LowPass = 0,
  Dilation = 1,
  Antialiased = 2,
  BandLimit = 3
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

/// The variance the filter adds to a footprint's 2D covariance (BandLimit: its floor), px^2.
inline double FilterVariance(FootprintFilter filter)
{
  return filter == FootprintFilter::LowPass || filter == FootprintFilter::BandLimit
    ? 1.0
    : CaptureDilation;
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

/// Why a capture kernel is not drawn.
enum class CaptureSkip
{
  Kept = 0,
  NearPlane,     ///< center less than the near distance in front of the eye
  OutsideView,   ///< no pixel where its alpha reaches 1/255
};

/**
 * A frame's constants for MakeCaptureFootprints, in float as the reference computes: the rows
 * x, y and w of eyeToClip, the viewport's half size, the linear map toEye from the coordinates
 * of the kernels' covariances (the model's, so that the 3 x 3 products are done once as 2 x 3
 * ones) to eye coordinates, the near distance and the filter.
 */
struct CaptureFrame
{
  float Clip[4][3]; ///< per column of eyeToClip, its rows x, y and w
  float HalfSize[2];
  float ToEye[3][3]; ///< per column, as glm's
  float NearDistance;
  float FilterVariance;
  bool Antialiased;

  CaptureFrame(const glm::dmat4& eyeToClip, const glm::dvec2& viewport, const glm::dmat3& toEye,
    FootprintFilter filter)
    : HalfSize{ static_cast<float>(0.5 * viewport.x), static_cast<float>(0.5 * viewport.y) }
    , NearDistance(static_cast<float>(NearPlaneDistance(eyeToClip)))
    , FilterVariance(static_cast<float>(splat::FilterVariance(filter)))
    , Antialiased(filter == FootprintFilter::Antialiased)
  {
    for (int column = 0; column < 4; ++column)
    {
      this->Clip[column][0] = static_cast<float>(eyeToClip[column][0]);
      this->Clip[column][1] = static_cast<float>(eyeToClip[column][1]);
      this->Clip[column][2] = static_cast<float>(eyeToClip[column][3]);
    }
    for (int column = 0; column < 3; ++column)
    {
      for (int row = 0; row < 3; ++row)
      {
        this->ToEye[column][row] = static_cast<float>(toEye[column][row]);
      }
    }
  }
};

/**
 * Eight capture kernels, one per lane, for MakeCaptureFootprints. In: their centers in eye
 * coordinates, their covariances in the coordinates CaptureFrame::ToEye maps to eye
 * coordinates (xx, xy, xz, yy, yz, zz) and their peak opacities. Out, where Visible has the
 * lane's bit: the footprint alpha(x) = min(0.99, Opacity exp(-q(x - Center))) with q(d) =
 * ConicXX d.x^2 + ConicXY d.x d.y + ConicYY d.y^2 (half the conic's quadratic form), Opacity
 * the filtered peak, Level the largest q(d) where alpha can reach 1/255 (a little more, for
 * float rounding), and the half sizes of the box around Center holding the pixels of the
 * reference's square where alpha can reach 1/255; Depth, -z of the center in eye
 * coordinates (the sort key), in every lane.
 */
struct CaptureLanes
{
  Float8 Eye[3];
  Float8 Covariance[6];
  Float8 Opacity;
  Float8 CenterX, CenterY;
  Float8 ConicXX, ConicXY, ConicYY;
  Float8 Level;
  Float8 Depth;
  Float8 HalfExtentX, HalfExtentY;
  int InFront = 0; ///< lanes whose center is at least the near distance in front of the eye
  int Visible = 0; ///< lanes in front whose alpha reaches 1/255 (before the viewport's clip)
};

/**
 * The footprints of eight kernels under the rules of the file comment, in float (the
 * reference's precision). A kernel not InFront is skipped as CaptureSkip::NearPlane; one in
 * front but not Visible, or whose box (CoveredPixels) holds no pixel, as OutsideView.
 */
SPLAT_ALWAYS_INLINE void MakeCaptureFootprints(const CaptureFrame& frame, CaptureLanes& k)
{
  const Float8 zero(0.0f), one(1.0f);
  k.Depth = zero - k.Eye[2];
  Float8 clip[3];
  for (int row = 0; row < 3; ++row)
  {
    clip[row] = k.Eye[0] * frame.Clip[0][row] + k.Eye[1] * frame.Clip[1][row] +
      k.Eye[2] * frame.Clip[2][row] + frame.Clip[3][row];
  }
  const int behind =
    Float8::LessMask(k.Depth, frame.NearDistance) | Float8::LessMask(clip[2], 1e-30f);
  k.InFront = ~behind & 0xff;
  // Lanes behind the eye divide by one: they are left out.
  const Float8 inverseW = one / Float8::SelectLess(clip[2], 1e-30f, one, clip[2]);
  const Float8 ndcX = clip[0] * inverseW, ndcY = clip[1] * inverseW;
  k.CenterX = (ndcX + 1.0f) * frame.HalfSize[0];
  k.CenterY = (ndcY + 1.0f) * frame.HalfSize[1];
  // The Jacobian's rows d(pixel)/d(eye) at the center with its NDC clamped (no effect for a
  // parallel projection, whose clip w does not depend on the position).
  const float bound = static_cast<float>(CaptureJacobianClamp);
  const auto clamped = [bound](const Float8& x)
  { return Float8::SelectLess(x, -bound, -bound, Float8::SelectLess(bound, x, bound, x)); };
  const Float8 clampedX = clamped(ndcX), clampedY = clamped(ndcY);
  const Float8 scaleX = inverseW * frame.HalfSize[0], scaleY = inverseW * frame.HalfSize[1];
  Float8 J[2][3];
  for (int axis = 0; axis < 3; ++axis)
  {
    J[0][axis] = (Float8(frame.Clip[axis][0]) - clampedX * frame.Clip[axis][2]) * scaleX;
    J[1][axis] = (Float8(frame.Clip[axis][1]) - clampedY * frame.Clip[axis][2]) * scaleY;
  }
  // T = J toEye, then T V T^T through W = T V.
  Float8 T[2][3];
  for (int row = 0; row < 2; ++row)
  {
    for (int column = 0; column < 3; ++column)
    {
      T[row][column] = J[row][0] * frame.ToEye[column][0] + J[row][1] * frame.ToEye[column][1] +
        J[row][2] * frame.ToEye[column][2];
    }
  }
  const Float8* V = k.Covariance;
  Float8 W[2][3];
  for (int row = 0; row < 2; ++row)
  {
    W[row][0] = T[row][0] * V[0] + T[row][1] * V[1] + T[row][2] * V[2];
    W[row][1] = T[row][0] * V[1] + T[row][1] * V[3] + T[row][2] * V[4];
    W[row][2] = T[row][0] * V[2] + T[row][1] * V[4] + T[row][2] * V[5];
  }
  const Float8 projectedXX = W[0][0] * T[0][0] + W[0][1] * T[0][1] + W[0][2] * T[0][2];
  const Float8 projectedXY = W[0][0] * T[1][0] + W[0][1] * T[1][1] + W[0][2] * T[1][2];
  const Float8 projectedYY = W[1][0] * T[1][0] + W[1][1] * T[1][1] + W[1][2] * T[1][2];
  const Float8 xx = projectedXX + frame.FilterVariance;
  const Float8 yy = projectedYY + frame.FilterVariance;
  const Float8 det = xx * yy - projectedXY * projectedXY;
  if (frame.Antialiased)
  {
    // The peak scaled by sqrt(|V'| / |V' + 0.3 I|), as PeakOpacityCompensation.
    const Float8 unfiltered = projectedXX * projectedYY - projectedXY * projectedXY;
    const Float8 ratio = Float8::SelectLess(zero, det, unfiltered / det, zero);
    k.Opacity = k.Opacity * Float8::Sqrt(Float8::SelectLess(ratio, zero, zero, ratio));
  }
  k.Visible = k.InFront & Float8::LessMask(zero, det) &
    ~Float8::LessMask(k.Opacity, CaptureMinimumAlpha);
  const Float8 inverseDet = one / Float8::SelectLess(zero, det, det, one);
  k.ConicXX = 0.5f * yy * inverseDet;
  k.ConicXY = (zero - projectedXY) * inverseDet;
  k.ConicYY = 0.5f * xx * inverseDet;
  // The reference's square: 3 standard deviations along the larger eigenvalue, rounded up
  // (read only for the visible lanes: the others' can be NaN).
  const Float8 mid = 0.5f * (xx + yy);
  const Float8 spread = mid * mid - det;
  const Float8 largest = mid + Float8::Sqrt(Float8::SelectLess(spread, 0.1f, 0.1f, spread));
  const Float8 reach = 3.0f * Float8::Sqrt(largest);
  const Float8 truncated = Float8::Truncated(reach);
  const Float8 radius = Float8::SelectLess(truncated, reach, truncated + 1.0f, truncated);
  // Within it, alpha reaches 1/255 only inside the ellipse d^T Conic d <= 2 ln(255 opacity),
  // whose bounding box is sqrt(level V'_xx) by sqrt(level V'_yy); a little wider, so that float
  // rounding at its edge stays inside.
  alignas(32) float opacities[8];
  alignas(32) float levels[8];
  k.Opacity.Store(opacities);
  for (int lane = 0; lane < 8; ++lane)
  {
    levels[lane] = k.Visible >> lane & 1
      ? std::log(std::min(opacities[lane], 1.0f) / CaptureMinimumAlpha) * 1.001f
      : 0.0f;
  }
  k.Level = Float8::Load(levels);
  const Float8 level = 2.0f * k.Level;
  const Float8 boxX = Float8::Sqrt(level * xx) + 1e-3f;
  const Float8 boxY = Float8::Sqrt(level * yy) + 1e-3f;
  k.HalfExtentX = Float8::SelectLess(radius, boxX, radius, boxX);
  k.HalfExtentY = Float8::SelectLess(radius, boxY, radius, boxY);
}

} // namespace splat

#endif
