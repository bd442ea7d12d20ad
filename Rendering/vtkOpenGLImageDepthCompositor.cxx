// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenGLImageDepthCompositor.h"

#include "SplatOpenGLUtilities.h"
#include "vtkAbstractMapper.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>

vtkStandardNewMacro(vtkOpenGLImageDepthCompositor);

namespace
{
const char* CompositeFragmentShader = R"(//VTK::System::Dec
in vec2 texCoord;
uniform sampler2D splatColor;
uniform sampler2D splatDepth;
//VTK::Output::Dec
void main()
{
  vec4 color = texture(splatColor, texCoord);
  if (color.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = color;
  // The opacity target of VTK's order-independent translucent pass (ignored elsewhere).
  gl_FragData[1] = vec4(color.a);
  gl_FragDepth = texture(splatDepth, texCoord).r;
}
)";
}

//------------------------------------------------------------------------------
vtkOpenGLImageDepthCompositor::vtkOpenGLImageDepthCompositor() = default;

//------------------------------------------------------------------------------
vtkOpenGLImageDepthCompositor::~vtkOpenGLImageDepthCompositor() = default;

//------------------------------------------------------------------------------
void vtkOpenGLImageDepthCompositor::Draw(vtkRenderer* renderer, int width, int height,
  const std::uint8_t* rgba, const float* depth, Blending blending)
{
  const int whole[4] = { 0, 0, width - 1, height - 1 };
  this->DrawRegion(renderer, width, height, rgba, depth, whole, blending);
}

//------------------------------------------------------------------------------
void vtkOpenGLImageDepthCompositor::DrawRegion(vtkRenderer* renderer, int width, int height,
  const std::uint8_t* rgba, const float* depth, const int region[4], Blending blending)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  const int x0 = std::max(region[0], 0);
  const int y0 = std::max(region[1], 0);
  const int x1 = std::min(region[2], width - 1);
  const int y1 = std::min(region[3], height - 1);
  if (!window || x0 > x1 || y0 > y1)
  {
    return;
  }
  for (vtkTextureObject* texture : { this->ColorTexture.Get(), this->DepthTexture.Get() })
  {
    splat::SetNearest(texture, window);
  }
  // The region's rows are read out of the whole image's.
  vtkOpenGLState* state = window->GetState();
  state->vtkglPixelStorei(GL_UNPACK_ROW_LENGTH, width);
  const std::size_t first = static_cast<std::size_t>(y0) * width + x0;
  const int regionWidth = x1 - x0 + 1;
  const int regionHeight = y1 - y0 + 1;
  this->ColorTexture->Create2DFromRaw(regionWidth, regionHeight, 4, VTK_UNSIGNED_CHAR,
    const_cast<void*>(static_cast<const void*>(rgba + 4 * first)));
  this->DepthTexture->Create2DFromRaw(regionWidth, regionHeight, 1, VTK_FLOAT,
    const_cast<void*>(static_cast<const void*>(depth + first)));
  state->vtkglPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  // Drawn into the region's part of the renderer's viewport.
  vtkOpenGLState::ScopedglViewport viewport(state);
  int whole[4];
  state->vtkglGetIntegerv(GL_VIEWPORT, whole);
  state->vtkglViewport(whole[0] + x0, whole[1] + y0, regionWidth, regionHeight);
  this->DrawTextures(renderer, this->ColorTexture, this->DepthTexture, blending);
}

//------------------------------------------------------------------------------
void vtkOpenGLImageDepthCompositor::DrawTextures(
  vtkRenderer* renderer, vtkTextureObject* color, vtkTextureObject* depth, Blending blending)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    return;
  }
  if (!splat::ReadyQuad(this->Quad, window, CompositeFragmentShader))
  {
    vtkErrorMacro("The splat compositing shader did not compile.");
    return;
  }

  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglEnable(GL_BLEND);
  if (blending != Blending::OrderIndependent)
  {
    state->vtkglBlendFuncSeparate(
      GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  }
  state->vtkglDepthFunc(GL_LEQUAL);
  state->vtkglDepthMask(blending == Blending::Opaque ? GL_TRUE : GL_FALSE);

  color->Activate();
  depth->Activate();
  this->Quad->Program->SetUniformi("splatColor", color->GetTextureUnit());
  this->Quad->Program->SetUniformi("splatDepth", depth->GetTextureUnit());
  this->Quad->Render();
  color->Deactivate();
  depth->Deactivate();
}

//------------------------------------------------------------------------------
bool vtkOpenGLImageDepthCompositor::ReadDepths(vtkRenderer* renderer, std::vector<float>& depths)
{
  depths.clear();
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    return false;
  }
  int width, height, x, y;
  renderer->GetTiledSizeAndOrigin(&width, &height, &x, &y);
  vtkOpenGLState* state = window->GetState();
  // Read from the framebuffer being drawn into (the window's or a render pass's).
  GLint drawFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
  state->PushReadFramebufferBinding();
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer));
  while (glGetError() != GL_NO_ERROR)
  {
    // Clear earlier errors: the check below is about this read only.
  }
  depths.resize(static_cast<std::size_t>(width) * height);
  glReadPixels(x, y, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depths.data());
  const bool ok = glGetError() == GL_NO_ERROR;
  state->PopReadFramebufferBinding();
  if (!ok)
  {
    depths.clear();
  }
  return ok;
}

//------------------------------------------------------------------------------
void vtkOpenGLImageDepthCompositor::ReleaseGraphicsResources(vtkWindow* window)
{
  this->ColorTexture->ReleaseGraphicsResources(window);
  this->DepthTexture->ReleaseGraphicsResources(window);
  if (this->Quad)
  {
    this->Quad->ReleaseGraphicsResources(window);
    this->Quad.reset();
  }
}

//------------------------------------------------------------------------------
void vtkOpenGLImageDepthCompositor::MoveGraphicsResources(
  vtkRenderer* renderer, vtkAbstractMapper* mapper)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (window == this->ResourceWindow)
  {
    return;
  }
  if (vtkOpenGLRenderWindow* previous = this->ResourceWindow)
  {
    previous->PushContext();
    mapper->ReleaseGraphicsResources(previous);
    previous->PopContext();
  }
  this->ResourceWindow = window;
}

//------------------------------------------------------------------------------
void vtkOpenGLImageDepthCompositor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
