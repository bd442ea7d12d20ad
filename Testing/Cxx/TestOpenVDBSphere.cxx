// SPDX-License-Identifier: BSD-3-Clause
// The level set ../shared/data/sphere.vdb (grid "ls_sphere": a sphere of radius 3 centered at
// the origin, voxel size 0.05, narrow band of 3 voxels; its values are the signed distance to
// that sphere) through vtkOpenVDBReader as surfels:
// - every surfel lies on the analytic sphere within MAX_DISTANCE voxel sizes and its normal
//   within MAX_NORMAL_DEGREES of the sphere's;
// - drawn by vtkSurfaceSplatMapper in a parallel view, its silhouette matches the sphere's disk
//   (IoU at least MIN_IOU) with no background pixel (hole) inside the disk shrunk by 2 pixels.
// Skips (125) when the file is absent.
#include "SplatTestUtilities.h"
#include "vtkOpenVDBReader.h"
#include "vtkSurfaceSplatMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <cstdio>

namespace
{
int failures = 0;
void Check(bool ok, const char* what, double measured)
{
  std::printf("%s: %g\n", what, measured);
  if (!ok)
  {
    std::fprintf(stderr, "FAILED: %s (%g)\n", what, measured);
    ++failures;
  }
}

const double Radius = 3.0;
const double VoxelSize = 0.05;
}

int main(int argc, char* argv[])
{
  const std::string path = splattest::Argument(argc, argv, "-D") + "/sphere.vdb";
  if (!splattest::FileExists(path))
  {
    std::printf("%s is absent: skipped\n", path.c_str());
    return splattest::SkipReturnCode;
  }
  vtkNew<vtkOpenVDBReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* surfels = reader->GetOutput();
  vtkDataArray* normals = surfels->GetPointData()->GetNormals();
  vtkDataArray* radii = surfels->GetPointData()->GetArray("Radius");
  const vtkIdType n = surfels->GetNumberOfPoints();
  Check(n > 10000 && normals && radii, "surfels", static_cast<double>(n));
  if (failures)
  {
    return 1;
  }
  double maxDistance = 0.0, maxAngle = 0.0, sumSquares = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3], normal[3];
    surfels->GetPoint(i, p);
    normals->GetTuple(i, normal);
    const double r = vtkMath::Norm(p);
    const double distance = std::abs(r - Radius) / VoxelSize;
    maxDistance = std::max(maxDistance, distance);
    sumSquares += distance * distance;
    const double cosine = vtkMath::Dot(p, normal) / (r * vtkMath::Norm(normal));
    maxAngle = std::max(maxAngle, vtkMath::DegreesFromRadians(std::acos(std::min(cosine, 1.0))));
  }
  Check(maxDistance <= MAX_DISTANCE, "largest distance to the sphere (voxels)", maxDistance);
  std::printf("RMS distance (voxels): %g\n", std::sqrt(sumSquares / n));
  Check(maxAngle <= MAX_NORMAL_DEGREES, "largest normal error (degrees)", maxAngle);
  Check(radii->GetRange()[0] == radii->GetRange()[1] &&
      std::abs(radii->GetRange()[0] - VoxelSize) < 1e-6,
    "surfel radius", radii->GetRange()[0]);

  // Silhouette in a parallel view down an oblique axis: the disk of radius 3 about the center.
  const int size = 300;
  auto window = splattest::MakeRenderWindow(size, size);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  renderer->SetBackground(0.0, 0.0, 0.0);
  vtkNew<vtkSurfaceSplatMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(1.0, 1.0, 1.0);
  actor->GetProperty()->SetAmbient(0.3);
  renderer->AddActor(actor);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetPosition(5.0, 4.0, 7.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetParallelScale(4.0);
  renderer->ResetCameraClippingRange();
  window->Render();
  auto image = splattest::Capture(window);
  const double pixel = 2.0 * 4.0 / size; // world units per pixel
  vtkIdType both = 0, either = 0, holes = 0;
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      double rgb[3];
      splattest::Pixel(image, x, y, rgb);
      const bool drawn = rgb[0] + rgb[1] + rgb[2] > 0.0;
      const double d = std::hypot(x + 0.5 - 0.5 * size, y + 0.5 - 0.5 * size) * pixel;
      const bool inside = d <= Radius;
      both += drawn && inside;
      either += drawn || inside;
      holes += !drawn && d <= Radius - 2.0 * pixel;
    }
  }
  const double iou = static_cast<double>(both) / either;
  Check(iou >= MIN_IOU, "silhouette IoU", iou);
  Check(holes == 0, "background pixels inside the disk", static_cast<double>(holes));
  return failures == 0 ? 0 : 1;
}
