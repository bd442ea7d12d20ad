// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatVTKConversions.h
 * @brief VTK types to the GLM types of the splatting core, shared by the mappers: matrices and
 * the renderer's lights.
 */
#ifndef SplatVTKConversions_h
#define SplatVTKConversions_h

#include "SplatLighting.h"

#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkRenderer.h"

#include <glm/glm.hpp>

#include <cmath>
#include <vector>

namespace splat
{
/// A vtkMatrix4x4 (row-major, element (row, column)) as a column-major GLM matrix.
inline glm::dmat4 ToGlm(vtkMatrix4x4* m)
{
  glm::dmat4 result;
  for (int row = 0; row < 4; ++row)
  {
    for (int column = 0; column < 4; ++column)
    {
      result[column][row] = m->GetElement(row, column);
    }
  }
  return result;
}

/// The renderer's lights that are on, in eye coordinates, as VTK's OpenGL2 polydata shader sees
/// them.
inline std::vector<Light> EyeLights(vtkRenderer* ren, const glm::dmat4& worldToEye)
{
  std::vector<Light> lights;
  vtkLightCollection* collection = ren->GetLights();
  vtkCollectionSimpleIterator it;
  collection->InitTraversal(it);
  const glm::dmat3 rotation(worldToEye);
  while (vtkLight* light = collection->GetNextLight(it))
  {
    if (!light->GetSwitch() || light->GetIntensity() <= 0.0)
    {
      continue;
    }
    Light l;
    const double* color = light->GetDiffuseColor();
    l.Color = glm::vec3(glm::dvec3(color[0], color[1], color[2]) * light->GetIntensity());
    double position[3], focalPoint[3];
    light->GetTransformedPosition(position);
    light->GetTransformedFocalPoint(focalPoint);
    const glm::dvec3 p(position[0], position[1], position[2]);
    const glm::dvec3 f(focalPoint[0], focalPoint[1], focalPoint[2]);
    const glm::dvec3 direction = f - p;
    if (!(glm::length(direction) > 0.0))
    {
      continue;
    }
    l.Direction = glm::vec3(glm::normalize(rotation * direction));
    l.Headlight = light->LightTypeIsHeadlight();
    if (light->GetPositional())
    {
      l.Positional = true;
      l.Position = glm::vec3(glm::dvec3(worldToEye * glm::dvec4(p, 1.0)));
      const double* a = light->GetAttenuationValues();
      l.Attenuation = glm::vec3(a[0], a[1], a[2]);
      if (light->GetConeAngle() < 90.0)
      {
        l.ConeCosine =
          static_cast<float>(std::cos(vtkMath::RadiansFromDegrees(light->GetConeAngle())));
        l.Exponent = static_cast<float>(light->GetExponent());
      }
    }
    lights.push_back(l);
  }
  return lights;
}
} // namespace splat

#endif
