//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// The per-splat setup of the surface splats, once per surfel and frame: one vertex per surfel,
// drawn as points with the rasterizer off, whose outputs transform feedback captures as the
// splat's record; vtkSurfaceSplatVS.glsl's four corners read it. The setup mirrors
// SplatSurfelKernel.h (ProjectSurfel, Foreshortening, MakeResamplingKernel) and
// vtkSurfaceSplatRasterizer.cxx line by line.

in vec3 position; // relative to the shift folded into modelToEye
in vec3 axis0;
in vec3 axis1;
in vec3 normal;
in vec4 color; // rgb, opacity
in vec2 curvature; // a differential point's principal curvatures along axis0 and axis1

uniform mat4 modelToEye;
uniform mat3 normalToEye;
uniform mat4 eyeToClip;
uniform vec2 viewportSize;
uniform float nearDepth;
uniform float farDepth;
uniform float cutoff;
uniform float antialiasingCutoff; // SplatCutoff's least cutoff where the low-pass matters
uniform float minifiedLowPass; // LowPassVariance's variance for minified splats
uniform float magnifiedLowPass; // and for magnified ones
uniform int filterMode; // 0 EWA, 1 circular, 2 unfiltered, 3 approximate
uniform int differential; // axes are the rectangles' half-widths along the principal directions
uniform int perspective;
uniform int cullBackFaces;
uniform float depthThreshold;

// The record, captured in this order (RecordFields in vtkOpenGLSurfaceSplatRasterizer.cxx).
out vec4 recordBox;    // the pixel box (lo, hi); empty (hi < lo) for a culled splat
out vec4 recordCenter; // the kernel's center in pixels, and the curvatures (negated with a
                       // back-facing normal)
out vec4 recordConic;  // 1/2 M^-1 as (xx, 2 xy, yy): beta = dx^2 xx + dx dy xy + dy^2 yy, and
                       // the kernel's amplitude
out vec4 recordPoint;  // eye space, and the depth threshold
out vec4 recordNormal; // eye space, either side, and the splat's cutoff
out vec4 recordAxis0;  // eye space, and the axis's length in model units
out vec4 recordAxis1;
out vec4 recordColor;

const float InverseTwoPi = 0.15915494309189533577;
const float EdgeOnForeshortening = 1e-3;
const float UnfilteredMinimumVariance = 1e-6;
const float LowPassFadeStart = 0.75;
const float LowPassFadeEnd = 1.5;
const float CutoffFadeStart = 8.0;
const float CutoffFadeEnd = 32.0;

void cull()
{
  // The strip shader draws no quad for an empty box; the rest of the record is not read.
  recordBox = vec4(1.0, 1.0, -1.0, -1.0);
}

void main()
{
  vec3 p = (modelToEye * vec4(position, 1.0)).xyz;
  vec3 a0 = mat3(modelToEye) * axis0;
  vec3 a1 = mat3(modelToEye) * axis1;
  bool rectangle = differential != 0 && filterMode == 2;
  float footprint = differential != 0 && !rectangle ? sqrt(2.0) : 1.0;
  // Culled when the whole splat lies outside the depth range: a large one reaches past the
  // near or far plane from a center outside it (its fragments are clipped there).
  float reach =
    footprint * max(sqrt(max(cutoff, antialiasingCutoff)), 1.0) * (abs(a0.z) + abs(a1.z));
  if (!(-p.z + reach >= nearDepth && -p.z - reach <= farDepth))
  {
    cull();
    return;
  }

  // ProjectSurfel: center and Jacobian of the projective map, in pixels.
  vec4 c = eyeToClip * vec4(p, 1.0);
  if (!(c.w > 0.0))
  {
    cull();
    return;
  }
  vec2 ndc = c.xy / c.w;
  vec2 halfSize = 0.5 * viewportSize;
  vec2 center = (ndc + 1.0) * halfSize;
  // A filtered differential point's Gaussian passes through its rectangle's corners, with the
  // rectangle's area as its mass (footprint); unfiltered, the rectangle itself is drawn.
  vec4 d0 = eyeToClip * vec4(footprint * a0, 0.0);
  vec4 d1 = eyeToClip * vec4(footprint * a1, 0.0);
  vec2 j0 = (d0.xy - ndc * d0.w) / c.w * halfSize;
  vec2 j1 = (d1.xy - ndc * d1.w) / c.w * halfSize;

  vec3 n = normalize(normalToEye * normal);
  vec3 view = perspective != 0 ? p : vec3(0.0, 0.0, -1.0);
  if (cullBackFaces != 0 && dot(n, view) > 0.0)
  {
    cull();
    return;
  }
  // Foreshortening: edge-on splats are negligible next to their neighbors.
  float detJ = j0.x * j1.y - j1.x * j0.y;
  float squaredAxes = dot(j0, j0) + dot(j1, j1);
  if (!(2.0 * abs(detJ) >= EdgeOnForeshortening * squaredAxes))
  {
    cull();
    return;
  }

  // MakeResamplingKernel: M = J Vr J^T (+ v I), Vr = 1/2 I.
  float mxx = 0.5 * (j0.x * j0.x + j1.x * j1.x);
  float mxy = 0.5 * (j0.x * j0.y + j1.x * j1.y);
  float myy = 0.5 * (j0.y * j0.y + j1.y * j1.y);
  float lowPass = 1.0;
  float splatCutoff = cutoff;
  if (filterMode == 0)
  {
    // LowPassVariance: fades from the minified to the magnified variance as the largest
    // warped variance grows;
    // SplatCutoff: raised to the antialiasing cutoff while the low-pass is a sizable part.
    float largest =
      0.5 * (mxx + myy) + sqrt(0.25 * (mxx - myy) * (mxx - myy) + mxy * mxy);
    lowPass = mix(max(minifiedLowPass, UnfilteredMinimumVariance), magnifiedLowPass,
      clamp((largest - LowPassFadeStart) / (LowPassFadeEnd - LowPassFadeStart), 0.0, 1.0));
    splatCutoff = cutoff + max(antialiasingCutoff - cutoff, 0.0) *
        (1.0 - clamp((largest - CutoffFadeStart) / (CutoffFadeEnd - CutoffFadeStart), 0.0, 1.0));
  }
  else if (filterMode == 2)
  {
    lowPass = UnfilteredMinimumVariance;
  }
  mxx += lowPass;
  myy += lowPass;
  if (filterMode == 1)
  {
    float mean = 0.5 * (mxx + myy);
    float halfDifference = 0.5 * (mxx - myy);
    mxx = myy = mean + sqrt(halfDifference * halfDifference + mxy * mxy);
    mxy = 0.0;
  }
  float detM = mxx * myy - mxy * mxy;
  // The approximate filter's screen-space part is the unit low-pass alone; its box is EWA's,
  // which holds both the object-space ellipse and the low-pass disk.
  vec3 conic = filterMode == 3 ? vec3(0.5, 0.0, 0.5) : vec3(0.5 * myy, -mxy, 0.5 * mxx) / detM;
  float amplitude = filterMode == 3 ? 1.0 : abs(detJ) * InverseTwoPi / sqrt(detM);
  // TruncatedMassScale: the mass the kernel would keep at the frame's cutoff.
  amplitude *= footprint * footprint;
  if (splatCutoff > cutoff)
  {
    amplitude *= (1.0 - exp(-cutoff)) / (1.0 - exp(-splatCutoff));
  }
  vec2 lo = center - sqrt(2.0 * splatCutoff * vec2(mxx, myy));
  vec2 hi = 2.0 * center - lo;
  if (rectangle)
  {
    // The box of the corners' exact projections.
    lo = vec2(1e30);
    hi = vec2(-1e30);
    for (int k = 0; k < 4; ++k)
    {
      vec3 corner = p + (float(k & 1) * 2.0 - 1.0) * a0 + (float(k >> 1) * 2.0 - 1.0) * a1;
      vec4 q = eyeToClip * vec4(corner, 1.0);
      if (!(q.w > 0.0))
      {
        cull();
        return;
      }
      vec2 cornerPixel = (q.xy / q.w + 1.0) * halfSize;
      lo = min(lo, cornerPixel);
      hi = max(hi, cornerPixel);
    }
  }
  if (hi.x < 0.0 || hi.y < 0.0 || lo.x > viewportSize.x || lo.y > viewportSize.y)
  {
    cull();
    return;
  }

  recordBox = vec4(lo, hi);
  recordCenter = vec4(center, curvature);
  recordConic = vec4(conic, amplitude);
  recordPoint = vec4(p, depthThreshold * max(length(a0), length(a1)));
  recordNormal = vec4(n, splatCutoff); // either side: the attribute pass turns it (AddNormal)
  recordAxis0 = vec4(a0, length(axis0));
  recordAxis1 = vec4(a1, length(axis1));
  recordColor = color;
}
