// SPDX-License-Identifier: BSD-3-Clause
/**
 * The image a 3D Gaussian Splatting capture was optimized to produce: the forward pass of the
 * published rasterizer (Kerbl et al. 2023, graphdeco-inria diff-gaussian-rasterization,
 * cuda_rasterizer/forward.cu) written again for clarity, single-threaded and in double
 * precision, sharing no code with the mapper (its own quaternions, covariances, projection and
 * spherical harmonics). The tests measure vtkVolumeSplatMapper against it.
 *
 * The rules (forward.cu), with the two choices the mapper documents:
 * - the view: x right, y down, z forward (COLMAP); a world point p is at R p + t;
 *   fx = W / (2 tan(fovx / 2)), fy likewise, the principal point at the image's center; pixel
 *   (u, v), v counted from the top row, has its center at the integer coordinates (u, v), so a
 *   view point (x, y, z) lands at (fx x / z + W / 2 - 0.5, fy y / z + H / 2 - 0.5);
 * - Gaussians whose center is less than `Near` in front of the eye are left out (the reference
 *   hard-codes 0.2; the mapper takes the camera's near clipping distance);
 * - the 2D covariance J W Sigma W^T J^T + 0.3 I, with x/z and y/z clamped to 1.3 tan(fov / 2)
 *   in J; the conic its inverse; the radius ceil(3 sqrt(lambda_max)), lambda_max at least
 *   mid + sqrt(0.1);
 * - a pixel takes a Gaussian when it lies within the radius of the center along both axes
 *   (the reference's rectangle, per pixel rather than per 16 x 16 tile), with
 *   alpha = min(0.99, opacity exp(power)), power = -1/2 d^T conic d <= 0, alpha >= 1/255;
 * - the Gaussians front to back by view z (ties in input order); a pixel stops before the
 *   Gaussian that would take its transmittance below 1e-4;
 * - colors from the spherical harmonics (the reference's basis, signs and constants) for the
 *   direction from the camera's position to the center, plus 0.5, clamped to [0, 1] (the
 *   reference clamps below only; the mapper clamps both ways);
 * - the background black.
 *
 * From a VTK camera (RenderReference): the view is diag(1, -1, -1) times VTK's eye coordinates
 * (x right, y up, z backwards); VTK's view angle is the vertical field of view, the horizontal
 * one follows from the aspect ratio; VTK's rows count from the bottom, so reference row v is
 * VTK row H - 1 - v. The image returned is in VTK's order (RGB, rows from the bottom), as the
 * render window's.
 */
#ifndef SplatCaptureReference_h
#define SplatCaptureReference_h

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkGaussianSplatReader.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkSmartPointer.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <numeric>
#include <vector>

namespace splattest
{
/// The reference rasterizer's camera (see the file comment).
struct ReferenceCamera
{
  double R[3][3] = {}; ///< world to view, rows
  double T[3] = {};
  double Position[3] = {}; ///< the camera's center in world coordinates
  double TanFovX = 1.0, TanFovY = 1.0;
  double Near = 0.2;
  int Width = 0, Height = 0;
};

/// The reference camera of a VTK camera rendering a width x height image.
inline ReferenceCamera ReferenceCameraOf(vtkCamera* camera, int width, int height)
{
  ReferenceCamera c;
  vtkMatrix4x4* m = camera->GetModelViewTransformMatrix();
  const double flip[3] = { 1.0, -1.0, -1.0 };
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      c.R[i][j] = flip[i] * m->GetElement(i, j);
    }
    c.T[i] = flip[i] * m->GetElement(i, 3);
  }
  camera->GetPosition(c.Position);
  c.TanFovY = std::tan(0.5 * camera->GetViewAngle() * 3.14159265358979323846 / 180.0);
  c.TanFovX = c.TanFovY * width / height;
  c.Near = camera->GetClippingRange()[0];
  c.Width = width;
  c.Height = height;
  return c;
}

/// The reference's spherical-harmonics color (forward.cu, computeColorFromSH) of the
/// coefficients sh (degree d, (d + 1)^2 RGB triples) for the unit direction (x, y, z).
inline void ReferenceColor(const double* sh, int degree, double x, double y, double z,
  double rgb[3])
{
  const double C0 = 0.28209479177387814;
  const double C1 = 0.4886025119029199;
  const double C2[5] = { 1.0925484305920792, -1.0925484305920792, 0.31539156525252005,
    -1.0925484305920792, 0.5462742152960396 };
  const double C3[7] = { -0.5900435899266435, 2.890611442640554, -0.4570457994644658,
    0.3731763325901154, -0.4570457994644658, 1.445305721320277, -0.5900435899266435 };
  std::vector<double> basis = { C0 };
  if (degree > 0)
  {
    basis.insert(basis.end(), { -C1 * y, C1 * z, -C1 * x });
  }
  const double xx = x * x, yy = y * y, zz = z * z;
  if (degree > 1)
  {
    basis.insert(basis.end(), { C2[0] * x * y, C2[1] * y * z, C2[2] * (2.0 * zz - xx - yy),
                                C2[3] * x * z, C2[4] * (xx - yy) });
  }
  if (degree > 2)
  {
    basis.insert(basis.end(),
      { C3[0] * y * (3.0 * xx - yy), C3[1] * x * y * z, C3[2] * y * (4.0 * zz - xx - yy),
        C3[3] * z * (2.0 * zz - 3.0 * xx - 3.0 * yy), C3[4] * x * (4.0 * zz - xx - yy),
        C3[5] * z * (xx - yy), C3[6] * x * (xx - 3.0 * yy) });
  }
  for (int c = 0; c < 3; ++c)
  {
    double sum = 0.5;
    for (std::size_t k = 0; k < basis.size(); ++k)
    {
      sum += basis[k] * sh[3 * k + c];
    }
    rgb[c] = std::min(std::max(sum, 0.0), 1.0);
  }
}

/**
 * The reference image of `capture` (arrays Scale, Rotation (w, x, y, z), Opacity, and
 * SphericalHarmonics of `degree` or else Color) seen by `camera`: RGB in [0, 1], rows from the
 * bottom. `dilation` is the variance added to the 2D covariances (0.3 in the reference); with
 * `compensate`, each opacity is scaled by sqrt(|cov| / |cov + dilation I|) (gsplat's
 * antialiased mode).
 */
inline std::vector<double> RenderReference(vtkPointSet* capture, const ReferenceCamera& cam,
  int degree, double dilation = 0.3, bool compensate = false)
{
  vtkPointData* pd = capture->GetPointData();
  vtkDataArray* scales = pd->GetArray("Scale");
  vtkDataArray* rotations = pd->GetArray("Rotation");
  vtkDataArray* opacities = pd->GetArray("Opacity");
  vtkDataArray* harmonics = pd->GetArray("SphericalHarmonics");
  vtkDataArray* colors = pd->GetArray("Color");
  const int W = cam.Width, H = cam.Height;
  const double fx = W / (2.0 * cam.TanFovX);
  const double fy = H / (2.0 * cam.TanFovY);

  struct Projected
  {
    double U, V, A, B, C, Opacity, Depth, Radius, Rgb[3];
  };
  std::vector<Projected> gaussians;
  const vtkIdType n = capture->GetNumberOfPoints();
  std::vector<double> sh(harmonics ? harmonics->GetNumberOfComponents() : 3);
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    capture->GetPoint(i, p);
    double t[3];
    for (int r = 0; r < 3; ++r)
    {
      t[r] = cam.R[r][0] * p[0] + cam.R[r][1] * p[1] + cam.R[r][2] * p[2] + cam.T[r];
    }
    if (t[2] < cam.Near)
    {
      continue;
    }
    // Sigma = Q diag(s^2) Q^T, Q the rotation of the normalized quaternion.
    double s[3], q[4];
    scales->GetTuple(i, s);
    rotations->GetTuple(i, q);
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double w = q[0] / norm, x = q[1] / norm, y = q[2] / norm, z = q[3] / norm;
    const double Q[3][3] = { { 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y) },
      { 2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x) },
      { 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y) } };
    double sigma[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        sigma[r][c] = 0.0;
        for (int k = 0; k < 3; ++k)
        {
          sigma[r][c] += Q[r][k] * s[k] * s[k] * Q[c][k];
        }
      }
    }
    // J (2 x 3) at the clamped center, then M = J R and the 2D covariance M Sigma M^T.
    const double limX = 1.3 * cam.TanFovX, limY = 1.3 * cam.TanFovY;
    const double tx = std::min(limX, std::max(-limX, t[0] / t[2])) * t[2];
    const double ty = std::min(limY, std::max(-limY, t[1] / t[2])) * t[2];
    const double J[2][3] = { { fx / t[2], 0.0, -fx * tx / (t[2] * t[2]) },
      { 0.0, fy / t[2], -fy * ty / (t[2] * t[2]) } };
    double M[2][3];
    for (int r = 0; r < 2; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        M[r][c] = J[r][0] * cam.R[0][c] + J[r][1] * cam.R[1][c] + J[r][2] * cam.R[2][c];
      }
    }
    double cov[2][2];
    for (int r = 0; r < 2; ++r)
    {
      for (int c = 0; c < 2; ++c)
      {
        cov[r][c] = 0.0;
        for (int k = 0; k < 3; ++k)
        {
          for (int l = 0; l < 3; ++l)
          {
            cov[r][c] += M[r][k] * sigma[k][l] * M[c][l];
          }
        }
      }
    }
    const double unfiltered = cov[0][0] * cov[1][1] - cov[0][1] * cov[0][1];
    cov[0][0] += dilation;
    cov[1][1] += dilation;
    const double det = cov[0][0] * cov[1][1] - cov[0][1] * cov[0][1];
    if (det == 0.0)
    {
      continue;
    }
    Projected g;
    g.A = cov[1][1] / det;
    g.B = -cov[0][1] / det;
    g.C = cov[0][0] / det;
    const double mid = 0.5 * (cov[0][0] + cov[1][1]);
    g.Radius = std::ceil(3.0 * std::sqrt(mid + std::sqrt(std::max(0.1, mid * mid - det))));
    g.U = fx * t[0] / t[2] + 0.5 * W - 0.5;
    g.V = fy * t[1] / t[2] + 0.5 * H - 0.5;
    g.Opacity = opacities->GetComponent(i, 0) *
      (compensate ? std::sqrt(std::max(unfiltered, 0.0) / det) : 1.0);
    g.Depth = t[2];
    if (harmonics)
    {
      harmonics->GetTuple(i, sh.data());
      double d[3] = { p[0] - cam.Position[0], p[1] - cam.Position[1], p[2] - cam.Position[2] };
      const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      ReferenceColor(sh.data(), degree, d[0] / length, d[1] / length, d[2] / length, g.Rgb);
    }
    else
    {
      colors->GetTuple(i, g.Rgb);
    }
    gaussians.push_back(g);
  }
  std::stable_sort(gaussians.begin(), gaussians.end(),
    [](const Projected& a, const Projected& b) { return a.Depth < b.Depth; });

  // Front to back, each Gaussian over the pixels of its rectangle.
  std::vector<double> transmittance(static_cast<std::size_t>(W) * H, 1.0);
  std::vector<bool> done(transmittance.size(), false);
  std::vector<double> rgb(3 * transmittance.size(), 0.0);
  for (const Projected& g : gaussians)
  {
    const int u0 = std::max(0, static_cast<int>(std::ceil(g.U - g.Radius)));
    const int u1 = std::min(W - 1, static_cast<int>(std::floor(g.U + g.Radius)));
    const int v0 = std::max(0, static_cast<int>(std::ceil(g.V - g.Radius)));
    const int v1 = std::min(H - 1, static_cast<int>(std::floor(g.V + g.Radius)));
    for (int v = v0; v <= v1; ++v)
    {
      for (int u = u0; u <= u1; ++u)
      {
        const std::size_t pixel = static_cast<std::size_t>(H - 1 - v) * W + u; // VTK's row
        if (done[pixel])
        {
          continue;
        }
        const double dx = g.U - u, dy = g.V - v;
        const double power = -0.5 * (g.A * dx * dx + g.C * dy * dy) - g.B * dx * dy;
        if (power > 0.0)
        {
          continue;
        }
        const double alpha = std::min(0.99, g.Opacity * std::exp(power));
        if (alpha < 1.0 / 255.0)
        {
          continue;
        }
        const double next = transmittance[pixel] * (1.0 - alpha);
        if (next < 1e-4)
        {
          done[pixel] = true;
          continue;
        }
        for (int c = 0; c < 3; ++c)
        {
          rgb[3 * pixel + c] += g.Rgb[c] * alpha * transmittance[pixel];
        }
        transmittance[pixel] = next;
      }
    }
  }
  for (double& value : rgb)
  {
    value = std::min(value, 1.0);
  }
  return rgb;
}

/// A camera looking at a capture.
struct CaptureView
{
  std::string Name;
  std::array<double, 3> Position, FocalPoint, Up;
};

/// Views of a capture centered at c with a typical radius r: around it, close, and from inside.
inline std::vector<CaptureView> CaptureViews(const std::array<double, 3>& c, double r)
{
  auto at = [&c](double x, double y, double z)
  { return std::array<double, 3>{ c[0] + x, c[1] + y, c[2] + z }; };
  return { { "front", at(0.4 * r, -3.0 * r, 1.5 * r), c, { 0, 0, 1 } },
    { "side", at(3.2 * r, 0.6 * r, -0.4 * r), c, { 0, 1, 0 } },
    { "close", at(-1.2 * r, 0.5 * r, 0.9 * r), at(-0.3 * r, 0.1 * r, 0.0), { 0, 0, 1 } },
    { "inside", at(0.05 * r, 0.02 * r, 0.0), at(r, 0.3 * r, 0.1 * r), { 0, 0, 1 } },
    { "inside-back", at(-0.1 * r, 0.0, 0.05 * r), at(-r, -0.5 * r, -0.2 * r), { 0, 1, 0 } } };
}

/// The capture's robust center and radius: the median position, the median distance from it
/// (real captures carry far floaters that the bounds would frame).
inline void RobustFrame(vtkPointSet* data, std::array<double, 3>& center, double& radius)
{
  const vtkIdType n = data->GetNumberOfPoints();
  std::vector<double> values(n);
  for (int axis = 0; axis < 3; ++axis)
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      values[i] = data->GetPoint(i)[axis];
    }
    std::nth_element(values.begin(), values.begin() + n / 2, values.end());
    center[axis] = values[n / 2];
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double* p = data->GetPoint(i);
    values[i] = std::sqrt((p[0] - center[0]) * (p[0] - center[0]) +
      (p[1] - center[1]) * (p[1] - center[1]) + (p[2] - center[2]) * (p[2] - center[2]));
  }
  std::nth_element(values.begin(), values.begin() + n / 2, values.end());
  radius = values[n / 2];
}

/// A capture with the views the tests and the report draw it from.
struct CaptureScene
{
  std::string Name;
  vtkSmartPointer<vtkPointSet> Data;
  int Degree;
  std::vector<CaptureView> Views;
};

/// The capture file at `path` (vtkGaussianSplatReader), viewed around its robust frame.
inline CaptureScene ReadCapture(const std::string& path)
{
  vtkNew<vtkGaussianSplatReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  CaptureScene capture{ vtksys::SystemTools::GetFilenameName(path), reader->GetOutput(),
    reader->GetSphericalHarmonicsDegree(), {} };
  std::array<double, 3> center;
  double radius;
  RobustFrame(capture.Data, center, radius);
  capture.Views = CaptureViews(center, radius);
  return capture;
}

/// Peak signal-to-noise ratio of two RGB images in [0, 1], in dB.
inline double PSNR(const std::vector<double>& a, const std::vector<double>& b)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    sum += (a[i] - b[i]) * (a[i] - b[i]);
  }
  const double mse = sum / static_cast<double>(a.size());
  return mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : 200.0;
}
}

#endif
