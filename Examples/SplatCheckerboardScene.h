// SPDX-License-Identifier: BSD-3-Clause
// The checkerboard scene of splat_report and TestSurfaceSplatCheckerboardError: a checkerboard
// plane seen at a grazing angle (paper 000, figure 8), strong magnification near the camera and
// strong minification toward the horizon, drawn as a regular grid of surfels colored with the
// checkerboard's exact average over their grid cells (a box prefilter). Its analytic reference
// is in SplatCheckerboardReference.h, apart, so that the scene needs no OpenImageIO.
//
// The configuration is the caller's: the image size is an argument, the number of surfels
// follows from Checkerboard::Far (Checkerboard::FitPoints).
#ifndef SplatCheckerboardScene_h
#define SplatCheckerboardScene_h

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace splatexample
{
//------------------------------------------------------------------------------------------------
// The checkerboard scene.
struct Checkerboard
{
  double CameraHeight = 1.0;
  double PitchDegrees = 8.0; // the view direction's angle below the horizon
  double Check = 0.2;        // side of a check
  double Spacing = 0.05;     // surfel grid spacing h (and radius)
  double Far = 80.0;         // the plane ends at y = Far (a grid-cell boundary)
  std::array<double, 3> Light = { 235 / 255.0, 235 / 255.0, 235 / 255.0 };
  std::array<double, 3> Dark = { 20 / 255.0, 20 / 255.0, 20 / 255.0 };
  std::array<double, 3> Background = { 0.45, 0.6, 0.85 };

  // Sets Far for about `points` surfels in view: the visible grid's size grows with Far squared,
  // 1 M surfels at Far = 80 (the report's default), at least Far = 5; Far is rounded to a
  // multiple of Spacing. The surfels' count does not depend on the image size.
  void FitPoints(long long points)
  {
    this->Far = std::max(5.0, 80.0 * std::sqrt(points / 1.0e6));
    this->Far = std::round(this->Far / this->Spacing) * this->Spacing;
  }

  // Integral from 0 to t of the square wave that is 1 on the odd checks [c(2k+1), c(2k+2)).
  double OddIntegral(double t) const
  {
    const double u = t / this->Check;
    const double pairs = std::floor(0.5 * u);
    return this->Check * (pairs + std::max(0.0, u - 2.0 * pairs - 1.0));
  }

  // Mean of the square wave over [a, b] (its value at a when the interval is empty).
  double OddMean(double a, double b) const
  {
    if (b - a < 1e-12 * this->Check)
    {
      return std::fmod(std::floor(a / this->Check), 2.0) != 0.0 ? 1.0 : 0.0;
    }
    return (this->OddIntegral(b) - this->OddIntegral(a)) / (b - a);
  }

  // Fraction of the box [x0,x1] x [y0,y1] covered by dark checks (exact: the box filter).
  double DarkFraction(double x0, double x1, double y0, double y1) const
  {
    const double mx = this->OddMean(x0, x1);
    const double my = this->OddMean(y0, y1);
    return mx + my - 2.0 * mx * my; // the mean of mx XOR my for independent x and y
  }

  void SetCamera(vtkCamera* camera) const
  {
    const double pitch = vtkMath::RadiansFromDegrees(this->PitchDegrees);
    camera->SetPosition(0.0, 0.0, this->CameraHeight);
    camera->SetFocalPoint(0.0, std::cos(pitch), this->CameraHeight - std::sin(pitch));
    camera->SetViewUp(0.0, 0.0, 1.0);
    camera->SetViewAngle(30.0);
    camera->SetClippingRange(0.05, 2.0 * this->Far);
  }
};

// Calls visit(i, j, visible) for every cell [ih, (i+1)h] x [jh, (j+1)h] of the grid of spacing
// h over the plane up to y = Far and across the view, row by row; a cell is visible when the
// point 2h farther from the camera and 2h closer to the view's center line than its center
// projects into the image, so every splat that can reach a pixel is there.
template <typename Visit>
void ForEachGridCell(
  const Checkerboard& board, vtkCamera* camera, int width, int height, Visit&& visit)
{
  vtkNew<vtkMatrix4x4> clip;
  vtkMatrix4x4::Multiply4x4(
    camera->GetProjectionTransformMatrix(static_cast<double>(width) / height, -1.0, 1.0),
    camera->GetModelViewTransformMatrix(), clip);
  const double h = board.Spacing;
  const double halfWidth = board.Far * 0.6 + 1.0; // beyond the 40-degree horizontal view
  const long long jmax = std::llround(board.Far / h);
  const long long imax = static_cast<long long>(std::ceil(halfWidth / h));
  for (long long j = 0; j < jmax; ++j)
  {
    const double y = (j + 0.5) * h;
    for (long long i = -imax; i < imax; ++i)
    {
      const double x = (i + 0.5) * h;
      const double nearer[4] = { x - std::copysign(std::min(2.0 * h, std::abs(x)), x),
        y + 2.0 * h, 0.0, 1.0 };
      double p[4];
      clip->MultiplyPoint(nearer, p);
      visit(i, j, p[3] > 0.0 && std::abs(p[0]) <= p[3] && std::abs(p[1]) <= p[3]);
    }
  }
}

// Surfels on the grid of spacing h over the visible part of the plane (the visible cells of
// ForEachGridCell, y up to Far), each at its cell's center with radius h, normal +z and the
// checkerboard's exact mean over its cell (the box prefilter) as an 8-bit RGB color.
inline vtkSmartPointer<vtkPolyData> CheckerboardSurfels(
  const Checkerboard& board, vtkCamera* camera, int width, int height)
{
  const double h = board.Spacing;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> radii;
  radii->SetName("Radius");
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  ForEachGridCell(board, camera, width, height, [&](long long i, long long j, bool visible) {
    if (!visible)
    {
      return;
    }
    points->InsertNextPoint((i + 0.5) * h, (j + 0.5) * h, 0.0);
    normals->InsertNextTuple3(0.0, 0.0, 1.0);
    radii->InsertNextValue(static_cast<float>(h));
    const double dark = board.DarkFraction(i * h, (i + 1) * h, j * h, (j + 1) * h);
    unsigned char rgb[3];
    for (int k = 0; k < 3; ++k)
    {
      const double c = board.Light[k] + dark * (board.Dark[k] - board.Light[k]);
      rgb[k] = static_cast<unsigned char>(std::lround(255.0 * c));
    }
    colors->InsertNextTypedTuple(rgb);
  });
  auto surfels = vtkSmartPointer<vtkPolyData>::New();
  surfels->SetPoints(points);
  surfels->GetPointData()->SetNormals(normals);
  surfels->GetPointData()->AddArray(radii);
  surfels->GetPointData()->SetScalars(colors);
  return surfels;
}

// The scene's look: lighting off (the surfels' colors as they are), colors from the surfels'
// RGB array as they are (direct scalars).
inline void StyleCheckerboardActor(vtkActor* actor)
{
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetAmbient(0.0);
  actor->GetProperty()->SetDiffuse(1.0);
  if (auto* mapper = actor->GetMapper())
  {
    mapper->ScalarVisibilityOn();
    mapper->SetColorModeToDirectScalars();
  }
}
}

#endif
