// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSplatBackend.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtk_glew.h"

#include <cstring>

vtkStandardNewMacro(vtkSplatBackend);

//------------------------------------------------------------------------------
const char* vtkSplatBackend::GetBackendAsString(int backend)
{
  switch (backend)
  {
    case AUTO:
      return "Auto";
    case CPU:
      return "CPU";
    case OPENGL:
      return "OpenGL";
    default:
      return "Unknown";
  }
}

//------------------------------------------------------------------------------
bool vtkSplatBackend::IsSoftwareRenderer(vtkRenderWindow* window)
{
  if (!vtkOpenGLRenderWindow::SafeDownCast(window))
  {
    return true;
  }
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (!renderer)
  {
    return true;
  }
  for (const char* software : { "llvmpipe", "softpipe", "swrast", "Software Rasterizer" })
  {
    if (std::strstr(renderer, software))
    {
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
int vtkSplatBackend::Resolve(int requested, vtkRenderWindow* window)
{
  if (requested == CPU || requested == OPENGL)
  {
    return requested;
  }
  return IsSoftwareRenderer(window) ? CPU : OPENGL;
}

//------------------------------------------------------------------------------
void vtkSplatBackend::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
