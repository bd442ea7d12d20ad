//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// Normalization and deferred shading of one peeled layer of splats (paper 000, section 5): the
// summed attributes divided by the summed weights, lit with VTK's lights and the actor's
// property (vtkSplatLighting.glsl), opacity times coverage (section 7), written
// premultiplied. Two-sided lighting: the summed normal, whose terms were added on one side
// (SplatSurfaceFragment.h's AddNormal), is turned towards the viewer. The first layer also writes its window depth.

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

//VTK::SplatLighting::Dec

//VTK::Output::Dec

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
  if (dot(normal, rayDirection * pixel) > 0.0)
  {
    normal = -normal;
  }
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
