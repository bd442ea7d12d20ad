// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkVolumeSplatSheetCompositor
 * @brief   composites image data's axis lists sheet by sheet in sheet-aligned intermediate
 *          images, warped to the screen once per list and frame (vtkVolumeSplatRasterizer)
 *
 * For image data a list is a stack of sheets (the voxels at one index along the list's axis),
 * and inside a sheet every kernel has the same covariance. So, as in the shear-warp
 * factorization (Lacroute and Levoy), the sheets are composited front to back in an
 * intermediate image on the plane of the front sheet, at one pixel per voxel of that sheet:
 * the central projection from the eye (or the parallel one along the view direction) maps
 * every sheet onto that plane by a scale and a shift, under which its footprints are all one 2D
 * Gaussian, the integral of the voxel's 3D Gaussian along the rays, low-pass filtered with the
 * screen pixel mapped onto the sheet at its center. Each intermediate pixel is a view ray; the
 * path length per sheet along it scales each voxel's optical depth. Once composited, the image
 * is resampled bilinearly at the screen pixels that take the list (the final projective warp),
 * and vtkVolumeSplatRasterizer merges the lists' buffers with the per-pixel weights as for its
 * exact per-kernel path.
 *
 * Per pixel and sheet this is one footprint evaluation per voxel and intermediate pixel, about
 * as many as the voxels' own count, instead of one per covered screen pixel; the per-kernel
 * setup and binning disappear. The approximations against the exact path: one footprint per
 * sheet (in a perspective view the ray direction, and so the footprint's shape, of the sheet's
 * center), and the bilinear warp of an image sampled once per voxel. Intermediate pixels no
 * screen pixel reads are left out, and pixels stop integrating at the rasterizer's
 * termination opacity.
 *
 * It applies when the eye is outside the slab of a used list's sheets (with the kernels'
 * reach), the kernels stay in front of the near plane and the opaque scene lies behind them;
 * BeginFrame says whether it does.
 *
 * @sa vtkVolumeSplatRasterizer
 */
#ifndef vtkVolumeSplatSheetCompositor_h
#define vtkVolumeSplatSheetCompositor_h

#include "SplatRenderingModule.h" // For export macro
#include "vtkObject.h"
#include "vtkVolumeSplatRasterizer.h" // For Kernels, Camera

#include <glm/glm.hpp> // For the buffers

#include <array>  // For the used lists
#include <memory> // For the internals
#include <vector> // For the buffers

class SPLATRENDERING_EXPORT vtkVolumeSplatSheetCompositor : public vtkObject
{
public:
  static vtkVolumeSplatSheetCompositor* New();
  vtkTypeMacro(vtkVolumeSplatSheetCompositor, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  using Kernels = vtkVolumeSplatRasterizer::Kernels;
  using Camera = vtkVolumeSplatRasterizer::Camera;

  /**
   * Forgets the per-list tables built from the kernels: to be called when they change.
   */
  void Reset();

  /**
   * Prepares a frame of the image data `kernels` (GridIds set) seen by `camera`, for the lists
   * marked in `used`. Returns false where the sheets do not apply (see the class comment):
   * nearestSceneDepth is the smallest eye depth of the opaque scene (infinity for none).
   */
  bool BeginFrame(const Kernels& kernels, const Camera& camera, double cutoff,
    double nearestSceneDepth, const std::array<bool, 3>& used);

  /**
   * Composites list `list` of the frame (order: its kernels, GetList of the rasterizer) into
   * its intermediate image, with colors (three per kernel) in place of the kernels' Colors, and
   * resamples it into `buffer` at the pixels whose weight for the list has the sign of the
   * traversal; the other pixels become transparent. The colors are copied into list order
   * again when perFrameColors is set or they are not those of the last frame. Returns the
   * number of kernels splatted.
   */
  vtkIdType Render(int list, const std::vector<vtkIdType>& order, const float* colors,
    bool perFrameColors, const float* weights, std::vector<glm::vec4>& buffer);

  /**
   * The last frame's intermediate image size of list `list` (0 when it was not rendered).
   */
  glm::ivec2 GetIntermediateSize(int list) const;

protected:
  vtkVolumeSplatSheetCompositor();
  ~vtkVolumeSplatSheetCompositor() override;

private:
  vtkVolumeSplatSheetCompositor(const vtkVolumeSplatSheetCompositor&) = delete;
  void operator=(const vtkVolumeSplatSheetCompositor&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
