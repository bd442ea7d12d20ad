// SPDX-License-Identifier: BSD-3-Clause
// CLIPPED ordering across the X/Z region boundary: each pixel from one list, so the order
// switches along the boundary line and a seam may show. The jump ratio is printed for
// comparison with TestVolumeSplatSeamsBlended and must exceed MIN_SEAM_RATIO, which shows the
// seam measure detects what blending removes; the last frame matches the regression image.
#include "VolumeSplatSeams.h"

int main(int argc, char* argv[])
{
  vtkNew<vtkVolumeSplatMapper> mapper;
  mapper->SetOrderingModeToClipped();
  auto window = splattest::MakeRenderWindow(300, 300);
  const double ratio = splattest::SweepSeams(mapper, window, 9);
  std::printf("CLIPPED: largest boundary/elsewhere jump ratio %.2f\n", ratio);
  if (!(ratio >= MIN_SEAM_RATIO))
  {
    std::fprintf(stderr, "seam ratio %.2f below %.2f\n", ratio, MIN_SEAM_RATIO);
    return EXIT_FAILURE;
  }
  return !vtkRegressionTestImage(window);
}
