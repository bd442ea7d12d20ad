//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
// The list buffers merged per pixel with the squared weights (paper 003, eq. 1):
// C = sum C_a w_a^2 / sum w_a^2 over the lists the frame traversed, clamped and premultiplied
// (a color channel never exceeds alpha), as vtkVolumeSplatRasterizer's step 4 ends.

in vec2 texCoord;
uniform sampler2D pixelWeights;
uniform sampler2D list0;
uniform sampler2D list1;
uniform sampler2D list2;
uniform vec3 traversed; // 1 for the lists drawn this frame, 0 for the others

//VTK::Output::Dec

void main()
{
  vec3 w = texture(pixelWeights, texCoord).xyz * traversed;
  vec3 w2 = w * w;
  float sum = w2.x + w2.y + w2.z;
  vec4 color = vec4(0.0);
  if (w2.x > 0.0)
  {
    color += w2.x * texture(list0, texCoord);
  }
  if (w2.y > 0.0)
  {
    color += w2.y * texture(list1, texCoord);
  }
  if (w2.z > 0.0)
  {
    color += w2.z * texture(list2, texCoord);
  }
  color = clamp(sum > 0.0 ? color / sum : vec4(0.0), 0.0, 1.0);
  gl_FragData[0] = vec4(min(color.rgb, vec3(color.a)), color.a);
}
