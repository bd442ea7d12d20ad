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
#include "vtkSurfelSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace splattest
{
/// CTest's SKIP_RETURN_CODE for tests whose optional data is absent.
constexpr int SkipReturnCode = 125;

/// The number of checks that failed so far (Check counts them).
inline int& Failures()
{
  static int failures = 0;
  return failures;
}

/// Prints "FAILED: what" and counts a failure when `ok` is false.
inline void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::fprintf(stderr, "FAILED: %s\n", what.c_str());
    ++Failures();
  }
}

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

/// The image's RGB as floats in [0, 1].
inline std::vector<double> ToRGB(vtkImageData* image)
{
  const int* dims = image->GetDimensions();
  std::vector<double> rgb(3 * dims[0] * dims[1]);
  auto* data = static_cast<unsigned char*>(image->GetScalarPointer());
  const int components = image->GetNumberOfScalarComponents();
  for (int p = 0; p < dims[0] * dims[1]; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      rgb[3 * p + c] = data[components * p + c] / 255.0;
    }
  }
  return rgb;
}

/// Root mean square difference of two RGB images, over all channels of all pixels.
inline double RMSE(const std::vector<double>& a, const std::vector<double>& b)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    sum += (a[i] - b[i]) * (a[i] - b[i]);
  }
  return std::sqrt(sum / a.size());
}

/// The largest difference of two RGB images in any channel of any pixel.
inline double LargestDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    largest = std::max(largest, std::abs(a[i] - b[i]));
  }
  return largest;
}

/// n surfels spread uniformly over a sphere (vtkSurfelSphereSource), a copy the test may edit.
inline vtkSmartPointer<vtkPolyData> SurfelSphere(vtkIdType n, double radius)
{
  vtkNew<vtkSurfelSphereSource> source;
  source->SetNumberOfPoints(n);
  source->SetRadius(radius);
  source->Update();
  auto sphere = vtkSmartPointer<vtkPolyData>::New();
  sphere->DeepCopy(source->GetOutput());
  return sphere;
}

/// A regular nu x nv grid of surfels centered at `center` with step vectors u and v (their
/// lengths are the spacings), normals along u x v and the radius of the larger spacing.
inline vtkSmartPointer<vtkPolyData> SurfelPlane(
  const double center[3], const double u[3], const double v[3], int nu, int nv)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> radii;
  radii->SetName("Radius");
  double normal[3];
  vtkMath::Cross(u, v, normal);
  vtkMath::Normalize(normal);
  const float radius = static_cast<float>(std::max(vtkMath::Norm(u), vtkMath::Norm(v)));
  for (int j = 0; j < nv; ++j)
  {
    for (int i = 0; i < nu; ++i)
    {
      const double a = i - 0.5 * (nu - 1);
      const double b = j - 0.5 * (nv - 1);
      points->InsertNextPoint(center[0] + a * u[0] + b * v[0], center[1] + a * u[1] + b * v[1],
        center[2] + a * u[2] + b * v[2]);
      normals->InsertNextTuple(normal);
      radii->InsertNextValue(radius);
    }
  }
  auto plane = vtkSmartPointer<vtkPolyData>::New();
  plane->SetPoints(points);
  plane->GetPointData()->SetNormals(normals);
  plane->GetPointData()->AddArray(radii);
  return plane;
}

/// Adds constant RGB colors ("Colors", unsigned char) and opacities ("Opacity") to a point set.
inline void Paint(vtkPolyData* data, const double rgb[3], double opacity)
{
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> opacities;
  opacities->SetName("Opacity");
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    colors->InsertNextTuple3(255.0 * rgb[0], 255.0 * rgb[1], 255.0 * rgb[2]);
    opacities->InsertNextValue(static_cast<float>(opacity));
  }
  data->GetPointData()->SetScalars(colors);
  data->GetPointData()->AddArray(opacities);
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

/// Whether `flag` is on the command line.
inline bool HasFlag(int argc, char* argv[], const std::string& flag)
{
  for (int i = 1; i < argc; ++i)
  {
    if (flag == argv[i])
    {
      return true;
    }
  }
  return false;
}

inline bool FileExists(const std::string& path)
{
  struct stat info;
  return !path.empty() && stat(path.c_str(), &info) == 0;
}
}

#endif
