// SPDX-License-Identifier: BSD-3-Clause
// Data far from the origin renders like data at the origin, with either backend: a splatted
// sphere of radius 1 moved to (3e6, -2e6, 1e6), with the camera moved by the same offset,
// gives the image of the sphere at the origin within an RMSE of 1/255 (float positions there
// are 0.25 apart; both backends work in double precision until the data is camera-relative).
#include "SplatCheckerboardReference.h"
#include "SplatTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkSurfaceSplatMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <cstdio>

namespace
{
OIIO::ImageBuf Render(vtkPolyData* sphere, const double offset[3], int backend)
{
  auto moved = vtkSmartPointer<vtkPolyData>::New();
  moved->DeepCopy(sphere);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    const double* p = sphere->GetPoint(i);
    points->InsertNextPoint(p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]);
  }
  moved->SetPoints(points);
  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputData(moved);
  mapper->SetBackend(backend);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.9, 0.6, 0.3);
  actor->GetProperty()->SetSpecular(0.3);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  auto window = splattest::MakeRenderWindow(200, 200);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(offset);
  camera->SetPosition(offset[0] + 1.0, offset[1] - 2.0, offset[2] + 3.5);
  renderer->ResetCameraClippingRange();
  window->Render();
  return splatexample::CaptureWindow(window);
}
}

int main(int, char*[])
{
  vtkSmartPointer<vtkPolyData> sphere = splattest::SurfelSphere(20000, 1.0);
  const double origin[3] = { 0.0, 0.0, 0.0 };
  const double far[3] = { 3e6, -2e6, 1e6 };
  int failures = 0;
  for (int backend : { vtkSplatBackend::CPU, vtkSplatBackend::OPENGL })
  {
    const auto compared = OIIO::ImageBufAlgo::compare(
      Render(sphere, origin, backend), Render(sphere, far, backend), 1.0f, 1.0f);
    std::printf("%s: at the origin vs at (3e6, -2e6, 1e6): RMSE %.5f, max difference %.3f\n",
      vtkSplatBackend::GetBackendAsString(backend), compared.rms_error, compared.maxerror);
    failures += compared.rms_error <= 1.0 / 255.0 ? 0 : 1;
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
