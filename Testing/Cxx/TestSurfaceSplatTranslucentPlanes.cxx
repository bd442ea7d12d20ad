// SPDX-License-Identifier: BSD-3-Clause
// Two parallel translucent splat planes (red, opacity 0.5 at z = 0.2; blue, 0.6 at z = 0; actor
// opacity 0.9 on both) and an opaque green triangle plane must give the analytically blended
// color, whichever splat plane comes first in the input. With the green plane behind both:
// c = c_f a_f + c_b a_b (1 - a_f) + green (1 - a_f) (1 - a_b); with the green plane between
// them the blue plane is hidden: c = c_f a_f + green (1 - a_f).
#include "SplatTestUtilities.h"
#include "vtkSurfaceSplatMapper.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <cstdio>

namespace
{
// Renders the planes with the front one first or second and the green plane at height
// floorZ; returns the wrong probe pixels.
int CountWrongPixels(bool frontFirst, double floorZ)
{
  const double u[3] = { 0.02, 0.0, 0.0 };
  const double v[3] = { 0.0, 0.02, 0.0 };
  const double frontCenter[3] = { 0.0, 0.0, 0.2 };
  const double backCenter[3] = { 0.0, 0.0, 0.0 };
  const double red[3] = { 1.0, 0.0, 0.0 };
  const double blue[3] = { 0.0, 0.0, 1.0 };
  vtkSmartPointer<vtkPolyData> front = splattest::SurfelPlane(frontCenter, u, v, 61, 61);
  vtkSmartPointer<vtkPolyData> back = splattest::SurfelPlane(backCenter, u, v, 61, 61);
  splattest::Paint(front, red, 0.5);
  splattest::Paint(back, blue, 0.6);
  vtkNew<vtkAppendPolyData> planes;
  planes->AddInputData(frontFirst ? front : back);
  planes->AddInputData(frontFirst ? back : front);

  vtkNew<vtkSurfaceSplatMapper> splats;
  splats->SetInputConnection(planes->GetOutputPort());
  splats->SetColorModeToDirectScalars();
  vtkNew<vtkActor> splatActor;
  splatActor->SetMapper(splats);
  splatActor->GetProperty()->LightingOff();
  splatActor->GetProperty()->SetOpacity(0.9);

  vtkNew<vtkPlaneSource> floor;
  floor->SetOrigin(-2.0, -2.0, floorZ);
  floor->SetPoint1(2.0, -2.0, floorZ);
  floor->SetPoint2(-2.0, 2.0, floorZ);
  vtkNew<vtkPolyDataMapper> floorMapper;
  floorMapper->SetInputConnection(floor->GetOutputPort());
  vtkNew<vtkActor> floorActor;
  floorActor->SetMapper(floorMapper);
  floorActor->GetProperty()->SetColor(0.0, 1.0, 0.0);
  floorActor->GetProperty()->LightingOff();

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(floorActor);
  renderer->AddActor(splatActor);
  auto window = splattest::MakeRenderWindow(200, 200);
  window->AddRenderer(renderer);
  renderer->GetActiveCamera()->SetPosition(0.0, 0.0, 3.0);
  renderer->GetActiveCamera()->SetFocalPoint(0.0, 0.0, 0.0);
  renderer->ResetCameraClippingRange();
  window->Render();
  vtkSmartPointer<vtkImageData> image = splattest::Capture(window);

  const double af = 0.9 * 0.5;
  const double ab = floorZ < 0.0 ? 0.9 * 0.6 : 0.0; // the blue plane hidden behind the floor
  const double expected[3] = { af, (1.0 - af) * (1.0 - ab), ab * (1.0 - af) };
  int wrong = 0;
  for (int y = 70; y <= 130; y += 10)
  {
    for (int x = 70; x <= 130; x += 10)
    {
      double rgb[3];
      splattest::Pixel(image, x, y, rgb);
      if (std::abs(rgb[0] - expected[0]) > 0.02 || std::abs(rgb[1] - expected[1]) > 0.02 ||
        std::abs(rgb[2] - expected[2]) > 0.02)
      {
        std::printf("%s first, floor at %.1f: pixel (%d, %d) is (%.3f %.3f %.3f), expected "
                    "(%.3f %.3f %.3f)\n",
          frontFirst ? "front" : "back", floorZ, x, y, rgb[0], rgb[1], rgb[2], expected[0],
          expected[1], expected[2]);
        ++wrong;
      }
    }
  }
  return wrong;
}
}

int main(int, char*[])
{
  int wrong = 0;
  for (double floorZ : { -0.3, 0.1 })
  {
    wrong += CountWrongPixels(true, floorZ) + CountWrongPixels(false, floorZ);
  }
  std::printf("%d wrong probe pixels of 196\n", wrong);
  return wrong == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
