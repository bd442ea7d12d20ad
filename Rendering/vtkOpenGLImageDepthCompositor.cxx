// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenGLImageDepthCompositor.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

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
  const std::uint8_t* rgba, const float* depth)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window || width <= 0 || height <= 0)
  {
    return;
  }
  for (vtkTextureObject* texture : { this->ColorTexture.Get(), this->DepthTexture.Get() })
  {
    texture->SetContext(window);
    texture->SetMinificationFilter(vtkTextureObject::Nearest);
    texture->SetMagnificationFilter(vtkTextureObject::Nearest);
    texture->SetWrapS(vtkTextureObject::ClampToEdge);
    texture->SetWrapT(vtkTextureObject::ClampToEdge);
  }
  this->ColorTexture->Create2DFromRaw(width, height, 4, VTK_UNSIGNED_CHAR,
    const_cast<void*>(static_cast<const void*>(rgba)));
  this->DepthTexture->Create2DFromRaw(width, height, 1, VTK_FLOAT,
    const_cast<void*>(static_cast<const void*>(depth)));

  if (!this->Quad)
  {
    this->Quad.reset(new vtkOpenGLQuadHelper(window, nullptr, CompositeFragmentShader, ""));
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(this->Quad->Program);
  }
  if (!this->Quad->Program || !this->Quad->Program->GetCompiled())
  {
    vtkErrorMacro("The splat compositing shader did not compile.");
    return;
  }

  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDisable(GL_BLEND);
  state->vtkglDepthFunc(GL_LEQUAL);
  state->vtkglDepthMask(GL_TRUE);

  this->ColorTexture->Activate();
  this->DepthTexture->Activate();
  this->Quad->Program->SetUniformi("splatColor", this->ColorTexture->GetTextureUnit());
  this->Quad->Program->SetUniformi("splatDepth", this->DepthTexture->GetTextureUnit());
  this->Quad->Render();
  this->ColorTexture->Deactivate();
  this->DepthTexture->Deactivate();
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
void vtkOpenGLImageDepthCompositor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
