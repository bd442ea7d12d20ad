//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// Per pixel, the lists it uses (vtkVolumeSplatRasterizer's step 1): the signed weight of each of
// the three axis lists, positive where the list is traversed ascending (the ray's component
// along the axis is positive), negative where descending, zero where the pixel does not use it;
// and the eye depth of the opaque scene, which stops the kernels behind it.

in vec2 texCoord;
// The pixel's ray direction in the lists' frame: listRays (x, y, 1).
uniform mat3 listRays;
uniform int orderingMode; // 0 blended, 1 clipped, 2 single axis, 3 depth sorted
uniform int centralList;  // single axis: the central ray's dominant list
uniform float blendThreshold;
uniform int sceneTest;
uniform sampler2D sceneDepth; // eye depths, infinite where there is no opaque geometry

//VTK::Output::Dec

int dominant(vec3 a)
{
  return a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
}

void main()
{
  vec3 d = listRays * vec3(gl_FragCoord.xy, 1.0);
  vec3 a = abs(d);
  float largest = max(a.x, max(a.y, a.z));
  int major = dominant(a);
  vec3 weights = vec3(1.0, 0.0, 0.0); // depth sorted: one list, "ascending"
  if (orderingMode != 3)
  {
    for (int list = 0; list < 3; ++list)
    {
      float w = 0.0;
      if (orderingMode == 0)
      {
        w = max((a[list] / largest - blendThreshold) / (1.0 - blendThreshold), 0.0);
      }
      else
      {
        w = list == (orderingMode == 1 ? major : centralList) ? 1.0 : 0.0;
      }
      weights[list] = d[list] > 0.0 ? w : (d[list] < 0.0 ? -w : 0.0);
    }
  }
  float depth = sceneTest != 0 ? texture(sceneDepth, texCoord).r : 3.0e38;
  gl_FragData[0] = vec4(weights, depth);
}
