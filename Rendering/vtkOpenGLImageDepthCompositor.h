// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkOpenGLImageDepthCompositor
 * @brief   draws a rendered RGBA image with per-pixel depth into the current VTK framebuffer
 *
 * The CPU backends render splats into memory, the OpenGL backends into textures; this class
 * puts that image into the renderer's viewport as a full-viewport quad that writes gl_FragDepth and is depth-tested against what is
 * already there, so splats and ordinary actors occlude each other in either drawing order. The
 * colors are premultiplied by alpha and blended over the framebuffer (partly covered edge
 * pixels, translucent splats). Pixels with alpha 0 are discarded. It also reads the scene's
 * depth back, for translucent splats that must be hidden behind opaque geometry.
 */
#ifndef vtkOpenGLImageDepthCompositor_h
#define vtkOpenGLImageDepthCompositor_h

#include "SplatRenderingModule.h" // For export macro
#include "vtkNew.h"              // For vtkNew
#include "vtkObject.h"
#include "vtkWeakPointer.h" // For the window holding the resources

#include <cstdint> // For std::uint8_t
#include <memory>  // For std::unique_ptr
#include <vector>  // For the depth read-back

class vtkAbstractMapper;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
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
   * How the image joins the framebuffer.
   */
  enum class Blending
  {
    Opaque,          ///< premultiplied "over", writes depth
    Translucent,     ///< premultiplied "over", depth-tested only, so later geometry shows through
    OrderIndependent ///< inside VTK's order-independent translucent pass, which sets the blending
  };

  /**
   * Draws width x height pixels (rows from the bottom): premultiplied RGBA bytes and
   * window-space depth in [0, 1]. The size must be the renderer's viewport size.
   */
  void Draw(vtkRenderer* renderer, int width, int height, const std::uint8_t* rgba,
    const float* depth, Blending blending);

  /**
   * Draw() of the pixels in `region` only (x0, y0, x1, y1, inclusive; nothing where x0 > x1 or
   * y0 > y1), the image being transparent outside it: only they are uploaded and drawn.
   */
  void DrawRegion(vtkRenderer* renderer, int width, int height, const std::uint8_t* rgba,
    const float* depth, const int region[4], Blending blending);

  /**
   * Draws textures of the viewport's size: premultiplied RGBA and window-space depth (the
   * OpenGL backends' results, which stay on the GPU).
   */
  void DrawTextures(
    vtkRenderer* renderer, vtkTextureObject* color, vtkTextureObject* depth, Blending blending);

  /**
   * The window-space depth of the renderer's viewport as drawn so far, rows from the bottom.
   * Returns false (and leaves depths empty) when the framebuffer's depth cannot be read.
   */
  bool ReadDepths(vtkRenderer* renderer, std::vector<float>& depths);

  /**
   * Releases the textures and the shader program of the window.
   */
  void ReleaseGraphicsResources(vtkWindow* window);

  /**
   * Called by `mapper` (which holds this compositor) before it draws into `renderer`: where the
   * renderer's window is not the one whose OpenGL context holds the mapper's graphics resources
   * (a mapper shared by renderers of two windows), the mapper releases them in that window's
   * context first, so that it never draws with one context's objects in another. VTK's own
   * mappers do the same through their resource callbacks, whose header VTK 9.1 keeps private.
   */
  void MoveGraphicsResources(vtkRenderer* renderer, vtkAbstractMapper* mapper);

protected:
  vtkOpenGLImageDepthCompositor();
  ~vtkOpenGLImageDepthCompositor() override;

  vtkNew<vtkTextureObject> ColorTexture;
  vtkNew<vtkTextureObject> DepthTexture;
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
  vtkWeakPointer<vtkOpenGLRenderWindow> ResourceWindow; // see MoveGraphicsResources

private:
  vtkOpenGLImageDepthCompositor(const vtkOpenGLImageDepthCompositor&) = delete;
  void operator=(const vtkOpenGLImageDepthCompositor&) = delete;
};

#endif
