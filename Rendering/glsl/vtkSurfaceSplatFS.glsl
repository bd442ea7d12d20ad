//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// The per-fragment work of the splatting passes (An and Zhou, section 4): intersect the pixel's
// view ray with the splat's tangent plane (exact for large and near splats, where the affine
// approximation is not), reject the fragment outside the kernel's cutoff, and write the
// intersection's linear eye depth, so that the visibility offset is the same distance near and
// far. The weight is the screen-space EWA kernel of paper 000 eq. (6), set up once per splat;
// a differential point's normal is the one it predicts where the ray meets its tangent plane
// (SplatDifferentialPointNormal.h), and unfiltered, its rectangle has weight 1.
//   pass 0, visibility: depth of the intersection plus the splat's threshold, and the nearest
//           splat's normal;
//   pass 1, attributes: weight-times-color, weight, weight-times-normal, weight-times-opacity
//           and weight-times-depth, added up over the splats within the threshold of pass 0,
//           each normal turned to the side of the nearest one (the CPU's AddNormal turns it to
//           the running sum's, which blending cannot read);
//   pass 2, selection: the hardware selector's color, at the window depth of the intersection
//           pulled forward by a share of the threshold that shrinks with the kernel's exponent.

flat in vec2 splatCenter;
flat in vec3 splatConic;
flat in float splatAmplitude;
flat in vec3 splatPoint;
flat in vec3 splatNormal;
flat in vec3 splatAxis0;
flat in vec3 splatAxis1;
flat in vec2 splatExtent;
flat in vec2 splatCurvature;
flat in float splatThreshold;
flat in float splatCutoff;
flat in vec4 splatColor;
flat in vec2 splatPointId;

uniform int splatPass;
uniform int filterMode;
uniform int differential;
uniform int perspective;
// The view rays: pixel (x, y) sees rayOrigin (x, y, 1) + t rayDirection (x, y, 1) at eye depth t.
uniform mat3 rayOrigin;
uniform mat3 rayDirection;
// The viewport's lower-left pixel in the framebuffer drawn into.
uniform vec2 viewportOrigin;
uniform float nearDepth;
uniform float farDepth;
uniform vec2 depthProjection; // eye z to NDC z: (P22 z + P32) / (P23 z + P33), as (P22, P32)
uniform vec2 depthProjectionW; // (P23, P33)
// Peeling: fragments at or in front of the previous layer's visibility depth were drawn there,
// and pixels that the layers in front cover fully (alpha 1) show nothing behind them.
uniform int peel;
uniform sampler2D previousDepth;
uniform sampler2D layersInFront;
uniform sampler2D nearestNormal; // pass 0's normal, read by pass 1
// Translucent splats: fragments behind the opaque scene already drawn are hidden.
uniform int sceneTest;
uniform sampler2D sceneDepth;
uniform vec3 selectionColor; // actor, composite index and process passes
uniform int selectionIdPass; // 0: selectionColor, 1: low 24 bits of the id, 2: high 24 bits

//VTK::Output::Dec

float linearDepth(float t)
{
  return clamp((t - nearDepth) / (farDepth - nearDepth), 0.0, 1.0);
}

float windowDepth(float t)
{
  float z = -t;
  float ndc = (depthProjection.x * z + depthProjection.y) /
    (depthProjectionW.x * z + depthProjectionW.y);
  return clamp(0.5 * ndc + 0.5, 0.0, 1.0);
}

vec3 idColor(float id)
{
  // 24 bits as RGB bytes, as vtkHardwareSelector decodes them.
  float low = mod(id, 256.0);
  float middle = mod(floor(id / 256.0), 256.0);
  float high = floor(id / 65536.0);
  return vec3(low, middle, high) / 255.0;
}

// SplatDifferentialPointNormal.h's DifferentialNormalScale, line by line.
float differentialNormalScale(vec2 curvature, vec2 uv)
{
  float r2 = dot(uv, uv);
  if (!(r2 > 0.0))
  {
    return 1.0;
  }
  float k = curvature.x * uv.x * uv.x + curvature.y * uv.y * uv.y;
  float x2 = k * k / r2;
  if (x2 < 0.0625)
  {
    return 1.0 + x2 * (1.0 / 6.0 + x2 * (3.0 / 40.0 + x2 * 5.0 / 112.0));
  }
  float x = sqrt(x2);
  return asin(min(x, 1.0)) / x;
}

void main()
{
  vec2 fragment = gl_FragCoord.xy - viewportOrigin;
  // First, before any other work: on a GPU, most of a peeled layer's fragments end here.
  if (peel != 0 && texelFetch(layersInFront, ivec2(fragment), 0).a >= 1.0)
  {
    discard;
  }
  vec3 pixel = vec3(fragment, 1.0);
  vec3 origin = rayOrigin * pixel;
  vec3 direction = rayDirection * pixel;
  float t = dot(splatNormal, splatPoint - origin) / dot(splatNormal, direction);

  vec2 d = fragment - splatCenter;
  float beta = splatConic.x * d.x * d.x + splatConic.y * d.x * d.y + splatConic.z * d.y * d.y;
  // Where the ray meets the tangent plane, in axis units.
  vec2 u = vec2(0.0);
  if (filterMode == 3 || differential != 0)
  {
    vec3 local = origin + t * direction - splatPoint;
    mat2 gram = mat2(dot(splatAxis0, splatAxis0), dot(splatAxis0, splatAxis1),
      dot(splatAxis0, splatAxis1), dot(splatAxis1, splatAxis1));
    u = inverse(gram) * vec2(dot(local, splatAxis0), dot(local, splatAxis1));
  }
  bool rectangle = differential != 0 && filterMode == 2;
  if (filterMode == 3)
  {
    // Approximate filter: the larger of the object-space kernel, evaluated where the ray meets
    // the tangent plane, and the screen-space low-pass (Botsch et al. 2005).
    beta = min(beta, dot(u, u)); // 1/2 u^T Vr^-1 u with Vr = 1/2 I
  }
  if (rectangle)
  {
    beta = max(abs(u.x), abs(u.y)) <= 1.0 ? 0.0 : splatCutoff;
  }
  // A ray that meets the plane behind the eye does not see the splat; the near and far planes
  // clip it.
  if (!(beta < splatCutoff) || (perspective != 0 && !(t > 0.0)) ||
    !(t >= nearDepth && t <= farDepth))
  {
    discard;
  }
  if (splatPass == 2)
  {
    // Pulled toward the eye by up to the depth threshold, less the farther from the kernel's
    // center: within a surface, the splat whose kernel weighs most at the pixel wins; the
    // surface passes the depth the render before the selection left (the selector preserves
    // it), which lies within the threshold behind its front; a surface in front wins.
    gl_FragDepth = windowDepth(t - splatThreshold * (1.0 - beta / splatCutoff));
    gl_FragData[0] = vec4(selectionIdPass == 0 ? selectionColor
        : idColor(selectionIdPass == 1 ? splatPointId.x : splatPointId.y), 1.0);
    return;
  }
  ivec2 texel = ivec2(fragment);
  float depth = linearDepth(t);
  if ((peel != 0 && depth <= texelFetch(previousDepth, texel, 0).r) ||
    (sceneTest != 0 && windowDepth(t) > texelFetch(sceneDepth, texel, 0).r))
  {
    discard;
  }
  if (splatPass == 0)
  {
    gl_FragDepth = linearDepth(t + splatThreshold);
    gl_FragData[0] = vec4(splatNormal, 0.0);
    return;
  }
  vec3 normal = splatNormal;
  if (differential != 0)
  {
    vec2 uv = u * splatExtent;
    float g = differentialNormalScale(splatCurvature, uv);
    normal = normalize(splatNormal - g * (splatCurvature.x * uv.x * normalize(splatAxis0) +
      splatCurvature.y * uv.y * normalize(splatAxis1)));
  }
  if (dot(normal, texelFetch(nearestNormal, texel, 0).xyz) < 0.0)
  {
    normal = -normal;
  }
  float w = rectangle ? 1.0 : splatAmplitude * exp(-beta);
  gl_FragDepth = depth;
  gl_FragData[0] = vec4(w * splatColor.rgb, w);
  gl_FragData[1] = vec4(w * normal, w * splatColor.a);
  gl_FragData[2] = vec4(w * t);
}
