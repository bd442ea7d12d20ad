//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// One kernel's footprint at one pixel of one list's traversal (vtkVolumeSplatRasterizer's
// CompositeKernel): pixels that traverse the list in the other direction or not at all, pixels
// whose opaque scene lies in front of the kernel's center and pixels outside the cutoff ellipse
// are left alone; the others get the kernel's emission and absorption, premultiplied, blended
// front to back under what the kernels before it in the list left there. Captures in their
// depth order (captureRules) take the rules of SplatCaptureKernel.h instead of the cutoff:
// pixels within the footprint's box, alpha = min(0.99, opacity exp(-beta)), at least 1/255.

flat in vec2 splatCenter;
flat in vec3 splatConic;
flat in float splatAmplitude;
flat in float splatDepth;
flat in vec3 splatColor;
flat in vec2 splatHalfExtent;

// Per pixel: the signed weights of the three lists and the eye depth of the opaque scene.
uniform sampler2D pixelWeights;
uniform int list;
uniform int descending;
uniform float cutoff;
uniform int peakOpacity;
uniform int captureRules;

//VTK::Output::Dec

// The most a kernel of the 3D Gaussian Splatting convention covers a pixel, as in its viewers.
const float MaximumPeakOpacity = 0.99;
const float CaptureMinimumAlpha = 1.0 / 255.0;

void main()
{
  vec4 weights = texelFetch(pixelWeights, ivec2(gl_FragCoord.xy), 0);
  float w = weights[list];
  if (!(descending != 0 ? w < 0.0 : w > 0.0) || splatDepth > weights.a)
  {
    discard;
  }
  vec2 d = gl_FragCoord.xy - splatCenter;
  float beta = splatConic.x * d.x * d.x + splatConic.y * d.x * d.y + splatConic.z * d.y * d.y;
  bool inside = captureRules != 0 ? all(lessThanEqual(abs(d), splatHalfExtent)) : beta < cutoff;
  if (!inside)
  {
    discard;
  }
  float g = splatAmplitude * exp(-beta);
  if (captureRules != 0 && min(g, MaximumPeakOpacity) < CaptureMinimumAlpha)
  {
    discard;
  }
  // 1 - exp(-g) without the cancellation of small optical depths (expm1's series).
  float alpha = peakOpacity != 0 ? min(g, MaximumPeakOpacity)
                                 : (g < 1e-3 ? g * (1.0 - g * (0.5 - g / 6.0)) : 1.0 - exp(-g));
  gl_FragData[0] = vec4(alpha * splatColor, alpha);
}
