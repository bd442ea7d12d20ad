// SPDX-License-Identifier: BSD-3-Clause
// The lighting of both mappers' shaders: SplatLighting.h's Shade, line by line (VTK's OpenGL2
// polydata lighting model). Substituted for //VTK::SplatLighting::Dec; the uniforms are set by
// splat::SetLightingUniforms (SplatOpenGLUtilities.h). All vectors in eye coordinates.

const int MaximumLights = 8;
uniform int numberOfLights;
uniform int headlightOnly; // SplatLighting.h's HeadlightOnly
uniform vec3 lightColor[MaximumLights];
uniform vec3 lightDirection[MaximumLights];
uniform int lightPositional[MaximumLights];
uniform vec3 lightPosition[MaximumLights];
uniform vec3 lightAttenuation[MaximumLights];
uniform float lightConeCosine[MaximumLights];
uniform float lightExponent[MaximumLights];
uniform float ambient;
uniform vec3 ambientColor;
uniform int ambientFromColor;
uniform float diffuse;
uniform vec3 specular;
uniform float specularPower;
uniform int parallelProjection;

vec3 shade(vec3 color, vec3 position, vec3 normal)
{
  vec3 ambientTerm = ambient * (ambientFromColor != 0 ? color : ambientColor);
  vec3 diffuseColor = diffuse * color;
  if (numberOfLights == 0)
  {
    return ambientTerm + diffuseColor;
  }
  if (headlightOnly != 0)
  {
    float df = max(0.0, normal.z);
    float sf = df > 0.0 && specular != vec3(0.0) ? pow(df, specularPower) : 0.0;
    return ambientTerm + lightColor[0] * (df * diffuseColor + sf * specular);
  }
  vec3 toEye = parallelProjection != 0 ? vec3(0.0, 0.0, 1.0) : normalize(-position);
  vec3 diffuseSum = vec3(0.0);
  vec3 specularSum = vec3(0.0);
  for (int i = 0; i < numberOfLights; ++i)
  {
    vec3 direction = lightDirection[i];
    float attenuation = 1.0;
    if (lightPositional[i] != 0)
    {
      vec3 fromLight = position - lightPosition[i];
      float distance = length(fromLight);
      direction = fromLight / distance;
      attenuation = 1.0 /
        (lightAttenuation[i].x +
          distance * (lightAttenuation[i].y + distance * lightAttenuation[i].z));
      if (lightConeCosine[i] >= 0.0)
      {
        float coneDot = dot(direction, lightDirection[i]);
        attenuation = coneDot >= lightConeCosine[i]
          ? attenuation * pow(coneDot, lightExponent[i]) : 0.0;
      }
    }
    float df = max(0.0, -dot(normal, direction));
    diffuseSum += attenuation * df * lightColor[i];
    if (df > 0.0)
    {
      vec3 reflected = reflect(direction, normal);
      float sf = pow(max(0.0, dot(reflected, toEye)), specularPower);
      specularSum += attenuation * sf * lightColor[i];
    }
  }
  return ambientTerm + diffuseSum * diffuseColor + specularSum * specular;
}
