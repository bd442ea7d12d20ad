// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatOpenGLUtilities.h
 * @brief what the OpenGL backends of both mappers and the image compositor share: full-screen
 * passes, screen-sized textures, and the shift that keeps float positions near the origin.
 * Private to the module's OpenGL sources.
 */
#ifndef SplatOpenGLUtilities_h
#define SplatOpenGLUtilities_h

#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <limits>
#include <memory>

namespace splat
{
/**
 * The full-screen pass of fragment shader `fs` (made on first use), its program made current.
 * Null when the program did not compile.
 */
inline vtkShaderProgram* ReadyQuad(
  std::unique_ptr<vtkOpenGLQuadHelper>& quad, vtkOpenGLRenderWindow* window, const char* fs)
{
  if (!quad)
  {
    quad.reset(new vtkOpenGLQuadHelper(window, nullptr, fs, ""));
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(quad->Program);
  }
  return quad->Program && quad->Program->GetCompiled() ? quad->Program : nullptr;
}

/// A texture of the window sampled per pixel: nearest, clamped.
inline void SetNearest(vtkTextureObject* texture, vtkOpenGLRenderWindow* window)
{
  texture->SetContext(window);
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
}

/**
 * The center of the bounds of `count` points (xyz triples), the origin for none: positions are
 * uploaded relative to it, with the shift folded into the model-view matrix in double
 * precision, so that data far from the origin renders like data at the origin.
 */
inline glm::dvec3 BoundsCenter(const double* xyz, std::size_t count)
{
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (std::size_t i = 0; i < count; ++i)
  {
    const glm::dvec3 p(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return count > 0 ? 0.5 * (lo + hi) : glm::dvec3(0.0);
}
}

#endif
