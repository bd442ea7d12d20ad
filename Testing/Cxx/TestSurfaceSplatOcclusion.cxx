// SPDX-License-Identifier: BSD-3-Clause
// Occlusion between splats and triangles: a splatted plane z = x / 2 (red) interpenetrates a
// triangle plane z = 0 (green) along the y axis. Seen from +z, pixels with x > 0 must show the
// splats and pixels with x < 0 the triangles, whichever actor is drawn first, with either
// backend.
#include "SplatTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <cstdio>

namespace
{
vtkSmartPointer<vtkActor> FlatActor(vtkMapper* mapper, double r, double g, double b)
{
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, b);
  actor->GetProperty()->LightingOff();
  return actor;
}

// Renders with the splats added first or second; returns the number of wrong probe pixels.
int CountWrongPixels(bool splatsFirst, int backend)
{
  vtkNew<vtkSurfaceSplatMapper> splatMapper;
  splatMapper->SetBackend(backend);
  const double center[3] = { 0.0, 0.0, 0.0 };
  const double u[3] = { 0.025, 0.0, 0.0125 }; // the plane z = x / 2
  const double v[3] = { 0.0, 0.025, 0.0 };
  splatMapper->SetInputData(splattest::SurfelPlane(center, u, v, 81, 81));
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-1.0, -1.0, 0.0);
  plane->SetPoint1(1.0, -1.0, 0.0);
  plane->SetPoint2(-1.0, 1.0, 0.0);
  plane->SetResolution(4, 4);
  vtkNew<vtkPolyDataMapper> meshMapper;
  meshMapper->SetInputConnection(plane->GetOutputPort());
  auto splats = FlatActor(splatMapper, 1.0, 0.0, 0.0);
  auto mesh = FlatActor(meshMapper, 0.0, 1.0, 0.0);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(splatsFirst ? splats : mesh);
  renderer->AddActor(splatsFirst ? mesh : splats);
  auto window = splattest::MakeRenderWindow(300, 300);
  window->AddRenderer(renderer);
  renderer->GetActiveCamera()->SetPosition(0.0, 0.0, 4.0);
  renderer->GetActiveCamera()->SetFocalPoint(0.0, 0.0, 0.0);
  renderer->ResetCameraClippingRange();
  window->Render();
  vtkSmartPointer<vtkImageData> image = splattest::Capture(window);

  int wrong = 0;
  for (double x : { -0.8, -0.5, -0.2, -0.1, 0.1, 0.2, 0.5, 0.8 })
  {
    for (double y : { -0.6, 0.0, 0.6 })
    {
      // Probe where the nearer surface is: the splat plane for x > 0, the mesh for x < 0.
      renderer->SetWorldPoint(x, y, x > 0 ? 0.5 * x : 0.0, 1.0);
      renderer->WorldToDisplay();
      const double* display = renderer->GetDisplayPoint();
      double rgb[3];
      splattest::Pixel(image, static_cast<int>(display[0]), static_cast<int>(display[1]), rgb);
      const bool splatWins = rgb[0] > 0.9 && rgb[1] < 0.1;
      const bool meshWins = rgb[1] > 0.9 && rgb[0] < 0.1;
      if ((x > 0 && !splatWins) || (x < 0 && !meshWins))
      {
        std::printf("%s, splats %s: wrong color (%.2f %.2f %.2f) at x = %.1f, y = %.1f\n",
          vtkSplatBackend::GetBackendAsString(backend), splatsFirst ? "first" : "second",
          rgb[0], rgb[1], rgb[2], x, y);
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
  for (int backend : { vtkSplatBackend::CPU, vtkSplatBackend::OPENGL })
  {
    wrong += CountWrongPixels(true, backend) + CountWrongPixels(false, backend);
  }
  std::printf("%d wrong probe pixels of 96\n", wrong);
  return wrong == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
