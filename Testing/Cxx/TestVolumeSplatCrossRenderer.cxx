// SPDX-License-Identifier: BSD-3-Clause
// Cross-renderer checks of vtkVolumeSplatMapper at 512 x 512:
// 1. a Gaussian blob of extinction, whose image is analytic (SplatVolumeTestUtilities.h),
//    against that image, with vtkFixedPointVolumeRayCastMapper's error on the same scene
//    printed for comparison;
// 2. the MRI head ch2.nii.gz (mricron-data) with one transfer function through both mappers at
//    the same camera (skipped with 125 when the file is absent), unshaded and shaded (the volume
//    property's default lighting terms, the renderer's headlight); shaded, the splats must also
//    be closer to the shaded ray cast than the unshaded splats are.
// The RMSE bounds (MAX_BLOB_RMSE, MAX_MRI_RMSE, MAX_MRI_SHADED_RMSE) and their justification are
// in CMakeLists.txt.
// Each mapper's render time is printed.
#include "SplatVolumeScenes.h" // For splatexample::MriProperty
#include "SplatVolumeTestUtilities.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkFixedPointVolumeRayCastMapper.h"

#include <cstdio>

namespace
{
constexpr int Size = 512;

template <typename Place>
splattest::RenderedVolume Render(
  vtkAbstractVolumeMapper* mapper, vtkImageData* image, vtkVolumeProperty* property, Place place)
{
  return splattest::RenderVolume(mapper, image, property, Size, place);
}
}

int main(int, char*[])
{
  int failures = 0;

  // 1. The blob: sigma 0.25 on a 64^3 grid of spacing 1/32 (8 voxels per sigma), peak optical
  // depth through the center 6 sigma sqrt(2 pi) 0.25 = 3.8.
  {
    const double sigma = 0.25, peak = 6.0, rgb[3] = { 1.0, 0.7, 0.4 };
    auto image = splattest::GaussianBlob(64, 1.0 / 32.0, sigma, peak);
    auto property = splattest::ExtinctionProperty(peak, 1.0 / 32.0, rgb);
    std::vector<double> exact;
    auto place = [&](vtkRenderer* renderer)
    {
      vtkCamera* camera = renderer->GetActiveCamera();
      camera->SetPosition(0.9, 0.7, 2.6);
      camera->SetFocalPoint(0.0, 0.0, 0.0);
      camera->SetViewUp(0.0, 1.0, 0.0);
      camera->SetViewAngle(30.0);
      renderer->ResetCameraClippingRange();
      renderer->GetRenderWindow()->Render();
      exact = splattest::BlobImage(renderer, sigma, peak, rgb);
    };
    vtkNew<vtkVolumeSplatMapper> splat;
    const splattest::RenderedVolume ours = Render(splat, image, property, place);
    const double ourError = splattest::RMSE(ours.RGB, exact);
    vtkNew<vtkFixedPointVolumeRayCastMapper> rayCast;
    const splattest::RenderedVolume reference = Render(rayCast, image, property, place);
    const double rayCastError = splattest::RMSE(reference.RGB, exact);
    std::printf("blob RMSE against the analytic image: splat %.5f (%.1f ms), fixed-point ray cast "
                "%.5f (%.1f ms)\n",
      ourError, ours.Milliseconds, rayCastError, reference.Milliseconds);
    if (!(ourError <= MAX_BLOB_RMSE))
    {
      std::fprintf(stderr, "blob RMSE %.5f above the bound %.5f\n", ourError, MAX_BLOB_RMSE);
      ++failures;
    }
  }

  // 2. The MRI head.
  vtkSmartPointer<vtkImageData> head = splattest::ReadMri();
  if (!head)
  {
    return failures ? EXIT_FAILURE : splattest::SkipReturnCode;
  }
  vtkSmartPointer<vtkVolumeProperty> property = splatexample::MriProperty();
  auto place = splattest::PlaceMriCamera;
  vtkNew<vtkVolumeSplatMapper> splat;
  const splattest::RenderedVolume ours = Render(splat, head, property, place);
  vtkNew<vtkFixedPointVolumeRayCastMapper> rayCast;
  const splattest::RenderedVolume reference = Render(rayCast, head, property, place);
  const double error = splattest::RMSE(ours.RGB, reference.RGB);
  std::printf("MRI RMSE splat vs fixed-point ray cast: %.5f; %lld kernels of %d voxels, %lld "
              "projected; splat %.1f ms, ray cast %.1f ms at %dx%d\n",
    error, static_cast<long long>(splat->GetNumberOfKernels()),
    head->GetNumberOfPoints() > 0 ? static_cast<int>(head->GetNumberOfPoints()) : 0,
    static_cast<long long>(splat->GetNumberOfProjectedKernels()), ours.Milliseconds,
    reference.Milliseconds, Size, Size);
  if (!(error <= MAX_MRI_RMSE))
  {
    std::fprintf(stderr, "MRI RMSE %.5f above the bound %.5f\n", error, MAX_MRI_RMSE);
    ++failures;
  }

  property->ShadeOn();
  vtkNew<vtkVolumeSplatMapper> shadedSplat;
  const splattest::RenderedVolume shaded = Render(shadedSplat, head, property, place);
  vtkNew<vtkFixedPointVolumeRayCastMapper> shadedRayCast;
  const splattest::RenderedVolume shadedReference = Render(shadedRayCast, head, property, place);
  const double shadedError = splattest::RMSE(shaded.RGB, shadedReference.RGB);
  const double unshadedError = splattest::RMSE(ours.RGB, shadedReference.RGB);
  std::printf("MRI shaded RMSE splat vs fixed-point ray cast: %.5f (unshaded splats: %.5f); "
              "splat %.1f ms, ray cast %.1f ms\n",
    shadedError, unshadedError, shaded.Milliseconds, shadedReference.Milliseconds);
  if (!(shadedError <= MAX_MRI_SHADED_RMSE) || !(shadedError < unshadedError))
  {
    std::fprintf(stderr, "MRI shaded RMSE %.5f above the bound %.5f or not below %.5f\n",
      shadedError, MAX_MRI_SHADED_RMSE, unshadedError);
    ++failures;
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
