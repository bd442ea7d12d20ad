// SPDX-License-Identifier: BSD-3-Clause
// Per-pixel depth correction (An and Zhou, section 4.3 and figure 7), with either backend:
// 1. Two splatted planes that intersect at 8 degrees meet along a straight line: each pixel's
//    depth is its ray's intersection with each splat's tangent plane, so the visible surface
//    switches exactly where the planes cross, not in splat-sized steps (per-splat depths would
//    give a zigzag as wide as the splats). The boundary found in every image row must lie within
//    a pixel of a fitted straight line. Regression image of the OpenGL backend's rendering.
// 2. A near and a far copy of the same pair of parallel planes (red in front, blue behind at
//    twice the splat radius, the default depth threshold being one radius) use the same
//    threshold successfully: the depth is linear in eye space, so the threshold is the same
//    distance near and far, and the front plane hides the back one in both copies (with a 1/z
//    depth and a fixed window-space epsilon the far copy would blend the back plane in).
#include "SplatTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderer.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
constexpr int Size = 300;

vtkSmartPointer<vtkActor> PlaneActor(
  const double center[3], const double u[3], const double v[3], int n, const double rgb[3])
{
  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputData(splattest::SurfelPlane(center, u, v, n, n));
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(rgb[0], rgb[1], rgb[2]);
  actor->GetProperty()->LightingOff();
  return actor;
}

void SetBackend(vtkRenderer* renderer, int backend)
{
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor())
  {
    vtkSurfaceSplatMapper::SafeDownCast(actor->GetMapper())->SetBackend(backend);
  }
}

// The largest distance of the red/green boundary, row by row, from its least-squares line.
double BoundaryDeviation(vtkImageData* image)
{
  std::vector<double> ys, xs;
  for (int y = 20; y < Size - 20; ++y)
  {
    // The first green pixel after a red one, at sub-pixel precision from the mixed pixel.
    for (int x = 1; x < Size; ++x)
    {
      double left[3], right[3];
      splattest::Pixel(image, x - 1, y, left);
      splattest::Pixel(image, x, y, right);
      if (left[0] > left[1] && right[1] >= right[0] && left[0] > 0.5)
      {
        const double t = (left[0] - left[1]) / ((left[0] - left[1]) + (right[1] - right[0]));
        xs.push_back(x - 1 + t);
        ys.push_back(y);
        break;
      }
    }
  }
  if (xs.size() < Size / 2)
  {
    std::printf("the boundary was found in %zu rows only\n", xs.size());
    return 1e9;
  }
  double sy = 0, sx = 0, syy = 0, sxy = 0;
  const double n = static_cast<double>(xs.size());
  for (std::size_t i = 0; i < xs.size(); ++i)
  {
    sy += ys[i];
    sx += xs[i];
    syy += ys[i] * ys[i];
    sxy += ys[i] * xs[i];
  }
  const double slope = (n * sxy - sy * sx) / (n * syy - sy * sy);
  const double offset = (sx - slope * sy) / n;
  double deviation = 0.0;
  for (std::size_t i = 0; i < xs.size(); ++i)
  {
    deviation = std::max(deviation, std::abs(xs[i] - (slope * ys[i] + offset)));
  }
  return deviation;
}

// Pixels of the far copy's and the near copy's interior that show the back plane.
int BackPlanePixels(int backend, double distance)
{
  const double u[3] = { 0.1, 0.0, 0.0 };
  const double v[3] = { 0.0, 0.1, 0.0 };
  const double front[3] = { 0.0, 0.0, 0.0 };
  const double back[3] = { 0.0, 0.0, -0.2 }; // twice the splat radius behind
  const double red[3] = { 1.0, 0.0, 0.0 };
  const double blue[3] = { 0.0, 0.0, 1.0 };
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(PlaneActor(back, u, v, 21, blue));
  renderer->AddActor(PlaneActor(front, u, v, 21, red));
  SetBackend(renderer, backend);
  auto window = splattest::MakeRenderWindow(Size, Size);
  window->AddRenderer(renderer);
  renderer->GetActiveCamera()->SetPosition(0.3 * distance, 0.2 * distance, distance);
  renderer->GetActiveCamera()->SetFocalPoint(0.0, 0.0, 0.0);
  renderer->ResetCameraClippingRange();
  window->Render();
  vtkSmartPointer<vtkImageData> image = splattest::Capture(window);
  int wrong = 0, probed = 0;
  for (double x = -0.7; x <= 0.7; x += 0.1)
  {
    for (double y = -0.7; y <= 0.7; y += 0.1)
    {
      renderer->SetWorldPoint(x, y, 0.0, 1.0);
      renderer->WorldToDisplay();
      const double* display = renderer->GetDisplayPoint();
      double rgb[3];
      splattest::Pixel(image, static_cast<int>(display[0]), static_cast<int>(display[1]), rgb);
      ++probed;
      if (!(rgb[0] > 0.9 && rgb[2] < 0.1))
      {
        ++wrong;
      }
    }
  }
  std::printf("%s, camera at distance %g: %d of %d interior pixels not the front plane\n",
    vtkSplatBackend::GetBackendAsString(backend), distance, wrong, probed);
  return wrong;
}
}

int main(int argc, char* argv[])
{
  // 1. The crossing planes: z = 0 (red) and z = tan(8 deg) x (green), crossing along y; the
  //    green plane's grid is turned by 30 degrees within the plane, so the splats of the two
  //    planes do not line up along the intersection.
  const double angle = vtkMath::RadiansFromDegrees(8.0);
  const double turn = vtkMath::RadiansFromDegrees(30.0);
  const double center[3] = { 0.0, 0.0, 0.0 };
  const double u[3] = { 0.05, 0.0, 0.0 };
  const double v[3] = { 0.0, 0.05, 0.0 };
  const double tilted[3] = { 0.05 * std::cos(angle), 0.0, 0.05 * std::sin(angle) };
  double tiltedU[3], tiltedV[3];
  for (int c = 0; c < 3; ++c)
  {
    tiltedU[c] = std::cos(turn) * tilted[c] + std::sin(turn) * v[c];
    tiltedV[c] = -std::sin(turn) * tilted[c] + std::cos(turn) * v[c];
  }
  const double red[3] = { 1.0, 0.1, 0.1 };
  const double green[3] = { 0.1, 1.0, 0.1 };
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(PlaneActor(center, u, v, 41, red));
  renderer->AddActor(PlaneActor(center, tiltedU, tiltedV, 41, green));
  auto window = splattest::MakeRenderWindow(Size, Size);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.8, -1.0, 3.2);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.4, 1.0, 0.0);
  renderer->ResetCameraClippingRange();
  int failures = 0;
  for (int backend : { vtkSplatBackend::CPU, vtkSplatBackend::OPENGL })
  {
    SetBackend(renderer, backend);
    window->Render();
    const double deviation = BoundaryDeviation(splattest::Capture(window));
    std::printf("%s: intersection line within %.3f pixels of a straight line\n",
      vtkSplatBackend::GetBackendAsString(backend), deviation);
    failures += deviation <= 1.0 ? 0 : 1;
  }
  // The regression image is the OpenGL backend's (the last render).
  failures += vtkRegressionTestImage(window) == vtkTesting::FAILED ? 1 : 0;

  // 2. The near and the far copy, with the same threshold.
  for (int backend : { vtkSplatBackend::CPU, vtkSplatBackend::OPENGL })
  {
    for (double distance : { 3.0, 30.0 })
    {
      failures += BackPlanePixels(backend, distance) == 0 ? 0 : 1;
    }
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
