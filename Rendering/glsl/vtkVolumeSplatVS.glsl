//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// Volume splats as instanced quads: instance i draws kernel order[i] (or order[count - 1 - i]
// for the descending traversal of a list), four vertices (a triangle strip) covering the box of
// its footprint's cutoff ellipse. The per-kernel setup mirrors vtkVolumeSplatRasterizer's step 2
// and SplatVolumeKernel.h (CrossesNearPlane, ProjectVolumeKernel, MakeVolumeFootprint,
// TruncationCompensation), SplatCaptureKernel.h (MakeCaptureFootprints, for captures in their
// depth order) and CoveredPixels (SplatSurfelKernel.h) line by line, colors kernels
// with spherical harmonics as vtkVolumeSplatRasterizer::UpdateViewColors does and shades
// kernels with normals as vtkVolumeSplatRasterizer::ShadeKernel does.

// Per kernel, kernelStride texels: (position relative to the shift folded into modelToEye,
// strength), (color, unused), without a shared covariance (xx, xy, xz, yy), (yz, zz, -, -), and
// last, when shaded, (model normal, unused).
uniform samplerBuffer kernels;
uniform isamplerBuffer order;
uniform int kernelStride;
uniform int count;
uniform int descending;

uniform mat4 modelToEye;
uniform mat4 eyeToClip;
uniform vec2 viewportSize;
uniform float nearDistance;
uniform float farDistance;
uniform float cutoff;
uniform float compensation; // TruncationCompensation(cutoff)
uniform int perspective;
uniform int peakOpacity;
// Captures in their depth order: the rules of SplatCaptureKernel.h.
uniform int captureRules;
uniform float filterVariance; // FilterVariance(filter)
uniform int bandLimit;        // the filter's variance as a floor (FilteredCovariance)
uniform int antialiased;      // FootprintFilter::Antialiased
uniform int sharedCovariance;
uniform mat3 sharedEyeCovariance;
uniform int shaded;
uniform mat3 normalToEye;
uniform int twoSidedLighting;
// Per kernel, sphericalHarmonicsStride texels (half floats) of (RGB coefficient, unused) in the
// basis order of SplatSphericalHarmonics.h, evaluated up to sphericalHarmonicsDegree (0: the
// color texel) for the direction from viewPoint (in the coordinates of the kernels' positions)
// or, in a parallel projection, along viewAxis.
uniform samplerBuffer sphericalHarmonics;
uniform int sphericalHarmonicsStride;
uniform int sphericalHarmonicsDegree;
uniform vec3 viewPoint;
uniform vec3 viewAxis;

//VTK::SplatLighting::Dec
//VTK::SplatSphericalHarmonics::Dec

flat out vec2 splatCenter;
flat out vec3 splatConic; // 1/2 M^-1 as (xx, 2 xy, yy): beta = dx^2 xx + dx dy xy + dy^2 yy
flat out float splatAmplitude; // optical depth (density model) or opacity (peak model)
flat out float splatDepth;     // eye depth of the center
flat out vec3 splatColor;
flat out vec2 splatHalfExtent; // captures: the pixels whose centers lie within it

const float InverseTwoPi = 0.15915494309189533577;
const float CaptureJacobianClamp = 1.3;
const float CaptureMinimumAlpha = 1.0 / 255.0;

void cull()
{
  // Outside the clip volume: the quad yields no fragment.
  gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
}

void main()
{
  int k = texelFetch(order, descending != 0 ? count - 1 - gl_InstanceID : gl_InstanceID).r;
  vec4 positionStrength = texelFetch(kernels, kernelStride * k);
  vec3 e = (modelToEye * vec4(positionStrength.xyz, 1.0)).xyz;
  mat3 V = sharedEyeCovariance;
  if (sharedCovariance == 0)
  {
    vec4 c0 = texelFetch(kernels, kernelStride * k + 2);
    vec4 c1 = texelFetch(kernels, kernelStride * k + 3);
    mat3 W = mat3(modelToEye);
    V = W * mat3(c0.x, c0.y, c0.z, c0.y, c0.w, c1.x, c0.z, c1.x, c1.y) * transpose(W);
  }

  // CrossesNearPlane, then ProjectVolumeKernel (the center strictly in front of the eye), then
  // the far plane; captures: their center at least the near distance in front of the eye.
  float zExtent = sqrt(2.0 * cutoff * max(V[2][2], 0.0));
  vec4 c = eyeToClip * vec4(e, 1.0);
  bool drawn = captureRules != 0
    ? -e.z >= nearDistance && c.w > 0.0
    : -e.z - zExtent > nearDistance && c.w > 0.0 && !(-e.z - zExtent > farDistance);
  if (!drawn)
  {
    cull();
    return;
  }
  vec2 ndc = c.xy / c.w;
  vec2 halfSize = 0.5 * viewportSize;
  vec2 center = (ndc + 1.0) * halfSize;
  // Ray space: pixel x, pixel y, distance along the ray (from the eye, or the eye plane);
  // captures take the Jacobian at their center's NDC clamped to +-1.3.
  vec2 jacobianNdc =
    captureRules != 0 ? clamp(ndc, -CaptureJacobianClamp, CaptureJacobianClamp) : ndc;
  vec3 distanceGradient = perspective != 0 ? e / length(e) : vec3(0.0, 0.0, -1.0);
  mat3 J;
  for (int axis = 0; axis < 3; ++axis)
  {
    vec4 d = eyeToClip[axis];
    J[axis] = vec3((d.xy - jacobianNdc * d.w) / c.w * halfSize, distanceGradient[axis]);
  }

  // MakeVolumeFootprint: M = (J V J^T)_2x2 under the filter (FilteredCovariance): its
  // variance added, or as a floor of the eigenvalues l1 >= l2, by way of the projector
  // (C - l1 I) / (l2 - l1) onto the smaller one's direction.
  mat3 rayCovariance = J * V * transpose(J);
  mat2 m2 = mat2(rayCovariance);
  if (bandLimit == 0)
  {
    m2 += mat2(filterVariance);
  }
  else
  {
    float mean = 0.5 * (m2[0][0] + m2[1][1]);
    float difference = 0.5 * (m2[0][0] - m2[1][1]);
    float radius = sqrt(difference * difference + m2[1][0] * m2[1][0]);
    float l1 = mean + radius;
    float l2 = mean - radius;
    if (!(l1 > filterVariance))
    {
      m2 = mat2(filterVariance);
    }
    else if (l2 < filterVariance)
    {
      m2 += (filterVariance - l2) / (l2 - l1) * (m2 - mat2(l1));
    }
  }
  float mxx = m2[0][0];
  float mxy = m2[1][0];
  float myy = m2[1][1];
  float detM = mxx * myy - mxy * mxy;
  float strength = positionStrength.w;
  // PeakOpacityCompensation.
  float opacity = antialiased != 0
    ? strength * sqrt(max(rayCovariance[0][0] * rayCovariance[1][1] - mxy * mxy, 0.0) / detM)
    : strength;
  vec2 halfExtent = sqrt(2.0 * cutoff * vec2(mxx, myy));
  if (captureRules != 0)
  {
    // MakeCaptureFootprints: the reference's square, within it the ellipse where alpha can
    // reach 1/255.
    float mid = 0.5 * (mxx + myy);
    float radius = ceil(3.0 * sqrt(mid + sqrt(max(0.1, mid * mid - detM))));
    float level = 2.0 * log(min(opacity, 1.0) / CaptureMinimumAlpha) * 1.001;
    if (!(detM > 0.0) || !(opacity >= CaptureMinimumAlpha))
    {
      cull();
      return;
    }
    halfExtent = min(vec2(radius), sqrt(level * vec2(mxx, myy)) + 1e-3);
  }
  // CoveredPixels: some pixel center inside the viewport.
  vec2 lo = center - halfExtent - 0.5;
  vec2 hi = center + halfExtent - 0.5;
  if (!(hi.x >= 0.0 && hi.y >= 0.0 && lo.x <= viewportSize.x - 1.0 &&
        lo.y <= viewportSize.y - 1.0))
  {
    cull();
    return;
  }

  splatCenter = center;
  splatHalfExtent = halfExtent;
  splatConic = vec3(0.5 * myy, -mxy, 0.5 * mxx) / detM;
  splatAmplitude = peakOpacity != 0
    ? opacity
    : strength * abs(determinant(J)) * InverseTwoPi / sqrt(detM) * compensation;
  splatDepth = -e.z;
  splatColor = texelFetch(kernels, kernelStride * k + 1).rgb;
  if (sphericalHarmonicsDegree > 0)
  {
    vec3 coefficients[MaximumSphericalHarmonicsCoefficients];
    for (int i = 0; i < sphericalHarmonicsCoefficients(sphericalHarmonicsDegree); ++i)
    {
      coefficients[i] = texelFetch(sphericalHarmonics, sphericalHarmonicsStride * k + i).rgb;
    }
    vec3 direction = perspective != 0 ? positionStrength.xyz - viewPoint : viewAxis;
    splatColor = sphericalHarmonicsColor(coefficients, sphericalHarmonicsDegree, direction);
  }
  if (shaded != 0)
  {
    vec3 normal = normalToEye * texelFetch(kernels, kernelStride * k + kernelStride - 1).xyz;
    float normalLength = length(normal);
    normal = normalLength > 0.0 ? normal / normalLength : vec3(0.0);
    if (twoSidedLighting != 0 && dot(normal, e) > 0.0)
    {
      normal = -normal;
    }
    splatColor = clamp(shade(splatColor, e, normal), 0.0, 1.0);
  }

  // The corner of this vertex, with half a pixel of margin around the box.
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
  vec2 pixel = center + corner * (halfExtent + 0.5);
  gl_Position = vec4(pixel / viewportSize * 2.0 - 1.0, 0.0, 1.0);
}
