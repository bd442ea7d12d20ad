// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of SplatSphericalHarmonics.h: the basis against values computed by hand from the
// 3DGS polynomials at the axes and the diagonal, orthonormality on the sphere (which the
// constants must give), the degree from the component count, and colors (0.5 offset, clamping,
// degenerate directions).
#include "SplatSphericalHarmonics.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

namespace
{
constexpr double Pi = 3.14159265358979323846;

// The basis up to degree 3 at d, the entries past (degree + 1)^2 left at a sentinel.
std::array<float, 16> Basis(const glm::vec3& d, int degree)
{
  std::array<float, 16> basis;
  basis.fill(-7.0f);
  splat::SphericalHarmonicsBasis(d, degree, basis.data());
  return basis;
}

void ExpectBasis(const glm::vec3& d, const std::array<double, 16>& expected)
{
  for (int degree = 0; degree <= 3; ++degree)
  {
    const std::array<float, 16> basis = Basis(d, degree);
    const int n = (degree + 1) * (degree + 1);
    for (int k = 0; k < 16; ++k)
    {
      EXPECT_NEAR(basis[k], k < n ? expected[k] : -7.0, 1e-6) << "degree " << degree << " k " << k;
    }
  }
}
}

TEST(SplatSphericalHarmonics, DegreeOfComponents)
{
  EXPECT_EQ(splat::SphericalHarmonicsDegreeOf(3), 0);
  EXPECT_EQ(splat::SphericalHarmonicsDegreeOf(12), 1);
  EXPECT_EQ(splat::SphericalHarmonicsDegreeOf(27), 2);
  EXPECT_EQ(splat::SphericalHarmonicsDegreeOf(48), 3);
  for (int components : { 0, 1, 4, 9, 16, 45, 75 })
  {
    EXPECT_EQ(splat::SphericalHarmonicsDegreeOf(components), -1) << components;
  }
}

// Values by hand from the polynomials of eval_sh with the normalizations written as roots:
// Y0 = 1 / (2 sqrt(pi)), Y1 = sqrt(3 / (4 pi)) (-y, z, -x), Y2 = sqrt(15 / (4 pi)) (xy, -yz,
// (2zz - xx - yy) / (2 sqrt 3), -xz, (xx - yy) / 2), Y3 = (-sqrt(35 / (32 pi)) y (3xx - yy),
// sqrt(105 / (4 pi)) xyz, -sqrt(21 / (32 pi)) y (4zz - xx - yy), sqrt(7 / (16 pi)) z (2zz -
// 3xx - 3yy), -sqrt(21 / (32 pi)) x (4zz - xx - yy), sqrt(105 / (16 pi)) z (xx - yy),
// -sqrt(35 / (32 pi)) x (xx - 3yy)).
TEST(SplatSphericalHarmonics, BasisAtAxes)
{
  const double y0 = 0.5 / std::sqrt(Pi);
  const double y1 = std::sqrt(3.0 / (4.0 * Pi));
  const double y2 = std::sqrt(15.0 / (4.0 * Pi));
  const double y3a = std::sqrt(35.0 / (32.0 * Pi));
  const double y3c = std::sqrt(21.0 / (32.0 * Pi));
  const double y3d = std::sqrt(7.0 / (16.0 * Pi));
  // +z: only the zonal functions.
  ExpectBasis(glm::vec3(0, 0, 1),
    { y0, 0, y1, 0, 0, 0, y2 / std::sqrt(3.0), 0, 0, 0, 0, 0, 2.0 * y3d, 0, 0, 0 });
  // +x.
  ExpectBasis(glm::vec3(1, 0, 0),
    { y0, 0, 0, -y1, 0, 0, -y2 / (2.0 * std::sqrt(3.0)), 0, y2 / 2.0, 0, 0, 0, 0, y3c, 0,
      -y3a });
  // -y.
  ExpectBasis(glm::vec3(0, -1, 0),
    { y0, y1, 0, 0, 0, 0, -y2 / (2.0 * std::sqrt(3.0)), 0, -y2 / 2.0, -y3a, 0, -y3c, 0, 0, 0,
      0 });
  // The diagonal (1, 1, 1) / sqrt 3: xx = xy = ... = 1/3.
  const double s = 1.0 / std::sqrt(3.0);
  const double y3b = std::sqrt(105.0 / (4.0 * Pi));
  ExpectBasis(glm::vec3(static_cast<float>(s)),
    { y0, -y1 * s, y1 * s, -y1 * s, y2 / 3.0, -y2 / 3.0, 0, -y2 / 3.0, 0,
      -y3a * s * 2.0 / 3.0, y3b * s / 3.0, -y3c * s * 2.0 / 3.0, y3d * s * (2.0 - 6.0) / 3.0,
      -y3c * s * 2.0 / 3.0, 0, -y3a * s * (1.0 - 3.0) / 3.0 });
}

// The 16 functions are orthonormal over the sphere: midpoint rule in (theta, phi), 400 x 800
// cells. Measured largest deviation from the identity 1.8e-5; a constant wrong by 0.1% moves
// its diagonal entry by 0.002. (The order and signs are BasisAtAxes' to check.)
TEST(SplatSphericalHarmonics, Orthonormal)
{
  const int nt = 400, np = 800;
  double gram[16][16] = {};
  for (int i = 0; i < nt; ++i)
  {
    const double theta = (i + 0.5) * Pi / nt;
    for (int j = 0; j < np; ++j)
    {
      const double phi = (j + 0.5) * 2.0 * Pi / np;
      const glm::vec3 d(static_cast<float>(std::sin(theta) * std::cos(phi)),
        static_cast<float>(std::sin(theta) * std::sin(phi)), static_cast<float>(std::cos(theta)));
      const std::array<float, 16> b = Basis(d, 3);
      const double area = std::sin(theta) * (Pi / nt) * (2.0 * Pi / np);
      for (int k = 0; k < 16; ++k)
        for (int l = 0; l < 16; ++l)
        {
          gram[k][l] += area * b[k] * b[l];
        }
    }
  }
  for (int k = 0; k < 16; ++k)
    for (int l = 0; l < 16; ++l)
    {
      EXPECT_NEAR(gram[k][l], k == l ? 1.0 : 0.0, 1e-4) << k << ", " << l;
    }
}

TEST(SplatSphericalHarmonics, Color)
{
  // Degree 1, RGB interleaved per coefficient: k0, k1, k2, k3.
  const float c[12] = { 0.3f, -0.2f, 0.1f, 0.8f, 0.0f, -0.4f, 0.0f, 0.8f, 0.3f, -0.4f, 0.3f,
    0.8f };
  const double y0 = 0.5 / std::sqrt(Pi), y1 = std::sqrt(3.0 / (4.0 * Pi));
  // Seen along -z (any length): 0.5 + y0 k0 - y1 k2.
  const glm::vec3 down = splat::SphericalHarmonicsColor(c, 1, glm::vec3(0, 0, -5));
  for (int ch = 0; ch < 3; ++ch)
  {
    EXPECT_NEAR(down[ch], 0.5 + y0 * c[ch] - y1 * c[6 + ch], 1e-6);
  }
  // Degree 0, a zero direction and a NaN direction: the view-independent 0.5 + y0 k0.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const glm::vec3 color : { splat::SphericalHarmonicsColor(c, 0, glm::vec3(0, 0, -1)),
         splat::SphericalHarmonicsColor(c, 1, glm::vec3(0.0f)),
         splat::SphericalHarmonicsColor(c, 1, glm::vec3(nan, 0, 1)) })
  {
    for (int ch = 0; ch < 3; ++ch)
    {
      EXPECT_NEAR(color[ch], 0.5 + y0 * c[ch], 1e-6);
    }
  }
  // Clamped to [0, 1].
  const float large[3] = { 10.0f, -10.0f, 0.0f };
  const glm::vec3 clamped = splat::SphericalHarmonicsColor(large, 0, glm::vec3(1, 0, 0));
  EXPECT_EQ(clamped.r, 1.0f);
  EXPECT_EQ(clamped.g, 0.0f);
  EXPECT_NEAR(clamped.b, 0.5f, 1e-7);
}
