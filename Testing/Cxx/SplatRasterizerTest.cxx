// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the CPU rasterizer (vtkSurfaceSplatRasterizer): accumulation and normalization
// (paper 000, sections 4 and 7), elliptical surfels, culling, and thread-independent results.
#include "SplatRasterizerTestUtilities.h"
#include "SplatLighting.h"
#include "SplatSurfaceFragment.h"
#include "vtkSurfaceSplatRasterizer.h"

#include "vtkNew.h"
#include "vtkSMPTools.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <vector>

using namespace splat_test;

// A pixel's opaque surfaces once its layers are full: a sliver (below the negligible weight)
// gives way to a new surface wherever that lies, else the farthest to one in front of it; a new
// sliver takes no layer.
TEST(SurfaceSplatRasterizer, SliversGiveWayInFullLayers)
{
  auto pixel = [](std::initializer_list<std::pair<float, float>> surfaces)
  {
    std::vector<splat::SurfaceFragment> fragments;
    for (const auto& s : surfaces)
    {
      const float normal[3] = { 0.0f, 0.0f, 1.0f };
      const float color[3] = { 1.0f, 1.0f, 1.0f };
      fragments.push_back(splat::NewFragment(s.first, s.second, normal, color, 1.0f));
    }
    return fragments;
  };
  auto depths = [](const std::vector<splat::SurfaceFragment>& fragments)
  {
    std::vector<float> d;
    for (const auto& f : fragments)
    {
      d.push_back(f.Depth);
    }
    return d;
  };
  const float negligible = 0.01f;
  bool inserted = false;
  // (depth, weight): a sliver in front of the surface, the surface, and one behind.
  auto f = pixel({ { 1.0f, 0.001f }, { 2.0f, 0.5f }, { 3.0f, 0.5f } });
  std::uint8_t count = 3;
  // A surface behind all three takes the sliver's layer.
  int i = splat::OpaqueSlot(f.data(), count, 3, 4.0f, 0.1f, inserted, 0.3f, negligible);
  EXPECT_TRUE(inserted);
  EXPECT_EQ(i, 2);
  f[i].Depth = 4.0f;
  EXPECT_EQ(depths(f), std::vector<float>({ 2.0f, 3.0f, 4.0f }));
  // Without slivers, the farthest gives way to a surface in front of it ...
  i = splat::OpaqueSlot(f.data(), count, 3, 2.5f, 0.1f, inserted, 0.3f, negligible);
  EXPECT_EQ(i, 1);
  f[i].Depth = 2.5f;
  EXPECT_EQ(depths(f), std::vector<float>({ 2.0f, 2.5f, 3.0f }));
  // ... and none to one behind them all, nor to a sliver anywhere.
  EXPECT_EQ(splat::OpaqueSlot(f.data(), count, 3, 5.0f, 0.1f, inserted, 0.3f, negligible), -1);
  EXPECT_EQ(splat::OpaqueSlot(f.data(), count, 3, 0.5f, 0.1f, inserted, 0.001f, negligible), -1);
  EXPECT_EQ(count, 3);
  // Within the z threshold a sliver joins its surface.
  EXPECT_EQ(splat::OpaqueSlot(f.data(), count, 3, 2.55f, 0.1f, inserted, 0.001f, negligible), 1);
  EXPECT_FALSE(inserted);
  // A free layer takes any surface.
  f = pixel({ { 2.0f, 0.5f } });
  count = 1;
  f.resize(3);
  EXPECT_EQ(splat::OpaqueSlot(f.data(), count, 3, 1.0f, 0.1f, inserted, 0.001f, negligible), 0);
  EXPECT_TRUE(inserted);
  EXPECT_EQ(count, 2);
  EXPECT_EQ(f[1].Depth, 2.0f);
}

// Normals of either orientation, as scans estimate them: AddNormal sums them on one side, and
// a lit unit sphere of surfels comes out the same with random normal signs as with outward
// normals, shaded as the true sphere up to and across its silhouette. Turning each splat's
// normal towards the viewer before filtering (what the rasterizer did) bent the normals of the
// silhouette's pixels towards the eye: a mean error of 0.071 there, 0.042 now.
TEST(SurfaceSplatRasterizer, NormalsAddUpOnOneSide)
{
  const float up[3] = { 0.0f, 0.6f, 0.8f };
  const float down[3] = { 0.0f, -0.6f, -0.8f };
  float sum[3] = { 0.0f, 0.0f, 0.0f };
  splat::AddNormal(sum, 1.0f, up);
  splat::AddNormal(sum, 0.5f, down);
  EXPECT_FLOAT_EQ(sum[1], 0.9f);
  EXPECT_FLOAT_EQ(sum[2], 1.2f);

  // Fibonacci points on the unit sphere, surfels of radius 1.5 times their spacing.
  const int n = 2000;
  const float radius = 1.5f * std::sqrt(4.0f * 3.14159265f / n);
  std::vector<double> positions;
  std::vector<float> outward, randomSigns, axes0, axes1, colors(3 * n, 1.0f);
  const double distance = 4.0;
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double phi = 2.39996322972865332 * i;
    const glm::dvec3 p(std::sqrt(1.0 - z * z) * std::cos(phi),
      std::sqrt(1.0 - z * z) * std::sin(phi), z);
    const glm::dvec3 a0 = glm::normalize(glm::cross(p, std::abs(z) < 0.9
        ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(1.0, 0.0, 0.0)));
    const glm::dvec3 a1 = glm::cross(p, a0);
    const float sign = (i * 7919) % 3 == 0 ? -1.0f : 1.0f;
    for (int c = 0; c < 3; ++c)
    {
      positions.push_back(p[c]);
      outward.push_back(static_cast<float>(p[c]));
      randomSigns.push_back(sign * static_cast<float>(p[c]));
      axes0.push_back(radius * static_cast<float>(a0[c]));
      axes1.push_back(radius * static_cast<float>(a1[c]));
    }
  }
  // A light from the eye: a pixel's value is 255 times its normal's eye-space z.
  std::vector<splat::Light> lights(1);
  splat::Material material = Unlit();
  const int size = 160;
  auto render = [&](const std::vector<float>& normals)
  {
    vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
    rasterizer->Render(vtkSurfaceSplatRasterizer::Surfels::Of(positions, normals, axes0, axes1,
                         colors),
      FrontoParallelCamera(distance, size), lights, material);
    return rasterizer->GetColors();
  };
  // Mean error against the true sphere's shading (unpremultiplied) over the covered pixels of
  // its rim (normals beyond 70 degrees from the view ray) and beside it.
  auto rimError = [&](const std::vector<std::uint8_t>& rgba)
  {
    const double t = std::tan(glm::radians(15.0));
    double error = 0.0;
    int count = 0;
    for (int y = 0; y < size; ++y)
    {
      for (int x = 0; x < size; ++x)
      {
        const glm::dvec3 ray = glm::normalize(glm::dvec3(
          (2.0 * (x + 0.5) / size - 1.0) * t, (2.0 * (y + 0.5) / size - 1.0) * t, -1.0));
        const glm::dvec3 center(0.0, 0.0, -distance);
        const double b = glm::dot(ray, center);
        const double discriminant = b * b - (glm::dot(center, center) - 1.0);
        const std::uint8_t* pixel = &rgba[4 * (y * size + x)];
        if (pixel[3] == 0)
        {
          continue;
        }
        // Beside the sphere, the silhouette's shading: its normals n have n.z = 1 / distance.
        double expected = 1.0 / distance;
        if (discriminant > 0.0)
        {
          const glm::dvec3 normal = (b - std::sqrt(discriminant)) * ray - center;
          if (-glm::dot(normal, ray) > 0.35)
          {
            continue;
          }
          expected = normal.z;
        }
        error += std::abs(static_cast<double>(pixel[1]) / pixel[3] - expected);
        ++count;
      }
    }
    EXPECT_GT(count, 100);
    return error / std::max(count, 1);
  };
  const std::vector<std::uint8_t> image = render(outward);
  const std::vector<std::uint8_t> unoriented = render(randomSigns);
  for (std::size_t i = 0; i < image.size(); ++i)
  {
    ASSERT_LE(std::abs(image[i] - unoriented[i]), 1) << "byte " << i;
  }
  const double error = rimError(image);
  std::cout << "rim shading error: " << error << "\n";
  // 0.041 where edge-on normals were turned towards the viewer (FacingNormal), 0.033 now.
  EXPECT_LT(error, 0.037);
}

// Two-sided lighting turns a normal towards the viewer, but one seen edge-on from an oblique
// ray towards the view axis, the side the headlight lights; a parallel projection's axis-aligned
// rays see no difference.
TEST(SurfaceSplatRasterizer, EdgeOnNormalsFaceTheViewAxis)
{
  const glm::vec3 axis(0.0f, 0.0f, -1.0f);
  const glm::vec3 away = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
  EXPECT_EQ(splat::FacingNormal(away, axis), -away);
  EXPECT_EQ(splat::FacingNormal(-away, axis), -away);

  // An oblique ray (30 degrees off the axis, of length 2) and a normal 3 degrees from
  // perpendicular to it, pointing away from it and from the view axis: turned towards the
  // viewer it would face away from the headlight.
  const glm::vec3 ray = 2.0f * glm::vec3(0.5f, 0.0f, -std::sqrt(0.75f));
  const glm::vec3 perpendicular(std::sqrt(0.75f), 0.0f, 0.5f);
  const float tilt = glm::radians(3.0f);
  const glm::vec3 edgeOn =
    -(std::cos(tilt) * perpendicular + std::sin(tilt) * glm::normalize(ray));
  ASSERT_LT(edgeOn.z, 0.0f);
  ASSERT_LT(glm::dot(edgeOn, ray), 0.0f);
  EXPECT_EQ(splat::FacingNormal(edgeOn, ray), -edgeOn);
  EXPECT_EQ(splat::FacingNormal(-edgeOn, ray), -edgeOn);

  // Beyond the edge-on band the viewer's side wins, even where it faces away from the axis.
  const float steep = glm::radians(10.0f);
  const glm::vec3 seen =
    -std::cos(steep) * perpendicular - std::sin(steep) * glm::normalize(ray);
  ASSERT_LT(seen.z, 0.0f);
  ASSERT_LT(glm::dot(seen, ray), -splat::EdgeOnCosine * glm::length(ray));
  EXPECT_EQ(splat::FacingNormal(seen, ray), seen);
  EXPECT_EQ(splat::FacingNormal(-seen, ray), seen);
}

// Before normalization, kernels of surfels on a regular grid with radius = spacing sum to 1
// (partition of unity) under magnification and minification alike; truncation at the cutoff c
// keeps the fraction 1 - e^-c of each kernel's mass. Minified splats summed per pixel keep
// the mean, with a larger ripple.
TEST(SurfaceSplatRasterizer, PartitionOfUnityOnARegularGrid)
{
  struct Case
  {
    double Distance; // camera distance: sets pixels per spacing
    double Cutoff;
    double Expected;
    double Tolerance;
    bool Minified = false; // summed per pixel at the default MinifiedVariance, else exact
  };
  const double h = 0.01;
  const int n = 101;
  const int size = 256;
  const double e = std::exp(-1.0);
  const Case cases[] = {
    { 0.6, 12.0, 1.0, 0.01 },    // ~8 pixels per spacing: magnified
    { 12.0, 12.0, 1.0, 0.01 },   // ~0.4 pixels per spacing: minified, the low-pass dominates
    { 0.6, 1.0, 1.0 - e, 0.18 }, // default cutoff: mean 1 - 1/e, truncation ripple 0.46..0.78
    { 12.0, 12.0, 1.0, 0.02, true }, // minified, summed per pixel
  };
  const SurfelGrid grid(n, h, glm::vec3(1.0f));
  for (const Case& c : cases)
  {
    vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
    rasterizer->SetCutoff(c.Cutoff);
    if (!c.Minified)
    {
      rasterizer->SetMinifiedVariance(0.0);
    }
    rasterizer->Splat(grid.View(), FrontoParallelCamera(c.Distance, size));
    EXPECT_EQ(rasterizer->GetMinifiedCount() > 0, c.Minified);
    const std::vector<float>& weights = rasterizer->GetWeights();
    // The grid's interior: pixels at least 5 spacings inside its edges.
    const double halfWidth = (0.5 * (n - 1) - 5.0) * h * PixelsPerUnit(c.Distance, size);
    const int margin = std::max(0, static_cast<int>(std::ceil(0.5 * size - halfWidth)));
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

// Without the low-pass filter, minified splats alias: a sine with a period of 6 samples, smooth
// for the splats, seen at about 0.22 pixels per sample (a period of 1.3 pixels, above Nyquist)
// comes out as a false low-frequency pattern, where EWA's low-pass averages it to its mean,
// with exact kernels or summed per pixel (whose cells sum 4 or 5 splats per row: a weaker
// beat remains).
TEST(SurfaceSplatRasterizer, UnfilteredMinifiedSplatsAlias)
{
  const double h = 0.01;
  auto sine = [h](double x, double)
  { return glm::vec3(static_cast<float>(0.5 + 0.5 * std::sin(2.0 * M_PI * x / (6.0 * h)))); };
  const SurfelGrid grid(101, 101, h, h, h, h, sine);
  auto deviation = [&](splat::KernelFilter filter, bool exact)
  {
    vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
    rasterizer->SetFilter(filter);
    if (exact)
    {
      rasterizer->SetMinifiedVariance(0.0);
    }
    rasterizer->Render(grid.View(), FrontoParallelCamera(22.0, 256), {}, Unlit());
    const std::vector<std::uint8_t>& rgba = rasterizer->GetColors();
    double squared = 0.0;
    for (int y = 120; y < 136; ++y)
    {
      for (int x = 120; x < 136; ++x)
      {
        const double d = rgba[4 * (static_cast<std::size_t>(y) * 256 + x)] / 255.0 - 0.5;
        squared += d * d;
      }
    }
    return std::sqrt(squared / (16 * 16));
  };
  const double ewa = deviation(splat::KernelFilter::EWA, true);
  const double minified = deviation(splat::KernelFilter::EWA, false);
  const double unfiltered = deviation(splat::KernelFilter::Unfiltered, false);
  std::printf("deviation from the mean gray: EWA %.4f, EWA summed per pixel %.4f, unfiltered %.4f\n",
    ewa, minified, unfiltered);
  EXPECT_LT(ewa, 0.05);
  EXPECT_LT(minified, 0.08);
  EXPECT_GT(unfiltered, 0.2);
}

// After normalization (eq. 9) a constant-color plane renders exactly that color.
TEST(SurfaceSplatRasterizer, NormalizedConstantPlaneHasExactlyItsColor)
{
  const glm::vec3 color(0.2f, 0.6f, 0.8f);
  const SurfelGrid grid(61, 0.01, color);
  vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
  rasterizer->Render(grid.View(), FrontoParallelCamera(1.0, 128), {}, Unlit());
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

// A plane sampled 4:1 (spacing 4h along x, h along y) with matching elliptical surfels has no
// holes and reproduces a texture varying along y better than circular surfels of the major
// radius 4h, which blur it.
TEST(SurfaceSplatRasterizer, EllipticalSurfelsOnAnisotropicSampling)
{
  const double h = 0.01;
  const double frequency = 2.0 * M_PI / (8.0 * h); // a period of 8 samples along y
  auto texture = [frequency](double, double y)
  { return glm::vec3(static_cast<float>(0.5 + 0.4 * std::sin(frequency * y))); };
  const SurfelGrid elliptical(26, 101, 4.0 * h, h, 4.0 * h, h, texture);
  const SurfelGrid circular(26, 101, 4.0 * h, h, 4.0 * h, 4.0 * h, texture);
  const int size = 256;
  const double distance = 1.2;
  const double pixelsPerUnit = PixelsPerUnit(distance, size);

  auto error = [&](const SurfelGrid& grid, int& holes)
  {
    vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
    rasterizer->Render(grid.View(), FrontoParallelCamera(distance, size), {}, Unlit());
    const std::vector<std::uint8_t>& rgba = rasterizer->GetColors();
    double squared = 0.0;
    int count = 0;
    holes = 0;
    // The interior, 8 samples inside the grid's edges.
    const double half = 0.5 * 100 * h - 8.0 * h;
    for (int y = 0; y < size; ++y)
    {
      for (int x = 0; x < size; ++x)
      {
        const double px = (x + 0.5 - 0.5 * size) / pixelsPerUnit;
        const double py = (y + 0.5 - 0.5 * size) / pixelsPerUnit;
        if (std::abs(px) > half || std::abs(py) > half)
        {
          continue;
        }
        const std::size_t pixel = static_cast<std::size_t>(y) * size + x;
        holes += rgba[4 * pixel + 3] == 0;
        const double d = rgba[4 * pixel] / 255.0 - texture(px, py).x;
        squared += d * d;
        ++count;
      }
    }
    return std::sqrt(squared / count);
  };
  int ellipticalHoles = 0, circularHoles = 0;
  const double ellipticalError = error(elliptical, ellipticalHoles);
  const double circularError = error(circular, circularHoles);
  std::printf("texture RMSE: elliptical %.4f, circular %.4f\n", ellipticalError, circularError);
  EXPECT_EQ(ellipticalHoles, 0);
  EXPECT_LT(ellipticalError, 0.5 * circularError);
}

// Back-facing splats are left out only when asked, edge-on ones always, splats behind the eye
// always; all are counted.
TEST(SurfaceSplatRasterizer, CullsBackFacingNegligibleAndOutsideSplats)
{
  SurfelGrid grid(11, 0.05, glm::vec3(1.0f));
  const vtkIdType count = static_cast<vtkIdType>(grid.Normals.size() / 3);
  for (vtkIdType i = 1; i < count; i += 2)
  {
    grid.Normals[3 * i + 2] = -1.0f; // faces away from the camera on +z
  }
  // The center surfel (index 60, on the optical axis) edge-on: its plane holds the view ray.
  const std::size_t center = 60;
  grid.Normals[3 * center + 1] = 1.0f;
  grid.Normals[3 * center + 2] = 0.0f;
  grid.Axes1[3 * center + 1] = 0.0f;
  grid.Axes1[3 * center + 2] = 0.05f;

  vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
  rasterizer->Splat(grid.View(), FrontoParallelCamera(2.0, 128));
  EXPECT_EQ(rasterizer->GetBackfaceCulledCount(), 0);
  EXPECT_EQ(rasterizer->GetNegligibleCount(), 1);
  EXPECT_EQ(rasterizer->GetFrustumCulledCount(), 0);
  EXPECT_EQ(rasterizer->GetSplattedCount(), count - 1);

  rasterizer->BackfaceCullingOn();
  rasterizer->Splat(grid.View(), FrontoParallelCamera(2.0, 128));
  EXPECT_EQ(rasterizer->GetBackfaceCulledCount(), count / 2);
  EXPECT_EQ(rasterizer->GetNegligibleCount(), 1);
  EXPECT_EQ(rasterizer->GetSplattedCount(), count - count / 2 - 1);

  // A camera looking away from the grid: everything is behind the eye.
  vtkSurfaceSplatRasterizer::Camera away = FrontoParallelCamera(2.0, 128);
  away.ModelToEye = glm::lookAt(
    glm::dvec3(0.0, 0.0, 2.0), glm::dvec3(0.0, 0.0, 4.0), glm::dvec3(0.0, 1.0, 0.0));
  rasterizer->BackfaceCullingOff();
  rasterizer->Splat(grid.View(), away);
  EXPECT_EQ(rasterizer->GetSplattedCount(), 0);
  EXPECT_EQ(rasterizer->GetFrustumCulledCount(), count);
}

// The image does not depend on the number of threads: bands are splatted in input order.
TEST(SurfaceSplatRasterizer, SameImageForOneAndTwoThreads)
{
  auto texture = [](double x, double y)
  { return glm::vec3(static_cast<float>(0.5 + 0.5 * std::sin(40.0 * x)), 0.3f,
      static_cast<float>(0.5 + 0.5 * std::cos(30.0 * y))); };
  const SurfelGrid grid(201, 201, 0.005, 0.005, 0.006, 0.006, texture);
  std::vector<splat::Light> lights(1);
  lights[0].Direction = glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f));
  splat::Material material;
  material.Specular = glm::vec3(0.3f);
  material.SpecularPower = 20.0f;

  std::vector<std::vector<std::uint8_t>> images;
  std::vector<std::vector<float>> depths;
  for (int threads : { 1, 2, 1 })
  {
    vtkSMPTools::Initialize(threads);
    ASSERT_EQ(vtkSMPTools::GetEstimatedNumberOfThreads(), threads);
    vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
    rasterizer->Render(grid.View(), FrontoParallelCamera(1.5, 300), lights, material);
    images.push_back(rasterizer->GetColors());
    depths.push_back(rasterizer->GetDepths());
  }
  EXPECT_TRUE(images[0] == images[1]);
  EXPECT_TRUE(images[0] == images[2]);
  EXPECT_TRUE(depths[0] == depths[1]);
}

// Two parallel translucent planes blend as eq. (12) says, whichever is splatted first.
TEST(SurfaceSplatRasterizer, TranslucentPlanesBlendInEitherOrder)
{
  const glm::vec3 frontColor(1.0f, 0.2f, 0.0f), backColor(0.0f, 0.4f, 1.0f);
  const float frontAlpha = 0.5f, backAlpha = 0.6f;
  const SurfelGrid plane(61, 0.01, glm::vec3(1.0f));
  // The expected premultiplied result over nothing: c_f a_f + c_b a_b (1 - a_f).
  const glm::vec3 expected =
    frontColor * frontAlpha + backColor * backAlpha * (1.0f - frontAlpha);
  const float expectedAlpha = frontAlpha + backAlpha * (1.0f - frontAlpha);

  for (bool frontFirst : { true, false })
  {
    SurfelGrid planes;
    for (bool front : { frontFirst, !frontFirst })
    {
      planes.AppendLayer(plane, front ? 0.1 : 0.0, front ? frontColor : backColor,
        front ? frontAlpha : backAlpha);
    }
    vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
    rasterizer->Render(planes.View(), FrontoParallelCamera(1.0, 64), {}, Unlit());
    const std::vector<std::uint8_t>& rgba = rasterizer->GetColors();
    for (int y = 16; y < 48; ++y)
    {
      for (int x = 16; x < 48; ++x)
      {
        const std::uint8_t* p = &rgba[4 * (static_cast<std::size_t>(y) * 64 + x)];
        for (int c = 0; c < 3; ++c)
        {
          ASSERT_NEAR(p[c] / 255.0, expected[c], 1.5 / 255.0)
            << (frontFirst ? "front first" : "back first") << ", pixel " << x << " " << y;
        }
        ASSERT_NEAR(p[3] / 255.0, expectedAlpha, 1.5 / 255.0);
      }
    }
  }
}

// More surfaces than layers: the two nearest in depth merge, and the result stays the
// front-to-back blend when the merged pair is adjacent.
TEST(SurfaceSplatRasterizer, MergesTheNearestFragmentsWhenLayersRunOut)
{
  const SurfelGrid plane(41, 0.01, glm::vec3(1.0f));
  const double depths[4] = { 0.0, 0.1, 0.12, 0.3 }; // the middle two are nearest
  const float alpha = 0.4f;
  const glm::vec3 layerColors[4] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 0, 0, 1 } };
  SurfelGrid planes;
  for (int layer = 3; layer >= 0; --layer) // back to front: the worst order for insertion
  {
    planes.AppendLayer(plane, depths[layer], layerColors[layer], alpha);
  }

  // Front to back: z = 0.3 (blue), 0.12 (blue), 0.1 (green), 0 (red).
  glm::vec4 expected(0.0f);
  for (int layer = 3; layer >= 0; --layer)
  {
    expected += (1.0f - expected.a) * glm::vec4(layerColors[layer] * alpha, alpha);
  }
  vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
  rasterizer->SetNumberOfLayers(3);
  rasterizer->Render(planes.View(), FrontoParallelCamera(1.0, 64), {}, Unlit());
  const std::uint8_t* p = &rasterizer->GetColors()[4 * (32 * 64 + 32)];
  for (int c = 0; c < 4; ++c)
  {
    EXPECT_NEAR(p[c] / 255.0, expected[c], 2.0 / 255.0) << "channel " << c;
  }
}

// Edge antialiasing: the silhouette of a splatted disk has intermediate alpha, the inside none.
TEST(SurfaceSplatRasterizer, DiskEdgeHasPartialCoverageOnly)
{
  SurfelGrid disk(81, 0.01, glm::vec3(1.0f));
  disk.Keep([](double x, double y) { return std::hypot(x, y) <= 0.3; });
  const int size = 200;
  const double distance = 2.0;
  const double pixelsPerUnit = PixelsPerUnit(distance, size);
  for (bool antialiasing : { true, false })
  {
    vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
    rasterizer->SetEdgeAntialiasing(antialiasing);
    rasterizer->Render(disk.View(), FrontoParallelCamera(distance, size), {}, Unlit());
    const std::vector<std::uint8_t>& rgba = rasterizer->GetColors();
    int partialInside = 0, partialAtEdge = 0;
    // The box of the covered pixels, which the compositor alone uploads and draws.
    int covered[4] = { size, size, -1, -1 };
    for (int y = 0; y < size; ++y)
    {
      for (int x = 0; x < size; ++x)
      {
        const double r = std::hypot(x + 0.5 - 0.5 * size, y + 0.5 - 0.5 * size) / pixelsPerUnit;
        const std::uint8_t a = rgba[4 * (static_cast<std::size_t>(y) * size + x) + 3];
        const bool partial = a > 0 && a < 255;
        partialInside += partial && r < 0.3 - 0.02;
        partialAtEdge += partial && r >= 0.3 - 0.02;
        if (a > 0)
        {
          covered[0] = std::min(covered[0], x);
          covered[1] = std::min(covered[1], y);
          covered[2] = std::max(covered[2], x);
          covered[3] = std::max(covered[3], y);
        }
      }
    }
    const int* region = rasterizer->GetCoveredRegion();
    EXPECT_TRUE(std::equal(covered, covered + 4, region))
      << region[0] << " " << region[1] << " " << region[2] << " " << region[3];
    // The disk's diameter, widened on each side by its splats' radius and the low-pass filter.
    EXPECT_NEAR(region[2] - region[0] + 1, 0.62 * pixelsPerUnit + 2.0, 3.0);
    EXPECT_EQ(partialInside, 0) << (antialiasing ? "with" : "without") << " antialiasing";
    if (antialiasing)
    {
      // The circumference is ~ 2 pi 0.3 * pixelsPerUnit pixels long.
      EXPECT_GT(partialAtEdge, 2.0 * M_PI * 0.3 * pixelsPerUnit);
    }
    else
    {
      EXPECT_EQ(partialAtEdge, 0);
    }
  }
}

// Data far from the origin renders like data at the origin: the setup runs in double precision
// relative to the eye, the per-pixel loop in single precision relative to each splat.
TEST(SurfaceSplatRasterizer, FarFromTheOriginRendersTheSame)
{
  auto texture = [](double x, double y)
  { return glm::vec3(static_cast<float>(0.5 + 0.4 * std::sin(60.0 * x)), 0.5f,
      static_cast<float>(0.5 + 0.4 * std::cos(45.0 * y))); };
  const SurfelGrid near(121, 121, 0.005, 0.005, 0.005, 0.005, texture);
  std::vector<splat::Light> lights(1);
  splat::Material material;
  material.Specular = glm::vec3(0.3f);
  material.SpecularPower = 20.0f;
  std::vector<std::uint8_t> images[2];
  for (int far = 0; far < 2; ++far)
  {
    const glm::dvec3 offset = far ? glm::dvec3(3.0e6, -2.0e6, 1.0e6) : glm::dvec3(0.0);
    SurfelGrid grid = near;
    for (std::size_t i = 0; i < grid.Positions.size(); ++i)
    {
      grid.Positions[i] += offset[i % 3];
    }
    vtkSurfaceSplatRasterizer::Camera camera = FrontoParallelCamera(1.0, 128);
    camera.ModelToEye = glm::lookAt(offset + glm::dvec3(0.2, 0.1, 1.0), offset,
      glm::dvec3(0.0, 1.0, 0.0));
    vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
    rasterizer->Render(grid.View(), camera, lights, material);
    images[far] = rasterizer->GetColors();
  }
  int differing = 0;
  for (std::size_t i = 0; i < images[0].size(); ++i)
  {
    ASSERT_LE(std::abs(images[0][i] - images[1][i]), 2) << "byte " << i;
    differing += images[0][i] != images[1][i];
  }
  EXPECT_LT(differing, static_cast<int>(images[0].size() / 100));
}

// Extreme splats: a screen-filling one right in front of the camera, one crossing the eye's
// plane and one with a radius of 1e-12 give finite, bounded work and no NaN pixel.
TEST(SurfaceSplatRasterizer, ExtremeSplatsStayFiniteAndBounded)
{
  SurfelGrid grid(3, 0.1, glm::vec3(0.8f));
  // 0: huge and close, 1: crossing z = camera plane, 2: microscopic.
  const double positions[3][3] = { { 0.0, 0.0, 1.5 }, { 0.0, 0.5, 2.0 }, { 0.1, 0.0, 0.0 } };
  const float radii[3] = { 1e3f, 5.0f, 1e-12f };
  for (int i = 0; i < 3; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      grid.Positions[3 * i + c] = positions[i][c];
    }
    grid.Axes0[3 * i] = radii[i];
    grid.Axes1[3 * i + 1] = radii[i];
  }
  grid.Normals[3 * 1 + 1] = 1.0f; // the crossing splat stands edge-on across the eye's plane
  grid.Normals[3 * 1 + 2] = 0.0f;
  grid.Axes1[3 * 1 + 1] = 0.0f;
  grid.Axes1[3 * 1 + 2] = 5.0f;
  vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
  const int size = 64;
  rasterizer->Render(grid.View(), FrontoParallelCamera(2.0, size), std::vector<splat::Light>(1),
    splat::Material());
  // Every pixel is written at most once per splat.
  EXPECT_LE(rasterizer->GetFragmentCount(), static_cast<vtkIdType>(9) * size * size);
  for (float depth : rasterizer->GetDepths())
  {
    ASSERT_TRUE(depth >= 0.0f && depth <= 1.0f);
  }
  int covered = 0;
  for (std::size_t pixel = 0; pixel < rasterizer->GetColors().size() / 4; ++pixel)
  {
    covered += rasterizer->GetColors()[4 * pixel + 3] > 0;
  }
  EXPECT_EQ(covered, size * size); // the screen-filling splat covers everything
}
