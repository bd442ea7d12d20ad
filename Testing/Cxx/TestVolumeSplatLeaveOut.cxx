// SPDX-License-Identifier: BSD-3-Clause
// What vtkVolumeSplatMapper leaves out, from its statistics (paper 003, table 1):
// - a view straight down the Z axis traverses exactly one list, the Z list;
// - a transfer function that hides half the voxels keeps about half the kernels and projects
//   about half as many;
// - image data is never sorted, in any axis-list mode; the depth-sorted baseline sorts once per
//   frame;
// - the lists are rebuilt when the transfer function changes, and only then;
// - point sets are sorted once per list they need.
#include "SplatVolumeTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkVolumeSplatMapper.h"

#include <cstdio>

namespace
{
int failures = 0;
void Check(bool ok, const char* what)
{
  if (!ok)
  {
    std::fprintf(stderr, "FAILED: %s\n", what);
    ++failures;
  }
}
}

int main(int, char*[])
{
  // A 40^3 ramp: the scalar is the x index.
  vtkNew<vtkImageData> image;
  image->SetDimensions(40, 40, 40);
  image->SetSpacing(0.05, 0.05, 0.05);
  image->SetOrigin(-1.0, -1.0, -1.0);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetNumberOfTuples(40 * 40 * 40);
  for (vtkIdType id = 0; id < 40 * 40 * 40; ++id)
  {
    scalars->SetValue(id, static_cast<float>(id % 40));
  }
  image->GetPointData()->SetScalars(scalars);
  const double rgb[3] = { 1.0, 0.8, 0.6 };
  auto property = splattest::ExtinctionProperty(39.0, 0.05, rgb);
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity();
  opacity->RemoveAllPoints();
  opacity->AddPoint(0.0, 0.05);
  opacity->AddPoint(39.0, 0.05);

  vtkNew<vtkVolumeSplatMapper> mapper;
  mapper->SetInputData(image);
  vtkNew<vtkRenderer> renderer;
  vtkVolume* volume = splattest::AddVolume(renderer, mapper, property);
  auto window = splattest::MakeRenderWindow(200, 200);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.0, 0.0, 6.0);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  renderer->ResetCameraClippingRange();
  window->Render();

  std::printf("down Z: lists %d %d %d, projected %lld %lld %lld of %lld kernels\n",
    mapper->GetListTraversed(0), mapper->GetListTraversed(1), mapper->GetListTraversed(2),
    static_cast<long long>(mapper->GetNumberOfProjectedKernels(0)),
    static_cast<long long>(mapper->GetNumberOfProjectedKernels(1)),
    static_cast<long long>(mapper->GetNumberOfProjectedKernels(2)),
    static_cast<long long>(mapper->GetNumberOfKernels()));
  Check(!mapper->GetListTraversed(0) && !mapper->GetListTraversed(1) &&
      mapper->GetListTraversed(2),
    "a view down Z traverses the Z list only");
  Check(mapper->GetNumberOfProjectedKernels() == 64000, "every kernel projected once");
  Check(mapper->GetNumberOfListBuilds() == 1, "one list built");
  const vtkIdType allProjected = mapper->GetNumberOfProjectedKernels();

  // Unchanged: no rebuild.
  window->Render();
  Check(mapper->GetNumberOfListBuilds() == 1, "no list rebuilt without a change");

  // Hide the voxels with x index below 20: half the kernels.
  opacity->RemoveAllPoints();
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(19.4, 0.0);
  opacity->AddPoint(19.6, 0.05);
  opacity->AddPoint(39.0, 0.05);
  window->Render();
  std::printf("half hidden: %lld kernels, %lld transparent, %lld projected\n",
    static_cast<long long>(mapper->GetNumberOfKernels()),
    static_cast<long long>(mapper->GetNumberOfTransparentKernels()),
    static_cast<long long>(mapper->GetNumberOfProjectedKernels()));
  Check(mapper->GetNumberOfKernels() == 32000 && mapper->GetNumberOfTransparentKernels() == 32000,
    "half the kernels in the lists");
  Check(std::abs(2 * mapper->GetNumberOfProjectedKernels() - allProjected) <= allProjected / 50,
    "about half the kernels projected");
  Check(mapper->GetNumberOfListBuilds() == 2, "the lists rebuilt after the transfer function changed");

  // An oblique view needs several lists; none of the axis modes sorts image data.
  camera->SetPosition(4.0, 3.0, 3.5);
  renderer->ResetCameraClippingRange();
  for (int mode : { vtkVolumeSplatMapper::BLENDED, vtkVolumeSplatMapper::CLIPPED,
         vtkVolumeSplatMapper::SINGLE_AXIS })
  {
    mapper->SetOrderingMode(mode);
    window->Render();
  }
  Check(mapper->GetNumberOfSorts() == 0, "image data is never sorted");
  // The camera moves, the transfer function stays: no data-only work again.
  const vtkIdType kernelBuilds = mapper->GetNumberOfKernelBuilds();
  const vtkIdType listBuilds = mapper->GetNumberOfListBuilds();
  for (int frame = 0; frame < 3; ++frame)
  {
    camera->Azimuth(3.0);
    camera->Elevation(2.0);
    camera->OrthogonalizeViewUp();
    window->Render();
  }
  Check(kernelBuilds == 2 && mapper->GetNumberOfKernelBuilds() == kernelBuilds &&
      mapper->GetNumberOfListBuilds() == listBuilds,
    "a moved camera rebuilds neither kernels nor lists");
  mapper->SetOrderingModeToDepthSorted();
  window->Render();
  window->Render();
  Check(mapper->GetNumberOfSorts() == 2, "the depth-sorted baseline sorts once per frame");
  Check(mapper->GetListTraversed(3) && mapper->GetNumberOfProjectedKernels(3) > 0,
    "the depth-sorted list is reported");

  // A point set: its lists are sorted when first needed, once.
  vtkNew<vtkPolyData> points;
  vtkNew<vtkPoints> positions;
  vtkNew<vtkFloatArray> covariances;
  covariances->SetName("Covariance");
  covariances->SetNumberOfComponents(6);
  vtkNew<vtkFloatArray> values;
  values->SetName("Scalar");
  for (int i = 0; i < 500; ++i)
  {
    positions->InsertNextPoint(
      std::sin(1.7 * i), std::cos(2.3 * i), std::sin(0.37 * i + 1.0));
    covariances->InsertNextTuple6(0.01, 0.0, 0.0, 0.01, 0.0, 0.01);
    values->InsertNextValue(30.0f);
  }
  points->SetPoints(positions);
  points->GetPointData()->AddArray(covariances);
  points->GetPointData()->SetScalars(values);
  vtkNew<vtkVolumeSplatMapper> pointMapper;
  pointMapper->SetInputData(points);
  volume->SetMapper(pointMapper);
  camera->SetPosition(0.0, 0.0, 6.0);
  renderer->ResetCameraClippingRange();
  window->Render();
  window->Render();
  Check(pointMapper->GetNumberOfSorts() == 1 && pointMapper->GetNumberOfListBuilds() == 1,
    "a point set is sorted once for the one list it needs");

  // Ordering, cutoff, blend threshold and backend leave the kernels and their lists alone; the
  // scalar selection does not.
  pointMapper->SetOrderingModeToClipped();
  pointMapper->SetCutoff(3.0);
  pointMapper->SetBlendThreshold(0.8);
  pointMapper->SetBackend(vtkSplatBackend::CPU);
  window->Render();
  Check(pointMapper->GetNumberOfSorts() == 1 && pointMapper->GetNumberOfListBuilds() == 1,
    "no re-sort after changing ordering, cutoff, blend threshold and backend");
  pointMapper->SetScalarModeToUsePointFieldData();
  pointMapper->SelectScalarArray("Scalar");
  window->Render();
  Check(pointMapper->GetNumberOfSorts() == 2 && pointMapper->GetNumberOfListBuilds() == 2,
    "the kernels rebuilt and re-sorted after the scalar selection changed");

  // An empty input draws nothing and reports nothing.
  pointMapper->SetInputData(vtkNew<vtkPolyData>());
  window->Render();
  Check(pointMapper->GetNumberOfKernels() == 0 && pointMapper->GetNumberOfProjectedKernels() == 0,
    "an empty input reports no kernels");
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
