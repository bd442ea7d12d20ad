// SPDX-License-Identifier: BSD-3-Clause
// vtkVolumeSplatMapper against opaque geometry: a red Gaussian blob of extinction between two
// green opaque squares seen from +z, one in front of it covering x < 0, one behind it covering
// x > 0. In front, the square hides the volume entirely; behind, the square shows through where
// the volume is thin and the volume is drawn over it.
#include "SplatVolumeTestUtilities.h"
#include "vtkVolumeSplatMapper.h"

#include <cstdio>

namespace
{
std::vector<double> Render(bool squares)
{
  const double sigma = 0.25, peak = 2.0, rgb[3] = { 1.0, 0.3, 0.1 };
  vtkNew<vtkVolumeSplatMapper> mapper;
  mapper->SetInputData(splattest::GaussianBlob(48, 1.0 / 24.0, sigma, peak));
  vtkNew<vtkRenderer> renderer;
  splattest::AddVolume(renderer, mapper, splattest::ExtinctionProperty(peak, 1.0 / 24.0, rgb));
  if (squares)
  {
    renderer->AddActor(splattest::OpaqueSquare(-1.0, 0.0, 0.9));
    renderer->AddActor(splattest::OpaqueSquare(0.0, 1.0, -0.9));
  }
  auto window = splattest::MakeRenderWindow(200, 200);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.0, 0.0, 4.0);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetClippingRange(1.0, 10.0);
  window->Render();
  return splattest::ToRGB(splattest::Capture(window));
}
}

int main(int, char*[])
{
  const std::vector<double> alone = Render(false);
  const std::vector<double> scene = Render(true);
  auto at = [](const std::vector<double>& image, int x, int y, int c)
  { return image[3 * (y * 200 + x) + c]; };
  int failures = 0;
  // Left of the center, 0.1 units from the blob's center: the front square only.
  const int left = 90, right = 110, row = 100;
  std::printf("front: (%.3f %.3f %.3f), behind: (%.3f %.3f %.3f), volume alone: (%.3f %.3f %.3f)\n",
    at(scene, left, row, 0), at(scene, left, row, 1), at(scene, left, row, 2),
    at(scene, right, row, 0), at(scene, right, row, 1), at(scene, right, row, 2),
    at(alone, right, row, 0), at(alone, right, row, 1), at(alone, right, row, 2));
  if (!(at(alone, left, row, 0) > 0.5 && at(scene, left, row, 0) < 0.01 &&
        at(scene, left, row, 1) > 0.99))
  {
    std::fprintf(stderr, "the square in front does not hide the volume\n");
    ++failures;
  }
  // Right of the center: the volume over the square behind it; the green shows through as
  // (1 - alpha) of the square, and the volume's red is unchanged.
  const double transmitted = at(scene, right, row, 1) - at(alone, right, row, 1);
  if (!(transmitted > 0.05 && std::abs(at(scene, right, row, 0) - at(alone, right, row, 0)) < 0.02))
  {
    std::fprintf(stderr, "the square behind does not show through the volume\n");
    ++failures;
  }
  // Far from the blob, the square behind is fully visible.
  if (!(at(scene, 170, row, 1) > 0.98))
  {
    std::fprintf(stderr, "the square behind is not visible outside the volume\n");
    ++failures;
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
