//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// Normalization and deferred shading of one peeled layer of splats (paper 000, section 5): the
// summed attributes divided by the summed weights, lit with VTK's lights and the actor's
// property (vtkSplatLighting.glsl), opacity times coverage (section 7), written
// premultiplied. Two-sided lighting: the summed normal, whose terms were added on one side
// (SplatSurfaceFragment.h's AddNormal), is turned towards the viewer (facingNormal). The first
// layer also writes its window depth.

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
uniform float opaqueAlpha; // SplatSurfaceFragment.h's OpaqueAlpha
uniform float edgeOnCosine; // SplatLighting.h's EdgeOnCosine
// Raise coverage dips of the front layer of opaque splats (SplatSurfaceFragment.h's
// DipCoverage): the lowest share of full coverage, and the depth tolerance per unit eye depth
// (perspective) or in eye units (parallel).
uniform int closeDips;
uniform float dipCoverage;
uniform float dipTolerance;
uniform int perspective;

//VTK::SplatLighting::Dec

//VTK::Output::Dec

// SplatLighting.h's FacingNormal: the unit normal turned towards the viewer along `ray`, or,
// seen edge-on, towards the view axis.
vec3 facingNormal(vec3 normal, vec3 ray)
{
  float cosine = dot(normal, ray) / length(ray);
  bool away = abs(cosine) < edgeOnCosine ? normal.z < 0.0 : cosine > 0.0;
  return away ? -normal : normal;
}

// Whether pixel `at` holds an opaque surface covered at least `weight`, and its ray depth.
bool opaqueAt(ivec2 at, float weight, out float depth)
{
  float w = texelFetch(weightedColor, at, 0).a;
  depth = texelFetch(weightedDepth, at, 0).r / w;
  return w >= weight && texelFetch(weightedNormal, at, 0).a >= opaqueAlpha * w;
}

// Whether this pixel, covered `weight` at ray depth t, is a local minimum of an opaque surface's
// coverage: each pair of opposite neighbors holds an opaque surface covered at least as much,
// whose depths lie on a line through t within the depth tolerance
// (vtkSurfaceSplatRasterizer::CloseCoverageDips, in one pass).
bool coverageDip(float weight, float t)
{
  ivec2 size = textureSize(weightedColor, 0);
  ivec2 center = ivec2(gl_FragCoord.xy);
  if (any(lessThan(center, ivec2(1))) || any(greaterThanEqual(center, size - 1)))
  {
    return false;
  }
  float tolerance = dipTolerance * (perspective != 0 ? t : 1.0);
  ivec2 steps[4] = ivec2[4](ivec2(1, 0), ivec2(1, 1), ivec2(0, 1), ivec2(-1, 1));
  for (int i = 0; i < 4; ++i)
  {
    float ahead, behind;
    if (!opaqueAt(center + steps[i], weight, ahead) ||
      !opaqueAt(center - steps[i], weight, behind) || abs(ahead + behind - 2.0 * t) > tolerance)
    {
      return false;
    }
  }
  return true;
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
  normal = facingNormal(normal, rayDirection * pixel);
  vec3 shaded = clamp(shade(colorSum.rgb / weight, position, normal), 0.0, 1.0);
  float alpha = normalSum.a / weight;
  if (edgeAntialiasing != 0)
  {
    float covered = min(1.0, weight / fullCoverage);
    if (closeDips != 0 && covered < 1.0 && weight >= dipCoverage * fullCoverage &&
      alpha >= opaqueAlpha && coverageDip(weight, t))
    {
      covered = 1.0;
    }
    alpha *= covered;
  }
  gl_FragData[0] = vec4(shaded * alpha, alpha);
  float ndc = (depthProjection.x * -t + depthProjection.y) / (depthProjectionW.x * -t + depthProjectionW.y);
  gl_FragData[1] = vec4(clamp(0.5 * ndc + 0.5, 0.0, 1.0));
}
