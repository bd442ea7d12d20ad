// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkVolumeSplatSheetCompositor
 * @brief   composites image data's axis lists sheet by sheet in sheet-aligned intermediate
 *          images, warped to the screen once per list and frame (vtkVolumeSplatRasterizer)
 *
 * For image data a list is a stack of sheets (the voxels at one index along the list's axis),
 * and inside a sheet every kernel has the same covariance. So, as in the shear-warp
 * factorization (Lacroute and Levoy), the sheets are composited front to back in an
 * intermediate image on the plane of the front sheet: the central projection from the eye (or
 * the parallel one along the view direction) maps every sheet onto that plane by a scale and a
 * shift, under which a sheet's footprints are one 2D Gaussian, the integral of the voxel's 3D
 * Gaussian along the rays, screen-filtered with the screen pixel mapped onto the sheet. In a
 * perspective view the rays' direction changes across a sheet, so each sheet has a footprint per
 * tile of 4 x 4 (the rays through the tile's center). The intermediate image has 0.7 pixels per
 * standard deviation of the narrowest footprint of the front sheet (about one per voxel when a
 * voxel covers a few pixels, fewer when voxels are smaller than pixels). Each intermediate pixel
 * is a view ray; the path length per sheet along each voxel's ray scales its optical depth. A
 * footprint's exponential is factored into per-row, per-column and per-sheet tables
 * (splat::VolumeLayerCompositor::AddFactored). Once composited, the intermediate image is
 * resampled with Catmull-Rom weights at the screen pixels that take the list (the final
 * projective warp), and vtkVolumeSplatRasterizer merges the lists' buffers with the per-pixel
 * weights as for its exact per-kernel path.
 *
 * Per sheet this is one footprint of a few intermediate pixels per voxel instead of one per
 * covered screen pixel, and the per-kernel setup and binning disappear.
 *
 * With MergePairs (the default) the layers composited are pairs of sheets (2j, 2j + 1) rather
 * than sheets, half the footprints: the two voxels at one lattice point of a pair become one
 * kernel of their summed strength and strength-weighted color, centered on their
 * strength-weighted center along the axis (so a voxel whose partner is transparent stays where
 * it is), of the voxels' covariance. Where the rays run along the axis a ray integrates both
 * voxels either way; obliquely the pair's two footprints, offset by the rays' shear, become one,
 * and the order within a pair is lost: about tau1 tau2 / 2 times the voxels' color difference.
 * So only voxels whose optical depths per sheet add up to at most 1/2 merge; more opaque ones
 * (a surface's) stay apart, the lower voxel in the pair's first layer and the upper one in a
 * second layer composited after it (before it for descending traversals). The pair's axial
 * spread (a quarter of a sheet squared for equal strengths) is not added to the covariance: in
 * a volume's interior the rays cross many pairs and it averages out, at its boundaries the
 * strengths differ and the spread is smaller, and the images measured closer to the exact path
 * without it (MRI RMSE 0.0012 against 0.0014 with it). A lone last sheet is a layer of its own.
 *
 * The approximations against the exact path: one footprint per tile of a layer, the pairs, and
 * the warp of an image sampled at 0.7 samples per footprint deviation and at least 0.6 per
 * screen pixel (TestVolumeSplatSheets bounds the difference, with and without the pairs).
 * Intermediate pixels that no screen pixel reads are left out, and pixels stop integrating at
 * the rasterizer's termination opacity: a voxel row, or a voxel, whose footprints reach only
 * such pixels is passed over before its setup, and a band of rows ends its traversal once all
 * its pixels have stopped (all exact).
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

  ///@{
  /**
   * Whether each list's sheets are merged by pairs along its axis (see the class comment),
   * from the next frame on. Default on.
   */
  void SetMergePairs(bool merge);
  bool GetMergePairs() const;
  ///@}

  ///@{
  /**
   * The screen filter of the footprints, a splat::FootprintFilter (vtkVolumeSplatRasterizer's),
   * from the next frame on. Default LowPass.
   */
  void SetFootprintFilter(int filter);
  int GetFootprintFilter() const;
  ///@}

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

  /**
   * The layers (sheets, or pairs of sheets) list `list` composited in the last frame (0 when
   * it was not rendered).
   */
  int GetNumberOfLayers(int list) const;

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
