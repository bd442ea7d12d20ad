// SPDX-License-Identifier: BSD-3-Clause
// Regression image: three mutually perpendicular translucent splat planes (red, green, blue,
// opacity 0.5) intersecting at the origin, lit, seen obliquely: every region blends its layers
// back to front, with no holes along the intersection lines.
#include "SplatTestUtilities.h"
#include "vtkSurfaceSplatMapper.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderer.h"

int main(int argc, char* argv[])
{
  const double origin[3] = { 0.0, 0.0, 0.0 };
  const double h = 0.02;
  const double x[3] = { h, 0.0, 0.0 };
  const double y[3] = { 0.0, h, 0.0 };
  const double z[3] = { 0.0, 0.0, h };
  const double colors[3][3] = { { 1.0, 0.2, 0.2 }, { 0.2, 1.0, 0.2 }, { 0.2, 0.2, 1.0 } };
  vtkSmartPointer<vtkPolyData> planes[3] = { splattest::SurfelPlane(origin, x, y, 61, 61),
    splattest::SurfelPlane(origin, y, z, 61, 61), splattest::SurfelPlane(origin, z, x, 61, 61) };
  vtkNew<vtkAppendPolyData> append;
  for (int i = 0; i < 3; ++i)
  {
    splattest::Paint(planes[i], colors[i], 0.5);
    append->AddInputData(planes[i]);
  }

  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputConnection(append->GetOutputPort());
  mapper->SetColorModeToDirectScalars();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetAmbient(0.4);
  actor->GetProperty()->SetDiffuse(0.7);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  auto window = splattest::MakeRenderWindow(300, 300);
  window->AddRenderer(renderer);
  renderer->GetActiveCamera()->SetPosition(2.0, 1.5, 2.5);
  renderer->GetActiveCamera()->SetFocalPoint(0.0, 0.0, 0.0);
  renderer->ResetCamera();
  window->Render();
  return vtkRegressionTestImage(window) == vtkTesting::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
