//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// Surface splats as instanced quads: one instance per surfel, four vertices (a triangle strip)
// covering the pixel box of the record that vtkSurfaceSplatSetupVS.glsl wrote for the splat
// this frame (the tight bounding box of its resampling kernel's cutoff ellipse, or of a
// differential point's rectangle); the record goes on to the fragment shader unchanged.

// The splat's record (instanced; vtkSurfaceSplatSetupVS.glsl says what each holds).
in vec4 recordBox;
in vec4 recordCenter;
in vec4 recordConic;
in vec4 recordPoint;
in vec4 recordNormal;
in vec4 recordAxis0;
in vec4 recordAxis1;
in vec4 recordColor;
in vec2 pointId; // the input point's id in two 24-bit halves; selection passes only

uniform vec2 viewportSize;

flat out vec2 splatCenter;
flat out vec3 splatConic; // 1/2 M^-1 as (xx, 2 xy, yy): beta = dx^2 xx + dx dy xy + dy^2 yy
flat out float splatAmplitude;
flat out vec3 splatPoint;   // eye space
flat out vec3 splatNormal;  // eye space, facing the viewer
flat out vec3 splatAxis0;   // eye space, for the approximate filter and differential points
flat out vec3 splatAxis1;
flat out vec2 splatExtent;    // differential points: the axes' lengths in model units
flat out vec2 splatCurvature; // and the curvatures, negated with a back-facing normal
flat out float splatThreshold;
flat out float splatCutoff;
flat out vec4 splatColor;
flat out vec2 splatPointId;

void main()
{
  vec2 lo = recordBox.xy;
  vec2 hi = recordBox.zw;
  if (!(lo.x <= hi.x))
  {
    // A culled splat (an empty box): outside the clip volume, the quad yields no fragment.
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }

  splatCenter = recordCenter.xy;
  splatCurvature = recordCenter.zw;
  splatConic = recordConic.xyz;
  splatAmplitude = recordConic.w;
  splatPoint = recordPoint.xyz;
  splatThreshold = recordPoint.w;
  splatNormal = recordNormal.xyz;
  splatCutoff = recordNormal.w;
  splatAxis0 = recordAxis0.xyz;
  splatAxis1 = recordAxis1.xyz;
  splatExtent = vec2(recordAxis0.w, recordAxis1.w);
  splatColor = recordColor;
  splatPointId = pointId;

  // The corner of this vertex, with half a pixel of margin around the box.
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
  vec2 pixel = 0.5 * (lo + hi) + corner * (0.5 * (hi - lo) + 0.5);
  gl_Position = vec4(pixel / viewportSize * 2.0 - 1.0, 0.0, 1.0);
}
