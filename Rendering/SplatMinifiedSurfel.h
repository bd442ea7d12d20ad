// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatMinifiedSurfel.h
 * @brief The single-precision setup of a surfel that decides whether it is minified (its warped
 * basis function far below a pixel) and, if so, what the pixel holding its center sums of it
 * or, under a low-pass below the paper's, its own kernel.
 *
 * VTK-free (GLM only). The CPU rasterizer runs it on every surfel of a frame that sums minified
 * splats per pixel, before, and mostly instead of, the double-precision setup of the exact
 * kernel (SplatSurfelKernel.h): a minified splat needs its projected center, the Jacobian J of
 * its projection (whose J Vr J^T decides), its depth plane and its normal, and single precision
 * is ample for them once the position is in eye space. Only the position is transformed in
 * double precision, so that surfels far from the origin keep their place.
 */
#ifndef SplatMinifiedSurfel_h
#define SplatMinifiedSurfel_h

#include "SplatSurfelKernel.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace splat
{

/// floor(x) for |x| < 2^31, without a call or a rounding-mode change.
inline int FloorToInt(float x)
{
  const int truncated = static_cast<int>(x);
  return truncated - (x < static_cast<float>(truncated));
}

/**
 * What the pixel holding a minified splat's center sums of it (its mass is the |J| its
 * resampling kernel integrates to, eq. 6).
 */
struct MinifiedSurfel
{
  float CenterX, CenterY;
  // Eye depth of its tangent plane at its pixel's center, and how it changes per pixel: at
  // grazing angles a pixel spans more depth than the z threshold.
  float Depth;
  float DepthSlope[2];
  float Threshold;
  float Mass;
  float Spread; // the warped basis function's mean variance, pixels^2
  float Normal[3];
  float Color[3];
  float Alpha;
};

/**
 * Projects surfels for the minified test, with a frame's matrices converted once.
 */
class MinifiedSurfelProjector
{
public:
  /// Why a surfel is not minified, or that it is.
  enum Outcome
  {
    Culled,     ///< behind the eye, outside the depth range, or its center off the padded viewport
    FacingAway, ///< back-facing with back faces culled
    EdgeOn,     ///< foreshortened below EdgeOnForeshortening
    Magnified,  ///< to be drawn with its exact kernel
    Minified
  };

  struct Frame
  {
    glm::dmat4 ModelToEye{ 1.0 };
    glm::dmat4 EyeToClip{ 1.0 };
    glm::dvec2 Viewport{ 1.0 };
    double NearDepth = 0.0, FarDepth = 1.0; ///< eye depths of the near and far planes
    double DepthReach = 1.0;      ///< how far a splat reaches along an axis, in axis units
    double MaximumVariance = 0.0; ///< the largest eigenvalue of J Vr J^T that is minified
    double DepthThreshold = 1.0;  ///< z threshold relative to the longer eye-space axis
    int Reach = 0;                ///< cells kept outside the viewport on each side
    bool Perspective = true;
    bool CullBackFaces = false;
  };

  explicit MinifiedSurfelProjector(const Frame& frame)
    : PositionToEye(frame.ModelToEye)
    , EyeTranslation(frame.ModelToEye[3])
    , AxisToEye(glm::dmat3(frame.ModelToEye))
    , NormalToEye(glm::transpose(glm::inverse(glm::dmat3(frame.ModelToEye))))
    // Only clip x, y and w matter: the rows x, y, w of the eye-to-clip matrix.
    , ClipRows(frame.EyeToClip[0][0], frame.EyeToClip[0][1], frame.EyeToClip[0][3],
        frame.EyeToClip[1][0], frame.EyeToClip[1][1], frame.EyeToClip[1][3],
        frame.EyeToClip[2][0], frame.EyeToClip[2][1], frame.EyeToClip[2][3])
    , ClipTranslation(frame.EyeToClip[3][0], frame.EyeToClip[3][1], frame.EyeToClip[3][3])
    , HalfSize(0.5 * frame.Viewport)
    , Low(static_cast<float>(-frame.Reach))
    , High(glm::vec2(frame.Viewport) + static_cast<float>(frame.Reach))
    , NearDepth(static_cast<float>(frame.NearDepth))
    , FarDepth(static_cast<float>(frame.FarDepth))
    , DepthReach(static_cast<float>(frame.DepthReach))
    , MaximumVariance(static_cast<float>(frame.MaximumVariance))
    , DepthThreshold(static_cast<float>(frame.DepthThreshold))
    , Perspective(frame.Perspective)
    , CullBackFaces(frame.CullBackFaces)
  {
  }

  /// Surfels projected together: the single-precision work runs on all of them at once, as
  /// vector instructions (structure of arrays, no branches).
  static constexpr int BatchSize = 64;
  struct Batch
  {
    // Loaded: the eye-space center, the model-space axes and normal, and the mass scale.
    // Project replaces the normal with the eye-space one, unit length, either side (AddNormal).
    float PX[BatchSize], PY[BatchSize], PZ[BatchSize];
    float A0X[BatchSize], A0Y[BatchSize], A0Z[BatchSize];
    float A1X[BatchSize], A1Y[BatchSize], A1Z[BatchSize];
    float NX[BatchSize], NY[BatchSize], NZ[BatchSize];
    float MassScale[BatchSize];
    // Projected.
    int Outcome[BatchSize];
    float CenterX[BatchSize], CenterY[BatchSize];
    float SlopeX[BatchSize], SlopeY[BatchSize];
    float Threshold[BatchSize], Mass[BatchSize];
    float WarpedXX[BatchSize], WarpedXY[BatchSize], WarpedYY[BatchSize]; // J Vr J^T, pixels^2
  };

  /// Loads surfel j of a batch: its position in double precision to eye space (so that
  /// surfels far from the origin keep their place), the rest as it is.
  void Load(Batch& batch, int j, const double* position, const float* normal, const float* axis0,
    const float* axis1, float massScale) const
  {
    const glm::vec3 p(
      this->PositionToEye * glm::dvec3(position[0], position[1], position[2]) +
      this->EyeTranslation);
    batch.PX[j] = p.x;
    batch.PY[j] = p.y;
    batch.PZ[j] = p.z;
    batch.A0X[j] = axis0[0];
    batch.A0Y[j] = axis0[1];
    batch.A0Z[j] = axis0[2];
    batch.A1X[j] = axis1[0];
    batch.A1Y[j] = axis1[1];
    batch.A1Z[j] = axis1[2];
    batch.NX[j] = normal[0];
    batch.NY[j] = normal[1];
    batch.NZ[j] = normal[2];
    batch.MassScale[j] = massScale;
  }

  /**
   * Projects the first `count` surfels of a batch: each one's outcome and, where it is
   * Minified, what Fill needs. The decisions are those of the exact setup
   * (vtkSurfaceSplatRasterizer), in single precision.
   */
  void Project(Batch& batch, int count) const
  {
    // The frame's matrices as local scalars, which the batch's arrays cannot alias.
    const glm::mat3 R = this->AxisToEye;
    const glm::mat3 N = this->NormalToEye;
    const glm::mat3 C = this->ClipRows;
    const glm::vec3 t = this->ClipTranslation;
    const glm::vec2 half = this->HalfSize;
    const float nearDepth = this->NearDepth, farDepth = this->FarDepth;
    const float depthReach = this->DepthReach, maximumVariance = this->MaximumVariance;
    const float depthThreshold = this->DepthThreshold;
    const float perspective = this->Perspective ? 1.0f : 0.0f;
    const bool cullBackFaces = this->CullBackFaces;
    const float edgeOn = static_cast<float>(EdgeOnForeshortening);
    const float vr = static_cast<float>(SurfelBasisVariance);
    for (int j = 0; j < count; ++j)
    {
      const float px = batch.PX[j], py = batch.PY[j], pz = batch.PZ[j];
      // The axes in eye space.
      const float a0x = R[0][0] * batch.A0X[j] + R[1][0] * batch.A0Y[j] + R[2][0] * batch.A0Z[j];
      const float a0y = R[0][1] * batch.A0X[j] + R[1][1] * batch.A0Y[j] + R[2][1] * batch.A0Z[j];
      const float a0z = R[0][2] * batch.A0X[j] + R[1][2] * batch.A0Y[j] + R[2][2] * batch.A0Z[j];
      const float a1x = R[0][0] * batch.A1X[j] + R[1][0] * batch.A1Y[j] + R[2][0] * batch.A1Z[j];
      const float a1y = R[0][1] * batch.A1X[j] + R[1][1] * batch.A1Y[j] + R[2][1] * batch.A1Z[j];
      const float a1z = R[0][2] * batch.A1X[j] + R[1][2] * batch.A1Y[j] + R[2][2] * batch.A1Z[j];
      // Culled when the whole splat lies outside the depth range, or its center is behind.
      const float depthExtent = depthReach * (std::abs(a0z) + std::abs(a1z));
      const float cw = C[0][2] * px + C[1][2] * py + C[2][2] * pz + t.z;
      const bool inRange =
        (-pz + depthExtent >= nearDepth) & (-pz - depthExtent <= farDepth) & (cw > 0.0f);
      // The center in pixels; J: d(pixel) along each axis, d(c.xy / c.w) = (d.xy - ndc d.w) /
      // c.w, then the viewport.
      const float inverseW = 1.0f / (cw > 0.0f ? cw : 1.0f);
      const float ndcX = (C[0][0] * px + C[1][0] * py + C[2][0] * pz + t.x) * inverseW;
      const float ndcY = (C[0][1] * px + C[1][1] * py + C[2][1] * pz + t.y) * inverseW;
      const float sx = inverseW * half.x, sy = inverseW * half.y;
      const float j0x =
        (C[0][0] * a0x + C[1][0] * a0y + C[2][0] * a0z - ndcX * (C[0][2] * a0x + C[1][2] * a0y +
          C[2][2] * a0z)) * sx;
      const float j0y =
        (C[0][1] * a0x + C[1][1] * a0y + C[2][1] * a0z - ndcY * (C[0][2] * a0x + C[1][2] * a0y +
          C[2][2] * a0z)) * sy;
      const float j1x =
        (C[0][0] * a1x + C[1][0] * a1y + C[2][0] * a1z - ndcX * (C[0][2] * a1x + C[1][2] * a1y +
          C[2][2] * a1z)) * sx;
      const float j1y =
        (C[0][1] * a1x + C[1][1] * a1y + C[2][1] * a1z - ndcY * (C[0][2] * a1x + C[1][2] * a1y +
          C[2][2] * a1z)) * sy;
      // The normal in eye space, facing the viewer or not.
      const float nx = N[0][0] * batch.NX[j] + N[1][0] * batch.NY[j] + N[2][0] * batch.NZ[j];
      const float ny = N[0][1] * batch.NX[j] + N[1][1] * batch.NY[j] + N[2][1] * batch.NZ[j];
      const float nz = N[0][2] * batch.NX[j] + N[1][2] * batch.NY[j] + N[2][2] * batch.NZ[j];
      const float facing =
        perspective * (nx * px + ny * py + nz * pz) - (1.0f - perspective) * nz;
      // Foreshortening(J) = 2 |J| / (|j0|^2 + |j1|^2), and J Vr J^T's largest eigenvalue.
      const float det = j0x * j1y - j1x * j0y;
      const float squaredAxes = j0x * j0x + j0y * j0y + j1x * j1x + j1y * j1y;
      const bool edge = !((squaredAxes > 0.0f) & (2.0f * std::abs(det) >= edgeOn * squaredAxes));
      const float xx = vr * (j0x * j0x + j1x * j1x);
      const float yy = vr * (j0y * j0y + j1y * j1y);
      const float xy = vr * (j0x * j0y + j1x * j1y);
      const float halfDifference = 0.5f * (xx - yy);
      const bool minified = 0.5f * (xx + yy) +
          std::sqrt(halfDifference * halfDifference + xy * xy) <=
        maximumVariance;
      // Selected one condition at a time, which vectorizes (a chain of conditions does not).
      int outcome = minified ? Minified : Magnified;
      outcome = edge ? EdgeOn : outcome;
      outcome = (facing > 0.0f) & cullBackFaces ? FacingAway : outcome;
      batch.Outcome[j] = inRange ? outcome : Culled;
      batch.CenterX[j] = (ndcX + 1.0f) * half.x;
      batch.CenterY[j] = (ndcY + 1.0f) * half.y;
      // Along the axes the eye depth changes by -(a0.z, a1.z) per axis unit, and the pixel
      // position by J.
      const float inverseDet = 1.0f / (det != 0.0f ? det : 1.0f);
      batch.SlopeX[j] = (a1z * j0y - a0z * j1y) * inverseDet;
      batch.SlopeY[j] = (a0z * j1x - a1z * j0x) * inverseDet;
      batch.Threshold[j] = depthThreshold *
        std::sqrt(std::max(a0x * a0x + a0y * a0y + a0z * a0z, a1x * a1x + a1y * a1y + a1z * a1z));
      batch.Mass[j] = batch.MassScale[j] * std::abs(det);
      batch.WarpedXX[j] = xx;
      batch.WarpedXY[j] = xy;
      batch.WarpedYY[j] = yy;
      // Normalized, not turned: two-sided lighting turns the filtered normal (AddNormal).
      const float scale = 1.0f / std::sqrt(nx * nx + ny * ny + nz * nz);
      batch.NX[j] = scale * nx;
      batch.NY[j] = scale * ny;
      batch.NZ[j] = scale * nz;
    }
  }

  /// The kernels of a projected batch's minified surfels, for frames that draw each of them
  /// (under a screen low-pass below the paper's) instead of summing them per pixel.
  struct Kernels
  {
    float ConicXX[BatchSize], ConicXY[BatchSize], ConicYY[BatchSize]; // 1/2 M^-1
    float Amplitude[BatchSize];
    float ReachX[BatchSize], ReachY[BatchSize]; // half sizes of the cutoff ellipse's box
    // The tangent plane's eye depth at pixel (x, y): N.(x, y, 1) / D.(x, y, 1) (PlaneDepth).
    float Numerator[3][BatchSize], Denominator[3][BatchSize];
  };

  /**
   * The EWA kernels (MakeResamplingKernel) of the first `count` surfels of a projected batch
   * under a screen low-pass of variance `lowPass` (at least UnfilteredMinimumVariance), cut off
   * at `cutoff`, their mass scaled by `massScale`; their depth planes from the frame's pixel
   * rays (MakePlaneDepth). Meaningful where the outcome is Minified.
   */
  void ProjectKernels(const Batch& batch, int count, float lowPass, float cutoff,
    float massScale, const glm::mat3& rayOrigin, const glm::mat3& rayDirection,
    Kernels& out) const
  {
    const float amplitudeScale = massScale * static_cast<float>(InverseTwoPi);
    const float perspective = this->Perspective ? 1.0f : 0.0f;
    for (int j = 0; j < count; ++j)
    {
      const float xx = batch.WarpedXX[j] + lowPass;
      const float yy = batch.WarpedYY[j] + lowPass;
      const float xy = batch.WarpedXY[j];
      const float det = xx * yy - xy * xy;
      const float inverseDet = 1.0f / (det > 0.0f ? det : 1.0f);
      out.ConicXX[j] = 0.5f * yy * inverseDet;
      out.ConicXY[j] = -xy * inverseDet;
      out.ConicYY[j] = 0.5f * xx * inverseDet;
      out.Amplitude[j] =
        det > 0.0f ? amplitudeScale * batch.Mass[j] * std::sqrt(inverseDet) : 0.0f;
      out.ReachX[j] = std::sqrt(2.0f * cutoff * xx);
      out.ReachY[j] = std::sqrt(2.0f * cutoff * yy);
      // MakePlaneDepth; a plane seen edge-on takes the center's depth.
      const float px = batch.PX[j], py = batch.PY[j], pz = batch.PZ[j];
      const float nx = batch.NX[j], ny = batch.NY[j], nz = batch.NZ[j];
      float origin[3], direction[3];
      for (int c = 0; c < 3; ++c)
      {
        origin[c] = nx * rayOrigin[c][0] + ny * rayOrigin[c][1] + nz * rayOrigin[c][2];
        direction[c] =
          nx * rayDirection[c][0] + ny * rayDirection[c][1] + nz * rayDirection[c][2];
      }
      // n . (p / -p.z) with perspective, n . (0, 0, -1) without: against the ray's length.
      const float inverseDepth = 1.0f / (pz != 0.0f ? -pz : 1.0f);
      const float rayX = perspective * px * inverseDepth, rayY = perspective * py * inverseDepth;
      const float facing = rayX * nx + rayY * ny - nz;
      const bool plane = facing * facing > 1e-12f * (rayX * rayX + rayY * rayY + 1.0f);
      out.Numerator[0][j] = plane ? -origin[0] : 0.0f;
      out.Numerator[1][j] = plane ? -origin[1] : 0.0f;
      out.Numerator[2][j] = plane ? nx * px + ny * py + nz * pz - origin[2] : -pz;
      out.Denominator[0][j] = plane ? direction[0] : 0.0f;
      out.Denominator[1][j] = plane ? direction[1] : 0.0f;
      out.Denominator[2][j] = plane ? direction[2] : 1.0f;
    }
  }

  /**
   * What the pixel holding the center of minified surfel j of a projected batch sums of it,
   * but for its color and alpha; false when its center is outside the depth range or off the
   * viewport padded by Reach cells (it is drawn whole, or not).
   */
  bool Fill(const Batch& batch, int j, MinifiedSurfel& out) const
  {
    // Compared before they are floored (the bounds are whole numbers), which keeps the
    // conversions in range.
    const float depth = -batch.PZ[j];
    if (!(depth >= this->NearDepth && depth <= this->FarDepth &&
          batch.CenterX[j] >= this->Low && batch.CenterX[j] < this->High.x &&
          batch.CenterY[j] >= this->Low && batch.CenterY[j] < this->High.y))
    {
      return false;
    }
    const float cellX = static_cast<float>(FloorToInt(batch.CenterX[j]));
    const float cellY = static_cast<float>(FloorToInt(batch.CenterY[j]));
    out.CenterX = batch.CenterX[j];
    out.CenterY = batch.CenterY[j];
    out.Depth = depth + batch.SlopeX[j] * (cellX + 0.5f - out.CenterX) +
      batch.SlopeY[j] * (cellY + 0.5f - out.CenterY);
    out.DepthSlope[0] = batch.SlopeX[j];
    out.DepthSlope[1] = batch.SlopeY[j];
    out.Threshold = batch.Threshold[j];
    out.Mass = batch.Mass[j];
    out.Spread = 0.5f * (batch.WarpedXX[j] + batch.WarpedYY[j]);
    out.Normal[0] = batch.NX[j];
    out.Normal[1] = batch.NY[j];
    out.Normal[2] = batch.NZ[j];
    return true;
  }

private:
  glm::dmat3 PositionToEye;
  glm::dvec3 EyeTranslation;
  glm::mat3 AxisToEye;
  glm::mat3 NormalToEye;
  glm::mat3 ClipRows;
  glm::vec3 ClipTranslation;
  glm::vec2 HalfSize;
  float Low;
  glm::vec2 High;
  float NearDepth, FarDepth, DepthReach, MaximumVariance, DepthThreshold;
  bool Perspective, CullBackFaces;
};

} // namespace splat

#endif
