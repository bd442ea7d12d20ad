// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of vtkSurfelHierarchy, the CPU backend's levels of detail: every level keeps the
// surfels' mass, mean color and first moments; the two sides of a thin plate never merge; the
// selection follows the camera's distance and draws each surfel once; degenerate input gets
// level 0 only.
#include "SplatRasterizerTestUtilities.h"
#include "vtkSurfelHierarchy.h"

#include "vtkNew.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace splat_test;

namespace
{
// Node `node` of the hierarchy: its mass (area) and its mass-weighted position and color.
struct NodeMass
{
  double Mass;
  glm::dvec3 Position;
  glm::dvec3 Color;
};

NodeMass MassOf(const vtkSurfelHierarchy* hierarchy, std::size_t node)
{
  const vtkSurfaceSplatRasterizer::Surfels merged = hierarchy->GetNodes();
  const glm::dvec3 a0(
    merged.Axes0[3 * node], merged.Axes0[3 * node + 1], merged.Axes0[3 * node + 2]);
  const glm::dvec3 a1(
    merged.Axes1[3 * node], merged.Axes1[3 * node + 1], merged.Axes1[3 * node + 2]);
  const double mass = hierarchy->GetMassScales()[node] * glm::length(glm::cross(a0, a1));
  const double* p = merged.Positions + 3 * node;
  const float* c = merged.Colors + 3 * node;
  return { mass, mass * glm::dvec3(p[0], p[1], p[2]), mass * glm::dvec3(c[0], c[1], c[2]) };
}

// A fronto-parallel camera at distance d from the plane z = 0 (looking down -z).
vtkSurfaceSplatRasterizer::Camera CameraAt(double d, int size)
{
  vtkSurfaceSplatRasterizer::Camera camera;
  camera.ModelToEye = glm::lookAt(glm::dvec3(0.0, 0.0, d), glm::dvec3(0.0), glm::dvec3(0, 1, 0));
  camera.EyeToClip = glm::perspective(glm::radians(30.0), 1.0, 0.01, 100.0);
  camera.Viewport = glm::ivec2(size, size);
  return camera;
}
}

// Every level of a colored plane, level 0 (the sorted copy of the surfels) included, keeps the
// total mass, the center of mass and the mean color.
TEST(SurfelHierarchy, LevelsKeepMassCenterAndColor)
{
  const SurfelGrid plane(256, 256, 0.01, 0.01, 0.01, 0.01,
    [](double x, double y) { return glm::vec3(0.5 + x, 0.5 + y, 0.25); });
  vtkNew<vtkSurfelHierarchy> hierarchy;
  hierarchy->Build(plane.View());
  ASSERT_GT(hierarchy->GetNumberOfLevels(), 3);
  NodeMass surfels{ 0.0, glm::dvec3(0.0), glm::dvec3(0.0) };
  for (std::size_t i = 0; i < plane.Normals.size() / 3; ++i)
  {
    const double area = 0.01 * 0.01;
    surfels.Mass += area;
    surfels.Position += area * glm::dvec3(plane.Positions[3 * i], plane.Positions[3 * i + 1], 0.0);
    surfels.Color +=
      area * glm::dvec3(plane.Colors[3 * i], plane.Colors[3 * i + 1], plane.Colors[3 * i + 2]);
  }
  std::size_t node = 0;
  for (int level = 0; level < hierarchy->GetNumberOfLevels(); ++level)
  {
    const vtkIdType nodes = hierarchy->GetNumberOfNodes(level);
    if (level > 0)
    {
      EXPECT_LT(nodes, hierarchy->GetNumberOfNodes(level - 1)) << "level " << level;
    }
    NodeMass sum{ 0.0, glm::dvec3(0.0), glm::dvec3(0.0) };
    for (vtkIdType j = 0; j < nodes; ++j, ++node)
    {
      const NodeMass m = MassOf(hierarchy, node);
      sum.Mass += m.Mass;
      sum.Position += m.Position;
      sum.Color += m.Color;
    }
    EXPECT_NEAR(sum.Mass / surfels.Mass, 1.0, 1e-5) << "level " << level;
    EXPECT_LT(glm::length(sum.Position - surfels.Position) / surfels.Mass, 1e-6);
    EXPECT_LT(glm::length(sum.Color - surfels.Color) / surfels.Mass, 1e-5);
  }
  EXPECT_EQ(node, hierarchy->GetNodes().Count);
}

// A plate of two sides 1e-4 apart with opposite normals: no node mixes them, so every merged
// normal is +z or -z and both sides keep the same number of nodes at every level.
TEST(SurfelHierarchy, SidesOfAThinPlateNeverMerge)
{
  SurfelGrid plate(128, 0.01, glm::vec3(1.0f));
  const std::size_t n = plate.Normals.size() / 3;
  for (std::size_t i = 0; i < n; ++i)
  {
    plate.Positions.insert(
      plate.Positions.end(), { plate.Positions[3 * i], plate.Positions[3 * i + 1], -1e-4 });
    plate.Normals.insert(plate.Normals.end(), { 0.0f, 0.0f, -1.0f });
    for (auto member : { &SurfelGrid::Axes0, &SurfelGrid::Axes1, &SurfelGrid::Colors })
    {
      std::vector<float>& v = plate.*member;
      v.insert(v.end(), { v[3 * i], v[3 * i + 1], v[3 * i + 2] });
    }
  }
  vtkNew<vtkSurfelHierarchy> hierarchy;
  hierarchy->Build(plate.View());
  ASSERT_GT(hierarchy->GetNumberOfLevels(), 2);
  const vtkSurfaceSplatRasterizer::Surfels merged = hierarchy->GetNodes();
  std::size_t node = 0;
  for (int level = 0; level < hierarchy->GetNumberOfLevels(); ++level)
  {
    vtkIdType up = 0;
    for (vtkIdType j = 0; j < hierarchy->GetNumberOfNodes(level); ++j, ++node)
    {
      EXPECT_GT(std::abs(merged.Normals[3 * node + 2]), 0.9999f);
      up += merged.Normals[3 * node + 2] > 0.0f;
    }
    EXPECT_EQ(2 * up, hierarchy->GetNumberOfNodes(level)) << "level " << level;
  }
}

// Near, nothing merges and every surfel is selected once, from level 0; far, merged nodes stand
// for all of them; along a strip from near to far, each surfel is drawn once, by itself or by
// the node that stands for it.
TEST(SurfelHierarchy, SelectionFollowsTheDistance)
{
  const SurfelGrid plane(200, 0.005, glm::vec3(1.0f));
  const std::size_t n = plane.Normals.size() / 3;
  vtkNew<vtkSurfelHierarchy> hierarchy;
  hierarchy->Build(plane.View());
  std::vector<std::uint32_t> items;
  // Near: 0.005 units span about 4.7 pixels at distance 2 in 512^2.
  EXPECT_EQ(hierarchy->Select(CameraAt(2.0, 512), 0.75, items), 0);
  ASSERT_EQ(items.size(), n);
  std::vector<std::uint32_t> sorted(items);
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < n; ++k)
  {
    EXPECT_EQ(sorted[k], k);
  }
  // Far: 0.005 units span about 0.19 pixels at distance 50.
  const vtkIdType merged = hierarchy->Select(CameraAt(50.0, 512), 0.75, items);
  EXPECT_EQ(merged, static_cast<vtkIdType>(n));
  EXPECT_LT(items.size(), n / 16);
  for (const std::uint32_t item : items)
  {
    EXPECT_GE(item, n);
  }
  std::printf("plane of %zu surfels: %zu splats at distance 50\n", n, items.size());

  const SurfelGrid strip(40, 2000, 0.005, 0.005, 0.005, 0.005,
    [](double, double) { return glm::vec3(1.0f); });
  const std::size_t m = strip.Normals.size() / 3;
  hierarchy->Build(strip.View());
  vtkSurfaceSplatRasterizer::Camera camera = CameraAt(1.0, 512);
  camera.ModelToEye =
    glm::lookAt(glm::dvec3(0.0, -8.0, 1.0), glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0));
  const vtkIdType stripMerged = hierarchy->Select(camera, 0.75, items);
  std::vector<int> drawn(m, 0);
  vtkIdType surfels = 0;
  for (const std::uint32_t item : items)
  {
    if (item < m)
    {
      ++drawn[item];
      ++surfels;
    }
  }
  std::printf("strip of %zu surfels: %lld drawn merged, %lld as they are, %zu splats\n", m,
    static_cast<long long>(stripMerged), static_cast<long long>(surfels), items.size());
  EXPECT_GT(stripMerged, 0);
  EXPECT_GT(surfels, 0);
  EXPECT_EQ(stripMerged + surfels, static_cast<vtkIdType>(m));
  EXPECT_TRUE(std::all_of(drawn.begin(), drawn.end(), [](int d) { return d <= 1; }));
}

// Surfels without area or at one point get level 0 only; an empty set selects nothing.
TEST(SurfelHierarchy, DegenerateInputKeepsTheSurfels)
{
  SurfelGrid flat(16, 0.01, glm::vec3(1.0f));
  std::fill(flat.Axes0.begin(), flat.Axes0.end(), 0.0f);
  vtkNew<vtkSurfelHierarchy> hierarchy;
  hierarchy->Build(flat.View());
  EXPECT_EQ(hierarchy->GetNumberOfLevels(), 1);
  std::vector<std::uint32_t> items;
  EXPECT_EQ(hierarchy->Select(CameraAt(50.0, 512), 0.75, items), 0);
  EXPECT_TRUE(items.empty());

  SurfelGrid point(4, 0.01, glm::vec3(1.0f));
  std::fill(point.Positions.begin(), point.Positions.end(), 0.5);
  hierarchy->Build(point.View());
  EXPECT_GE(hierarchy->GetNumberOfLevels(), 1);
  hierarchy->Select(CameraAt(50.0, 512), 0.75, items);
  EXPECT_FALSE(items.empty());

  hierarchy->Build(vtkSurfaceSplatRasterizer::Surfels());
  EXPECT_EQ(hierarchy->GetNumberOfLevels(), 1);
  EXPECT_EQ(hierarchy->GetNumberOfSurfels(), 0);
}
