// SPDX-License-Identifier: BSD-3-Clause
// The analytic reference of the checkerboard scene (SplatCheckerboardScene.h): per pixel, the
// exact checkerboard on exact ray/plane intersections, supersampled and weighted by EWA's screen
// low-pass filter, a Gaussian of unit variance in pixels truncated at 3 sigma, or by the pixel's
// box; and the window capture the rendered image is compared in (float RGB in [0,1], top row
// first, for OpenImageIO's ImageBufAlgo::compare).
//
// The reference's sub-samples per pixel are an argument.
#ifndef SplatCheckerboardReference_h
#define SplatCheckerboardReference_h

#include "SplatCheckerboardScene.h"

#include "vtkImageData.h"
#include "vtkRenderWindow.h"
#include "vtkSMPTools.h"
#include "vtkWindowToImageFilter.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

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
}

#endif
