// SPDX-License-Identifier: BSD-3-Clause
// vtkVolumeSplatMapper's sheet resampling of image data (vtkVolumeSplatSheetCompositor, the
// default), with its sheets merged by pairs (the default) and without (SetSheetMerging(false)),
// against its exact per-kernel path (SetSheetResampling(false)) at 512 x 512, BLENDED:
// 1. the Gaussian blob of TestVolumeSplatCrossRenderer from its perspective camera, along the
//    diagonal (all three lists) and in a parallel projection;
// 2. the MRI head ch2.nii.gz (mricron-data; skipped with 125 when absent) with the camera and
//    transfer functions of TestVolumeSplatCrossRenderer, unshaded and shaded, and the demo's
//    shaded face, whose opaque skin the pairs must not merge; under the default band-limit
//    filter and under EWA's low-pass, which the sheets apply themselves.
// Each view's RMSE and largest difference must stay within MAX_BLOB_RMSE, MAX_MRI_RMSE (the
// face: MAX_FACE_RMSE; under the band limit the shaded views: BAND_LIMIT_MAX_SHADED_RMSE and
// BAND_LIMIT_MAX_FACE_RMSE) and MAX_DIFFERENCE (their measurements are in CMakeLists.txt), and
// the paths must differ at all (else the sheets or the pairs did not run). The paths' frame
// times are printed.
#include "SplatVolumeScenes.h" // For splatexample::MriProperty
#include "SplatVolumeTestUtilities.h"
#include "vtkVolumeSplatMapper.h"

#include <cstdio>
#include <functional>
#include <string>

namespace
{
constexpr int Size = 512;

// Renders `image` from the camera set by `place` under the footprint filter `filter` with
// sheets merged by pairs (the default), sheets one by one and the exact path; counts a failure
// when either sheet image differs from the exact one by more than the bounds, or when no two of
// them differ at all (else the sheets or the pairs did not run).
int Compare(const std::string& name, vtkImageData* image, vtkVolumeProperty* property,
  const std::function<void(vtkRenderer*)>& place, int filter, double maximumRMSE)
{
  enum Path
  {
    Pairs,
    Sheets,
    Exact
  };
  splattest::RenderedVolume paths[3];
  for (const Path path : { Pairs, Sheets, Exact })
  {
    vtkNew<vtkVolumeSplatMapper> mapper;
    mapper->SetSheetResampling(path != Exact);
    mapper->SetSheetMerging(path == Pairs);
    mapper->SetFootprintFilter(filter);
    paths[path] = splattest::RenderVolume(mapper, image, property, Size, place);
  }
  int failures = 0;
  for (const Path path : { Pairs, Sheets })
  {
    const double rmse = splattest::RMSE(paths[path].RGB, paths[Exact].RGB);
    double largest = 0.0;
    for (std::size_t i = 0; i < paths[path].RGB.size(); ++i)
    {
      largest = std::max(largest, std::abs(paths[path].RGB[i] - paths[Exact].RGB[i]));
    }
    const char* which = path == Pairs ? "pairs" : "sheets";
    std::printf("%-24s %-6s vs exact RMSE %.5f (bound %.4f), largest %.3f (bound %.3f); %.1f ms, "
                "exact %.1f ms\n",
      name.c_str(), which, rmse, maximumRMSE, largest, MAX_DIFFERENCE, paths[path].Milliseconds,
      paths[Exact].Milliseconds);
    if (!(rmse <= maximumRMSE) || !(largest <= MAX_DIFFERENCE) || !(rmse > 0.0))
    {
      std::fprintf(stderr, "FAILED: %s: the %s differ from the exact path out of bounds, or did "
                           "not run\n",
        name.c_str(), which);
      ++failures;
    }
  }
  if (!(splattest::RMSE(paths[Pairs].RGB, paths[Sheets].RGB) > 0.0))
  {
    std::fprintf(stderr, "FAILED: %s: the pairs did not run\n", name.c_str());
    ++failures;
  }
  return failures;
}

// A camera looking at the origin from `position`, perspective or parallel.
std::function<void(vtkRenderer*)> LookFrom(double x, double y, double z, bool parallel)
{
  return [=](vtkRenderer* renderer)
  {
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(x, y, z);
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    camera->SetViewAngle(30.0);
    camera->SetParallelProjection(parallel);
    camera->SetParallelScale(0.8);
    renderer->ResetCameraClippingRange();
  };
}
}

int main(int, char*[])
{
  using M = vtkVolumeSplatMapper;
  int failures = 0;
  // 1. The blob: sigma 0.25 on a 64^3 grid of spacing 1/32.
  const double sigma = 0.25, peak = 6.0, rgb[3] = { 1.0, 0.7, 0.4 };
  auto blob = splattest::GaussianBlob(64, 1.0 / 32.0, sigma, peak);
  auto extinction = splattest::ExtinctionProperty(peak, 1.0 / 32.0, rgb);
  const int automatic = M::AUTOMATIC_FILTER;
  failures +=
    Compare("blob", blob, extinction, LookFrom(0.9, 0.7, 2.6, false), automatic, MAX_BLOB_RMSE);
  failures += Compare("blob diagonal", blob, extinction, LookFrom(1.6, 1.6, 1.6, false),
    automatic, MAX_BLOB_RMSE);
  failures += Compare("blob parallel", blob, extinction, LookFrom(0.9, 0.7, 2.6, true),
    automatic, MAX_BLOB_RMSE);

  // 2. The MRI head.
  vtkSmartPointer<vtkImageData> head = splattest::ReadMri();
  if (!head)
  {
    return failures ? EXIT_FAILURE : splattest::SkipReturnCode;
  }
  const auto placeFace = [&head](vtkRenderer* renderer)
  { splatexample::PlaceMriFaceCamera(renderer, head); };
  struct Filter
  {
    int Value;
    const char* Name;
    double ShadedBound, FaceBound;
  };
  for (const Filter& f :
    { Filter{ M::AUTOMATIC_FILTER, "", BAND_LIMIT_MAX_SHADED_RMSE, BAND_LIMIT_MAX_FACE_RMSE },
      Filter{ M::LOW_PASS_FILTER, ", low-pass", MAX_MRI_RMSE, MAX_FACE_RMSE } })
  {
    const std::string suffix = f.Name;
    vtkSmartPointer<vtkVolumeProperty> property = splatexample::MriProperty();
    failures +=
      Compare("MRI" + suffix, head, property, splattest::PlaceMriCamera, f.Value, MAX_MRI_RMSE);
    property->ShadeOn();
    failures += Compare(
      "MRI shaded" + suffix, head, property, splattest::PlaceMriCamera, f.Value, f.ShadedBound);
    // The demo's view of the face, whose opaque skin keeps its voxels' pairs apart.
    failures += Compare("MRI face" + suffix, head, splatexample::MriFaceProperty(), placeFace,
      f.Value, f.FaceBound);
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
