// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkGaussianSplatRasterizer
 * @brief   CPU rasterizer of 3D Gaussian Splatting captures in their exact depth order
 *
 * vtkGaussianSplatRasterizer draws kernels with a peak opacity (the captures that
 * vtkGaussianSplatReader reads) as the published rasterizer they were optimized against does
 * (SplatCaptureKernel.h): each kernel's footprint under the reference's projection and filter,
 * alpha = min(0.99, opacity exp(-q)), contributions below 1/255 skipped, front to back in the
 * order of the centers' eye depths, each pixel stopping before the kernel that would take its
 * transmittance below 1e-4.
 *
 * A frame has three steps, as in the reference: the footprints, in parallel over kernels; the
 * kept kernels binned into 16 x 16 pixel tiles (a counting sort in parallel over fixed chunks),
 * each entry its kernel's depth and id in one 64-bit key; and the tiles in parallel, each list
 * sorted (by depth, ties by id, the order of a stable sort) and composited front to back, eight
 * pixels of a row at a time (those groups of eight only that a kernel's ellipse reaches and
 * whose pixels still integrate), until none of the tile's pixels integrates any more. The image
 * does not depend on the number of threads.
 *
 * vtkVolumeSplatRasterizer, the CPU backend of vtkVolumeSplatMapper, hands its captures here in
 * the DEPTH_SORTED ordering (the mapper's default for them).
 *
 * @sa vtkVolumeSplatRasterizer vtkVolumeSplatMapper vtkGaussianSplatReader
 */
#ifndef vtkGaussianSplatRasterizer_h
#define vtkGaussianSplatRasterizer_h

#include "SplatCaptureKernel.h"   // For splat::FootprintFilter
#include "SplatRenderingModule.h" // For export macro
#include "vtkObject.h"
#include "vtkVolumeSplatRasterizer.h" // For Kernels and Camera

#include <glm/glm.hpp> // For the image

#include <vector> // For the image

class SPLATRENDERING_EXPORT vtkGaussianSplatRasterizer : public vtkObject
{
public:
  static vtkGaussianSplatRasterizer* New();
  vtkTypeMacro(vtkGaussianSplatRasterizer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The screen filter of the footprints (splat::FootprintFilter). Default Dilation, the one
   * captures are trained with.
   */
  void SetFootprintFilter(splat::FootprintFilter filter) { this->FootprintFilter = filter; }
  splat::FootprintFilter GetFootprintFilter() const { return this->FootprintFilter; }
  ///@}

  /**
   * Draws `kernels` (their Strengths the peak opacities) with `colors`
   * (RGB per kernel for this view) into `image`: premultiplied RGBA per pixel, row by row from
   * the bottom, alpha 1 minus the transmittance. sceneDepths, when not null, holds the opaque
   * scene's eye depth per pixel: a kernel whose center lies behind it adds nothing there.
   */
  void Render(const vtkVolumeSplatRasterizer::Kernels& kernels, const float* colors,
    const vtkVolumeSplatRasterizer::Camera& camera, const float* sceneDepths,
    std::vector<glm::vec4>& image);

  ///@{
  /**
   * What the last frame did: kernels drawn, left out because their center lies less than the
   * near distance in front of the eye, left out because they reach no pixel (or their peak
   * opacity is below 1/255), and the (tile, kernel) pairs composited.
   */
  vtkGetMacro(ProjectedCount, vtkIdType);
  vtkGetMacro(NearPlaneCount, vtkIdType);
  vtkGetMacro(OutsideViewCount, vtkIdType);
  vtkGetMacro(TileEntryCount, vtkIdType);
  ///@}

protected:
  vtkGaussianSplatRasterizer();
  ~vtkGaussianSplatRasterizer() override;

  splat::FootprintFilter FootprintFilter = splat::FootprintFilter::Dilation;
  vtkIdType ProjectedCount = 0;
  vtkIdType NearPlaneCount = 0;
  vtkIdType OutsideViewCount = 0;
  vtkIdType TileEntryCount = 0;

private:
  vtkGaussianSplatRasterizer(const vtkGaussianSplatRasterizer&) = delete;
  void operator=(const vtkGaussianSplatRasterizer&) = delete;

  struct Internals;
  Internals* Internal;
};

#endif
