// SPDX-License-Identifier: BSD-3-Clause
// The checkerboard scene of splat_report and TestSurfaceSplatCheckerboardError: a checkerboard
// plane seen at a grazing angle (paper 000, figure 8), strong magnification near the camera and
// strong minification toward the horizon, drawn as a regular grid of surfels colored with the
// checkerboard's exact average over their grid cells (a box prefilter); its analytic reference
// (per pixel, the exact checkerboard on exact ray/plane intersections, supersampled and weighted
// by EWA's screen low-pass filter, a Gaussian of unit variance in pixels truncated at 3 sigma,
// or by the pixel's box); and the window capture the rendered image is compared in (float RGB
// in [0,1], top row first, for OpenImageIO's ImageBufAlgo::compare).
//
// The configuration is the caller's: the image size and the reference's sub-samples per pixel
// are arguments, the number of surfels follows from Checkerboard::Far
// (Checkerboard::FitPoints).
#ifndef SplatCheckerboardScene_h
#define SplatCheckerboardScene_h

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace splatexample
{
//------------------------------------------------------------------------------------------------
// Images: OpenImageIO ImageBufs of float RGB in [0,1], top row first.

// The window's last frame (no re-render) as float RGB, top row first.
inline OIIO::ImageBuf CaptureWindow(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->SetInputBufferTypeToRGB();
  capture->ReadFrontBufferOff();
  capture->ShouldRerenderOff();
  capture->Update();
  vtkImageData* image = capture->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  // VTK's rows run bottom to top: wrap the bytes, flip, convert to float.
  OIIO::ImageBuf wrapped(OIIO::ImageSpec(dims[0], dims[1], 3, OIIO::TypeDesc::UINT8),
    image->GetScalarPointer());
  OIIO::ImageBuf flipped = OIIO::ImageBufAlgo::flip(wrapped);
  OIIO::ImageBuf result;
  if (!result.copy(flipped, OIIO::TypeDesc::FLOAT))
  {
    throw std::runtime_error("cannot convert the captured image: " + result.geterror());
  }
  return result;
}

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

// World-space rays through window positions of a camera: the inverse of VTK's own
// projection * view matrices, as the mappers use them.
struct RayCaster
{
  double Inverse[16]; // (P * MV)^-1, row-major, acting on column vectors
  double Eye[3];
  int Width, Height;

  RayCaster(vtkCamera* camera, int width, int height)
    : Width(width)
    , Height(height)
  {
    vtkNew<vtkMatrix4x4> clip;
    vtkMatrix4x4::Multiply4x4(
      camera->GetProjectionTransformMatrix(static_cast<double>(width) / height, -1.0, 1.0),
      camera->GetModelViewTransformMatrix(), clip);
    vtkMatrix4x4::Invert(*clip->Element, this->Inverse);
    double eye[4];
    vtkNew<vtkMatrix4x4> view;
    view->DeepCopy(camera->GetModelViewTransformMatrix());
    view->Invert();
    const double origin[4] = { 0, 0, 0, 1 };
    view->MultiplyPoint(origin, eye);
    for (int i = 0; i < 3; ++i)
    {
      this->Eye[i] = eye[i] / eye[3];
    }
  }

  // Where the ray through window position (x, y) (pixels, y up, pixel centers at +0.5) meets
  // the plane z = 0; false when it does not (the ray points at or above the horizon).
  bool HitGround(double x, double y, double& hx, double& hy) const
  {
    const double ndc[4] = { 2.0 * x / this->Width - 1.0, 2.0 * y / this->Height - 1.0, 1.0, 1.0 };
    double p[4];
    vtkMatrix4x4::MultiplyPoint(this->Inverse, ndc, p);
    const double d[3] = { p[0] / p[3] - this->Eye[0], p[1] / p[3] - this->Eye[1],
      p[2] / p[3] - this->Eye[2] };
    if (!(d[2] < 0.0))
    {
      return false;
    }
    const double t = -this->Eye[2] / d[2];
    hx = this->Eye[0] + t * d[0];
    hy = this->Eye[1] + t * d[1];
    return std::isfinite(hx) && std::isfinite(hy);
  }
};

// A separable pixel filter on the sub-pixel cells of CheckerboardReferences: output pixel p
// (along one axis) is the weighted sum of the cells p * S + First + k, k < Weights.size().
struct PixelFilter
{
  int First;
  std::vector<double> Weights;
};

// The analytic references of the checkerboard scene: the image of the plane filtered with
// (0) a Gaussian of unit variance in pixels (EWA's screen low-pass filter), truncated at 3 sigma,
// and (1) the pixel's box (its exact area average). Each pixel integrates samples x samples
// sub-pixel cells per pixel over the filter's support; each cell's value is the checkerboard's
// exact mean over the bounding box of the cell's footprint on the plane (so a cell is alias-free
// however many checks it covers), times the covered fraction of the plane (which ends at
// y = Far), plus the background for the rest. Both filters are separable and the cells form a
// tensor grid, so each filter runs as two 1D passes over the same cells.
inline std::array<OIIO::ImageBuf, 2> CheckerboardReferences(
  const Checkerboard& board, vtkCamera* camera, int width, int height, int samples)
{
  const RayCaster rays(camera, width, height);
  constexpr int Radius = 3; // the Gaussian's support in pixels (3 sigma)
  const int S = samples;
  const int cols = (width + 2 * Radius) * S; // cells, from x = -Radius to width + Radius
  const int rows = (height + 2 * Radius) * S;

  // Cell i's center lies at -Radius + (i + 0.5) / S pixels. The Gaussian's taps are the cells
  // whose centers lie within 3 pixels of the pixel's center p + 0.5 (symmetric when S is even);
  // the box's taps are the S cells inside the pixel.
  std::array<PixelFilter, 2> filters;
  filters[0].First = S / 2;
  filters[0].Weights.resize(2 * Radius * S);
  filters[1].First = Radius * S;
  filters[1].Weights.assign(S, 1.0 / S);
  double sum = 0.0;
  for (std::size_t k = 0; k < filters[0].Weights.size(); ++k)
  {
    // The distance from the pixel's center to the center of tap k, in pixels.
    const double d = -Radius + (S / 2 + k + 0.5) / S - 0.5;
    filters[0].Weights[k] = std::exp(-0.5 * d * d);
    sum += filters[0].Weights[k];
  }
  for (double& w : filters[0].Weights)
  {
    w /= sum;
  }

  // Horizontal passes, parallel over rows of cells: each row's cells are evaluated on the fly and
  // filtered into `width` values per filter.
  std::array<std::vector<float>, 2> horizontal;
  for (auto& buffer : horizontal)
  {
    buffer.resize(static_cast<std::size_t>(rows) * width * 3);
  }
  vtkSMPTools::For(0, rows, [&](vtkIdType first, vtkIdType last) {
    std::vector<double> hx[2], hy[2];
    std::vector<char> hit[2];
    std::vector<double> cell(static_cast<std::size_t>(cols) * 3);
    for (int r = 0; r < 2; ++r)
    {
      hx[r].resize(cols + 1);
      hy[r].resize(cols + 1);
      hit[r].resize(cols + 1);
    }
    for (vtkIdType row = first; row < last; ++row)
    {
      for (int r = 0; r < 2; ++r)
      {
        const double y = -Radius + static_cast<double>(row + r) / S;
        for (int c = 0; c <= cols; ++c)
        {
          hit[r][c] = rays.HitGround(-Radius + static_cast<double>(c) / S, y, hx[r][c], hy[r][c]);
        }
      }
      for (int c = 0; c < cols; ++c)
      {
        double coverage = 0.0, dark = 0.0;
        if (hit[0][c] && hit[0][c + 1] && hit[1][c] && hit[1][c + 1])
        {
          const double x0 = std::min({ hx[0][c], hx[0][c + 1], hx[1][c], hx[1][c + 1] });
          const double x1 = std::max({ hx[0][c], hx[0][c + 1], hx[1][c], hx[1][c + 1] });
          const double y0 = std::min({ hy[0][c], hy[0][c + 1], hy[1][c], hy[1][c + 1] });
          const double y1 = std::max({ hy[0][c], hy[0][c + 1], hy[1][c], hy[1][c + 1] });
          if (y0 < board.Far)
          {
            const double top = std::min(y1, board.Far);
            coverage = y1 > y0 ? (top - y0) / (y1 - y0) : 1.0;
            dark = board.DarkFraction(x0, x1, y0, top);
          }
        }
        for (int k = 0; k < 3; ++k)
        {
          const double texture = board.Light[k] + dark * (board.Dark[k] - board.Light[k]);
          cell[3 * c + k] = coverage * texture + (1.0 - coverage) * board.Background[k];
        }
      }
      for (int f = 0; f < 2; ++f)
      {
        const PixelFilter& filter = filters[f];
        float* out = &horizontal[f][static_cast<std::size_t>(row) * width * 3];
        for (int x = 0; x < width; ++x)
        {
          double acc[3] = { 0, 0, 0 };
          const double* in = &cell[3 * (static_cast<std::size_t>(x) * S + filter.First)];
          for (std::size_t k = 0; k < filter.Weights.size(); ++k)
          {
            acc[0] += filter.Weights[k] * in[3 * k];
            acc[1] += filter.Weights[k] * in[3 * k + 1];
            acc[2] += filter.Weights[k] * in[3 * k + 2];
          }
          for (int ch = 0; ch < 3; ++ch)
          {
            out[3 * x + ch] = static_cast<float>(acc[ch]);
          }
        }
      }
    }
  });

  // Vertical passes into the images, top row first (window row y = height - 1 - top row).
  std::array<OIIO::ImageBuf, 2> images;
  for (int f = 0; f < 2; ++f)
  {
    const PixelFilter& filter = filters[f];
    std::vector<float> pixels(static_cast<std::size_t>(width) * height * 3);
    vtkSMPTools::For(0, height, [&](vtkIdType first, vtkIdType last) {
      for (vtkIdType y = first; y < last; ++y)
      {
        float* out = &pixels[static_cast<std::size_t>(height - 1 - y) * width * 3];
        for (int x = 0; x < width; ++x)
        {
          double acc[3] = { 0, 0, 0 };
          for (std::size_t k = 0; k < filter.Weights.size(); ++k)
          {
            const float* in = &horizontal[f][(static_cast<std::size_t>(y) * S + filter.First + k) *
                width * 3 +
              3 * x];
            acc[0] += filter.Weights[k] * in[0];
            acc[1] += filter.Weights[k] * in[1];
            acc[2] += filter.Weights[k] * in[2];
          }
          for (int ch = 0; ch < 3; ++ch)
          {
            out[3 * x + ch] = static_cast<float>(acc[ch]);
          }
        }
      }
    });
    OIIO::ImageBuf wrapped(
      OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT), pixels.data());
    images[f].copy(wrapped); // owns its pixels
  }
  return images;
}

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
