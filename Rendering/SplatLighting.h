// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatLighting.h
 * @brief Deferred per-pixel shading of splats with the lighting model of VTK's OpenGL2 polydata
 * shader (ambient + diffuse + Phong specular, headlight, directional and positional lights with
 * attenuation and spot cones), so splats and triangles lit by the same vtkLight and vtkProperty
 * look the same. VTK-free (GLM only). All vectors are in eye coordinates.
 */
#ifndef SplatLighting_h
#define SplatLighting_h

#include <glm/glm.hpp>

#include <cmath>
#include <vector>

namespace splat
{

struct Light
{
  glm::vec3 Color{ 1.0f };             ///< diffuse color times intensity
  glm::vec3 Direction{ 0, 0, -1 };     ///< direction the light travels, unit
  bool Positional = false;
  glm::vec3 Position{ 0.0f };          ///< for positional lights
  glm::vec3 Attenuation{ 1, 0, 0 };    ///< constant, linear, quadratic
  float ConeCosine = -1.0f;            ///< cos(cone angle); spots only when >= 0 and angle < 90
  float Exponent = 1.0f;               ///< spot exponent
  bool Headlight = false;              ///< a vtkLight of type headlight
};

/// Whether the lights are VTK's single headlight (its light complexity 1, the default
/// renderer's light), which VTK shades with the view axis as half vector.
inline bool HeadlightOnly(const std::vector<Light>& lights)
{
  return lights.size() == 1 && lights[0].Headlight && !lights[0].Positional;
}

/// Below this cosine between a pixel's ray and its filtered normal the pixel sees its surface
/// edge-on (within about 6 degrees), where which side faces the viewer is below what the splats
/// resolve.
constexpr float EdgeOnCosine = 0.1f;

/**
 * Two-sided lighting: the unit filtered normal turned towards the viewer along `ray` (the
 * pixel's ray direction, of any length). Seen edge-on, the side facing the view axis is taken
 * instead, the side the headlight lights: the tangent disks of splats just past a curved
 * silhouette overshoot it and show the surface edge-on from behind, and turned towards the
 * viewer their normals point away from the light and draw dark dots along the silhouette. In a
 * parallel projection both rules agree.
 */
inline glm::vec3 FacingNormal(const glm::vec3& normal, const glm::vec3& ray)
{
  const float cosine = glm::dot(normal, ray) / glm::length(ray);
  const bool away = std::abs(cosine) < EdgeOnCosine ? normal.z < 0.0f : cosine > 0.0f;
  return away ? -normal : normal;
}

/**
 * The vtkProperty terms. The surface color (a point's scalar color or the property's diffuse
 * color, filtered across splats) is multiplied in at shading time: into the diffuse term always
 * and into the ambient term when AmbientFromColor is set (VTK's default for scalar coloring).
 */
struct Material
{
  float Ambient = 0.0f;
  glm::vec3 AmbientColor{ 1.0f };
  bool AmbientFromColor = false;
  float Diffuse = 1.0f;
  glm::vec3 Specular{ 0.0f }; ///< specular coefficient times specular color
  float SpecularPower = 1.0f;
};

/**
 * Shades a surface point of color `color` at eye position `position` with unit normal `normal`
 * facing the viewer. The direction to the eye is the view axis in a parallel projection, as in
 * VTK. With no lights (lighting off) the result is ambient + diffuse, as in VTK.
 */
inline glm::vec3 Shade(const std::vector<Light>& lights, const Material& material,
  const glm::vec3& color, const glm::vec3& position, const glm::vec3& normal,
  bool parallelProjection)
{
  const glm::vec3 ambient =
    material.Ambient * (material.AmbientFromColor ? color : material.AmbientColor);
  const glm::vec3 diffuseColor = material.Diffuse * color;
  if (lights.empty())
  {
    return ambient + diffuseColor;
  }
  if (HeadlightOnly(lights))
  {
    const float df = std::max(0.0f, normal.z);
    // No pow where nothing specular is added (VTK's default property).
    const bool specular = df > 0.0f && material.Specular != glm::vec3(0.0f);
    const float sf = specular ? std::pow(df, material.SpecularPower) : 0.0f;
    return ambient + lights[0].Color * (df * diffuseColor + sf * material.Specular);
  }
  const glm::vec3 toEye =
    parallelProjection ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::normalize(-position);
  glm::vec3 diffuse(0.0f), specular(0.0f);
  for (const Light& light : lights)
  {
    glm::vec3 direction = light.Direction;
    float attenuation = 1.0f;
    if (light.Positional)
    {
      const glm::vec3 fromLight = position - light.Position;
      const float distance = glm::length(fromLight);
      direction = fromLight / distance;
      attenuation = 1.0f /
        (light.Attenuation.x + distance * (light.Attenuation.y + distance * light.Attenuation.z));
      if (light.ConeCosine >= 0.0f)
      {
        const float coneDot = glm::dot(direction, light.Direction);
        attenuation = coneDot >= light.ConeCosine ? attenuation * std::pow(coneDot, light.Exponent)
                                                  : 0.0f;
      }
    }
    const float df = std::max(0.0f, -glm::dot(normal, direction));
    diffuse += attenuation * df * light.Color;
    if (df > 0.0f)
    {
      const glm::vec3 reflected = glm::reflect(direction, normal);
      const float sf =
        std::pow(std::max(0.0f, glm::dot(reflected, toEye)), material.SpecularPower);
      specular += attenuation * sf * light.Color;
    }
  }
  return ambient + diffuse * diffuseColor + specular * material.Specular;
}

} // namespace splat

#endif
