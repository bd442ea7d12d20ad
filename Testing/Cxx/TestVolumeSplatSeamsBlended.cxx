// SPDX-License-Identifier: BSD-3-Clause
// BLENDED ordering across the X/Z region boundary: no seam. The jump across the boundary line
// stays within MAX_SEAM_RATIO times the jump elsewhere over the whole camera path (see
// VolumeSplatSeams.h), and the last frame matches the regression image.
#include "VolumeSplatSeams.h"

int main(int argc, char* argv[])
{
  vtkNew<vtkVolumeSplatMapper> mapper;
  mapper->SetOrderingModeToBlended();
  auto window = splattest::MakeRenderWindow(300, 300);
  const double ratio = splattest::SweepSeams(mapper, window, 9);
  std::printf("BLENDED: largest boundary/elsewhere jump ratio %.2f\n", ratio);
  if (!(ratio <= MAX_SEAM_RATIO))
  {
    std::fprintf(stderr, "seam ratio %.2f above %.2f\n", ratio, MAX_SEAM_RATIO);
    return EXIT_FAILURE;
  }
  return !vtkRegressionTestImage(window);
}
