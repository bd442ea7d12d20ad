// SPDX-License-Identifier: BSD-3-Clause
// splat_report's images: OpenImageIO ImageBufs of float RGB in [0,1], top row first; captures of
// the render window, supersampled references, and PNG files and montages.
#ifndef SplatReportImages_h
#define SplatReportImages_h

#include "SplatExampleUtilities.h"

#include "vtkFloatArray.h"
#include "vtkImageCast.h"
#include "vtkImageData.h"
#include "vtkImageGaussianSmooth.h"
#include "vtkImageShrink3D.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace splatreport
{
// A float RGB vtkImageData (rows from the bottom) times `scale` as an image (rows from the top).
inline OIIO::ImageBuf ToImageBuf(vtkImageData* image, float scale)
{
  int dims[3];
  image->GetDimensions(dims);
  OIIO::ImageBuf wrapped(
    OIIO::ImageSpec(dims[0], dims[1], 3, OIIO::TypeDesc::FLOAT), image->GetScalarPointer());
  return OIIO::ImageBufAlgo::mul(OIIO::ImageBufAlgo::flip(wrapped), scale);
}

// The pixels of `image` whose color differs from `background` by more than 1/255 in a channel.
inline long long CoveredPixels(const OIIO::ImageBuf& image, const double background[3])
{
  const float color[3] = { static_cast<float>(background[0]), static_cast<float>(background[1]),
    static_cast<float>(background[2]) };
  const float eps[3] = { 1.0f / 255.0f, 1.0f / 255.0f, 1.0f / 255.0f };
  OIIO::imagesize_t matching = 0;
  if (!OIIO::ImageBufAlgo::color_count(image, &matching, 1, color, eps))
  {
    throw std::runtime_error("counting the background's pixels failed: " + image.geterror());
  }
  return static_cast<long long>(image.spec().image_pixels() - matching);
}

// The window rendered at `factor` times its size, reduced to its size with two pixel filters:
// [0] a Gaussian of variance 1 - 1/12 pixels^2 followed by [1]'s box, together a filter of unit
// variance like EWA's screen low-pass filter; [1] the pixel's box (factor x factor blocks
// averaged, i.e. factor x factor supersampling).
inline std::array<OIIO::ImageBuf, 2> CaptureSupersampled(vtkRenderWindow* window, int factor)
{
  const int* size = window->GetSize();
  const int width = size[0];
  const int height = size[1];
  window->SetSize(width * factor, height * factor);
  window->Render();
  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->SetInputBufferTypeToRGB();
  capture->ReadFrontBufferOff();
  capture->ShouldRerenderOff();
  vtkNew<vtkImageCast> toFloat;
  toFloat->SetInputConnection(capture->GetOutputPort());
  toFloat->SetOutputScalarTypeToFloat();
  toFloat->Update();
  window->SetSize(width, height);

  vtkNew<vtkImageGaussianSmooth> gaussian;
  gaussian->SetInputConnection(toFloat->GetOutputPort());
  gaussian->SetDimensionality(2);
  const double sigma = factor * std::sqrt(1.0 - 1.0 / 12.0); // in the large image's pixels
  gaussian->SetStandardDeviations(sigma, sigma, 0.0);
  gaussian->SetRadiusFactors(3.0, 3.0, 0.0);
  std::array<OIIO::ImageBuf, 2> images;
  for (int f = 0; f < 2; ++f)
  {
    vtkNew<vtkImageShrink3D> shrink; // the box filter: each output pixel is a block's mean
    shrink->SetInputConnection(f == 0 ? gaussian->GetOutputPort() : toFloat->GetOutputPort());
    shrink->SetShrinkFactors(factor, factor, 1);
    shrink->AveragingOn();
    shrink->Update();
    vtkImageData* image = shrink->GetOutput();
    int dims[3];
    image->GetDimensions(dims);
    if (dims[0] != width || dims[1] != height)
    {
      throw std::runtime_error("the supersampled capture has the wrong size");
    }
    images[f] = ToImageBuf(image, 1.0f / 255.0f);
  }
  return images;
}

// A volume scene's reference (RGB floats, rows from the bottom) as [0] itself and [1] filtered
// like EWA's screen low-pass filter: a Gaussian of unit variance in pixels, truncated at 3 sigma.
inline std::array<OIIO::ImageBuf, 2> VolumeReferenceImages(
  const std::vector<float>& rgb, int width, int height)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(width, height, 1);
  vtkNew<vtkFloatArray> pixels;
  pixels->SetNumberOfComponents(3);
  pixels->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  std::copy(rgb.begin(), rgb.end(), pixels->GetPointer(0));
  image->GetPointData()->SetScalars(pixels);
  vtkNew<vtkImageGaussianSmooth> gaussian;
  gaussian->SetInputData(image);
  gaussian->SetDimensionality(2);
  gaussian->SetStandardDeviations(1.0, 1.0, 0.0);
  gaussian->SetRadiusFactors(3.0, 3.0, 0.0);
  gaussian->Update();
  return { ToImageBuf(image, 1.0f), ToImageBuf(gaussian->GetOutput(), 1.0f) };
}

inline void WriteImage(const OIIO::ImageBuf& image, const std::string& path)
{
  if (!image.write(path, OIIO::TypeDesc::UINT8))
  {
    throw std::runtime_error("cannot write '" + path + "': " + image.geterror());
  }
}

// Tiles the PNG files (of equal size) `columns` wide into one PNG, like paper 000's figure 8.
// Files that are absent are left black.
inline void WriteMontage(
  const std::vector<std::string>& files, int columns, const std::string& path)
{
  if (files.empty())
  {
    return;
  }
  OIIO::ImageBuf first(files[0]);
  if (!first.read(0, 0, true, OIIO::TypeDesc::FLOAT))
  {
    return;
  }
  const int width = first.spec().width;
  const int height = first.spec().height;
  const int rows = (static_cast<int>(files.size()) + columns - 1) / columns;
  OIIO::ImageBuf montage(
    OIIO::ImageSpec(columns * width, rows * height, first.nchannels(), OIIO::TypeDesc::FLOAT));
  OIIO::ImageBufAlgo::zero(montage);
  for (std::size_t i = 0; i < files.size(); ++i)
  {
    OIIO::ImageBuf tile(files[i]);
    if (tile.read(0, 0, true, OIIO::TypeDesc::FLOAT))
    {
      OIIO::ImageBufAlgo::paste(montage, static_cast<int>(i % columns) * width,
        static_cast<int>(i / columns) * height, 0, 0, tile);
    }
  }
  WriteImage(montage, path);
}
}

#endif
