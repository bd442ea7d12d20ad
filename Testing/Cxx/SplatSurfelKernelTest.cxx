// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the screen-space EWA kernel math (SplatSurfelKernel.h; paper 000, sections 3.3
// and 4): Jacobian, kernel, bounding box, filters and tangent-plane depth.
#include "SplatSurfelKernel.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace
{
const glm::dvec2 Viewport(640.0, 480.0);

glm::dmat4 Projection()
{
  return glm::perspective(glm::radians(30.0), Viewport.x / Viewport.y, 0.1, 100.0);
}

// The exact (non-linearized) map from axis units to pixels.
glm::dvec2 ProjectToPixel(const glm::dmat4& modelToClip, const glm::dvec3& x)
{
  const glm::dvec4 c = modelToClip * glm::dvec4(x, 1.0);
  return (glm::dvec2(c) / c.w + 1.0) * 0.5 * Viewport;
}

}

// J of eq. (4) against central differences of the real perspective projection.
TEST(SurfelKernel, JacobianMatchesFiniteDifferences)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const glm::dmat4 view =
    glm::lookAt(glm::dvec3(0.3, -0.4, 5.0), glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
  const glm::dmat4 modelToClip = Projection() * view;
  for (int trial = 0; trial < 100; ++trial)
  {
    const glm::dvec3 p(unit(random), unit(random), unit(random));
    const glm::dvec3 n = glm::normalize(glm::dvec3(unit(random), unit(random), unit(random)));
    glm::dvec3 t0, t1;
    splat::TangentFrame(n, t0, t1);
    const double radius = 0.05 * (1.5 + unit(random));
    const glm::dvec3 a0 = radius * t0, a1 = radius * t1;
    splat::SurfelProjection projection;
    ASSERT_TRUE(splat::ProjectSurfel(modelToClip, Viewport, p, a0, a1, projection));

    EXPECT_NEAR(glm::distance(projection.Center, ProjectToPixel(modelToClip, p)), 0.0, 1e-9);
    const double step = 1e-5;
    const glm::dvec2 d0 = (ProjectToPixel(modelToClip, p + step * a0) -
                            ProjectToPixel(modelToClip, p - step * a0)) / (2.0 * step);
    const glm::dvec2 d1 = (ProjectToPixel(modelToClip, p + step * a1) -
                            ProjectToPixel(modelToClip, p - step * a1)) / (2.0 * step);
    const double scale = std::max(glm::length(d0), glm::length(d1));
    EXPECT_NEAR(glm::distance(projection.Jacobian[0], d0) / scale, 0.0, 1e-6);
    EXPECT_NEAR(glm::distance(projection.Jacobian[1], d1) / scale, 0.0, 1e-6);
  }
}

// Points behind the eye have no linearization and are refused.
TEST(SurfelKernel, RefusesPointsBehindTheEye)
{
  const glm::dmat4 view =
    glm::lookAt(glm::dvec3(0.0, 0.0, 5.0), glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
  splat::SurfelProjection projection;
  EXPECT_FALSE(splat::ProjectSurfel(Projection() * view, Viewport, glm::dvec3(0.0, 0.0, 6.0),
    glm::dvec3(0.1, 0.0, 0.0), glm::dvec3(0.0, 0.1, 0.0), projection));
}

// The bounding box contains the cutoff ellipse 1/2 x^T M^-1 x = c and touches it on all sides.
TEST(SurfelKernel, BoundingBoxIsTightAroundTheCutoffEllipse)
{
  std::mt19937 random(11);
  std::uniform_real_distribution<double> entry(-20.0, 20.0);
  for (int trial = 0; trial < 200; ++trial)
  {
    splat::SurfelProjection projection;
    projection.Center = glm::dvec2(entry(random), entry(random));
    projection.Jacobian = glm::dmat2(entry(random), entry(random), entry(random), entry(random));
    if (trial % 10 == 0)
    {
      projection.Jacobian[1] = 0.5 * projection.Jacobian[0]; // edge-on: singular J
    }
    const double cutoff = 0.5 + 4.0 * trial / 200.0;
    const splat::ResamplingKernel kernel = splat::MakeResamplingKernel(projection, cutoff);
    ASSERT_TRUE(std::isfinite(kernel.Amplitude));

    // Boundary points m + L sqrt(2c) (cos t, sin t) with M = L L^T (Cholesky).
    const glm::dmat2& M = kernel.Covariance;
    const double l00 = std::sqrt(M[0][0]);
    const double l10 = M[0][1] / l00;
    const double l11 = std::sqrt(M[1][1] - l10 * l10);
    glm::dvec2 reach(0.0);
    for (int s = 0; s < 3600; ++s)
    {
      const double t = 2.0 * M_PI * s / 3600.0;
      const glm::dvec2 u = std::sqrt(2.0 * cutoff) * glm::dvec2(std::cos(t), std::sin(t));
      const glm::dvec2 x(l00 * u.x, l10 * u.x + l11 * u.y);
      EXPECT_NEAR(kernel.Exponent(kernel.Center + x), cutoff, 1e-9 * cutoff);
      EXPECT_LE(std::abs(x.x), kernel.HalfExtent.x * (1.0 + 1e-12));
      EXPECT_LE(std::abs(x.y), kernel.HalfExtent.y * (1.0 + 1e-12));
      reach = glm::max(reach, glm::abs(x));
    }
    // Tight: the sampled ellipse reaches the box edges within the angular sampling error.
    EXPECT_GT(reach.x, kernel.HalfExtent.x * (1.0 - 1e-5));
    EXPECT_GT(reach.y, kernel.HalfExtent.y * (1.0 - 1e-5));
  }
}

// The tangent plane's depth along each pixel's ray is exact: a tilted plane's depth at every
// covered pixel equals the ray/plane intersection, not the affine approximation.
TEST(SurfelKernel, PlaneDepthIsTheRayIntersection)
{
  const glm::dmat4 projections[2] = { Projection(),
    glm::ortho(-2.0, 2.0, -1.5, 1.5, 0.5, 20.0) };
  const glm::dvec3 p(0.1, -0.2, -3.3); // eye space
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.6, 0.2, 0.7));
  for (const glm::dmat4& projection : projections)
  {
    const splat::PixelRays rays = splat::MakePixelRays(projection, Viewport);
    splat::PlaneDepth depth;
    ASSERT_TRUE(splat::MakePlaneDepth(rays, p, n, depth));
    const glm::dmat4 clipToEye = glm::inverse(projection);
    for (double x = 100.5; x < 600.0; x += 50.0)
    {
      for (double y = 50.5; y < 450.0; y += 50.0)
      {
        // The pixel's ray through its near and far points, unprojected.
        const glm::dvec2 ndc(2.0 * x / Viewport.x - 1.0, 2.0 * y / Viewport.y - 1.0);
        const glm::dvec4 nearPoint = clipToEye * glm::dvec4(ndc, -1.0, 1.0);
        const glm::dvec4 farPoint = clipToEye * glm::dvec4(ndc, 1.0, 1.0);
        const glm::dvec3 a = glm::dvec3(nearPoint) / nearPoint.w;
        const glm::dvec3 b = glm::dvec3(farPoint) / farPoint.w;
        const double t = glm::dot(n, p - a) / glm::dot(n, b - a);
        const double expected = -(a + t * (b - a)).z;
        EXPECT_NEAR(depth(x, y), expected, 1e-9 * expected);
      }
    }
  }
}

// The figure-8 baselines: circular kernels are the circle of the EWA ellipse's major axis;
// unfiltered kernels drop the low-pass and shrink below a pixel when minified.
TEST(SurfelKernel, CircularAndUnfilteredFilters)
{
  splat::SurfelProjection projection;
  projection.Jacobian = glm::dmat2(6.0, 1.0, 0.5, 0.3); // magnified along one axis only
  const splat::ResamplingKernel ewa = splat::MakeResamplingKernel(projection, 1.0);
  const splat::ResamplingKernel circle =
    splat::MakeResamplingKernel(projection, 1.0, splat::KernelFilter::Circular);
  const double trace = ewa.Covariance[0][0] + ewa.Covariance[1][1];
  const double major = 0.5 * trace +
    std::sqrt(0.25 * trace * trace - glm::determinant(ewa.Covariance));
  EXPECT_NEAR(circle.Covariance[0][0], major, 1e-12 * major);
  EXPECT_NEAR(circle.Covariance[1][1], major, 1e-12 * major);
  EXPECT_EQ(circle.Covariance[0][1], 0.0);
  EXPECT_DOUBLE_EQ(circle.HalfExtent.x, circle.HalfExtent.y);

  projection.Jacobian = glm::dmat2(0.1, 0.0, 0.0, 0.1); // minified: 0.1 pixel per axis unit
  const splat::ResamplingKernel unfiltered =
    splat::MakeResamplingKernel(projection, 1.0, splat::KernelFilter::Unfiltered);
  const splat::ResamplingKernel filtered = splat::MakeResamplingKernel(projection, 1.0);
  EXPECT_LT(unfiltered.HalfExtent.x, 0.2);
  EXPECT_GT(filtered.HalfExtent.x, 1.4); // the low-pass keeps at least a pixel
  // Edge-on: finite whatever the filter, and recognized as edge-on.
  projection.Jacobian = glm::dmat2(3.0, 0.0, 6.0, 0.0);
  EXPECT_EQ(splat::Foreshortening(projection), 0.0);
  for (splat::KernelFilter filter : { splat::KernelFilter::EWA, splat::KernelFilter::Circular,
         splat::KernelFilter::Unfiltered })
  {
    const splat::ResamplingKernel k = splat::MakeResamplingKernel(projection, 1.0, filter);
    EXPECT_TRUE(std::isfinite(k.Amplitude) && std::isfinite(k.HalfExtent.x) &&
      std::isfinite(k.Conic[0][0]));
    EXPECT_EQ(k.Amplitude, 0.0);
  }
}

// The EWA low-pass: the paper's unit variance for splats below a pixel, the magnified variance
// once the splat is wider than LowPassFadeEnd, linear between; an edge-on splat's M stays
// invertible at the smallest low-pass.
TEST(SurfelKernel, LowPassFadesForMagnifiedSplats)
{
  const double small = splat::BoxFilterVariance;
  splat::SurfelProjection projection;
  // Warped variances 1/2 J J^T: 0.5 (below the fade), 8 (magnified), and 1.125 (halfway).
  for (const auto& [scale, lowPass] : { std::pair<double, double>{ 1.0, 1.0 },
         { 4.0, small }, { 1.5, 0.5 * (1.0 + small) } })
  {
    projection.Jacobian = glm::dmat2(scale, 0.0, 0.0, scale);
    const splat::ResamplingKernel k =
      splat::MakeResamplingKernel(projection, 1.0, splat::KernelFilter::EWA, small);
    EXPECT_NEAR(k.Covariance[0][0], 0.5 * scale * scale + lowPass, 1e-12) << scale;
    EXPECT_EQ(k.Covariance[0][1], 0.0);
    // The paper's filter whatever the size at magnified variance 1.
    EXPECT_NEAR(splat::MakeResamplingKernel(projection, 1.0).Covariance[1][1],
      0.5 * scale * scale + 1.0, 1e-12);
  }
  // Anisotropic: the largest warped variance decides (magnified along one axis only).
  projection.Jacobian = glm::dmat2(4.0, 0.0, 0.0, 0.1);
  const splat::ResamplingKernel grazing =
    splat::MakeResamplingKernel(projection, 1.0, splat::KernelFilter::EWA, small);
  EXPECT_NEAR(grazing.Covariance[1][1], 0.005 + small, 1e-12);
  projection.Jacobian = glm::dmat2(3.0, 0.0, 6.0, 0.0); // edge-on
  const splat::ResamplingKernel edgeOn =
    splat::MakeResamplingKernel(projection, 1.0, splat::KernelFilter::EWA, small);
  EXPECT_GT(glm::determinant(edgeOn.Covariance), 0.0);
  EXPECT_TRUE(std::isfinite(edgeOn.Conic[0][0]) && std::isfinite(edgeOn.HalfExtent.y));
}

// The antialiasing cutoff raises small splats' cutoff only (never lowers it), fades out
// between CutoffFadeStart and CutoffFadeEnd, and the amplitude keeps the frame cutoff's mass:
// weight times the share 1 - e^-c kept inside the kernel's own cutoff is the same.
TEST(SurfelKernel, AntialiasingCutoffRaisesSmallSplats)
{
  const double middle = 0.5 * (splat::CutoffFadeStart + splat::CutoffFadeEnd);
  EXPECT_EQ(splat::SplatCutoff(0.0, 0.6, 1.0), 1.0);
  EXPECT_EQ(splat::SplatCutoff(splat::CutoffFadeStart, 0.6, 1.0), 1.0);
  EXPECT_NEAR(splat::SplatCutoff(middle, 0.6, 1.0), 0.8, 1e-12);
  EXPECT_EQ(splat::SplatCutoff(splat::CutoffFadeEnd, 0.6, 1.0), 0.6);
  EXPECT_EQ(splat::SplatCutoff(0.0, 2.0, 1.0), 2.0);
  EXPECT_EQ(splat::SplatCutoff(0.0, 0.6, 0.0), 0.6);

  splat::SurfelProjection projection;
  // Warped variances 1/2 J J^T: 0.5, halfway through the fade, and far beyond it.
  for (const auto& [scale, c] : { std::pair<double, double>{ 1.0, 1.0 },
         { std::sqrt(2.0 * middle), 0.8 }, { 100.0, 0.6 } })
  {
    projection.Jacobian = glm::dmat2(scale, 0.0, 0.0, scale);
    const splat::ResamplingKernel plain = splat::MakeResamplingKernel(projection, 0.6);
    const splat::ResamplingKernel raised =
      splat::MakeResamplingKernel(projection, 0.6, splat::KernelFilter::EWA, 1.0, 1.0);
    EXPECT_NEAR(raised.Cutoff, c, 1e-12) << scale;
    EXPECT_NEAR(raised.Amplitude * (1.0 - std::exp(-raised.Cutoff)),
      plain.Amplitude * (1.0 - std::exp(-0.6)), 1e-12 * plain.Amplitude) << scale;
    EXPECT_NEAR(raised.HalfExtent.x, std::sqrt(2.0 * c * raised.Covariance[0][0]), 1e-9);
  }
  // Only the EWA filter takes it.
  projection.Jacobian = glm::dmat2(1.0);
  EXPECT_EQ(
    splat::MakeResamplingKernel(projection, 0.6, splat::KernelFilter::Unfiltered, 1.0, 1.0).Cutoff,
    0.6);
}

// Foreshortening depends on the angle of view only: 1 face-on, cos(angle) for a tilted circle,
// whatever the distance (the minified far splats of a plane are not edge-on).
TEST(SurfelKernel, ForeshorteningIgnoresDistance)
{
  for (double scale : { 1e-3, 1.0, 1e3 })
  {
    splat::SurfelProjection projection;
    projection.Jacobian = glm::dmat2(scale, 0.0, 0.0, scale);
    EXPECT_NEAR(splat::Foreshortening(projection), 1.0, 1e-12);
    const double c = std::cos(glm::radians(80.0));
    projection.Jacobian = glm::dmat2(scale, 0.0, 0.0, scale * c);
    EXPECT_NEAR(splat::Foreshortening(projection), 2.0 * c / (1.0 + c * c), 1e-12);
  }
}
