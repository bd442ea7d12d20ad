// SPDX-License-Identifier: BSD-3-Clause
// vtkVolumeSplatMapper (CPU, every axis ordering) on the Gaussian blob of extinction of
// TestVolumeSplatCrossRenderer from views where the list weights are extreme, against the blob's
// analytic image (SplatVolumeTestUtilities.h):
// - exactly along the diagonal (1, 1, 1), parallel: every pixel's ray has three equal components,
//   so BLENDED gives the three lists equal weight everywhere; and in perspective, where the
//   weights vary around that balance;
// - very oblique: a 90-degree perspective camera 40 degrees off the X axis, whose rays run from
//   nearly along X to nearly along Z across the image;
// - the eye inside the volume's bounds (and inside the blob), a 90-degree perspective camera.
// Each image must be finite, within MAX_RMSE (MAX_INSIDE_RMSE from inside, where kernels that
// reach the near plane are left out) of the analytic image, and without seams: its largest jump
// between neighboring pixels at most MAX_JUMP_RATIO times the analytic image's plus one 8-bit
// step. The seams scene of TestVolumeSplatSeamsBlended (VolumeSplatSeams.h: random colors, whose
// order shows) from the same perspective views in BLENDED: the jump across the boundaries
// between the rays' dominant axes at most MAX_SEAM_RATIO times the jump elsewhere. Bounds and
// their measurements are in CMakeLists.txt.
#include "VolumeSplatSeams.h"
#include "vtkSplatBackend.h"

#include <cstdio>
#include <string>

namespace
{
constexpr int Size = 256;

struct View
{
  const char* Name;
  double Position[3];
  bool Parallel;
  double Angle; // view angle (perspective) or parallel scale
  double MaxRMSE;
};


void Place(vtkRenderer* renderer, const View& view)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(view.Position);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->OrthogonalizeViewUp();
  camera->SetParallelProjection(view.Parallel);
  camera->SetParallelScale(view.Angle);
  camera->SetViewAngle(view.Angle);
  // Near enough that the eye-inside view clips little of the volume; far beyond it.
  camera->SetClippingRange(0.01, 10.0);
}
}

int main(int, char*[])
{
  const double sigma = 0.25, peak = 6.0, rgb[3] = { 1.0, 0.7, 0.4 };
  auto image = splattest::GaussianBlob(64, 1.0 / 32.0, sigma, peak);
  auto property = splattest::ExtinctionProperty(peak, 1.0 / 32.0, rgb);
  const View views[] = {
    { "diagonal, parallel", { 2.0, 2.0, 2.0 }, true, 0.8, MAX_RMSE },
    { "diagonal, perspective", { 1.5, 1.5, 1.5 }, false, 40.0, MAX_RMSE },
    { "very oblique", { 1.2, 0.3, 1.0 }, false, 90.0, MAX_RMSE },
    { "eye inside", { 0.12, 0.08, 0.3 }, false, 90.0, MAX_INSIDE_RMSE },
  };
  const int modes[] = { vtkVolumeSplatMapper::BLENDED, vtkVolumeSplatMapper::CLIPPED,
    vtkVolumeSplatMapper::SINGLE_AXIS };
  int failures = 0;
  for (const View& view : views)
  {
    for (int mode : modes)
    {
      vtkNew<vtkVolumeSplatMapper> mapper;
      mapper->SetBackend(vtkSplatBackend::CPU);
      mapper->SetOrderingMode(mode);
      mapper->SetInputData(image);
      vtkNew<vtkRenderer> renderer;
      splattest::AddVolume(renderer, mapper, property);
      renderer->SetBackground(0.0, 0.0, 0.0);
      auto window = splattest::MakeRenderWindow(Size, Size);
      window->AddRenderer(renderer);
      vtkCamera* camera = renderer->GetActiveCamera();
      Place(renderer, view);
      window->Render();
      const std::vector<double> rendered = splattest::ToRGB(splattest::Capture(window));
      const std::vector<double> exact = splattest::BlobImage(renderer, sigma, peak, rgb);
      const double rmse = splattest::RMSE(rendered, exact);
      const double jump = splattest::LargestNeighborJump(rendered, Size);
      const double exactJump = splattest::LargestNeighborJump(exact, Size);
      const std::string name = std::string(view.Name) + ", mode " + std::to_string(mode);
      std::printf("%s: RMSE %.5f, largest neighbor jump %.4f (analytic %.4f), lists %d%d%d\n",
        name.c_str(), rmse, jump, exactJump, mapper->GetListTraversed(0),
        mapper->GetListTraversed(1), mapper->GetListTraversed(2));
      // RMSE is NaN where a pixel is; a NaN pixel fails here.
      if (!(rmse <= view.MaxRMSE))
      {
        std::fprintf(stderr, "%s: RMSE %.5f above %.5f\n", name.c_str(), rmse, view.MaxRMSE);
        ++failures;
      }
      if (!(jump <= MAX_JUMP_RATIO * exactJump + 1.0 / 255.0))
      {
        std::fprintf(stderr, "%s: a seam: neighbor jump %.4f against the analytic %.4f\n",
          name.c_str(), jump, exactJump);
        ++failures;
      }
      if (mode == vtkVolumeSplatMapper::BLENDED && view.Parallel &&
        !(mapper->GetListTraversed(0) && mapper->GetListTraversed(1) &&
          mapper->GetListTraversed(2)))
      {
        std::fprintf(stderr, "%s: the diagonal view does not use all three lists\n", name.c_str());
        ++failures;
      }
    }
  }
  for (const View& view : views)
  {
    if (view.Parallel)
    {
      continue; // every pixel has the same weights: no boundary
    }
    vtkNew<vtkVolumeSplatMapper> mapper;
    mapper->SetBackend(vtkSplatBackend::CPU);
    mapper->SetOrderingModeToBlended();
    auto window = splattest::MakeRenderWindow(Size, Size);
    vtkRenderer* renderer = splattest::AddSeamsScene(mapper, window);
    Place(renderer, view);
    window->Render();
    const double ratio = splattest::SeamRatio(renderer, window, view.Name);
    if (!(ratio <= MAX_SEAM_RATIO))
    {
      std::fprintf(stderr, "%s: seam ratio %.2f above %.2f\n", view.Name, ratio, MAX_SEAM_RATIO);
      ++failures;
    }
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
