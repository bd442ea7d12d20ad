// SPDX-License-Identifier: BSD-3-Clause
// Volume scenes and image measures shared by the volume splatting tests (and usable from
// programs): a Gaussian blob whose image is analytic, transfer functions, image differences.
#ifndef SplatVolumeTestUtilities_h
#define SplatVolumeTestUtilities_h

#include "SplatTestUtilities.h"
#include "SplatVolumeScenes.h" // MriHead

#include "vtkAbstractVolumeMapper.h"
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace splattest
{
/**
 * A vtkVolume drawing `mapper` with `property` (the default property when null), added to
 * `renderer`, which keeps it.
 */
inline vtkVolume* AddVolume(
  vtkRenderer* renderer, vtkAbstractVolumeMapper* mapper, vtkVolumeProperty* property)
{
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  if (property)
  {
    volume->SetProperty(property);
  }
  renderer->AddVolume(volume);
  return volume;
}

/**
 * `data` drawn by `mapper` (its default property, on black) in a size x size window from the
 * camera at `position` looking at `focalPoint` with `up`; the window, rendered, keeps the
 * renderer and its camera.
 */
inline vtkSmartPointer<vtkRenderWindow> DrawVolume(vtkAbstractVolumeMapper* mapper,
  vtkDataSet* data, const double position[3], const double focalPoint[3], const double up[3],
  int size)
{
  auto window = MakeRenderWindow(size, size);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.0, 0.0, 0.0);
  window->AddRenderer(renderer);
  mapper->SetInputDataObject(data);
  vtkNew<vtkVolumeProperty> property;
  AddVolume(renderer, mapper, property);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(position);
  camera->SetFocalPoint(focalPoint);
  camera->SetViewUp(up);
  renderer->ResetCameraClippingRange();
  window->Render();
  return window;
}

/**
 * The arrays of a kernel set in the 3D Gaussian Splatting convention, under
 * vtkVolumeSplatMapper's default names, empty: Scale (3 components), Rotation (4, w x y z),
 * Opacity (1) and Color (3). AddTo() puts them on a point set's point data.
 */
template <typename ArrayType>
struct KernelSetArrays
{
  vtkNew<ArrayType> Scale, Rotation, Opacity, Color;
  KernelSetArrays()
  {
    this->Scale->SetName("Scale");
    this->Scale->SetNumberOfComponents(3);
    this->Rotation->SetName("Rotation");
    this->Rotation->SetNumberOfComponents(4);
    this->Opacity->SetName("Opacity");
    this->Color->SetName("Color");
    this->Color->SetNumberOfComponents(3);
  }
  void AddTo(vtkDataSet* data)
  {
    for (ArrayType* array : { this->Scale.Get(), this->Rotation.Get(), this->Opacity.Get(),
           this->Color.Get() })
    {
      data->GetPointData()->AddArray(array);
    }
  }
};

/**
 * An opaque, unlit green square over [x0, x1] x [-1, 1] in the plane at height z, to hide or
 * show the volume in front of or behind it.
 */
inline vtkSmartPointer<vtkActor> OpaqueSquare(double x0, double x1, double z)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(x0, -1.0, z);
  plane->SetPoint1(x1, -1.0, z);
  plane->SetPoint2(x0, 1.0, z);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.0, 1.0, 0.0);
  actor->GetProperty()->LightingOff();
  return actor;
}

/**
 * A cube of n^3 voxels of spacing h centered at the origin holding the extinction of a Gaussian
 * blob, tau(x) = peak exp(-|x|^2 / (2 sigma^2)), as float scalars.
 */
inline vtkSmartPointer<vtkImageData> GaussianBlob(int n, double h, double sigma, double peak)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(h, h, h);
  const double o = -0.5 * (n - 1) * h;
  image->SetOrigin(o, o, o);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("Extinction");
  scalars->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double x = o + i * h, y = o + j * h, z = o + k * h;
        scalars->SetValue(i + n * (j + n * k),
          static_cast<float>(peak * std::exp(-(x * x + y * y + z * z) / (2.0 * sigma * sigma))));
      }
  image->GetPointData()->SetScalars(scalars);
  return image;
}

/**
 * A volume property whose scalar is the extinction itself: the opacity transfer function is
 * alpha(s) = 1 - exp(-s unitDistance), sampled finely enough to be linear in s to 1e-4, and the
 * color constant. Shading off.
 */
inline vtkSmartPointer<vtkVolumeProperty> ExtinctionProperty(
  double maximum, double unitDistance, const double rgb[3])
{
  vtkNew<vtkPiecewiseFunction> opacity;
  const int samples = 256;
  for (int i = 0; i <= samples; ++i)
  {
    const double s = maximum * i / samples;
    opacity->AddPoint(s, 1.0 - std::exp(-s * unitDistance));
  }
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, rgb[0], rgb[1], rgb[2]);
  color->AddRGBPoint(maximum, rgb[0], rgb[1], rgb[2]);
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetScalarOpacityUnitDistance(unitDistance);
  property->ShadeOff();
  property->SetInterpolationTypeToLinear();
  return property;
}

/**
 * The exact image of the blob of GaussianBlob() over a black background: per pixel ray, from its
 * point on the near plane on (perspective or parallel projections alike), the optical depth is
 * peak sigma sqrt(2 pi) exp(-d^2 / (2 sigma^2)) (1 + erf(t / (sigma sqrt 2))) / 2, with d the
 * ray's distance to the center and t the distance along the ray from the near plane to the
 * point closest to the center (1 when the whole blob is in front), and the color
 * rgb (1 - exp(-depth)). RGB floats in [0, 1], rows from the bottom.
 */
inline std::vector<double> BlobImage(
  vtkRenderer* renderer, double sigma, double peak, const double rgb[3])
{
  int* size = renderer->GetRenderWindow()->GetSize();
  std::vector<double> image(3 * size[0] * size[1]);
  for (int y = 0; y < size[1]; ++y)
    for (int x = 0; x < size[0]; ++x)
    {
      double ends[2][3];
      for (int end = 0; end < 2; ++end)
      {
        renderer->SetDisplayPoint(x + 0.5, y + 0.5, end);
        renderer->DisplayToWorld();
        double p[4];
        renderer->GetWorldPoint(p);
        for (int c = 0; c < 3; ++c)
        {
          ends[end][c] = p[c] / p[3];
        }
      }
      const double* o = ends[0];
      double d[3] = { ends[1][0] - o[0], ends[1][1] - o[1], ends[1][2] - o[2] };
      vtkMath::Normalize(d);
      // The point of the ray o + t d closest to the center (the origin).
      const double t = -vtkMath::Dot(o, d);
      double closest[3];
      for (int c = 0; c < 3; ++c)
      {
        closest[c] = o[c] + t * d[c];
      }
      const double r2 = vtkMath::Dot(closest, closest);
      const double depth = peak * sigma * std::sqrt(2.0 * vtkMath::Pi()) *
        std::exp(-r2 / (2.0 * sigma * sigma)) * 0.5 *
        (1.0 + std::erf(t / (sigma * std::sqrt(2.0))));
      for (int c = 0; c < 3; ++c)
      {
        image[3 * (y * size[0] + x) + c] = rgb[c] * -std::expm1(-depth);
      }
    }
  return image;
}

/**
 * The largest difference between horizontally or vertically neighboring pixels of an RGB image
 * of width `width`, over all channels: a seam shows as a jump above the image's own gradient.
 */
inline double LargestNeighborJump(const std::vector<double>& rgb, int width)
{
  const int height = static_cast<int>(rgb.size() / (3 * width));
  double largest = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
      {
        const double v = rgb[3 * (y * width + x) + c];
        if (x + 1 < width)
        {
          largest = std::max(largest, std::abs(rgb[3 * (y * width + x + 1) + c] - v));
        }
        if (y + 1 < height)
        {
          largest = std::max(largest, std::abs(rgb[3 * ((y + 1) * width + x) + c] - v));
        }
      }
  return largest;
}

/// A volume image rendered offscreen: its RGB and the time of a frame.
struct RenderedVolume
{
  std::vector<double> RGB;
  double Milliseconds;
};

/**
 * Renders `image` through `mapper` with `property` in a size x size window, from the camera set
 * by `place(renderer)`; the time is the best of three renders after the first (which builds the
 * kernels or the ray caster's tables).
 */
template <typename Place>
RenderedVolume RenderVolume(vtkAbstractVolumeMapper* mapper, vtkImageData* image,
  vtkVolumeProperty* property, int size, Place place)
{
  mapper->SetInputDataObject(image);
  vtkNew<vtkRenderer> renderer;
  vtkVolume* volume = AddVolume(renderer, mapper, property);
  renderer->SetBackground(0.0, 0.0, 0.0);
  auto window = MakeRenderWindow(size, size);
  window->AddRenderer(renderer);
  place(renderer.Get());
  window->Render();
  double best = 1e300;
  for (int i = 0; i < 3; ++i)
  {
    volume->Modified();
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    best = std::min(best,
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  return { ToRGB(Capture(window)), best };
}

/// The MRI head of splat_bench and splat_render (splatexample::MriFile: Debian's mricron-data, or
/// $SPLAT_MRI_FILE), or null when the file is absent.
inline vtkSmartPointer<vtkImageData> ReadMri()
{
  vtkSmartPointer<vtkImageData> image = splatexample::MriHead(1);
  if (!image)
  {
    std::printf("%s is absent (Debian package mricron-data): MRI comparison skipped\n",
      splatexample::MriFile().c_str());
  }
  return image;
}

/// The MRI tests' camera: from below and the side, framing the head.
inline void PlaceMriCamera(vtkRenderer* renderer)
{
  renderer->ResetCamera();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->Elevation(-70.0);
  camera->OrthogonalizeViewUp();
  camera->Azimuth(35.0);
  renderer->ResetCameraClippingRange();
}
}

#endif
