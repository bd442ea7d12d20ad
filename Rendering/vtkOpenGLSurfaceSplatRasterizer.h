// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkOpenGLSurfaceSplatRasterizer
 * @brief   the OpenGL backend of vtkSurfaceSplatMapper: EWA surface splatting in shaders
 *
 * Renders the same surfels, camera and settings as vtkSurfaceSplatRasterizer, on the GPU, in
 * the render window's own context (An and Zhou's two-pass splatting with Zwicker's exact kernel):
 * - setup, once per render (and per selection pass): a vertex shader sets each surfel's kernel
 *   up (SplatSurfelKernel.h in GLSL: projection, resampling kernel, bounding box, culling), one
 *   point per surfel drawn with the rasterizer off, and transform feedback writes a record per
 *   splat into a buffer; nothing is computed per splat on the CPU, and the surfels are uploaded
 *   once per input change;
 * - every surfel is one instance of a four-vertex triangle strip covering the tight bounding box
 *   of its kernel's cutoff ellipse: the strip's vertex shader reads the box and the rest of the
 *   kernel from the splat's record (a culled splat's strip draws nothing), so that all the
 *   passes below share one setup;
 * - pass 1, visibility: each fragment intersects its pixel's view ray with the splat's tangent
 *   plane, drops what lies outside the cutoff, and writes the linear eye depth of the
 *   intersection plus the splat's depth threshold (DepthThreshold times its radius);
 * - pass 2, attributes: the same fragments, depth-tested against pass 1 without depth writes,
 *   add weight-times-color, weight, weight-times-normal, weight-times-opacity and
 *   weight-times-depth into float render targets; the weight is the screen-space EWA kernel of
 *   paper 000 eq. (6), or the cheaper approximate filter on request;
 * - pass 3, normalization and deferred shading with VTK's lights, into a layer image;
 * - layers: translucent splats and antialiased edges (which show what lies behind them) peel up
 *   to NumberOfLayers surfaces front to back, each splatted with passes 1-2, shaded, and blended
 *   under the ones in front; a peeled layer's fragments end at once where the layers in front
 *   cover the pixel fully (most of an opaque surface with antialiased edges: on a GPU whose
 *   fragment work is the cost, each further layer then costs a fraction of the first);
 *   peeling stops at the first layer that no fragment reaches;
 * - the result (premultiplied color and the window depth of the front surface) is then drawn
 *   into VTK's framebuffer by vtkOpenGLImageDepthCompositor, like the CPU backend's image.
 * Positions are uploaded relative to the center of the input's bounds, with that shift folded
 * into the model-view matrix in double precision, so data far from the origin renders like data
 * at the origin.
 *
 * Hardware picking: RenderSelection draws the splats into vtkHardwareSelector's passes with the
 * actor's color and the point ids, at the depth of each fragment's true intersection.
 *
 * Not wrapped: the interface is vtkSurfaceSplatRasterizer's GLM types.
 *
 * @sa vtkSurfaceSplatRasterizer vtkSurfaceSplatMapper vtkOpenGLImageDepthCompositor
 */
#ifndef vtkOpenGLSurfaceSplatRasterizer_h
#define vtkOpenGLSurfaceSplatRasterizer_h

#include "SplatRenderingModule.h" // For export macro
#include "vtkObject.h"
#include "vtkSurfaceSplatRasterizer.h" // For the surfel and camera types

#include <memory> // For std::unique_ptr
#include <vector> // For the lights

class vtkHardwareSelector;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

class SPLATRENDERING_EXPORT vtkOpenGLSurfaceSplatRasterizer : public vtkObject
{
public:
  static vtkOpenGLSurfaceSplatRasterizer* New();
  vtkTypeMacro(vtkOpenGLSurfaceSplatRasterizer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The approximate filter (Botsch et al. 2005; as in most GPU splatting): the larger of the
   * object-space Gaussian, evaluated where the pixel's ray meets the tangent plane, and the
   * screen-space unit low-pass, without normalization. Cheaper than the exact EWA kernel and
   * close to it, except where splats are minified. Default off: the exact EWA kernel (or the
   * rasterizer's filter).
   */
  vtkSetMacro(ApproximateFilter, bool);
  vtkGetMacro(ApproximateFilter, bool);
  vtkBooleanMacro(ApproximateFilter, bool);
  ///@}

  /**
   * Uploads the surfels into vertex buffers when `version` differs from the last upload's.
   * The window's context must be current.
   */
  void SetSurfels(const vtkSurfaceSplatRasterizer::Surfels& surfels, vtkMTimeType version);

  /**
   * Splats the surfels into the layer images with the settings of `settings` (cutoff, depth
   * threshold, layers, edge antialiasing and coverage, filter, backface culling). Opacities
   * below one make the input translucent; `sceneDepths` (the window depths of the viewport,
   * rows from the bottom, or empty) then hide fragments behind opaque geometry.
   */
  void Render(vtkRenderer* renderer, const vtkSurfaceSplatRasterizer::Camera& camera,
    const std::vector<splat::Light>& lights, const splat::Material& material,
    vtkSurfaceSplatRasterizer* settings, const std::vector<float>& sceneDepths);

  ///@{
  /**
   * The last render's result, for vtkOpenGLImageDepthCompositor: premultiplied RGBA (float)
   * and window-space depth of the front surface.
   */
  vtkTextureObject* GetColorTexture();
  vtkTextureObject* GetDepthTexture();
  ///@}

  /**
   * The number of layers the last render kept (the settings' NumberOfLayers, the paper's 3
   * where that is automatic, 1 for an opaque input without edge antialiasing), and how many of
   * them it peeled before the pixels were covered.
   */
  vtkGetMacro(LastNumberOfLayers, int);
  vtkGetMacro(PeeledLayers, int);

  /**
   * Draws the surfels into the current pass of the renderer's hardware selector, each with the
   * id of its input point (pointIds[i] for surfel i; uploaded once per surfel version).
   */
  void RenderSelection(vtkRenderer* renderer, vtkHardwareSelector* selector,
    const vtkSurfaceSplatRasterizer::Camera& camera, vtkSurfaceSplatRasterizer* settings,
    const std::vector<vtkIdType>& pointIds);

  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkOpenGLSurfaceSplatRasterizer();
  ~vtkOpenGLSurfaceSplatRasterizer() override;

  bool ApproximateFilter = false;
  int LastNumberOfLayers = 0;
  int PeeledLayers = 0;

private:
  vtkOpenGLSurfaceSplatRasterizer(const vtkOpenGLSurfaceSplatRasterizer&) = delete;
  void operator=(const vtkOpenGLSurfaceSplatRasterizer&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
