// SPDX-License-Identifier: BSD-3-Clause
// A generated 3D Gaussian Splatting capture for splat_bench: the kernel set that
// vtkGaussianSplatReader makes of a capture file (the arrays "Scale", "Rotation", "Opacity",
// "Color" and "SphericalHarmonics"), of Gaussians flattened onto a torus as an optimized capture's
// are onto its surfaces, with view-dependent colors of degree up to 3.
#ifndef SplatCaptureScene_h
#define SplatCaptureScene_h

#include "SplatVolumeScenes.h" // For ResetView, FitClippingRange

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <random>

namespace splatexample
{
/// The torus of the capture: major radius 0.7, minor 0.3, around z.
constexpr double CaptureMajorRadius = 0.7;
constexpr double CaptureMinorRadius = 0.3;

/// n Gaussians on the torus (the same for the same n, degree and seed): centers uniform in the
/// torus's angles (u around z, v around the tube), each flattened onto the surface (standard
/// deviations of 0.7 to 1.0 times the mean spacing along the surface and a tenth of it across,
/// rotated to the surface frame), peak opacities 0.5 to 0.99, base colors in stripes along u
/// and v, and spherical-harmonic coefficients of degree 1 to `degree` drawn from a normal
/// distribution of deviation 0.15 / l (a sheen that changes with the view, as in real captures).
/// "SphericalHarmonics" holds 3 (degree + 1)^2 components, coefficient-major with RGB
/// interleaved, the DC term first; "Color" is the degree-0 color 0.5 + C0 dc.
inline vtkSmartPointer<vtkPolyData> SyntheticCapture(
  vtkIdType n, int degree, unsigned seed = 20261123u)
{
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double area = 4.0 * vtkMath::Pi() * vtkMath::Pi() * CaptureMajorRadius *
    CaptureMinorRadius;
  const double spacing = std::sqrt(area / static_cast<double>(n));
  const int coefficients = (degree + 1) * (degree + 1);
  constexpr double C0 = 0.28209479177387814; // the degree-0 basis function

  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(n);
  const auto makeArray = [n](const char* name, int components)
  {
    vtkNew<vtkFloatArray> array;
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(n);
    return vtkSmartPointer<vtkFloatArray>(array);
  };
  auto scales = makeArray("Scale", 3);
  auto rotations = makeArray("Rotation", 4);
  auto opacities = makeArray("Opacity", 1);
  auto colors = makeArray("Color", 3);
  auto harmonics = makeArray("SphericalHarmonics", 3 * coefficients);
  for (vtkIdType i = 0; i < n; ++i)
  {
    // Uniform on the surface: v by rejection against the area element (R + r cos v).
    const double u = 2.0 * vtkMath::Pi() * uniform(random);
    double v;
    do
    {
      v = 2.0 * vtkMath::Pi() * uniform(random);
    } while (uniform(random) * (CaptureMajorRadius + CaptureMinorRadius) >
      CaptureMajorRadius + CaptureMinorRadius * std::cos(v));
    const double ring = CaptureMajorRadius + CaptureMinorRadius * std::cos(v);
    points->SetPoint(i, ring * std::cos(u), ring * std::sin(u), CaptureMinorRadius * std::sin(v));
    // The surface frame: tangents along u and v and the normal, as the columns of a rotation.
    const glm::dvec3 tu(-std::sin(u), std::cos(u), 0.0);
    const glm::dvec3 nrm(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
    const glm::dquat q = glm::quat_cast(glm::dmat3(tu, glm::cross(nrm, tu), nrm));
    rotations->SetTuple4(i, q.w, q.x, q.y, q.z);
    scales->SetTuple3(i, spacing * (0.7 + 0.3 * uniform(random)),
      spacing * (0.7 + 0.3 * uniform(random)), 0.1 * spacing);
    opacities->SetValue(i, static_cast<float>(0.5 + 0.49 * uniform(random)));
    const bool stripeU = std::fmod(u * 12.0 / vtkMath::Pi(), 2.0) < 1.0;
    const bool stripeV = std::fmod(v * 4.0 / vtkMath::Pi(), 2.0) < 1.0;
    const double rgb[3] = { stripeU ? 0.85 : 0.25, stripeV ? 0.7 : 0.3,
      stripeU == stripeV ? 0.2 : 0.8 };
    colors->SetTuple(i, rgb);
    for (int c = 0; c < 3; ++c)
    {
      harmonics->SetComponent(i, c, (rgb[c] - 0.5) / C0);
    }
    for (int k = 1; k < coefficients; ++k)
    {
      const double band = std::floor(std::sqrt(static_cast<double>(k))); // l of coefficient k
      for (int c = 0; c < 3; ++c)
      {
        harmonics->SetComponent(i, 3 * k + c, 0.15 / band * normal(random));
      }
    }
  }
  auto capture = vtkSmartPointer<vtkPolyData>::New();
  capture->SetPoints(points);
  for (vtkFloatArray* array : { scales, rotations, opacities, colors, harmonics })
  {
    capture->GetPointData()->AddArray(array);
  }
  return capture;
}

/// The capture seen from above and the side, framing the torus.
inline void PlaceCaptureCamera(vtkRenderer* renderer)
{
  const double reach = CaptureMajorRadius + CaptureMinorRadius;
  const double bounds[6] = { -reach, reach, -reach, reach, -CaptureMinorRadius,
    CaptureMinorRadius };
  ResetView(renderer, bounds);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(1.2, -3.0, 2.2);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 0.0, 1.0);
  FitClippingRange(renderer, bounds);
}
}

#endif
