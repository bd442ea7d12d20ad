// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the CPU rasterizer's minified splats (vtkSurfaceSplatRasterizer::
// SetMinifiedVariance): summed per pixel and spread by the low-pass filter once per pixel, they
// stay within a stated error of the exact per-splat kernels, keep antialiased silhouettes against
// the background and against another surface, and give the same image for any number of threads;
// under a pixel's box filter (surfels of one color) each draws its own kernel instead.
#include "SplatRasterizerTestUtilities.h"
#include "vtkSurfaceSplatRasterizer.h"
#include "vtkSurfelHierarchy.h"

#include "vtkNew.h"
#include "vtkSMPTools.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace splat_test;

namespace
{
constexpr int Size = 256;

// n surfels on a sphere (Fibonacci sampling) of the given radius and center, radial normals,
// circular with radius = the sampling spacing, colored by position.
SurfelGrid SurfelSphere(int n, double radius, const glm::dvec3& center)
{
  SurfelGrid sphere;
  const double spacing = radius * std::sqrt(4.0 * M_PI / n);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double r = std::sqrt(1.0 - z * z);
    const glm::dvec3 normal(r * std::cos(golden * i), r * std::sin(golden * i), z);
    glm::dvec3 t0, t1;
    splat::TangentFrame(normal, t0, t1);
    const glm::dvec3 p = center + radius * normal;
    const glm::vec3 color = glm::vec3(0.5 + 0.5 * normal);
    for (int c = 0; c < 3; ++c)
    {
      sphere.Positions.push_back(p[c]);
      sphere.Normals.push_back(static_cast<float>(normal[c]));
      sphere.Axes0.push_back(static_cast<float>(spacing * t0[c]));
      sphere.Axes1.push_back(static_cast<float>(spacing * t1[c]));
      sphere.Colors.push_back(color[c]);
    }
  }
  return sphere;
}

// Surfels of one color on a sphere of the given radius, centered at the origin, sampled as
// vtkSphereSource tessellates it (`rings` of latitude, as many meridians), each circular with
// the radius of the longest edge at its vertex, the diagonal of its cell, as vtkSurfelGenerator
// gives a mesh's vertices.
SurfelGrid LatitudeLongitudeSphere(int rings, double radius)
{
  SurfelGrid sphere;
  const double step = M_PI / rings;
  for (int i = 1; i < rings; ++i)
  {
    const double theta = i * step;
    for (int j = 0; j < rings; ++j)
    {
      const double phi = 2.0 * j * step;
      const glm::dvec3 normal(
        std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      glm::dvec3 t0, t1;
      splat::TangentFrame(normal, t0, t1);
      const double reach = radius * step * std::sqrt(1.0 + 4.0 * std::pow(std::sin(theta), 2));
      for (int c = 0; c < 3; ++c)
      {
        sphere.Positions.push_back(radius * normal[c]);
        sphere.Normals.push_back(static_cast<float>(normal[c]));
        sphere.Axes0.push_back(static_cast<float>(reach * t0[c]));
        sphere.Axes1.push_back(static_cast<float>(reach * t1[c]));
        sphere.Colors.push_back(0.8f);
      }
    }
  }
  return sphere;
}

void Append(SurfelGrid& to, const SurfelGrid& from)
{
  to.Positions.insert(to.Positions.end(), from.Positions.begin(), from.Positions.end());
  for (auto member : { &SurfelGrid::Normals, &SurfelGrid::Axes0, &SurfelGrid::Axes1,
         &SurfelGrid::Colors })
  {
    (to.*member).insert((to.*member).end(), (from.*member).begin(), (from.*member).end());
  }
}

struct Frame
{
  std::vector<std::uint8_t> Colors;
  vtkIdType Splatted = 0;
  vtkIdType Minified = 0;
  vtkIdType Merged = 0;
  vtkIdType Hidden = 0;
};

enum class Path
{
  Exact,        // every splat with its own kernel
  Minified,     // the default settings: minified splats summed per pixel
  LevelOfDetail // and the surfels' hierarchy, as vtkSurfaceSplatMapper draws them
};

const char* Name(Path path)
{
  return path == Path::Exact ? "exact" : path == Path::Minified ? "minified" : "level of detail";
}

// `minifiedLowPass` below 1: minified splats are drawn each with its kernel, not summed.
// `cutoff` and `coverageThreshold` as the rasterizer's.
Frame Draw(const SurfelGrid& surfels, const vtkSurfaceSplatRasterizer::Camera& camera, Path path,
  double minifiedLowPass = 1.0, double cutoff = 1.0,
  double coverageThreshold = splat::PaperCoverageThreshold)
{
  std::vector<splat::Light> lights(1);
  lights[0].Direction = glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f));
  splat::Material material;
  material.Specular = glm::vec3(0.3f);
  material.SpecularPower = 20.0f;
  vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
  // One layer count for every path: automatic layers differ between minified and exact frames.
  rasterizer->SetNumberOfLayers(vtkSurfaceSplatRasterizer::PaperLayers);
  rasterizer->SetMinifiedLowPassVariance(minifiedLowPass);
  rasterizer->SetCutoff(cutoff);
  rasterizer->SetCoverageThreshold(coverageThreshold);
  if (path == Path::Exact)
  {
    rasterizer->SetMinifiedVariance(0.0);
  }
  vtkSurfaceSplatRasterizer::Surfels view = surfels.View();
  vtkNew<vtkSurfelHierarchy> hierarchy;
  if (path == Path::LevelOfDetail)
  {
    hierarchy->Build(view);
    view.Hierarchy = hierarchy;
  }
  rasterizer->Render(view, camera, lights, material);
  return { rasterizer->GetColors(), rasterizer->GetSplattedCount(),
    rasterizer->GetMinifiedCount(), rasterizer->GetMergedCount(), rasterizer->GetHiddenCount() };
}

// Root mean square difference of channel `channel` (0..3) over the pixels where `where` holds.
template <typename Predicate>
double RMSE(const Frame& a, const Frame& b, int channel, Predicate where)
{
  double squared = 0.0;
  std::size_t count = 0;
  for (std::size_t pixel = 0; 4 * pixel < a.Colors.size(); ++pixel)
  {
    if (where(pixel))
    {
      const double d = (a.Colors[4 * pixel + channel] - b.Colors[4 * pixel + channel]) / 255.0;
      squared += d * d;
      ++count;
    }
  }
  return count ? std::sqrt(squared / count) : 0.0;
}

double ColorRMSE(const Frame& a, const Frame& b)
{
  double sum = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    sum += std::pow(RMSE(a, b, c, [](std::size_t) { return true; }), 2);
  }
  return std::sqrt(sum / 3.0);
}

// Pixels that are partly covered: the antialiased silhouette.
std::size_t PartlyCovered(const Frame& frame)
{
  std::size_t count = 0;
  for (std::size_t pixel = 0; 4 * pixel < frame.Colors.size(); ++pixel)
  {
    const std::uint8_t alpha = frame.Colors[4 * pixel + 3];
    count += alpha > 0 && alpha < 255;
  }
  return count;
}

// The radius in pixels of the disk whose area is the frame's summed coverage.
double CoveredRadius(const Frame& frame)
{
  double area = 0.0;
  for (std::size_t pixel = 0; 4 * pixel < frame.Colors.size(); ++pixel)
  {
    area += frame.Colors[4 * pixel + 3] / 255.0;
  }
  return std::sqrt(area / M_PI);
}

// The silhouette's radius in pixels of a sphere of radius r at distance d from a
// FrontoParallelCamera.
double SilhouetteRadius(double r, double d)
{
  return PixelsPerUnit(d, Size) * d * r / std::sqrt(d * d - r * r);
}

}

// A sphere of sub-pixel splats (about 0.45 pixels apart) renders within the stated RMSE of the
// exact kernels, and its silhouette against the background keeps its partial coverage: more
// partly covered pixels than the silhouette's circumference, and the covered area, drawn either
// way, within half a pixel of radius of the true silhouette. (It lay 1.5 pixels inside while the
// slivers of the grazing splats' fringe, at depths far off the surface, could push the
// surface's own fragments out of the layers: splat::OpaqueSlot.)
TEST(MinifiedSplats, SphereOfSubpixelSplatsMatchesTheExactKernels)
{
  const SurfelGrid sphere = SurfelSphere(400000, 0.3, glm::dvec3(0.0));
  const vtkSurfaceSplatRasterizer::Camera camera = FrontoParallelCamera(1.8, Size);
  const Frame exact = Draw(sphere, camera, Path::Exact);
  EXPECT_EQ(exact.Minified, 0);
  for (const Path path : { Path::Minified, Path::LevelOfDetail })
  {
    const Frame minified = Draw(sphere, camera, path);
    EXPECT_GT(minified.Minified, 0.99 * minified.Splatted);
    if (path == Path::Minified)
    {
      EXPECT_EQ(minified.Splatted, exact.Splatted);
    }
    else
    {
      // Merged nodes 0.9 pixels apart, the surfels themselves at grazing angles: under 40% of
      // the splats; and of the back half, the regions that the front half hides left out.
      EXPECT_GT(minified.Merged, 0.85 * 400000);
      EXPECT_LT(minified.Splatted, 0.4 * exact.Splatted);
      EXPECT_GT(minified.Hidden, 0.2 * minified.Splatted);
    }
    const double color = ColorRMSE(exact, minified);
    const double alpha = RMSE(exact, minified, 3, [](std::size_t) { return true; });
    const std::size_t edgeExact = PartlyCovered(exact);
    const std::size_t edgeMinified = PartlyCovered(minified);
    const double radius = SilhouetteRadius(0.3, 1.8);
    const double radiusExact = CoveredRadius(exact);
    const double radiusMinified = CoveredRadius(minified);
    std::printf("sphere, %s: %lld splats (%lld hidden), color RMSE %.4f, alpha RMSE %.4f, "
                "partly covered pixels %zu (exact %zu), covered radius %.2f (exact %.2f, true "
                "%.2f)\n",
      Name(path), static_cast<long long>(minified.Splatted),
      static_cast<long long>(minified.Hidden), color, alpha, edgeMinified, edgeExact,
      radiusMinified, radiusExact, radius);
    EXPECT_LT(color, 0.015);
    EXPECT_LT(alpha, 0.06);
    EXPECT_GT(edgeExact, 2.0 * M_PI * radius);
    EXPECT_GT(edgeMinified, 2.0 * M_PI * radius);
    // Merged nodes leave the silhouette a little wider than the per-pixel sums do; drawn by
    // merged nodes alone, without the surfels at grazing angles, it is ragged (8 times).
    EXPECT_LT(edgeMinified, (path == Path::Minified ? 2.0 : 2.5) * edgeExact);
    EXPECT_NEAR(radiusMinified, radius, 0.5);
    EXPECT_NEAR(radiusExact, radius, 0.5);
  }
}

// Under a pixel's box filter for minified splats (surfels of one color), the minified path
// draws each splat's kernel from its single-precision setup instead of summing it: the image of
// the exact kernels' double-precision setup, with a sharper silhouette than the unit low-pass
// draws, still partly covered.
TEST(MinifiedSplats, BoxFilteredSplatsMatchTheExactKernels)
{
  const SurfelGrid sphere = SurfelSphere(400000, 0.3, glm::dvec3(0.0));
  const vtkSurfaceSplatRasterizer::Camera camera = FrontoParallelCamera(1.8, Size);
  const double box = splat::BoxFilterVariance;
  const Frame exact = Draw(sphere, camera, Path::Exact, box);
  const Frame summed = Draw(sphere, camera, Path::Minified);
  for (const Path path : { Path::Minified, Path::LevelOfDetail })
  {
    const Frame filtered = Draw(sphere, camera, path, box);
    EXPECT_EQ(filtered.Minified, 0);
    // The level of detail draws fewer: merged nodes, and the back half mostly hidden.
    EXPECT_GT(filtered.Splatted, 0.2 * exact.Splatted);
    const double color = ColorRMSE(exact, filtered);
    const double alpha = RMSE(exact, filtered, 3, [](std::size_t) { return true; });
    const std::size_t edgeExact = PartlyCovered(exact);
    const std::size_t edge = PartlyCovered(filtered);
    const std::size_t edgeSummed = PartlyCovered(summed);
    std::printf("sphere, box-filtered, %s: color RMSE %.5f, alpha RMSE %.5f against the exact "
                "kernels; partly covered pixels %zu (exact %zu, summed %zu)\n",
      Name(path), color, alpha, edge, edgeExact, edgeSummed);
    EXPECT_LT(color, path == Path::Minified ? 0.003 : 0.015);
    EXPECT_LT(alpha, path == Path::Minified ? 0.003 : 0.03);
    EXPECT_GT(edge, SilhouetteRadius(0.3, 1.8));
    EXPECT_LT(edge, 0.75 * edgeSummed);
    EXPECT_NEAR(CoveredRadius(filtered), SilhouetteRadius(0.3, 1.8), 0.5);
  }
}

// The surfels of a tessellated sphere, drawn with the settings vtkSurfaceSplatMapper picks for
// surfels of one color: the box filter, cutoff 0.5, coverage threshold 0.8. Merged nodes leave
// the sphere's summed weight dipping below full coverage in a few percent of its interior
// pixels. Those dips are closed before the back half is tested, so that most of it is found
// hidden and left out (38 % of the splats; 15 % while the dips stayed open), the interior stays
// opaque, and the image stays that of the exact kernels.
TEST(MinifiedSplats, HierarchyClosesCoverageDipsAndHidesTheBackHalf)
{
  const SurfelGrid sphere = LatitudeLongitudeSphere(500, 0.3);
  const vtkSurfaceSplatRasterizer::Camera camera = FrontoParallelCamera(1.8, Size);
  const double box = splat::BoxFilterVariance;
  const double tau = splat::BoxFilterCoverageThreshold;
  const Frame exact = Draw(sphere, camera, Path::Exact, box, 0.5, tau);
  const Frame merged = Draw(sphere, camera, Path::LevelOfDetail, box, 0.5, tau);
  // Interior pixels, two pixels inside the silhouette, that are not opaque.
  const double radius = SilhouetteRadius(0.3, 1.8) - 2.0;
  std::size_t open = 0;
  for (int y = 0; y < Size; ++y)
  {
    for (int x = 0; x < Size; ++x)
    {
      const double dx = x + 0.5 - 0.5 * Size;
      const double dy = y + 0.5 - 0.5 * Size;
      open += dx * dx + dy * dy < radius * radius &&
        merged.Colors[4 * (static_cast<std::size_t>(y) * Size + x) + 3] < 255;
    }
  }
  const double color = ColorRMSE(exact, merged);
  std::printf("sphere, level of detail under the box filter: %lld splats, %lld hidden, %zu "
              "interior pixels not opaque, color RMSE %.4f against the exact kernels\n",
    static_cast<long long>(merged.Splatted), static_cast<long long>(merged.Hidden), open, color);
  EXPECT_GT(merged.Hidden, 0.3 * (merged.Splatted + merged.Hidden));
  EXPECT_EQ(open, 0u);
  EXPECT_LT(color, 0.015);
}

// A grid of surfels 1.3 times as wide as its spacing, under the box filter at cutoff 0.5 and
// coverage threshold 0.8: its summed weight dips below full coverage between the disks, in
// spots and in lines of a few pixels. Seen head-on or at a grazing 80 degrees, where a pixel
// spans more than four pixel widths of depth, those dips close: no pixel three pixels inside
// the covered area stays partly transparent. (With three passes and a dip's neighbors within
// four pixel widths of its depth, rather than on a line through it, 3.3 % stayed open head-on
// and 1.5 % at 80 degrees.)
TEST(MinifiedSplats, CoverageDipsCloseOnSteepSurfaces)
{
  const double h = 0.01;
  const double radius = 1.3 * h;
  const SurfelGrid grid(
    300, 300, h, h, radius, radius, [](double, double) { return glm::vec3(0.8f); });
  for (const double degrees : { 0.0, 80.0 })
  {
    const double angle = glm::radians(degrees);
    const double distance = 1.8;
    vtkSurfaceSplatRasterizer::Camera camera = FrontoParallelCamera(distance, Size);
    camera.ModelToEye = glm::lookAt(
      distance * glm::dvec3(0.0, -std::sin(angle), std::cos(angle)), glm::dvec3(0.0),
      glm::dvec3(0.0, std::cos(angle), std::sin(angle)));
    const Frame frame = Draw(grid, camera, Path::Exact, splat::BoxFilterVariance, 0.5,
      splat::BoxFilterCoverageThreshold);
    auto alpha = [&](int x, int y)
    { return frame.Colors[4 * (static_cast<std::size_t>(y) * Size + x) + 3]; };
    constexpr int Inside = 3;
    std::size_t interior = 0;
    std::size_t open = 0;
    for (int y = Inside; y < Size - Inside; ++y)
    {
      for (int x = Inside; x < Size - Inside; ++x)
      {
        bool covered = true;
        for (int dy = -Inside; dy <= Inside && covered; ++dy)
        {
          for (int dx = -Inside; dx <= Inside && covered; ++dx)
          {
            covered = alpha(x + dx, y + dy) > 0;
          }
        }
        interior += covered;
        open += covered && alpha(x, y) < 255;
      }
    }
    std::printf("grid at %.0f degrees, cutoff 0.5, coverage threshold 0.8: %zu of %zu interior "
                "pixels partly transparent\n",
      degrees, open, interior);
    EXPECT_GT(interior, Size * Size / 8);
    EXPECT_EQ(open, 0u);
  }
}

// Where a block of the hierarchy may hold a silhouette, its splats are listed front to back: a
// pixel's fragments take contributions in the order they come, and back splats that came first
// took the rim's fragments, turning their filtered normals edge-on (dark dots along the
// silhouette). Along the list, consecutive splats near the silhouette then come at increasing
// depths but where one block ends (99.5 %); in Morton order, 77 % did.
TEST(MinifiedSplats, HierarchyListsSilhouettesFrontToBack)
{
  const SurfelGrid sphere = SurfelSphere(400000, 0.3, glm::dvec3(0.0));
  const double distance = 1.8;
  vtkNew<vtkSurfelHierarchy> hierarchy;
  hierarchy->Build(sphere.View());
  std::vector<std::uint32_t> items;
  std::vector<vtkSurfelHierarchy::BackRegion> backRegions;
  ASSERT_GT(hierarchy->Select(FrontoParallelCamera(distance, Size), 0.75, items, backRegions), 0);
  const vtkSurfaceSplatRasterizer::Surfels nodes = hierarchy->GetNodes();
  const glm::dvec3 eye(0.0, 0.0, distance);
  // The eye depth of a splat within 5 degrees of the silhouette, or a negative number.
  auto silhouetteDepth = [&](std::uint32_t item)
  {
    const glm::dvec3 p(nodes.Positions[3 * item], nodes.Positions[3 * item + 1],
      nodes.Positions[3 * item + 2]);
    const glm::dvec3 n(
      nodes.Normals[3 * item], nodes.Normals[3 * item + 1], nodes.Normals[3 * item + 2]);
    const glm::dvec3 view = p - eye;
    const double cosine = glm::dot(n, view) / (glm::length(n) * glm::length(view));
    return std::abs(cosine) < std::sin(glm::radians(5.0)) ? distance - p.z : -1.0;
  };
  std::size_t pairs = 0;
  std::size_t ordered = 0;
  for (std::size_t k = 1; k < items.size(); ++k)
  {
    const double previous = silhouetteDepth(items[k - 1]);
    const double next = silhouetteDepth(items[k]);
    if (previous >= 0.0 && next >= 0.0)
    {
      ++pairs;
      ordered += next >= previous;
    }
  }
  std::printf("sphere, level of detail: %zu of %zu consecutive splats near the silhouette "
              "front to back\n",
    ordered, pairs);
  EXPECT_GT(pairs, 1000);
  EXPECT_GT(ordered, 0.95 * pairs);
}

// The same sphere in front of a plane of minified splats: where its silhouette crosses the
// plane, pixels blend the two surfaces as the exact kernels do.
TEST(MinifiedSplats, SilhouetteAgainstAnotherSurfaceStaysAntialiased)
{
  SurfelGrid scene = SurfelSphere(400000, 0.3, glm::dvec3(0.0));
  Append(scene, SurfelGrid(601, 0.0025, glm::vec3(1.0f, 0.9f, 0.1f)));
  for (std::size_t i = scene.Positions.size() - 3 * 601 * 601; i < scene.Positions.size();
       i += 3)
  {
    scene.Positions[i + 2] = -0.5; // the plane behind the sphere
  }
  const vtkSurfaceSplatRasterizer::Camera camera = FrontoParallelCamera(1.8, Size);
  const Frame exact = Draw(scene, camera, Path::Exact);
  for (const Path path : { Path::Minified, Path::LevelOfDetail })
  {
    const Frame minified = Draw(scene, camera, path);
    EXPECT_GT(minified.Minified, 0.99 * minified.Splatted);
    EXPECT_EQ(minified.Merged > 0, path == Path::LevelOfDetail);
    // The silhouette: pixels between 0.9 and 1.1 sphere radii from the image center.
    const double radius = SilhouetteRadius(0.3, 1.8);
    auto ring = [radius](std::size_t pixel)
    {
      const double x = pixel % Size + 0.5 - 0.5 * Size;
      const double y = pixel / Size + 0.5 - 0.5 * Size;
      const double r = std::sqrt(x * x + y * y);
      return r > 0.9 * radius && r < 1.1 * radius;
    };
    double ringColor = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      ringColor += std::pow(RMSE(exact, minified, c, ring), 2);
    }
    ringColor = std::sqrt(ringColor / 3.0);
    // Blended pixels: blue well below the sphere's and well above the plane's (0.1).
    auto blended = [](const Frame& frame, std::size_t pixel)
    {
      const int blue = frame.Colors[4 * pixel + 2];
      return blue > 60 && blue < 110;
    };
    std::size_t blendedExact = 0, blendedMinified = 0;
    for (std::size_t pixel = 0; pixel < static_cast<std::size_t>(Size) * Size; ++pixel)
    {
      blendedExact += ring(pixel) && blended(exact, pixel);
      blendedMinified += ring(pixel) && blended(minified, pixel);
    }
    std::printf("silhouette over a plane, %s: color RMSE %.4f in the ring, blended pixels %zu "
                "(exact %zu), color RMSE %.4f overall\n",
      Name(path), ringColor, blendedMinified, blendedExact, ColorRMSE(exact, minified));
    // Pixel by pixel the antialiased edges differ by up to about one pixel's coverage.
    EXPECT_LT(ringColor, 0.12);
    EXPECT_GT(blendedExact, 50u);
    EXPECT_GT(blendedMinified, 0.6 * blendedExact);
  }
}

// A checkerboard plane seen at a grazing angle: splats near the camera keep their exact
// kernels, those towards the horizon are minified; the image stays within the
// stated RMSE of the exact one, where the checks have blurred to gray as EWA prescribes.
TEST(MinifiedSplats, CheckerboardAtTheHorizonMatchesTheExactKernels)
{
  const double h = 0.004;
  auto checks = [](double x, double y)
  {
    const bool odd = (static_cast<int>(std::floor(x / 0.05)) + static_cast<int>(std::floor(y / 0.05))) % 2;
    return odd ? glm::vec3(0.9f) : glm::vec3(0.1f);
  };
  const SurfelGrid plane(501, 501, h, h, h, h, checks);
  vtkSurfaceSplatRasterizer::Camera camera;
  camera.ModelToEye =
    glm::lookAt(glm::dvec3(0.0, -1.3, 0.1), glm::dvec3(0.0, 0.5, 0.0), glm::dvec3(0.0, 0.0, 1.0));
  camera.EyeToClip = glm::perspective(glm::radians(40.0), 1.0, 0.01, 10.0);
  camera.Viewport = glm::ivec2(Size, Size);
  const Frame exact = Draw(plane, camera, Path::Exact);
  for (const Path path : { Path::Minified, Path::LevelOfDetail })
  {
    const Frame minified = Draw(plane, camera, path);
    EXPECT_GT(minified.Minified, 0.2 * minified.Splatted);
    EXPECT_LT(minified.Minified, 0.9 * minified.Splatted);
    const double color = ColorRMSE(exact, minified);
    std::printf("checkerboard, %s: %lld of %lld splats minified, %lld surfels merged, color "
                "RMSE %.4f\n",
      Name(path), static_cast<long long>(minified.Minified),
      static_cast<long long>(minified.Splatted), static_cast<long long>(minified.Merged), color);
    EXPECT_LT(color, 0.02);
  }
}

// A bowl (a hemisphere seen from its open side, tilted): its inside faces away from the eye
// and nothing hides it, so no region of it is left out: the level of detail draws it as the
// summed minified splats do, and those as the exact kernels do.
TEST(MinifiedSplats, VisibleBackFacesAreNotHidden)
{
  SurfelGrid bowl = SurfelSphere(400000, 0.3, glm::dvec3(0.0));
  std::size_t kept = 0;
  for (std::size_t i = 0; i < bowl.Normals.size() / 3; ++i)
  {
    if (bowl.Normals[3 * i + 2] < 0.0f)
    {
      for (auto member : { &SurfelGrid::Normals, &SurfelGrid::Axes0, &SurfelGrid::Axes1,
             &SurfelGrid::Colors })
      {
        std::copy_n((bowl.*member).begin() + 3 * i, 3, (bowl.*member).begin() + 3 * kept);
      }
      std::copy_n(bowl.Positions.begin() + 3 * i, 3, bowl.Positions.begin() + 3 * kept);
      ++kept;
    }
  }
  for (auto member : { &SurfelGrid::Normals, &SurfelGrid::Axes0, &SurfelGrid::Axes1,
         &SurfelGrid::Colors })
  {
    (bowl.*member).resize(3 * kept);
  }
  bowl.Positions.resize(3 * kept);
  vtkSurfaceSplatRasterizer::Camera camera;
  camera.ModelToEye =
    glm::lookAt(glm::dvec3(0.0, 0.8, 1.5), glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
  camera.EyeToClip = glm::perspective(glm::radians(30.0), 1.0, 0.1, 10.0);
  camera.Viewport = glm::ivec2(Size, Size);
  const Frame exact = Draw(bowl, camera, Path::Exact);
  const Frame minified = Draw(bowl, camera, Path::Minified);
  const Frame detail = Draw(bowl, camera, Path::LevelOfDetail);
  const double color = ColorRMSE(minified, detail);
  const double alpha = RMSE(minified, detail, 3, [](std::size_t) { return true; });
  const double colorExact = ColorRMSE(exact, minified);
  const double alphaExact = RMSE(exact, minified, 3, [](std::size_t) { return true; });
  std::printf("bowl: %lld of %lld surfels merged, %lld splats hidden, color RMSE %.4f, alpha "
              "RMSE %.4f against the summed minified splats (%lld hidden), which are within "
              "%.4f and %.4f of the exact kernels\n",
    static_cast<long long>(detail.Merged), static_cast<long long>(kept),
    static_cast<long long>(detail.Hidden), color, alpha,
    static_cast<long long>(minified.Hidden), colorExact, alphaExact);
  EXPECT_GT(detail.Merged, 0.5 * kept);
  EXPECT_EQ(detail.Hidden, 0);
  EXPECT_LT(color, 0.015);
  EXPECT_LT(alpha, 0.03);
  EXPECT_LT(colorExact, 0.015);
  EXPECT_LT(alphaExact, 0.06);
}

// The minified splats' sums do not depend on the number of threads.
TEST(MinifiedSplats, SameImageForOneAndTwoThreads)
{
  const SurfelGrid sphere = SurfelSphere(100000, 0.3, glm::dvec3(0.0));
  for (const Path path : { Path::Minified, Path::LevelOfDetail })
  {
    std::vector<Frame> frames;
    for (int threads : { 1, 2 })
    {
      vtkSMPTools::Initialize(threads);
      frames.push_back(Draw(sphere, FrontoParallelCamera(3.0, Size), path));
    }
    EXPECT_GT(frames[0].Minified, 0.9 * frames[0].Splatted);
    EXPECT_EQ(frames[0].Merged > 0, path == Path::LevelOfDetail);
    EXPECT_TRUE(frames[0].Colors == frames[1].Colors) << Name(path);
  }
}

// Translucent splats always take the exact kernels.
TEST(MinifiedSplats, TranslucentSplatsAreNotMinified)
{
  SurfelGrid sphere = SurfelSphere(100000, 0.3, glm::dvec3(0.0));
  sphere.Opacities.assign(100000, 0.5f);
  const Frame frame = Draw(sphere, FrontoParallelCamera(3.0, Size), Path::Minified);
  EXPECT_GT(frame.Splatted, 0);
  EXPECT_EQ(frame.Minified, 0);
}

// Automatic layers: the paper's 3 where minified splats each draw their own kernel (slices of
// a grazing surface would fill more) and where opaque EWA splats are magnified well past a
// pixel, 5 in other frames, 1 for an opaque frame without edge antialiasing; a count set by
// hand holds everywhere.
TEST(MinifiedSplats, AutomaticLayersFollowTheFramesPath)
{
  const SurfelGrid grid = SurfelSphere(100000, 0.3, glm::dvec3(0.0));
  const vtkSurfaceSplatRasterizer::Surfels sphere = grid.View();
  const vtkSurfaceSplatRasterizer::Camera camera = FrontoParallelCamera(1.8, Size);
  const std::vector<splat::Light> lights(1);
  const splat::Material material;
  vtkNew<vtkSurfaceSplatRasterizer> rasterizer;
  EXPECT_EQ(rasterizer->GetNumberOfLayers(), 0);
  auto layersOf = [&]()
  {
    rasterizer->Render(sphere, camera, lights, material);
    return rasterizer->GetLastNumberOfLayers();
  };
  rasterizer->SetMinifiedLowPassVariance(splat::BoxFilterVariance);
  EXPECT_EQ(layersOf(), vtkSurfaceSplatRasterizer::PaperLayers);
  EXPECT_GT(rasterizer->GetSplattedCount(), 0);
  rasterizer->SetMinifiedLowPassVariance(1.0); // minified splats summed per pixel
  EXPECT_EQ(layersOf(), vtkSurfaceSplatRasterizer::AutomaticLayers);
  EXPECT_GT(rasterizer->GetMinifiedCount(), 0);
  rasterizer->SetMinifiedLowPassVariance(splat::BoxFilterVariance);
  rasterizer->SetMinifiedVariance(0.0); // every splat its exact kernel
  EXPECT_EQ(layersOf(), vtkSurfaceSplatRasterizer::AutomaticLayers);
  rasterizer->SetEdgeAntialiasing(false);
  EXPECT_EQ(layersOf(), 1);
  rasterizer->SetEdgeAntialiasing(true);
  rasterizer->SetMinifiedVariance(0.75);
  rasterizer->SetNumberOfLayers(2);
  EXPECT_EQ(layersOf(), 2);

  // 200 surfels on the same sphere: splats about 20 pixels wide.
  SurfelGrid few = SurfelSphere(200, 0.3, glm::dvec3(0.0));
  rasterizer->SetNumberOfLayers(0);
  auto magnifiedLayers = [&]()
  {
    rasterizer->Render(few.View(), camera, lights, material);
    EXPECT_EQ(rasterizer->GetMinifiedCount(), 0);
    return rasterizer->GetLastNumberOfLayers();
  };
  EXPECT_EQ(magnifiedLayers(), vtkSurfaceSplatRasterizer::PaperLayers);
  rasterizer->SetFilter(splat::KernelFilter::Circular);
  EXPECT_EQ(magnifiedLayers(), vtkSurfaceSplatRasterizer::AutomaticLayers);
  rasterizer->SetFilter(splat::KernelFilter::EWA);
  few.Opacities.assign(200, 0.5f);
  EXPECT_EQ(magnifiedLayers(), vtkSurfaceSplatRasterizer::AutomaticLayers);
}
