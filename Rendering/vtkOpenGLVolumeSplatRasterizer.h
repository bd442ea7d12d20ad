// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkOpenGLVolumeSplatRasterizer
 * @brief   the OpenGL backend of vtkVolumeSplatMapper: EWA volume splatting in shaders
 *
 * Renders the kernels, camera and settings of a vtkVolumeSplatRasterizer on the GPU, in the
 * render window's own context, with the same image semantics (paper 003's per-axis buffers):
 * - the kernels are uploaded once per input change into a texture buffer (position relative to
 *   the center of their bounds, strength, color and, for point sets, the covariance; the
 *   spherical-harmonic coefficients of degree 1 to 3 in a second one, as half floats); each list
 *   the frame needs is uploaded once per input change as a buffer of kernel indices in the
 *   order vtkVolumeSplatRasterizer::GetList gives (the grid's sheets for image data, never
 *   sorted here); DEPTH_SORTED sorts the kernels by eye depth on the CPU each frame, like the
 *   CPU backend;
 * - a weights pass writes every pixel's signed list weights (BLENDED, CLIPPED, SINGLE_AXIS, from
 *   the pixel's view ray as in vtkVolumeSplatRasterizer's step 1) and the eye depth of the opaque
 *   scene;
 * - every list some pixel needs is splatted into its own RGBA32F texture: each kernel is one
 *   instance of a four-vertex triangle strip covering the box of its footprint's cutoff ellipse,
 *   set up in the vertex shader (SplatVolumeKernel.h in GLSL: near-plane and frustum tests,
 *   projection Jacobian, |J| G_{(J W V W^T J^T)_2x2 + I}, truncation compensation), drawn in
 *   list order ascending and then in reverse for the pixels whose ray runs against the axis;
 *   fragments of pixels whose weight for the list has the other sign, or that lie behind the
 *   opaque scene's depth, are discarded, the others are blended front to back "under" what is
 *   there (emission-absorption: alpha = 1 - exp(-optical depth), or min(opacity, 0.99) for
 *   peak-opacity kernels);
 * - a merge pass combines the list buffers per pixel, C = sum C_a w_a^2 / sum w_a^2, into the
 *   premultiplied result, which vtkOpenGLImageDepthCompositor::DrawTextures then blends over
 *   VTK's framebuffer.
 * Which lists (and directions) a frame needs is decided on the CPU from the pixel rays, exactly
 * for the pixel centers (row by row), so GetListTraversed reports what the CPU backend does.
 *
 * Differences from the CPU backend: no early ray termination (the CPU stops a pixel at an
 * accumulated opacity of 1 - 1/512; what lies behind changes such pixels by less than 1/512);
 * the kernel setup runs in single precision; the GPU does not count what it leaves out (the
 * projected, near-plane and frustum counts are the caller's to report as unknown).
 *
 * Not wrapped: the interface is vtkVolumeSplatRasterizer's GLM types.
 *
 * @sa vtkVolumeSplatRasterizer vtkVolumeSplatMapper vtkOpenGLImageDepthCompositor
 */
#ifndef vtkOpenGLVolumeSplatRasterizer_h
#define vtkOpenGLVolumeSplatRasterizer_h

#include "SplatRenderingModule.h" // For export macro
#include "vtkObject.h"
#include "vtkVolumeSplatRasterizer.h" // For the kernel and camera types

#include <array>  // For the traversed lists
#include <memory> // For std::unique_ptr
#include <vector> // For the scene depths

class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

class SPLATRENDERING_EXPORT vtkOpenGLVolumeSplatRasterizer : public vtkObject
{
public:
  static vtkOpenGLVolumeSplatRasterizer* New();
  vtkTypeMacro(vtkOpenGLVolumeSplatRasterizer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Uploads the kernels when `version` differs from the last upload's (the lists are uploaded
   * when a frame first needs them). The arrays are read during this call only. The window's
   * context must be current.
   */
  void SetKernels(const vtkVolumeSplatRasterizer::Kernels& kernels, vtkMTimeType version);

  /**
   * Splats the kernels with the settings of `settings` (ordering mode, blend threshold,
   * cutoff), in the order of its lists (GetList), which must hold the same kernels as the last
   * SetKernels. `sceneDepths` are the window depths of the opaque scene over the viewport, rows
   * from the bottom, or empty for none: kernels whose center lies behind them do not reach the
   * pixel.
   */
  void Render(vtkRenderer* renderer, const vtkVolumeSplatRasterizer::Camera& camera,
    vtkVolumeSplatRasterizer* settings, const std::vector<float>& sceneDepths);

  ///@{
  /**
   * The last render's result, for vtkOpenGLImageDepthCompositor: premultiplied RGBA (float),
   * and a window depth of 0 everywhere (occlusion is already applied, the volume writes no
   * depth).
   */
  vtkTextureObject* GetColorTexture();
  vtkTextureObject* GetDepthTexture();
  ///@}

  /**
   * Whether the last render traversed list `list` (0, 1, 2 for the axes, 3 for the per-frame
   * depth sort), as vtkVolumeSplatRasterizer::GetListTraversed.
   */
  bool GetListTraversed(int list) const;

  /**
   * Per-frame depth sorts done since this object was made (DEPTH_SORTED).
   */
  vtkGetMacro(SortCount, vtkIdType);

  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkOpenGLVolumeSplatRasterizer();
  ~vtkOpenGLVolumeSplatRasterizer() override;

  std::array<bool, 4> Traversed{};
  vtkIdType SortCount = 0;

private:
  vtkOpenGLVolumeSplatRasterizer(const vtkOpenGLVolumeSplatRasterizer&) = delete;
  void operator=(const vtkOpenGLVolumeSplatRasterizer&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
