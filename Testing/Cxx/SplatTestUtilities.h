// SPDX-License-Identifier: BSD-3-Clause
// Scenes and image helpers shared by the rendering tests.
#ifndef SplatTestUtilities_h
#define SplatTestUtilities_h

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <cmath>
#include <string>
#include <sys/stat.h>

namespace splattest
{
/// CTest's SKIP_RETURN_CODE for tests whose optional data is absent.
constexpr int SkipReturnCode = 125;

inline vtkSmartPointer<vtkRenderWindow> MakeRenderWindow(int width, int height)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(width, height);
  return window;
}

/// The window's current RGB image.
inline vtkSmartPointer<vtkImageData> Capture(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

/// RGB of pixel (x, y) in [0, 1].
inline void Pixel(vtkImageData* image, int x, int y, double rgb[3])
{
  auto* data = static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0));
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = data[c] / 255.0;
  }
}

/// n points uniformly spread on a sphere (Fibonacci lattice), radial normals and the radius
/// sqrt(4 pi r^2 / n) that matches the sampling spacing.
inline vtkSmartPointer<vtkPolyData> FibonacciSphere(vtkIdType n, double radius)
{
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints(n);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> radii;
  radii->SetName("Radius");
  radii->SetNumberOfTuples(n);
  const double golden = vtkMath::Pi() * (3.0 - std::sqrt(5.0));
  const double spacing = std::sqrt(4.0 * vtkMath::Pi() * radius * radius / n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(1.0 - z * z);
    const double phi = golden * i;
    const double normal[3] = { r * std::cos(phi), r * std::sin(phi), z };
    points->SetPoint(i, radius * normal[0], radius * normal[1], radius * normal[2]);
    normals->SetTuple(i, normal);
    radii->SetValue(i, static_cast<float>(spacing));
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  cloud->GetPointData()->SetNormals(normals);
  cloud->GetPointData()->AddArray(radii);
  return cloud;
}

/// A regular nx x ny grid of surfels with spacing h in the plane z = slope * x, centered at the
/// origin, normals perpendicular to that plane and radius h.
inline vtkSmartPointer<vtkPolyData> SurfelGrid(int nx, int ny, double h, double slope = 0.0)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> radii;
  radii->SetName("Radius");
  double normal[3] = { -slope, 0.0, 1.0 };
  vtkMath::Normalize(normal);
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const double x = (i - 0.5 * (nx - 1)) * h;
      const double y = (j - 0.5 * (ny - 1)) * h;
      points->InsertNextPoint(x, y, slope * x);
      normals->InsertNextTuple(normal);
      radii->InsertNextValue(static_cast<float>(h));
    }
  }
  auto grid = vtkSmartPointer<vtkPolyData>::New();
  grid->SetPoints(points);
  grid->GetPointData()->SetNormals(normals);
  grid->GetPointData()->AddArray(radii);
  return grid;
}

/// The value following `flag` on the command line, or "".
inline std::string Argument(int argc, char* argv[], const std::string& flag)
{
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (flag == argv[i])
    {
      return argv[i + 1];
    }
  }
  return std::string();
}

inline bool FileExists(const std::string& path)
{
  struct stat info;
  return !path.empty() && stat(path.c_str(), &info) == 0;
}
}

#endif
