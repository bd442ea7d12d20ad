// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the EWA volume footprint (SplatVolumeKernel.h) and of the CPU volume rasterizer:
// footprints against the exact integral along pixel rays, the Jacobian against finite
// differences, the voxel kernels' partition of unity, scale + quaternion against covariance,
// the near plane and degenerate kernels, the band-limit filter's floor, list selection, the
// optical model on a slab, determinism across thread counts, spherical-harmonic colors per view
// point, and the per-pixel loops' exponentials.
#include "SplatFloat8.h"
#include "SplatVolumeKernel.h"
#include "vtkVolumeSplatRasterizer.h"

#include "vtkNew.h"
#include "vtkSMPTools.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace
{
constexpr double Pi = 3.14159265358979323846;
const glm::dvec2 Viewport(400.0, 300.0);

glm::dmat4 Perspective()
{
  return glm::perspective(glm::radians(30.0), Viewport.x / Viewport.y, 0.5, 100.0);
}

glm::dmat4 Parallel(double halfHeight)
{
  const double halfWidth = halfHeight * Viewport.x / Viewport.y;
  return glm::ortho(-halfWidth, halfWidth, -halfHeight, halfHeight, 0.5, 100.0);
}

// A rotated anisotropic covariance.
glm::dmat3 Anisotropic(double s0, double s1, double s2)
{
  return splat::CovarianceFromScaleRotation(
    glm::dvec3(s0, s1, s2), glm::dvec4(0.9, 0.2, -0.3, 0.25));
}

// The exact integral of the kernel along the ray through pixel position x, against the
// footprint before the low-pass filter (covariance M - I). Returns the largest difference
// relative to the footprint's peak.
double FootprintError(const glm::dmat4& eyeToClip, const glm::dvec3& e, const glm::dmat3& V)
{
  splat::VolumeProjection projection;
  EXPECT_TRUE(splat::ProjectVolumeKernel(eyeToClip, Viewport, e, projection));
  splat::ResamplingKernel footprint = splat::MakeVolumeFootprint(projection, V, 50.0);
  footprint.Covariance -= glm::dmat2(1.0);
  footprint.Conic = glm::inverse(footprint.Covariance);
  footprint.Amplitude = std::abs(glm::determinant(projection.Jacobian)) /
    (2.0 * Pi * std::sqrt(glm::determinant(footprint.Covariance)));
  const splat::PixelRays rays = splat::MakePixelRays(eyeToClip, Viewport);
  double largest = 0.0;
  for (int dy = -30; dy <= 30; dy += 3)
  {
    for (int dx = -30; dx <= 30; dx += 3)
    {
      const glm::dvec2 x = projection.Center + glm::dvec2(dx, dy);
      const glm::dvec3 pixel(x, 1.0);
      const glm::dvec3 origin = rays.Origin * pixel;
      const glm::dvec3 direction = glm::normalize(rays.Direction * pixel);
      const double exact = splat::GaussianLineIntegral(origin, direction, e, V);
      largest = std::max(largest, std::abs(footprint.Weight(x) - exact));
    }
  }
  return largest / footprint.Amplitude;
}
}

TEST(SplatVolumeKernel, FootprintMatchesRayIntegralInPerspective)
{
  // About 10 pixels of standard deviation: the low-pass filter (1 pixel^2) adds 1% of variance.
  const glm::dvec3 e(0.4, -0.3, -6.0);
  const double error = FootprintError(Perspective(), e, Anisotropic(0.09, 0.05, 0.2));
  EXPECT_LT(error, 0.02);
}

TEST(SplatVolumeKernel, FootprintMatchesRayIntegralInParallel)
{
  const glm::dvec3 e(0.4, -0.3, -6.0);
  const double error = FootprintError(Parallel(1.5), e, Anisotropic(0.09, 0.05, 0.2));
  EXPECT_LT(error, 0.015);
}

TEST(SplatVolumeKernel, ParallelFootprintIsTheWorldProjection)
{
  // s model units per pixel: the footprint is the 2D marginal G_{V_xy} in model units.
  const double halfHeight = 1.5;
  const double s = 2.0 * halfHeight / Viewport.y;
  const glm::dmat3 V = Anisotropic(0.3, 0.2, 0.5);
  splat::VolumeProjection projection;
  ASSERT_TRUE(splat::ProjectVolumeKernel(Parallel(halfHeight), Viewport, glm::dvec3(0, 0, -5), projection));
  EXPECT_NEAR(std::abs(glm::determinant(projection.Jacobian)), 1.0 / (s * s), 1e-9 / (s * s));
  const splat::ResamplingKernel k = splat::MakeVolumeFootprint(projection, V, 50.0);
  const glm::dmat2 marginal(V);
  const double peak = 1.0 / (2.0 * Pi * std::sqrt(glm::determinant(marginal)));
  EXPECT_NEAR(k.Amplitude, peak, 2e-3 * peak); // the low-pass adds s^2 to variances of ~0.04
}

TEST(SplatVolumeKernel, JacobianMatchesFiniteDifferences)
{
  for (const glm::dmat4& P : { Perspective(), Parallel(2.0) })
  {
    const glm::dvec3 e(0.7, -0.4, -5.0);
    splat::VolumeProjection at;
    ASSERT_TRUE(splat::ProjectVolumeKernel(P, Viewport, e, at));
    const bool perspective = P[3][3] == 0.0;
    auto distance = [perspective](const glm::dvec3& p) { return perspective ? glm::length(p) : -p.z; };
    const double h = 1e-6;
    for (int axis = 0; axis < 3; ++axis)
    {
      glm::dvec3 step(0.0);
      step[axis] = h;
      splat::VolumeProjection plus, minus;
      ASSERT_TRUE(splat::ProjectVolumeKernel(P, Viewport, e + step, plus));
      ASSERT_TRUE(splat::ProjectVolumeKernel(P, Viewport, e - step, minus));
      const glm::dvec2 dPixel = (plus.Center - minus.Center) / (2.0 * h);
      const double dDistance = (distance(e + step) - distance(e - step)) / (2.0 * h);
      EXPECT_NEAR(at.Jacobian[axis][0], dPixel.x, 1e-4 * (1.0 + std::abs(dPixel.x)));
      EXPECT_NEAR(at.Jacobian[axis][1], dPixel.y, 1e-4 * (1.0 + std::abs(dPixel.y)));
      EXPECT_NEAR(at.Jacobian[axis][2], dDistance, 1e-6);
    }
  }
}

TEST(SplatVolumeKernel, VoxelKernelsAreAPartitionOfUnity)
{
  // An anisotropic grid, spacing (1, 1.5, 0.7), with a rotated direction matrix.
  const glm::dmat3 rotation(glm::dvec3(0.8, 0.6, 0.0), glm::dvec3(-0.6, 0.8, 0.0), glm::dvec3(0, 0, 1));
  const glm::dmat3 indexToModel = rotation * glm::dmat3(1.0, 0, 0, 0, 1.5, 0, 0, 0, 0.7);
  const glm::dmat3 V = splat::VoxelCovariance(indexToModel);
  const double volume = std::abs(glm::determinant(indexToModel));
  const double norm = 1.0 / (splat::TwoPiToThreeHalves * std::sqrt(glm::determinant(V)));
  const glm::dmat3 inverse = glm::inverse(V);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double lowest = 2.0, highest = 0.0;
  for (int sample = 0; sample < 200; ++sample)
  {
    const glm::dvec3 index(unit(random), unit(random), unit(random));
    const glm::dvec3 x = indexToModel * index;
    double sum = 0.0;
    for (int k = -6; k <= 6; ++k)
      for (int j = -6; j <= 6; ++j)
        for (int i = -6; i <= 6; ++i)
        {
          const glm::dvec3 d = x - indexToModel * glm::dvec3(i, j, k);
          sum += volume * norm * std::exp(-0.5 * glm::dot(d, inverse * d));
        }
    lowest = std::min(lowest, sum);
    highest = std::max(highest, sum);
  }
  std::printf("partition of unity with sigma %.2f h: [%.5f, %.5f]\n", splat::VoxelKernelSigma,
    lowest, highest);
  EXPECT_GT(lowest, 0.99);
  EXPECT_LT(highest, 1.01);
}

TEST(SplatVolumeKernel, ScaleAndQuaternionGiveTheCovariance)
{
  // 90 degrees about z: the x and y variances swap.
  const double c = std::sqrt(0.5);
  const glm::dmat3 V =
    splat::CovarianceFromScaleRotation(glm::dvec3(1.0, 2.0, 3.0), glm::dvec4(c, 0.0, 0.0, c));
  EXPECT_NEAR(V[0][0], 4.0, 1e-12);
  EXPECT_NEAR(V[1][1], 1.0, 1e-12);
  EXPECT_NEAR(V[2][2], 9.0, 1e-12);
  EXPECT_NEAR(V[1][0], 0.0, 1e-12);
  // Not normalized quaternions give the same; the covariance keeps the scales' determinant.
  const glm::dmat3 A = Anisotropic(0.1, 0.5, 2.0);
  const glm::dmat3 B =
    splat::CovarianceFromScaleRotation(glm::dvec3(0.1, 0.5, 2.0), 3.0 * glm::dvec4(0.9, 0.2, -0.3, 0.25));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
    {
      EXPECT_NEAR(A[i][j], B[i][j], 1e-12);
      EXPECT_DOUBLE_EQ(A[i][j], A[j][i]);
    }
  EXPECT_NEAR(glm::determinant(A), std::pow(0.1 * 0.5 * 2.0, 2), 1e-12);
  const double xyz[6] = { A[0][0], A[1][0], A[2][0], A[1][1], A[2][1], A[2][2] };
  EXPECT_EQ(splat::SymmetricFromComponents(xyz), A);
}

TEST(SplatVolumeKernel, NearPlaneAndDegenerateKernels)
{
  const glm::dmat4 P = Perspective();
  const double nearDistance = splat::NearPlaneDistance(P);
  EXPECT_NEAR(nearDistance, 0.5, 1e-9);
  EXPECT_NEAR(splat::FarPlaneDistance(P), 100.0, 1e-6);
  EXPECT_NEAR(splat::NearPlaneDistance(Parallel(1.0)), 0.5, 1e-9);
  EXPECT_NEAR(splat::FarPlaneDistance(Parallel(1.0)), 100.0, 1e-6);
  const glm::dmat3 V(0.01); // sigma 0.1: the cutoff 4.5 reaches 0.3
  EXPECT_FALSE(splat::CrossesNearPlane(glm::dvec3(0, 0, -1.0), V, nearDistance, 4.5));
  EXPECT_TRUE(splat::CrossesNearPlane(glm::dvec3(0, 0, -0.7), V, nearDistance, 4.5));
  EXPECT_TRUE(splat::CrossesNearPlane(glm::dvec3(0, 0, 2.0), V, nearDistance, 4.5));
  splat::VolumeProjection projection;
  EXPECT_FALSE(splat::ProjectVolumeKernel(P, Viewport, glm::dvec3(0, 0, 1.0), projection));
  EXPECT_FALSE(splat::ProjectVolumeKernel(P, Viewport, glm::dvec3(0, 0, 0.0), projection));

  // Zero covariance and eigenvalue ratios of 1e12: finite, invertible footprints.
  ASSERT_TRUE(splat::ProjectVolumeKernel(P, Viewport, glm::dvec3(0.1, 0.2, -3.0), projection));
  for (const glm::dmat3& degenerate : { glm::dmat3(0.0), Anisotropic(1e-6, 1.0, 1e-6),
         Anisotropic(1.0, 1e-6, 1.0), Anisotropic(0.0, 0.0, 1.0) })
  {
    const splat::ResamplingKernel k = splat::MakeVolumeFootprint(projection, degenerate, 4.5);
    EXPECT_TRUE(std::isfinite(k.Amplitude));
    EXPECT_TRUE(std::isfinite(k.HalfExtent.x) && std::isfinite(k.HalfExtent.y));
    EXPECT_GE(glm::determinant(k.Covariance), 1.0 - 1e-9);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        EXPECT_TRUE(std::isfinite(k.Conic[i][j]));
    EXPECT_TRUE(std::isfinite(k.Weight(projection.Center + glm::dvec2(0.3, -0.2))));
  }
}

// The band limit raises each eigenvalue of the footprint's covariance to at least the filter's
// variance and keeps its eigenvectors; the low-pass adds the variance; degenerate covariances
// come out finite and invertible under both.
TEST(SplatVolumeKernel, BandLimitFloorsTheEigenvalues)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> angle(0.0, Pi), logScale(-6.0, 3.0);
  for (int n = 0; n < 200; ++n)
  {
    const double a = angle(random);
    const glm::dvec2 e1(std::cos(a), std::sin(a)), e2(-e1.y, e1.x);
    const double l1 = std::pow(10.0, logScale(random)), l2 = std::pow(10.0, logScale(random));
    const glm::dmat2 c = l1 * glm::outerProduct(e1, e1) + l2 * glm::outerProduct(e2, e2);
    const glm::dmat2 floored = splat::FilteredCovariance(c, 1.0, true);
    EXPECT_NEAR(glm::dot(e1, floored * e1), std::max(l1, 1.0), 1e-9 * std::max(l1, 1.0));
    EXPECT_NEAR(glm::dot(e2, floored * e2), std::max(l2, 1.0), 1e-9 * std::max(l2, 1.0));
    EXPECT_NEAR(glm::dot(e1, floored * e2), 0.0, 1e-9 * std::max(std::max(l1, l2), 1.0));
    const glm::dmat2 summed = splat::FilteredCovariance(c, 1.0, false);
    EXPECT_NEAR(glm::dot(e1, summed * e1), l1 + 1.0, 1e-9 * (l1 + 1.0));
  }
  // Footprints already wider than a pixel are left as they are.
  const glm::dmat2 wide(4.0, 1.0, 1.0, 3.0);
  EXPECT_EQ(splat::FilteredCovariance(wide, 1.0, true), wide);
  splat::VolumeProjection projection;
  ASSERT_TRUE(
    splat::ProjectVolumeKernel(Perspective(), Viewport, glm::dvec3(0.1, 0.2, -3.0), projection));
  for (const glm::dmat3& degenerate : { glm::dmat3(0.0), Anisotropic(1e-6, 1.0, 1e-6),
         Anisotropic(1.0, 1e-6, 1.0), Anisotropic(0.0, 0.0, 1.0) })
  {
    const splat::ResamplingKernel k =
      splat::MakeVolumeFootprint(projection, degenerate, 4.5, 1.0, true);
    EXPECT_TRUE(std::isfinite(k.Amplitude));
    EXPECT_GE(glm::determinant(k.Covariance), 1.0 - 1e-6);
  }
}

namespace
{
// A grid of n^3 voxel kernels of spacing h centered at the origin, with extinction tau.
struct Grid
{
  std::vector<double> Positions;
  std::vector<float> Colors;
  std::vector<float> Strengths;
  std::vector<vtkIdType> Ids;
  vtkVolumeSplatRasterizer::Kernels Kernels;

  Grid(int n, double h, double tau)
  {
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
          for (double c : { i, j, k })
          {
            this->Positions.push_back((c - 0.5 * (n - 1)) * h);
          }
          this->Colors.insert(this->Colors.end(), { 0.2f + 0.6f * i / n, 0.5f, 0.8f - 0.6f * k / n });
          this->Strengths.push_back(static_cast<float>(tau * h * h * h));
          this->Ids.push_back(i + n * (j + n * k));
        }
    this->Kernels.Count = this->Strengths.size();
    this->Kernels.Positions = this->Positions.data();
    this->Kernels.Colors = this->Colors.data();
    this->Kernels.Strengths = this->Strengths.data();
    this->Kernels.SharedCovariance = splat::VoxelCovariance(glm::dmat3(h));
    this->Kernels.GridIds = this->Ids.data();
    this->Kernels.GridDimensions = glm::ivec3(n);
    this->Kernels.GridAxes = glm::dmat3(h);
    this->Kernels.GridOrigin = glm::dvec3(-0.5 * (n - 1) * h);
  }
};

vtkVolumeSplatRasterizer::Camera LookAt(const glm::dvec3& eye, const glm::dmat4& projection)
{
  vtkVolumeSplatRasterizer::Camera camera;
  const glm::dvec3 up = std::abs(glm::normalize(eye).y) > 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
  camera.ModelToEye = glm::lookAt(eye, glm::dvec3(0.0), up);
  camera.EyeToClip = projection;
  camera.Viewport = glm::ivec2(Viewport);
  return camera;
}
}

TEST(SplatVolumeKernel, ExponentialsKeepTheirBounds)
{
  // Scalar and per lane, against the C library's exp in double, on a grid that crosses each
  // rounding boundary of the polynomials' arguments.
  alignas(32) float x[8];
  alignas(32) float e[8];
  alignas(32) float e2[8];
  for (double start = 0.0; start < 120.0; start += 8.0 * 0.0137)
  {
    for (int lane = 0; lane < 8; ++lane)
    {
      x[lane] = static_cast<float>(start + 0.0137 * lane);
    }
    splat::Float8::NegativeExponential(splat::Float8::Load(x)).Store(e);
    splat::Float8::NegativeExponential2(splat::Float8::Load(x)).Store(e2);
    for (int lane = 0; lane < 8; ++lane)
    {
      const double exact = std::exp(-static_cast<double>(x[lane]));
      const double exact2 = std::exp2(-static_cast<double>(x[lane]));
      EXPECT_FLOAT_EQ(splat::NegativeExponential(x[lane]), e[lane]);
      EXPECT_FLOAT_EQ(splat::NegativeExponential2(x[lane]), e2[lane]);
      if (x[lane] < 87.0f)
      {
        // The rounding of x log2(e) grows with x: 6e-7 below 10, 4e-6 up to 87 without FMA.
        EXPECT_NEAR(e[lane] / exact, 1.0, x[lane] < 10.0f ? 1e-6 : 5e-6)
          << "exp(-" << x[lane] << ")";
      }
      EXPECT_NEAR(e2[lane] / exact2, 1.0, 3e-6) << "2^-" << x[lane];
    }
  }
  EXPECT_EQ(splat::NegativeExponential(100.0f), 0.0f);
  EXPECT_EQ(splat::NegativeExponential(std::numeric_limits<float>::infinity()), 0.0f);
  for (const float large : { 1000.0f, std::numeric_limits<float>::infinity(), std::nanf("") })
  {
    EXPECT_NEAR(splat::NegativeExponential2(large) / std::exp2(-126.0), 1.0, 3e-6) << large;
  }
}

TEST(VolumeSplatRasterizer, SlabOpacityFollowsTheOpticalModel)
{
  // A 20^3 block of spacing 0.05 (1 unit wide) seen straight down z in parallel projection:
  // away from the edges every ray crosses 1 unit of extinction tau, alpha = 1 - exp(-tau).
  const double tau = 0.8;
  Grid grid(20, 0.05, tau);
  vtkNew<vtkVolumeSplatRasterizer> rasterizer;
  rasterizer->SetKernels(grid.Kernels);
  rasterizer->Render(LookAt(glm::dvec3(0, 0, 5), Parallel(1.0)));
  const std::vector<float>& image = rasterizer->GetImage();
  const double expected = 1.0 - std::exp(-tau);
  double lowest = 1.0, highest = 0.0;
  for (int y = 130; y < 170; ++y)
    for (int x = 180; x < 220; ++x)
    {
      const double alpha = image[4 * (y * 400 + x) + 3];
      lowest = std::min(lowest, alpha);
      highest = std::max(highest, alpha);
    }
  std::printf("slab alpha [%.5f, %.5f], exact %.5f\n", lowest, highest, expected);
  EXPECT_NEAR(lowest, expected, 0.01 * expected);
  EXPECT_NEAR(highest, expected, 0.01 * expected);
  // Down the z axis only the Z list runs, and the image data is not sorted.
  EXPECT_FALSE(rasterizer->GetListTraversed(0));
  EXPECT_FALSE(rasterizer->GetListTraversed(1));
  EXPECT_TRUE(rasterizer->GetListTraversed(2));
  EXPECT_EQ(rasterizer->GetProjectedCount(2), 8000);
  EXPECT_EQ(rasterizer->GetSortCount(), 0);
}

TEST(VolumeSplatRasterizer, ListWeights)
{
  Grid grid(12, 0.1, 2.0);
  vtkNew<vtkVolumeSplatRasterizer> rasterizer;
  rasterizer->SetKernels(grid.Kernels);
  // A perspective view from (1, 1, 3): most rays are Z-dominant, but the field of view reaches
  // the X and Y regions near the corners only with blending, never with one list per frame.
  const auto camera = LookAt(glm::dvec3(1.2, 0.9, 3.0), Perspective());
  for (int mode : { vtkVolumeSplatRasterizer::SINGLE_AXIS, vtkVolumeSplatRasterizer::CLIPPED,
         vtkVolumeSplatRasterizer::BLENDED })
  {
    rasterizer->SetOrderingMode(mode);
    rasterizer->Render(camera);
    int lists = 0;
    for (int list = 0; list < 3; ++list)
    {
      lists += rasterizer->GetListTraversed(list);
      // A list may run for pixels no kernel reaches, but never splat without running.
      EXPECT_TRUE(rasterizer->GetListTraversed(list) || rasterizer->GetProjectedCount(list) == 0);
    }
    EXPECT_TRUE(rasterizer->GetListTraversed(2));
    if (mode == vtkVolumeSplatRasterizer::SINGLE_AXIS)
    {
      EXPECT_EQ(lists, 1);
    }
    else if (mode == vtkVolumeSplatRasterizer::BLENDED)
    {
      EXPECT_GE(lists, 2);
    }
    EXPECT_EQ(rasterizer->GetSortCount(), 0);
  }
  // A threshold near 1 approaches clipping; 0 uses every list for every pixel.
  rasterizer->SetBlendThreshold(0.0);
  rasterizer->Render(camera);
  for (int list = 0; list < 3; ++list)
  {
    EXPECT_EQ(rasterizer->GetProjectedCount(list), rasterizer->GetProjectedCount(2));
  }
  // The depth-sorted baseline sorts once per frame.
  rasterizer->SetOrderingMode(vtkVolumeSplatRasterizer::DEPTH_SORTED);
  rasterizer->Render(camera);
  EXPECT_EQ(rasterizer->GetSortCount(), 1);
  EXPECT_TRUE(rasterizer->GetListTraversed(vtkVolumeSplatRasterizer::DepthList));
  EXPECT_EQ(rasterizer->GetProjectedCount(), rasterizer->GetProjectedCount(vtkVolumeSplatRasterizer::DepthList));
}

TEST(VolumeSplatRasterizer, OrderingsAgreeWhereTheyShould)
{
  // Every ordering is a valid front-to-back order for an isotropic grid seen from a
  // Z-dominant direction: the images agree closely, the axis lists exactly where only Z runs.
  Grid grid(16, 0.08, 3.0);
  vtkNew<vtkVolumeSplatRasterizer> rasterizer;
  rasterizer->SetKernels(grid.Kernels);
  const auto camera = LookAt(glm::dvec3(0.3, 0.2, 4.0), Perspective());
  std::vector<std::vector<float>> images;
  for (int mode = vtkVolumeSplatRasterizer::BLENDED; mode <= vtkVolumeSplatRasterizer::DEPTH_SORTED; ++mode)
  {
    rasterizer->SetOrderingMode(mode);
    rasterizer->Render(camera);
    images.push_back(rasterizer->GetImage());
  }
  for (std::size_t m = 1; m < images.size(); ++m)
  {
    double largest = 0.0;
    for (std::size_t i = 0; i < images[0].size(); ++i)
    {
      largest = std::max(largest, static_cast<double>(std::abs(images[m][i] - images[0][i])));
    }
    EXPECT_LT(largest, m < 3 ? 1e-6 : 0.05) << "mode " << m;
  }
}

TEST(VolumeSplatRasterizer, NearPlaneAndFrustumSkipsAreCounted)
{
  Grid grid(10, 0.2, 1.0);
  vtkNew<vtkVolumeSplatRasterizer> rasterizer;
  rasterizer->SetKernels(grid.Kernels);
  // The eye inside the block: kernels behind it or reaching the near plane are skipped.
  rasterizer->Render(LookAt(glm::dvec3(0.05, 0.05, 0.3), Perspective()));
  EXPECT_GT(rasterizer->GetNearPlaneCount(), 0);
  EXPECT_GT(rasterizer->GetFrustumCulledCount(), 0);
  const std::vector<float>& image = rasterizer->GetImage();
  for (float v : image)
  {
    ASSERT_TRUE(std::isfinite(v));
  }
}

TEST(VolumeSplatRasterizer, SameImageForAnyThreadCount)
{
  Grid grid(24, 0.05, 4.0);
  vtkNew<vtkVolumeSplatRasterizer> rasterizer;
  rasterizer->SetKernels(grid.Kernels);
  const auto camera = LookAt(glm::dvec3(2.0, 1.6, 2.2), Perspective());
  std::vector<std::vector<std::uint8_t>> images;
  for (int threads : { 1, 2 })
  {
    vtkSMPTools::Initialize(threads);
    ASSERT_EQ(vtkSMPTools::GetEstimatedNumberOfThreads(), threads);
    rasterizer->Render(camera);
    images.push_back(rasterizer->GetColors());
  }
  EXPECT_EQ(images[0], images[1]);
}

// Spherical-harmonic colors: one kernel of degree 1 seen from two eyes; the color at its center
// is the one by hand for the direction from the eye, evaluated once per view point and degree
// (not again for a frame from the same eye, nor for degree 0, which uses the Colors).
TEST(VolumeSplatRasterizer, SphericalHarmonicColorsFollowTheViewPoint)
{
  const double position[3] = { 0.0, 0.0, 0.0 };
  const float covariance[6] = { 0.09f, 0.0f, 0.0f, 0.09f, 0.0f, 0.09f };
  const float degreeZero[3] = { 0.6f, 0.45f, 0.5f };
  const float strength = 1.0f;
  // k0 .. k3, RGB each.
  const float k[12] = { 0.3f, -0.2f, 0.1f, 0.8f, 0.0f, -0.4f, 0.0f, 0.8f, 0.3f, -0.4f, 0.3f,
    0.8f };
  vtkVolumeSplatRasterizer::Kernels kernels;
  kernels.Count = 1;
  kernels.Positions = position;
  kernels.Covariances = covariance;
  kernels.Colors = degreeZero;
  kernels.Strengths = &strength;
  kernels.PeakOpacity = true;
  kernels.SphericalHarmonics = k;
  kernels.SphericalHarmonicsDegree = 1;
  vtkNew<vtkVolumeSplatRasterizer> rasterizer;
  rasterizer->SetKernels(kernels);
  const double y0 = 0.5 / std::sqrt(Pi), y1 = std::sqrt(3.0 / (4.0 * Pi));
  auto expectCenter = [&](const glm::dvec3& eye, int degree)
  {
    rasterizer->Render(LookAt(eye, Perspective()));
    const glm::dvec3 d = -glm::normalize(eye);
    const float* pixel = &rasterizer->GetImage()[4 * (150 * 400 + 200)];
    for (int c = 0; c < 3; ++c)
    {
      const double color = degree == 0
        ? degreeZero[c]
        : 0.5 + y0 * k[c] - y1 * d.y * k[3 + c] + y1 * d.z * k[6 + c] - y1 * d.x * k[9 + c];
      // Premultiplied by the peak opacity 0.99.
      EXPECT_NEAR(pixel[c], 0.99 * color, 1e-3) << "channel " << c << " degree " << degree;
    }
  };
  const glm::dvec3 a(0.0, 0.0, 4.0), b(3.0, 1.0, 2.0);
  expectCenter(a, 1);
  expectCenter(a, 1);
  EXPECT_EQ(rasterizer->GetViewColorCount(), 1);
  expectCenter(b, 1);
  EXPECT_EQ(rasterizer->GetViewColorCount(), 2);
  rasterizer->SetMaximumSphericalHarmonicsDegree(0);
  expectCenter(a, 0);
  rasterizer->SetMaximumSphericalHarmonicsDegree(3); // the kernels' degree 1, as before at b
  expectCenter(b, 1);
  EXPECT_EQ(rasterizer->GetViewColorCount(), 2);
  rasterizer->SetKernels(kernels);
  expectCenter(b, 1);
  EXPECT_EQ(rasterizer->GetViewColorCount(), 3);
}
