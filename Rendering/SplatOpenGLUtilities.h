// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatOpenGLUtilities.h
 * @brief what the OpenGL backends of both mappers and the image compositor share: full-screen
 * passes, screen-sized textures, the shift that keeps float positions near the origin, and the
 * lighting (glsl/vtkSplatLighting.glsl).
 * Private to the module's OpenGL sources.
 */
#ifndef SplatOpenGLUtilities_h
#define SplatOpenGLUtilities_h

#include "SplatLighting.h"
#include "SplatSurfelKernel.h"
#include "vtkSplatLighting.h"

#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

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

/// The lights the shaders take (MaximumLights in vtkSplatLighting.glsl).
constexpr int MaximumLights = 8;

/// Shader source with the lighting code (vtkSplatLighting.glsl) put in for
/// //VTK::SplatLighting::Dec. Callers keep the result (a static), not remake it every frame.
inline std::string WithLighting(std::string source)
{
  vtkShaderProgram::Substitute(source, "//VTK::SplatLighting::Dec", vtkSplatLighting);
  return source;
}

/// Sets the uniforms of vtkSplatLighting.glsl: the first MaximumLights lights, the material and
/// the projection (the projection matrix `eyeToClip`).
inline void SetLightingUniforms(vtkShaderProgram* program, const std::vector<Light>& lights,
  const Material& material, const glm::dmat4& eyeToClip)
{
  const int count = std::min(static_cast<int>(lights.size()), MaximumLights);
  if (static_cast<int>(lights.size()) > MaximumLights)
  {
    vtkGenericWarningMacro("Splats are lit by the first " << MaximumLights << " of "
                                                          << lights.size() << " lights.");
  }
  float color[MaximumLights][3], direction[MaximumLights][3], position[MaximumLights][3],
    attenuation[MaximumLights][3], coneCosine[MaximumLights], exponent[MaximumLights];
  int positional[MaximumLights];
  for (int i = 0; i < count; ++i)
  {
    const Light& light = lights[i];
    for (int c = 0; c < 3; ++c)
    {
      color[i][c] = light.Color[c];
      direction[i][c] = light.Direction[c];
      position[i][c] = light.Position[c];
      attenuation[i][c] = light.Attenuation[c];
    }
    coneCosine[i] = light.ConeCosine;
    exponent[i] = light.Exponent;
    positional[i] = light.Positional;
  }
  program->SetUniformi("numberOfLights", count);
  program->SetUniformi("headlightOnly", HeadlightOnly(lights));
  if (count > 0)
  {
    program->SetUniform3fv("lightColor", count, color);
    program->SetUniform3fv("lightDirection", count, direction);
    program->SetUniform1iv("lightPositional", count, positional);
    program->SetUniform3fv("lightPosition", count, position);
    program->SetUniform3fv("lightAttenuation", count, attenuation);
    program->SetUniform1fv("lightConeCosine", count, coneCosine);
    program->SetUniform1fv("lightExponent", count, exponent);
  }
  program->SetUniformf("ambient", material.Ambient);
  program->SetUniform3f("ambientColor", glm::value_ptr(material.AmbientColor));
  program->SetUniformi("ambientFromColor", material.AmbientFromColor);
  program->SetUniformf("diffuse", material.Diffuse);
  program->SetUniform3f("specular", glm::value_ptr(material.Specular));
  program->SetUniformf("specularPower", material.SpecularPower);
  program->SetUniformi("parallelProjection", IsParallelProjection(eyeToClip) ? 1 : 0);
}
}

#endif
