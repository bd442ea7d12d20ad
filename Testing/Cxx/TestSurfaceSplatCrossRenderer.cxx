// SPDX-License-Identifier: BSD-3-Clause
// Cross-renderer check: a mesh drawn as triangles by vtkPolyDataMapper and as splats from its
// vertices by vtkSurfaceSplatMapper, same camera, lights and property (specular included, which
// VTK shades differently under its default headlight). The silhouettes must overlap
// (intersection over union) and the colors inside agree (mean absolute difference).
#include "SplatTestUtilities.h"
#include "vtkSurfaceSplatMapper.h"
#include "vtkSurfelGenerator.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkPLYReader.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <cstdio>

namespace
{
// Renders the mesh with the given mapper and returns the image. The camera is reset to the
// first mapper's bounds and then shared: the splats' bounds include their radii.
vtkSmartPointer<vtkImageData> Render(
  vtkAlgorithm* mesh, vtkPolyDataMapper* mapper, vtkCamera* camera, bool resetCamera)
{
  mapper->SetInputConnection(mesh->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.8, 0.7, 0.6);
  actor->GetProperty()->SetAmbient(0.1);
  actor->GetProperty()->SetDiffuse(0.9);
  actor->GetProperty()->SetSpecular(0.3);
  actor->GetProperty()->SetSpecularPower(20.0);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.0, 0.0, 0.0);
  auto window = splattest::MakeRenderWindow(400, 400);
  window->AddRenderer(renderer);
  renderer->SetActiveCamera(camera);
  if (resetCamera)
  {
    renderer->ResetCamera();
    camera->Azimuth(30.0);
    camera->Elevation(20.0);
    camera->OrthogonalizeViewUp();
    renderer->ResetCameraClippingRange();
  }
  window->Render();
  return splattest::Capture(window);
}

// Silhouette intersection over union and mean color difference on the intersection, in [0, 1].
bool Compare(const char* name, vtkAlgorithm* mesh, double minIoU, double maxColorDifference)
{
  vtkNew<vtkCamera> camera;
  vtkNew<vtkPolyDataMapper> triangles;
  vtkSmartPointer<vtkImageData> reference = Render(mesh, triangles, camera, true);
  vtkNew<vtkSurfelGenerator> surfels;
  surfels->SetInputConnection(mesh->GetOutputPort());
  vtkNew<vtkSurfaceSplatMapper> splats;
  vtkSmartPointer<vtkImageData> image = Render(surfels, splats, camera, false);

  int dims[3];
  image->GetDimensions(dims);
  long both = 0, either = 0;
  double difference = 0.0;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      double a[3], b[3];
      splattest::Pixel(reference, x, y, a);
      splattest::Pixel(image, x, y, b);
      const bool inA = a[0] + a[1] + a[2] > 0.0;
      const bool inB = b[0] + b[1] + b[2] > 0.0;
      either += inA || inB;
      if (inA && inB)
      {
        ++both;
        difference += (std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2])) / 3;
      }
    }
  }
  const double iou = either ? static_cast<double>(both) / either : 0.0;
  const double meanDifference = both ? difference / both : 1.0;
  std::printf("%s: silhouette IoU %.4f (bound >= %.3f), mean color difference %.4f (bound <= %.3f)\n",
    name, iou, minIoU, meanDifference, maxColorDifference);
  return iou >= minIoU && meanDifference <= maxColorDifference;
}
}

int main(int argc, char* argv[])
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(128);
  sphere->SetPhiResolution(64);
  bool ok = Compare("sphere", sphere, SPHERE_MIN_IOU, SPHERE_MAX_COLOR_DIFFERENCE);

  const std::string file = splattest::Argument(argc, argv, "-D") + "/bunny.ply";
  if (splattest::FileExists(file))
  {
    vtkNew<vtkPLYReader> bunny;
    bunny->SetFileName(file.c_str());
    ok = Compare("bunny", bunny, BUNNY_MIN_IOU, BUNNY_MAX_COLOR_DIFFERENCE) && ok;
  }
  else
  {
    std::cout << "bunny: " << file << " is absent, compared the sphere only.\n";
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
