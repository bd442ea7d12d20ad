// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the screen-space EWA kernel (SplatSurfelKernel.h) and of the CPU rasterizer's
// accumulation and normalization (paper 000, sections 3.3, 4 and 7).
#include "SplatSurfelKernel.h"
#include "vtkSurfaceSplatRasterizer.h"

#include "vtkNew.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

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

// Surfels on a regular grid of spacing h in the plane z = 0 with radius h.
struct SurfelGrid
{
  std::vector<double> Positions;
  std::vector<float> Normals, Axes0, Axes1, Colors;

  SurfelGrid(int n, double h, const glm::vec3& color)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const double p[3] = { (i - 0.5 * (n - 1)) * h, (j - 0.5 * (n - 1)) * h, 0.0 };
        const float normal[3] = { 0.f, 0.f, 1.f };
        const float a0[3] = { static_cast<float>(h), 0.f, 0.f };
        const float a1[3] = { 0.f, static_cast<float>(h), 0.f };
        for (int c = 0; c < 3; ++c)
        {
          this->Positions.push_back(p[c]);
          this->Normals.push_back(normal[c]);
          this->Axes0.push_back(a0[c]);
          this->Axes1.push_back(a1[c]);
          this->Colors.push_back(color[c]);
        }
      }
    }
  }

  vtkSurfaceSplatRasterizer::Surfels View() const
  {
    vtkSurfaceSplatRasterizer::Surfels s;
    s.Positions = this->Positions.data();
    s.Normals = this->Normals.data();
    s.Axes0 = this->Axes0.data();
    s.Axes1 = this->Axes1.data();
    s.Colors = this->Colors.data();
    s.Count = this->Normals.size() / 3;
    return s;
  }
};

// A camera looking down -z at the plane z = 0 from distance d, square viewport.
vtkSurfaceSplatRasterizer::Camera FrontoParallelCamera(double distance, int size)
{
  vtkSurfaceSplatRasterizer::Camera camera;
  camera.ModelToEye = glm::lookAt(
    glm::dvec3(0.0, 0.0, distance), glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
  camera.EyeToClip = glm::perspective(glm::radians(30.0), 1.0, 0.1 * distance, 10.0 * distance);
  camera.Viewport = glm::ivec2(size, size);
  return camera;
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

// Before normalization, kernels of surfels on a regular grid with radius = spacing sum to 1
// (partition of unity) under magnification and minification alike; truncation at the cutoff c
// keeps the fraction 1 - e^-c of each kernel's mass.
TEST(SurfelKernel, PartitionOfUnityOnARegularGrid)
{
  struct Case
  {
    double Distance; // camera distance: sets pixels per spacing
    double Cutoff;
    double Expected;
    double Tolerance;
  };
  const double h = 0.01;
  const int n = 101;
  const int size = 256;
  const double e = std::exp(-1.0);
  const Case cases[] = {
    { 0.6, 12.0, 1.0, 0.01 },  // ~8 pixels per spacing: magnified
    { 12.0, 12.0, 1.0, 0.01 }, // ~0.4 pixels per spacing: minified, the low-pass dominates
    { 0.6, 1.0, 1.0 - e, 0.18 }, // default cutoff: mean 1 - 1/e, truncation ripple 0.46..0.78
  };
  const SurfelGrid grid(n, h, glm::vec3(1.0f));
  for (const Case& c : cases)
  {
    vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
    rasterizer->SetCutoff(c.Cutoff);
    rasterizer->Splat(grid.View(), FrontoParallelCamera(c.Distance, size));
    const std::vector<float>& weights = rasterizer->GetWeights();
    // The grid's interior: pixels at least 5 spacings inside its edges.
    const double halfWidth = 0.5 * (n - 1) * h - 5.0 * h;
    const double pixelsPerUnit = 0.5 * size / (c.Distance * std::tan(glm::radians(15.0)));
    const int margin =
      std::max(0, static_cast<int>(std::ceil(0.5 * size - halfWidth * pixelsPerUnit)));
    ASSERT_LT(margin, size / 2);
    double sum = 0.0, low = 1e9, high = -1e9;
    int count = 0;
    for (int y = margin; y < size - margin; ++y)
    {
      for (int x = margin; x < size - margin; ++x)
      {
        const double w = weights[static_cast<std::size_t>(y) * size + x];
        sum += w;
        low = std::min(low, w);
        high = std::max(high, w);
        ++count;
      }
    }
    ASSERT_GT(count, 100);
    const double mean = sum / count;
    EXPECT_NEAR(mean, c.Expected, 0.01) << "distance " << c.Distance << " cutoff " << c.Cutoff;
    EXPECT_GT(low, c.Expected - c.Tolerance) << "distance " << c.Distance;
    EXPECT_LT(high, c.Expected + c.Tolerance) << "distance " << c.Distance;
    if (c.Cutoff == 1.0)
    {
      // Section 7's full-coverage threshold tau = 0.4 sits below every interior sum.
      EXPECT_GT(low, 0.4);
    }
  }
}

// After normalization (eq. 9) a constant-color plane renders exactly that color.
TEST(SurfelKernel, NormalizedConstantPlaneHasExactlyItsColor)
{
  const glm::vec3 color(0.2f, 0.6f, 0.8f);
  const SurfelGrid grid(61, 0.01, color);
  vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
  splat::Material unlit;
  unlit.Ambient = 0.0f;
  unlit.Diffuse = 1.0f;
  rasterizer->Render(grid.View(), FrontoParallelCamera(1.0, 128), {}, unlit);
  const std::vector<std::uint8_t>& rgba = rasterizer->GetColors();
  const int expected[3] = { 51, 153, 204 };
  int covered = 0;
  for (std::size_t pixel = 0; pixel < rgba.size() / 4; ++pixel)
  {
    if (rgba[4 * pixel + 3] == 0)
    {
      continue;
    }
    ++covered;
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_EQ(rgba[4 * pixel + c], expected[c]) << "pixel " << pixel;
    }
  }
  EXPECT_GT(covered, 128 * 128 / 2);
}

// The tangent plane's depth along each pixel's ray is exact: a tilted plane's depth at every
// covered pixel equals the ray/plane intersection, not the affine approximation.
TEST(SurfelKernel, PlaneDepthIsTheRayIntersection)
{
  const glm::dmat4 view =
    glm::lookAt(glm::dvec3(0.2, 0.1, 3.0), glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
  const glm::dmat4 projection = Projection();
  const glm::dmat4 modelToClip = projection * view;
  const glm::dvec3 p(0.1, -0.2, 0.3);
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.6, 0.2, 0.7));
  splat::PlaneDepth depth;
  ASSERT_TRUE(splat::MakePlaneDepth(
    glm::inverse(modelToClip), glm::inverse(projection), Viewport, p, n, depth));
  const glm::dmat4 eyeToModel = glm::inverse(view);
  const glm::dvec3 eyeModel(eyeToModel * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  for (double x = 100.5; x < 600.0; x += 50.0)
  {
    for (double y = 50.5; y < 450.0; y += 50.0)
    {
      // The pixel's ray through the far plane, back to model space.
      const glm::dvec4 farClip((2.0 * x / Viewport.x - 1.0), (2.0 * y / Viewport.y - 1.0), 1.0, 1.0);
      const glm::dvec4 farModel = glm::inverse(modelToClip) * farClip;
      const glm::dvec3 direction = glm::dvec3(farModel) / farModel.w - eyeModel;
      const double t = glm::dot(n, p - eyeModel) / glm::dot(n, direction);
      const glm::dvec3 hit = eyeModel + t * direction;
      const double expected = -(view * glm::dvec4(hit, 1.0)).z;
      EXPECT_NEAR(depth(x, y), expected, 1e-9 * expected);
    }
  }
}
