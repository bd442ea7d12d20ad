// SPDX-License-Identifier: BSD-3-Clause
// What the CPU rasterizer's unit tests share: surfels on a grid and a camera facing them.
#ifndef SplatRasterizerTestUtilities_h
#define SplatRasterizerTestUtilities_h

#include "vtkSurfaceSplatRasterizer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <functional>
#include <vector>

namespace splat_test
{
// Surfels on a regular nx x ny grid in the plane z = 0, spacing (hx, hy), centered at the origin,
// with tangent axes a0 = (ax, 0, 0), a1 = (0, ay, 0) and a color from a function of position.
struct SurfelGrid
{
  std::vector<double> Positions;
  std::vector<float> Normals, Axes0, Axes1, Colors, Opacities;

  SurfelGrid() = default;

  SurfelGrid(int nx, int ny, double hx, double hy, double ax, double ay,
    const std::function<glm::vec3(double, double)>& color)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        const double x = (i - 0.5 * (nx - 1)) * hx;
        const double y = (j - 0.5 * (ny - 1)) * hy;
        const glm::vec3 c = color(x, y);
        const float values[5][3] = { { 0.f, 0.f, 1.f }, { static_cast<float>(ax), 0.f, 0.f },
          { 0.f, static_cast<float>(ay), 0.f }, { c.x, c.y, c.z } };
        this->Positions.insert(this->Positions.end(), { x, y, 0.0 });
        this->Normals.insert(this->Normals.end(), values[0], values[0] + 3);
        this->Axes0.insert(this->Axes0.end(), values[1], values[1] + 3);
        this->Axes1.insert(this->Axes1.end(), values[2], values[2] + 3);
        this->Colors.insert(this->Colors.end(), values[3], values[3] + 3);
      }
    }
  }

  // A square grid of spacing h with circular surfels of radius h.
  SurfelGrid(int n, double h, const glm::vec3& color)
    : SurfelGrid(n, n, h, h, h, h, [color](double, double) { return color; })
  {
  }

  // Keeps the surfels whose position (x, y) satisfies the predicate.
  void Keep(const std::function<bool(double, double)>& keep)
  {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < this->Normals.size() / 3; ++i)
    {
      if (keep(this->Positions[3 * i], this->Positions[3 * i + 1]))
      {
        for (int c = 0; c < 3; ++c)
        {
          this->Positions[3 * kept + c] = this->Positions[3 * i + c];
          for (std::vector<float>* v : { &this->Normals, &this->Axes0, &this->Axes1, &this->Colors })
          {
            (*v)[3 * kept + c] = (*v)[3 * i + c];
          }
        }
        ++kept;
      }
    }
    this->Positions.resize(3 * kept);
    for (std::vector<float>* v : { &this->Normals, &this->Axes0, &this->Axes1, &this->Colors })
    {
      v->resize(3 * kept);
    }
  }

  vtkSurfaceSplatRasterizer::Surfels View() const
  {
    return vtkSurfaceSplatRasterizer::Surfels::Of(
      this->Positions, this->Normals, this->Axes0, this->Axes1, this->Colors, this->Opacities);
  }

  // Appends a copy of the grid moved to height z, with one color and opacity.
  void AppendLayer(const SurfelGrid& grid, double z, const glm::vec3& color, float opacity)
  {
    const std::size_t n = grid.Normals.size() / 3;
    for (std::size_t i = 0; i < n; ++i)
    {
      this->Positions.insert(
        this->Positions.end(), { grid.Positions[3 * i], grid.Positions[3 * i + 1], z });
      this->Colors.insert(this->Colors.end(), { color.x, color.y, color.z });
      this->Opacities.push_back(opacity);
    }
    this->Normals.insert(this->Normals.end(), grid.Normals.begin(), grid.Normals.end());
    this->Axes0.insert(this->Axes0.end(), grid.Axes0.begin(), grid.Axes0.end());
    this->Axes1.insert(this->Axes1.end(), grid.Axes1.begin(), grid.Axes1.end());
  }
};

// A camera on the +z axis at the given distance looking at the origin, square viewport.
inline vtkSurfaceSplatRasterizer::Camera FrontoParallelCamera(double distance, int size)
{
  vtkSurfaceSplatRasterizer::Camera camera;
  camera.ModelToEye = glm::lookAt(
    glm::dvec3(0.0, 0.0, distance), glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
  camera.EyeToClip = glm::perspective(glm::radians(30.0), 1.0, 0.1 * distance, 10.0 * distance);
  camera.Viewport = glm::ivec2(size, size);
  return camera;
}

// Pixels per model unit at the origin for FrontoParallelCamera.
inline double PixelsPerUnit(double distance, int size)
{
  return 0.5 * size / (distance * std::tan(glm::radians(15.0)));
}

inline splat::Material Unlit()
{
  splat::Material material;
  material.Ambient = 0.0f;
  material.Diffuse = 1.0f;
  return material;
}
} // namespace splat_test

#endif
