// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkOpenGLImageDepthCompositor
 * @brief   draws a CPU-rendered RGBA image with per-pixel depth into the current VTK framebuffer
 *
 * The CPU backends render splats into memory; this class puts that image into the renderer's
 * viewport as a full-viewport quad that writes gl_FragDepth and is depth-tested against what is
 * already there, so splats and ordinary actors occlude each other in either drawing order.
 * Pixels with alpha 0 are discarded.
 */
#ifndef vtkOpenGLImageDepthCompositor_h
#define vtkOpenGLImageDepthCompositor_h

#include "SplatRenderingModule.h" // For export macro
#include "vtkNew.h"              // For vtkNew
#include "vtkObject.h"

#include <cstdint> // For std::uint8_t
#include <memory>  // For std::unique_ptr

class vtkOpenGLQuadHelper;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

class SPLATRENDERING_EXPORT vtkOpenGLImageDepthCompositor : public vtkObject
{
public:
  static vtkOpenGLImageDepthCompositor* New();
  vtkTypeMacro(vtkOpenGLImageDepthCompositor, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Draws width x height pixels (rows from the bottom): RGBA bytes and window-space depth in
   * [0, 1]. The size must be the renderer's viewport size.
   */
  void Draw(vtkRenderer* renderer, int width, int height, const std::uint8_t* rgba,
    const float* depth);

  /**
   * Releases the textures and the shader program of the window.
   */
  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkOpenGLImageDepthCompositor();
  ~vtkOpenGLImageDepthCompositor() override;

  vtkNew<vtkTextureObject> ColorTexture;
  vtkNew<vtkTextureObject> DepthTexture;
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;

private:
  vtkOpenGLImageDepthCompositor(const vtkOpenGLImageDepthCompositor&) = delete;
  void operator=(const vtkOpenGLImageDepthCompositor&) = delete;
};

#endif
