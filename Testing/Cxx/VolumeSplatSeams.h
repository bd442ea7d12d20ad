// SPDX-License-Identifier: BSD-3-Clause
// The seams scene of TestVolumeSplatSeamsBlended and TestVolumeSplatSeamsClipped: a 10^3 grid of
// large, fairly opaque kernels of random colors, whose compositing order shows, seen with a
// 60-degree perspective camera that sweeps across the boundary between the X and Z regions
// (rays at 45 degrees in the XZ plane). Per frame, the jump across the boundary line (mean
// color difference of horizontal neighbors on either side of it) is compared with the jump
// elsewhere in the volume; the last frame is the regression image.
#ifndef VolumeSplatSeams_h
#define VolumeSplatSeams_h

#include "SplatVolumeTestUtilities.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkMinimalStandardRandomSequence.h"
#include "vtkRegressionTestImage.h"

#include <cstdio>
#include <string>

namespace splattest
{
/// The seams scene drawn by `mapper` in a new renderer of `window`, which keeps it.
inline vtkRenderer* AddSeamsScene(vtkVolumeSplatMapper* mapper, vtkRenderWindow* window)
{
  const int n = 10;
  vtkNew<vtkImageData> image;
  image->SetDimensions(n, n, n);
  image->SetSpacing(1.0 / n, 1.0 / n, 1.0 / n);
  image->SetOrigin(-0.5, -0.5, -0.5);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetNumberOfTuples(n * n * n);
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(5);
  for (vtkIdType id = 0; id < n * n * n; ++id)
  {
    scalars->SetValue(id, static_cast<float>(random->GetNextRangeValue(0.0, 1.0)));
  }
  image->GetPointData()->SetScalars(scalars);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.6);
  opacity->AddPoint(1.0, 0.6);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 1.0, 0.1, 0.1);
  color->AddRGBPoint(0.5, 0.1, 1.0, 0.1);
  color->AddRGBPoint(1.0, 0.1, 0.2, 1.0);
  vtkNew<vtkVolumeProperty> property;
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetScalarOpacityUnitDistance(1.0 / n);
  mapper->SetInputData(image);
  vtkNew<vtkRenderer> renderer;
  splattest::AddVolume(renderer, mapper, property);
  window->AddRenderer(renderer);
  return renderer;
}

/// For the image in `window` of the seams scene in `renderer`: the ratio of the mean jump
/// between horizontal neighbors whose rays have different dominant axes to the mean jump
/// elsewhere in the volume; 0 where no such boundary crosses the volume's image. Perspective
/// cameras only (the rays run from the eye).
inline double SeamRatio(vtkRenderer* renderer, vtkRenderWindow* window, const char* label)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  int* size = window->GetSize();
  auto rgb = ToRGB(Capture(window));
  // The dominant axis of each pixel's ray.
  std::vector<int> axis(size[0] * size[1]);
  double eye[3];
  camera->GetPosition(eye);
  for (int y = 0; y < size[1]; ++y)
    for (int x = 0; x < size[0]; ++x)
    {
      renderer->SetDisplayPoint(x + 0.5, y + 0.5, 0.0);
      renderer->DisplayToWorld();
      double p[4];
      renderer->GetWorldPoint(p);
      const double d[3] = { std::abs(p[0] / p[3] - eye[0]), std::abs(p[1] / p[3] - eye[1]),
        std::abs(p[2] / p[3] - eye[2]) };
      axis[y * size[0] + x] = d[0] >= d[1] && d[0] >= d[2] ? 0 : (d[1] >= d[2] ? 1 : 2);
    }
  double boundary = 0.0, elsewhere = 0.0;
  int boundaryCount = 0, elsewhereCount = 0;
  for (int y = 0; y < size[1]; ++y)
    for (int x = 3; x + 4 < size[0]; ++x)
    {
      const int p = y * size[0] + x;
      double jump = 0.0, brightness = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        jump += std::abs(rgb[3 * (p + 1) + c] - rgb[3 * p + c]) / 3.0;
        brightness += rgb[3 * p + c] + rgb[3 * (p + 1) + c];
      }
      if (brightness < 0.3)
      {
        continue; // outside the volume
      }
      if (axis[p] != axis[p + 1])
      {
        boundary += jump;
        ++boundaryCount;
      }
      else if (axis[p - 3] == axis[p + 4])
      {
        elsewhere += jump;
        ++elsewhereCount;
      }
    }
  if (boundaryCount == 0 || elsewhereCount == 0)
  {
    return 0.0;
  }
  const double ratio = (boundary / boundaryCount) / (elsewhere / elsewhereCount);
  std::printf("%s: jump across the boundary %.4f (%d pairs), elsewhere %.4f, ratio %.2f\n",
    label, boundary / boundaryCount, boundaryCount, elsewhere / elsewhereCount, ratio);
  return ratio;
}

/// The largest ratio of boundary jump to the jump elsewhere over the camera path.
inline double SweepSeams(vtkVolumeSplatMapper* mapper, vtkRenderWindow* window, int frames)
{
  vtkRenderer* renderer = AddSeamsScene(mapper, window);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetViewAngle(60.0);
  double worst = 0.0;
  for (int frame = 0; frame < frames; ++frame)
  {
    // The view direction turns from 36 to 44 degrees off -z: the 45-degree boundary moves
    // across the volume's image.
    const double angle = vtkMath::RadiansFromDegrees(36.0 + 8.0 * frame / std::max(frames - 1, 1));
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetPosition(1.3 * std::sin(angle), 0.15, 1.3 * std::cos(angle));
    camera->SetViewUp(0.0, 1.0, 0.0);
    renderer->ResetCameraClippingRange();
    window->Render();
    const std::string label = "frame " + std::to_string(frame);
    worst = std::max(worst, SeamRatio(renderer, window, label.c_str()));
  }
  return worst;
}
}

#endif
