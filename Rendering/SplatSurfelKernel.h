// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatSurfelKernel.h
 * @brief Screen-space EWA resampling kernel of one surfel (Zwicker et al. 2001, eq. 6-9).
 *
 * VTK-free (GLM only) so that the CPU rasterizer, the filters, the tests and the GLSL of the
 * OpenGL backend share one formulation.
 *
 * Conventions
 * - A surfel is a point p with two tangent axes a0, a1 (orthogonal to its normal). The lengths of
 *   the axes are the surfel's semi-axes; a circular surfel of radius R has |a0| = |a1| = R.
 * - The local parameterization is u = (u0, u1) in axis units: the surface point is p + u0 a0 + u1 a1.
 * - The basis function is the Gaussian r(u) = G_Vr(u) with Vr = 1/2 I in axis units, i.e. an
 *   object-space standard deviation sigma = R / sqrt(2) (variance R^2 / 2). With the default cutoff
 *   c = 1 the truncated support 1/2 u^T Vr^-1 u < c is exactly the disk |u| < 1: the radius is the
 *   visible extent of the splat before the screen low-pass filter. Surfels on a regular grid of
 *   spacing h with R = h have unit spacing in axis units, and unit-spaced Gaussians of variance 1/2
 *   sum to 1 within 1e-4 (the partition of unity of paper 000, section 7).
 * - Screen coordinates are pixels of the viewport, origin at its lower-left corner; pixel (i, j)
 *   has its center at (i + 0.5, j + 0.5).
 * - The resampling kernel is rho(x) = |J| G_M(x - m), M = J Vr J^T + v I (eq. 6), where J is the
 *   Jacobian of the projective map from axis units to pixels at u = 0 and m the projected center.
 *   It is evaluated while the exponent beta(x) = 1/2 (x - m)^T M^-1 (x - m) is below the cutoff c.
 *   v is the variance of the screen low-pass filter: the paper's 1 for splats below a pixel, and
 *   for magnified ones a smaller variance where their colors allow (LowPassVariance).
 */
#ifndef SplatSurfelKernel_h
#define SplatSurfelKernel_h

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace splat
{

/// Variance of the object-space basis function in axis units (see the file comment).
constexpr double SurfelBasisVariance = 0.5;

/// Gaussian normalization 1/(2 pi).
constexpr double InverseTwoPi = 0.15915494309189533577;

/**
 * The projective map of a surfel's tangent plane to pixels, linearized at its center.
 */
struct SurfelProjection
{
  glm::dvec2 Center{ 0.0 };   ///< m(u_k): the projected center in pixels
  glm::dmat2 Jacobian{ 1.0 }; ///< J: columns are d(pixel)/d(u0) and d(pixel)/d(u1)
};

/**
 * A point projected through a to-clip matrix and the viewport mapping, with what the
 * derivatives of its pixel position need.
 */
struct PointProjection
{
  glm::dvec2 Center{ 0.0 }; ///< pixels
  glm::dvec2 Ndc{ 0.0 };
  double InverseW = 1.0;
  glm::dvec2 HalfSize{ 0.0 };

  /// d(pixel) along a direction whose clip-space image is d: d(c.xy / c.w) = (d.xy - ndc d.w)
  /// / c.w, then the viewport scale.
  glm::dvec2 PixelDerivative(const glm::dvec4& d) const
  {
    return (glm::dvec2(d) - this->Ndc * d.w) * this->InverseW * this->HalfSize;
  }
};

/**
 * The projection of a point whose clip coordinates are (clipXY, ., clipW). Returns false when
 * it is not strictly in front of the eye (clip w <= 0), where the linearization does not exist.
 */
inline bool ProjectClip(const glm::dvec2& clipXY, double clipW, const glm::dvec2& viewportSize,
  PointProjection& out)
{
  if (!(clipW > 0.0))
  {
    return false;
  }
  out.InverseW = 1.0 / clipW;
  out.Ndc = clipXY * out.InverseW;
  out.HalfSize = 0.5 * viewportSize;
  out.Center = (out.Ndc + 1.0) * out.HalfSize;
  return true;
}

/// Projects p through toClip and the viewport mapping; false where ProjectClip says so.
inline bool ProjectPoint(const glm::dmat4& toClip, const glm::dvec2& viewportSize,
  const glm::dvec3& p, PointProjection& out)
{
  const glm::dvec4 c = toClip * glm::dvec4(p, 1.0);
  return ProjectClip(glm::dvec2(c), c.w, viewportSize, out);
}

/**
 * Projects the surfel (p, a0, a1) through the model-to-clip matrix and the viewport mapping.
 * Returns false when the center is not strictly in front of the eye (clip w <= 0), where the
 * linearization does not exist.
 */
inline bool ProjectSurfel(const glm::dmat4& modelToClip, const glm::dvec2& viewportSize,
  const glm::dvec3& p, const glm::dvec3& a0, const glm::dvec3& a1, SurfelProjection& out)
{
  // Only clip x, y and w matter, and directions have no translation: the rows x, y, w of the
  // matrix's 3x3 part (this runs once per splat per frame).
  const glm::dmat3 linear(modelToClip[0][0], modelToClip[0][1], modelToClip[0][3],
    modelToClip[1][0], modelToClip[1][1], modelToClip[1][3], modelToClip[2][0],
    modelToClip[2][1], modelToClip[2][3]);
  const glm::dvec3 c =
    linear * p + glm::dvec3(modelToClip[3][0], modelToClip[3][1], modelToClip[3][3]);
  PointProjection center;
  if (!ProjectClip(glm::dvec2(c), c.z, viewportSize, center))
  {
    return false;
  }
  out.Center = center.Center;
  const glm::dvec3 d0 = linear * a0;
  const glm::dvec3 d1 = linear * a1;
  out.Jacobian[0] = center.PixelDerivative(glm::dvec4(d0.x, d0.y, 0.0, d0.z));
  out.Jacobian[1] = center.PixelDerivative(glm::dvec4(d1.x, d1.y, 0.0, d1.z));
  return true;
}

/**
 * The screen-space resampling kernel rho(x) = Amplitude * exp(-beta(x)),
 * beta(x) = 1/2 (x - m)^T Conic (x - m), kept where beta(x) < Cutoff.
 */
struct ResamplingKernel
{
  glm::dvec2 Center{ 0.0 };
  glm::dmat2 Covariance{ 1.0 }; ///< M = J Vr J^T + v I
  glm::dmat2 Conic{ 1.0 };      ///< M^-1
  double Amplitude = 0.0;       ///< |J| / (2 pi sqrt|M|)
  double Cutoff = 1.0;
  glm::dvec2 HalfExtent{ 0.0 }; ///< half sizes of the tight bounding box of the cutoff ellipse

  /// The exponent beta at pixel position x.
  double Exponent(const glm::dvec2& x) const
  {
    const glm::dvec2 d = x - this->Center;
    return 0.5 * glm::dot(d, this->Conic * d);
  }

  /// rho(x), zero outside the cutoff.
  double Weight(const glm::dvec2& x) const
  {
    const double beta = this->Exponent(x);
    return beta < this->Cutoff ? this->Amplitude * std::exp(-beta) : 0.0;
  }
};

/// The paper's full-coverage weight tau for c = 1 (paper 000, section 7).
constexpr double PaperCoverageThreshold = 0.4;

/**
 * The full-coverage weight tau for splats under a pixel's box filter, where their surfels
 * cover their surface at it. A silhouette's summed weight then falls from the surface's to none
 * within about a pixel, and a pixel counts as fully covered once it has tau of it: the paper's
 * 0.4 draws pixels half covered as covered, widening silhouettes by part of a pixel.
 */
constexpr double BoxFilterCoverageThreshold = 0.8;

/**
 * The summed kernel weight above which a pixel counts as fully covered at a cutoff: tau is the
 * paper's threshold for c = 1; other cutoffs keep a different share 1 - e^-c of each kernel's
 * unit mass, and the threshold follows it.
 */
inline double FullCoverageWeight(double tau, double cutoff)
{
  return tau * (1.0 - std::exp(-cutoff)) / (1.0 - std::exp(-1.0));
}

/**
 * The screen-space filter of a kernel, as compared in paper 000, figure 8.
 */
enum class KernelFilter
{
  EWA,       ///< M = J Vr J^T + v I: the warped basis function band-limited by the screen low-pass
  Circular,  ///< a circle whose radius is the major axis of the EWA ellipse (Levoy, Shade)
  Unfiltered ///< M = J Vr J^T: elliptical splats without band-limiting; aliases when minified
};

/// Variance added to unfiltered kernels, in pixels^2, so that an edge-on surfel's M stays
/// invertible; far below a pixel, it does not band-limit.
constexpr double UnfilteredMinimumVariance = 1e-6;

/// Foreshortening below which a surfel is edge-on and left out: next to a face-on neighbor at
/// the same distance it weighs less than a thousandth (weights scale with |J|).
constexpr double EdgeOnForeshortening = 1e-3;

/**
 * How much the projection foreshortens a surfel: |J| relative to the mean squared length of its
 * projected axes, 1 for a face-on circle, 0 edge-on. Independent of distance and of the
 * surfel's size, unlike |J| itself, which also shrinks with the square of the distance.
 */
inline double Foreshortening(const SurfelProjection& projection)
{
  const glm::dmat2& J = projection.Jacobian;
  const double squaredAxes = glm::dot(J[0], J[0]) + glm::dot(J[1], J[1]);
  return squaredAxes > 0.0 ? 2.0 * std::abs(glm::determinant(J)) / squaredAxes : 0.0;
}

/// The largest eigenvalue of a symmetric 2x2 matrix.
inline double LargestEigenvalue(const glm::dmat2& m)
{
  const double mean = 0.5 * (m[0][0] + m[1][1]);
  const double half = 0.5 * (m[0][0] - m[1][1]);
  return mean + std::sqrt(half * half + m[0][1] * m[0][1]);
}

/// J Vr J^T: the object-space basis function warped to pixels, in pixels^2.
inline glm::dmat2 WarpedBasisVariance(const SurfelProjection& projection)
{
  const glm::dmat2& J = projection.Jacobian;
  return SurfelBasisVariance * (J * glm::transpose(J));
}

/// A pixel's box filter's variance, 1/12 pixels^2: the least screen low-pass a splat gets.
constexpr double BoxFilterVariance = 1.0 / 12.0;

/// Largest warped variance (pixels^2) up to which a splat gets the unit low-pass, and from which
/// on the magnified one (LowPassVariance).
constexpr double LowPassFadeStart = 0.75;
constexpr double LowPassFadeEnd = 1.5;

/**
 * The variance of the screen low-pass filter for a splat whose warped basis function has the
 * largest variance `largestWarped`: `minified` while that is at most LowPassFadeStart (a
 * splat below a pixel), `magnified` once it reaches LowPassFadeEnd, linear between. A
 * magnified splat's own reconstruction is wider than the pixel and band-limits it already; the
 * unit low-pass then only blurs what it draws.
 * Colors that vary from splat to splat (a texture) need the paper's filter, 1 for both (the CPU
 * rasterizer sums minified splats per pixel under it). Splats of one color have no colors to
 * alias: a pixel's own footprint, BoxFilterVariance, for both keeps their silhouettes
 * antialiased without spreading them.
 */
inline double LowPassVariance(double largestWarped, double minified, double magnified)
{
  const double t = std::clamp(
    (largestWarped - LowPassFadeStart) / (LowPassFadeEnd - LowPassFadeStart), 0.0, 1.0);
  return minified + (magnified - minified) * t;
}

/// Largest warped variance (pixels^2) up to which a splat gets at least the antialiasing cutoff
/// (SplatCutoff), and from which on the frame's cutoff alone.
constexpr double CutoffFadeStart = 8.0;
constexpr double CutoffFadeEnd = 32.0;

/**
 * The cutoff of a splat whose warped basis function has the largest variance `largestWarped`:
 * the frame's `cutoff`, raised to `antialiasingCutoff` while the screen low-pass is a sizable
 * part of the kernel (largest warped variance up to CutoffFadeStart, where the unit low-pass
 * is a ninth of it or more), linear to CutoffFadeEnd. A tight cutoff truncates the low-pass's
 * tail, which then no longer keeps colors that change from splat to splat from aliasing;
 * where the splat's own reconstruction dominates, a tight cutoff only sharpens what it
 * interpolates.
 */
inline double SplatCutoff(double largestWarped, double cutoff, double antialiasingCutoff)
{
  const double t = std::clamp(
    (largestWarped - CutoffFadeStart) / (CutoffFadeEnd - CutoffFadeStart), 0.0, 1.0);
  return cutoff + std::max(antialiasingCutoff - cutoff, 0.0) * (1.0 - t);
}

/**
 * The factor that gives a kernel truncated at `splatCutoff` the mass, 1 - e^-c, of one
 * truncated at the frame's `cutoff`, so that the frame's full-coverage weight
 * (FullCoverageWeight) holds for both.
 */
inline double TruncatedMassScale(double cutoff, double splatCutoff)
{
  return (1.0 - std::exp(-cutoff)) / (1.0 - std::exp(-splatCutoff));
}

/**
 * Builds the kernel of eq. (6) from a projection. With the EWA filter the low-pass term
 * (LowPassVariance: `magnifiedLowPass` at least BoxFilterVariance, `minifiedLowPass` at least
 * UnfilteredMinimumVariance) keeps M invertible even for an edge-on surfel whose J is
 * singular; its amplitude |J| then goes to zero. Its cutoff c is SplatCutoff's (`cutoff` but
 * where `antialiasingCutoff` raises it), its amplitude scaled to the mass it would keep at
 * `cutoff` (TruncatedMassScale). The bounding box of the ellipse
 * 1/2 x^T M^-1 x = c has half sizes sqrt(2 c M_xx), sqrt(2 c M_yy), with no
 * eigen-decomposition.
 */
inline ResamplingKernel MakeResamplingKernel(const SurfelProjection& projection, double cutoff,
  KernelFilter filter = KernelFilter::EWA, double magnifiedLowPass = 1.0,
  double antialiasingCutoff = 0.0, double minifiedLowPass = 1.0)
{
  ResamplingKernel k;
  const glm::dmat2& J = projection.Jacobian;
  k.Center = projection.Center;
  k.Cutoff = cutoff;
  double massScale = 1.0;
  const glm::dmat2 warped = WarpedBasisVariance(projection);
  switch (filter)
  {
    case KernelFilter::EWA:
    {
      const double largestWarped = LargestEigenvalue(warped);
      k.Covariance = warped +
        glm::dmat2(LowPassVariance(largestWarped,
          std::max(minifiedLowPass, UnfilteredMinimumVariance),
          std::max(magnifiedLowPass, BoxFilterVariance)));
      k.Cutoff = SplatCutoff(largestWarped, cutoff, antialiasingCutoff);
      if (k.Cutoff > cutoff)
      {
        massScale = TruncatedMassScale(cutoff, k.Cutoff);
      }
      break;
    }
    case KernelFilter::Circular:
    {
      // The larger eigenvalue of the EWA covariance: the squared major semi-axis.
      k.Covariance = glm::dmat2(LargestEigenvalue(warped + glm::dmat2(1.0)));
      break;
    }
    case KernelFilter::Unfiltered:
      k.Covariance = warped + glm::dmat2(UnfilteredMinimumVariance);
      break;
  }
  const double detM = glm::determinant(k.Covariance);
  k.Conic = glm::inverse(k.Covariance);
  k.Amplitude = massScale * std::abs(glm::determinant(J)) * InverseTwoPi / std::sqrt(detM);
  k.HalfExtent = glm::dvec2(std::sqrt(2.0 * k.Cutoff * k.Covariance[0][0]),
    std::sqrt(2.0 * k.Cutoff * k.Covariance[1][1]));
  return k;
}

/**
 * The pixels whose centers (i + 0.5, j + 0.5) lie in the box center +- halfExtent, clipped to
 * a width x height viewport, as inclusive bounds (x0, x1, y0, y1). Returns false when there
 * are none.
 */
inline bool CoveredPixels(const glm::dvec2& center, const glm::dvec2& halfExtent, int width,
  int height, glm::ivec4& box)
{
  const glm::dvec2 lo = center - halfExtent - 0.5;
  const glm::dvec2 hi = center + halfExtent - 0.5;
  if (!(hi.x >= 0.0 && hi.y >= 0.0 && lo.x <= width - 1 && lo.y <= height - 1))
  {
    return false;
  }
  box = glm::ivec4(static_cast<int>(std::ceil(std::max(lo.x, 0.0))),
    static_cast<int>(std::floor(std::min(hi.x, width - 1.0))),
    static_cast<int>(std::ceil(std::max(lo.y, 0.0))),
    static_cast<int>(std::floor(std::min(hi.y, height - 1.0))));
  return box.x <= box.y && box.z <= box.w;
}

/**
 * Depth of the surfel's tangent plane along each pixel's view ray, as the rational function
 * depth(x, y) = (N . (x, y, 1)) / (D . (x, y, 1)) of pixel coordinates, where depth is the eye-space
 * distance in front of the camera (-z_eye): linear in eye space, not the 1/z of the depth buffer
 * (An and Zhou). The plane is exact along every ray, not the affine approximation used for the
 * weights, so intersecting surfaces meet along their true intersection line.
 */
struct PlaneDepth
{
  glm::dvec3 Numerator{ 0.0 };
  glm::dvec3 Denominator{ 0.0, 0.0, 1.0 };

  double operator()(double x, double y) const
  {
    return glm::dot(this->Numerator, glm::dvec3(x, y, 1.0)) /
      glm::dot(this->Denominator, glm::dvec3(x, y, 1.0));
  }
};

/// Whether the projection eyeToClip is parallel (w does not depend on the eye position).
inline bool IsParallelProjection(const glm::dmat4& eyeToClip)
{
  return eyeToClip[3][3] != 0.0;
}

/**
 * The view rays of a frame: pixel position (x, y) sees the eye-space points
 * Origin(x, y) + t Direction(x, y) at depth t (the distance in front of the camera along -z),
 * each an affine function of (x, y): A x + B y + C. Perspective projections have Origin = 0 and
 * Direction.z = -1; parallel projections a constant Direction (0, 0, -1) and Origin.z = 0.
 */
struct PixelRays
{
  glm::dmat3 Origin{ 0.0 };    ///< columns A, B, C
  glm::dmat3 Direction{ 0.0 }; ///< columns A, B, C
  bool Perspective = true;
};

/**
 * The pixel rays of the projection eyeToClip (OpenGL clip space, NDC z in [-1, 1]) over a
 * viewport of the given size.
 */
inline PixelRays MakePixelRays(const glm::dmat4& eyeToClip, const glm::dvec2& viewportSize)
{
  // The eye-space point of pixel (x, y) on the near plane, E(x, y) = clipToEye (x_ndc, y_ndc,
  // -1, 1) / w, is affine in (x, y): the projection's w does not depend on x_ndc, y_ndc.
  const glm::dmat4 clipToEye = glm::inverse(eyeToClip);
  const glm::dvec4 corner = clipToEye * glm::dvec4(-1.0, -1.0, -1.0, 1.0);
  const double w = corner.w;
  const glm::dvec3 a = glm::dvec3(clipToEye[0]) * (2.0 / viewportSize.x) / w;
  const glm::dvec3 b = glm::dvec3(clipToEye[1]) * (2.0 / viewportSize.y) / w;
  const glm::dvec3 c = glm::dvec3(corner) / w;
  PixelRays rays;
  rays.Perspective = !IsParallelProjection(eyeToClip);
  if (rays.Perspective)
  {
    // Perspective: rays from the eye through E, scaled to unit depth.
    const double depth = -c.z;
    rays.Direction = glm::dmat3(a / depth, b / depth, c / depth);
  }
  else
  {
    // Parallel: rays along -z from E moved to the eye's plane z = 0.
    rays.Origin = glm::dmat3(a, b, glm::dvec3(c.x, c.y, 0.0));
    rays.Direction = glm::dmat3(glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0, 0.0, -1.0));
  }
  return rays;
}

/**
 * Window-space depths in [0, 1] (e.g. the opaque scene read back from the framebuffer) as
 * linear eye depths, the distance in front of the camera; the far plane and beyond become
 * infinity.
 */
inline std::vector<float> EyeDepthsOfWindowDepths(
  const glm::dmat4& clipToEye, const std::vector<float>& windowDepths)
{
  std::vector<float> eyeDepths(windowDepths.size());
  std::transform(windowDepths.begin(), windowDepths.end(), eyeDepths.begin(),
    [&clipToEye](float window)
    {
      if (!(window < 1.0f))
      {
        return std::numeric_limits<float>::infinity();
      }
      const glm::dmat4& C = clipToEye;
      const double zNdc = 2.0 * window - 1.0;
      return static_cast<float>(-(C[2][2] * zNdc + C[3][2]) / (C[2][3] * zNdc + C[3][3]));
    });
  return eyeDepths;
}

/**
 * The depth of the tangent plane through eye-space point p with eye-space normal n along each
 * pixel's ray: t = (n.p - n.Origin(x, y)) / (n.Direction(x, y)). Returns false when the plane
 * contains the view ray through p (edge-on), where its depth is not a function of the pixel.
 */
inline bool MakePlaneDepth(
  const PixelRays& rays, const glm::dvec3& p, const glm::dvec3& n, PlaneDepth& out)
{
  const glm::dvec3 nOrigin = n * rays.Origin;       // (n.A, n.B, n.C) of the origins
  const glm::dvec3 nDirection = n * rays.Direction; // and of the directions
  out.Numerator = glm::dvec3(-nOrigin.x, -nOrigin.y, glm::dot(n, p) - nOrigin.z);
  out.Denominator = nDirection;
  // The denominator on p's own ray, relative to the ray's length.
  const glm::dvec3 direction = rays.Perspective ? p / -p.z : glm::dvec3(0.0, 0.0, -1.0);
  return std::abs(glm::dot(n, direction)) > 1e-9 * glm::length(direction);
}

/**
 * Two unit tangent vectors completing the unit normal n to a right-handed orthonormal frame.
 * Branch-free construction (Duff et al. 2017), stable for every n.
 */
inline void TangentFrame(const glm::dvec3& n, glm::dvec3& t0, glm::dvec3& t1)
{
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  t0 = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  t1 = glm::dvec3(b, sign + n.y * n.y * a, -n.y);
}

} // namespace splat

#endif
