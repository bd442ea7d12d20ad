// SPDX-License-Identifier: BSD-3-Clause
// Bad input never crashes nor reaches the image: points with NaN/Inf positions, normals or
// radii, zero normals and non-positive radii are skipped and counted; the rest, normals of tiny
// and huge length included, renders, and an input without normals is refused with an error
// instead of drawing garbage.
#include "SplatTestUtilities.h"
#include "vtkSurfaceSplatMapper.h"

#include "vtkActor.h"
#include "vtkDoubleArray.h"
#include "vtkRenderer.h"
#include "vtkTestErrorObserver.h"

#include <cstdio>
#include <limits>

int main(int, char*[])
{
  vtkSmartPointer<vtkPolyData> cloud = splattest::SurfelSphere(2000, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  cloud->GetPoints()->SetPoint(0, nan, 0.0, 0.0);
  cloud->GetPoints()->SetPoint(1, 0.0, inf, 0.0);
  cloud->GetPointData()->GetNormals()->SetTuple3(2, 0.0, 0.0, 0.0);
  cloud->GetPointData()->GetNormals()->SetTuple3(3, nan, 1.0, 0.0);
  vtkDataArray* radius = cloud->GetPointData()->GetArray("Radius");
  radius->SetTuple1(4, 0.0);
  radius->SetTuple1(5, -1.0);
  radius->SetTuple1(6, inf);
  const vtkIdType bad = 7;
  // Valid normals of tiny and huge length (in doubles: the squares of their components under-
  // and overflow) are drawn, not skipped.
  vtkNew<vtkDoubleArray> normals;
  normals->DeepCopy(cloud->GetPointData()->GetNormals());
  for (const auto& scaled : { std::make_pair(7, 1e-170), std::make_pair(8, 1e170) })
  {
    double n[3];
    normals->GetTuple(scaled.first, n);
    normals->SetTuple3(scaled.first, n[0] * scaled.second, n[1] * scaled.second,
      n[2] * scaled.second);
  }
  cloud->GetPointData()->SetNormals(normals);

  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputData(cloud);
  vtkNew<vtkTest::ErrorObserver> warnings;
  mapper->AddObserver(vtkCommand::WarningEvent, warnings);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  auto window = splattest::MakeRenderWindow(200, 200);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  window->Render();

  int failures = 0;
  if (mapper->GetNumberOfSkippedPoints() != bad ||
    mapper->GetNumberOfSplats() != cloud->GetNumberOfPoints() - bad ||
    !warnings->GetWarning())
  {
    std::printf("expected %lld skipped with a warning, got %lld skipped of %lld\n",
      static_cast<long long>(bad), static_cast<long long>(mapper->GetNumberOfSkippedPoints()),
      static_cast<long long>(cloud->GetNumberOfPoints()));
    ++failures;
  }
  vtkSmartPointer<vtkImageData> image = splattest::Capture(window);
  double center[3];
  splattest::Pixel(image, 100, 100, center);
  if (!(center[0] + center[1] + center[2] > 0.5))
  {
    std::printf("the valid splats were not drawn\n");
    ++failures;
  }

  // No normals: an error, nothing drawn, no crash.
  vtkNew<vtkPolyData> bare;
  bare->SetPoints(cloud->GetPoints());
  vtkNew<vtkSurfaceSplatMapper> bareMapper;
  bareMapper->SetInputData(bare);
  vtkNew<vtkTest::ErrorObserver> errors;
  bareMapper->AddObserver(vtkCommand::ErrorEvent, errors);
  actor->SetMapper(bareMapper);
  window->Render();
  if (!errors->GetError() || bareMapper->GetNumberOfRenderedSplats() != 0)
  {
    std::printf("an input without normals was not refused\n");
    ++failures;
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
