//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// Normalization and deferred shading of one peeled layer of splats (paper 000, section 5): the
// summed attributes divided by the summed weights, lit with VTK's lights and the actor's
// property (SplatLighting.h's Shade, line by line), opacity times coverage (section 7), written
// premultiplied. The first layer also writes its window depth.

in vec2 texCoord;
uniform sampler2D weightedColor;   // (w r, w g, w b, w)
uniform sampler2D weightedNormal;  // (w nx, w ny, w nz, w opacity)
uniform sampler2D weightedDepth;   // w t
uniform mat3 rayOrigin;
uniform mat3 rayDirection;
uniform vec2 depthProjection;
uniform vec2 depthProjectionW;
uniform int edgeAntialiasing;
uniform float fullCoverage;

const int MaximumLights = 8;
uniform int numberOfLights;
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

//VTK::Output::Dec

vec3 shade(vec3 color, vec3 position, vec3 normal)
{
  vec3 ambientTerm = ambient * (ambientFromColor != 0 ? color : ambientColor);
  vec3 diffuseColor = diffuse * color;
  if (numberOfLights == 0)
  {
    return ambientTerm + diffuseColor;
  }
  vec3 toEye = normalize(-position);
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

void main()
{
  vec4 colorSum = texture(weightedColor, texCoord);
  float weight = colorSum.a;
  if (!(weight > 0.0))
  {
    discard;
  }
  vec4 normalSum = texture(weightedNormal, texCoord);
  float t = texture(weightedDepth, texCoord).r / weight;
  vec3 pixel = vec3(gl_FragCoord.xy, 1.0);
  vec3 position = rayOrigin * pixel + t * (rayDirection * pixel);
  float normalLength = length(normalSum.xyz);
  vec3 normal = normalLength > 0.0 ? normalSum.xyz / normalLength : vec3(0.0, 0.0, 1.0);
  vec3 shaded = clamp(shade(colorSum.rgb / weight, position, normal), 0.0, 1.0);
  float alpha = normalSum.a / weight;
  if (edgeAntialiasing != 0)
  {
    alpha *= min(1.0, weight / fullCoverage);
  }
  gl_FragData[0] = vec4(shaded * alpha, alpha);
  float ndc = (depthProjection.x * -t + depthProjection.y) / (depthProjectionW.x * -t + depthProjectionW.y);
  gl_FragData[1] = vec4(clamp(0.5 * ndc + 0.5, 0.0, 1.0));
}
