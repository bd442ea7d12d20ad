// SPDX-License-Identifier: BSD-3-Clause
// View-dependent colors from spherical harmonics of degree 0 to 3: SplatSphericalHarmonics.h,
// line by line (the 3D Gaussian Splatting convention, eval_sh of graphdeco-inria's
// utils/sh_utils.py). Substituted for //VTK::SplatSphericalHarmonics::Dec.

const int MaximumSphericalHarmonicsCoefficients = 16;

const float ShC0 = 0.28209479177387814;
const float ShC1 = 0.4886025119029199;
const float ShC2[5] = float[5](1.0925484305920792, -1.0925484305920792, 0.31539156525252005,
  -1.0925484305920792, 0.5462742152960396);
const float ShC3[7] = float[7](-0.5900435899266435, 2.890611442640554, -0.4570457994644658,
  0.3731763325901154, -0.4570457994644658, 1.445305721320277, -0.5900435899266435);

int sphericalHarmonicsCoefficients(int degree)
{
  return (degree + 1) * (degree + 1);
}

void sphericalHarmonicsBasis(vec3 d, int degree, out float basis[16])
{
  basis[0] = ShC0;
  if (degree < 1)
  {
    return;
  }
  float x = d.x, y = d.y, z = d.z;
  basis[1] = -ShC1 * y;
  basis[2] = ShC1 * z;
  basis[3] = -ShC1 * x;
  if (degree < 2)
  {
    return;
  }
  float xx = x * x, yy = y * y, zz = z * z;
  float xy = x * y, yz = y * z, xz = x * z;
  basis[4] = ShC2[0] * xy;
  basis[5] = ShC2[1] * yz;
  basis[6] = ShC2[2] * (2.0 * zz - xx - yy);
  basis[7] = ShC2[3] * xz;
  basis[8] = ShC2[4] * (xx - yy);
  if (degree < 3)
  {
    return;
  }
  basis[9] = ShC3[0] * y * (3.0 * xx - yy);
  basis[10] = ShC3[1] * xy * z;
  basis[11] = ShC3[2] * y * (4.0 * zz - xx - yy);
  basis[12] = ShC3[3] * z * (2.0 * zz - 3.0 * xx - 3.0 * yy);
  basis[13] = ShC3[4] * x * (4.0 * zz - xx - yy);
  basis[14] = ShC3[5] * z * (xx - yy);
  basis[15] = ShC3[6] * x * (xx - 3.0 * yy);
}

vec3 sphericalHarmonicsColor(vec3 coefficients[16], int degree, vec3 direction)
{
  float len = length(direction);
  vec3 d = len > 0.0 ? direction / len : vec3(0.0);
  float basis[MaximumSphericalHarmonicsCoefficients];
  sphericalHarmonicsBasis(d, degree, basis);
  vec3 color = vec3(0.5);
  for (int k = 0; k < sphericalHarmonicsCoefficients(degree); ++k)
  {
    color += basis[k] * coefficients[k];
  }
  return clamp(color, 0.0, 1.0);
}
