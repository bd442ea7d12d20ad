// SPDX-License-Identifier: BSD-3-Clause
// Regression image: a splatted sphere colored by a scalar through the mapper's lookup table,
// lit by the renderer's headlight with specular highlights.
#include "SplatTestUtilities.h"
#include "vtkSurfaceSplatMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderer.h"

int main(int argc, char* argv[])
{
  vtkSmartPointer<vtkPolyData> sphere = splattest::SurfelSphere(20000, 1.0);
  vtkNew<vtkFloatArray> height;
  height->SetName("Height");
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    height->InsertNextValue(static_cast<float>(sphere->GetPoint(i)[2]));
  }
  sphere->GetPointData()->SetScalars(height);

  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputData(sphere);
  mapper->SetScalarRange(-1.0, 1.0);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.4);
  actor->GetProperty()->SetSpecularPower(30.0);
  actor->RotateX(-60.0);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  auto window = splattest::MakeRenderWindow(300, 300);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.6);
  window->Render();

  if (mapper->GetNumberOfRenderedSplats() == 0 || mapper->GetNumberOfSkippedPoints() != 0)
  {
    std::cerr << "Expected every splat drawn, got " << mapper->GetNumberOfRenderedSplats()
              << " drawn and " << mapper->GetNumberOfSkippedPoints() << " skipped.\n";
    return EXIT_FAILURE;
  }
  // Colors from scalars keep the paper's low-pass: a smaller one would let them alias.
  if (mapper->GetLastMagnifiedLowPassVariance() != 1.0 ||
    mapper->GetLastMinifiedLowPassVariance() != 1.0)
  {
    std::cerr << "Expected the paper's low-pass for colors from scalars, got "
              << mapper->GetLastMagnifiedLowPassVariance() << " magnified and "
              << mapper->GetLastMinifiedLowPassVariance() << " minified.\n";
    return EXIT_FAILURE;
  }
  return vtkRegressionTestImage(window) == vtkTesting::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
