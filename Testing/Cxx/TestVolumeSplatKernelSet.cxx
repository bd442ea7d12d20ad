// SPDX-License-Identifier: BSD-3-Clause
// Kernel-set input of vtkVolumeSplatMapper:
// - a handful of anisotropic Gaussians given as covariances and as scale + quaternion render
//   identically, through the transfer functions (density model) and with direct color and
//   opacity arrays (the 3D Gaussian Splatting convention);
// - invalid kernels (NaN or Inf anywhere, zero quaternion, indefinite covariance) are skipped
//   and counted; degenerate ones (zero scales, eigenvalue ratio 1e12) and kernels behind the
//   eye render without a NaN pixel.
#include "SplatVolumeKernel.h"
#include "SplatVolumeTestUtilities.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkDoubleArray.h"

#include <cstdio>
#include <limits>

namespace
{
int failures = 0;
void Check(bool ok, const char* what)
{
  if (!ok)
  {
    std::fprintf(stderr, "FAILED: %s\n", what);
    ++failures;
  }
}

// Seven kernels: positions, standard deviations and quaternions (w, x, y, z).
const double Positions[7][3] = { { 0, 0, 0 }, { 0.5, 0.2, -0.1 }, { -0.4, 0.3, 0.2 },
  { 0.1, -0.5, 0.3 }, { -0.3, -0.3, -0.4 }, { 0.4, 0.5, 0.4 }, { -0.5, 0.1, -0.3 } };
const double Scales[7][3] = { { 0.2, 0.05, 0.1 }, { 0.02, 0.15, 0.06 }, { 0.1, 0.1, 0.3 },
  { 0.25, 0.03, 0.03 }, { 0.08, 0.12, 0.05 }, { 0.06, 0.06, 0.06 }, { 0.15, 0.02, 0.2 } };
const double Rotations[7][4] = { { 1, 0, 0, 0 }, { 0.9, 0.3, 0.1, 0 }, { 0.5, 0.5, 0.5, 0.5 },
  { 0.7, 0, 0.7, 0.1 }, { 0.2, 0.9, -0.3, 0.1 }, { 1, 1, 0, 0 }, { 0.3, -0.2, 0.8, 0.4 } };

vtkSmartPointer<vtkPolyData> Kernels(bool asCovariance)
{
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> covariance, scale, rotation, scalars, color, opacity;
  covariance->SetName("Covariance");
  covariance->SetNumberOfComponents(6);
  scale->SetName("Scale");
  scale->SetNumberOfComponents(3);
  rotation->SetName("Rotation");
  rotation->SetNumberOfComponents(4);
  scalars->SetName("Scalar");
  color->SetName("Color");
  color->SetNumberOfComponents(3);
  opacity->SetName("Opacity");
  for (int i = 0; i < 7; ++i)
  {
    points->InsertNextPoint(Positions[i]);
    const glm::dmat3 V = splat::CovarianceFromScaleRotation(
      glm::dvec3(Scales[i][0], Scales[i][1], Scales[i][2]),
      glm::dvec4(Rotations[i][0], Rotations[i][1], Rotations[i][2], Rotations[i][3]));
    covariance->InsertNextTuple6(V[0][0], V[1][0], V[2][0], V[1][1], V[2][1], V[2][2]);
    scale->InsertNextTuple(Scales[i]);
    rotation->InsertNextTuple(Rotations[i]);
    scalars->InsertNextValue(static_cast<float>(i + 1));
    color->InsertNextTuple3(0.2 + 0.1 * i, 0.9 - 0.1 * i, 0.5);
    opacity->InsertNextValue(0.3f + 0.1f * i);
  }
  data->SetPoints(points);
  data->GetPointData()->SetScalars(scalars);
  data->GetPointData()->AddArray(asCovariance ? covariance.Get() : scale.Get());
  if (!asCovariance)
  {
    data->GetPointData()->AddArray(rotation);
  }
  data->GetPointData()->AddArray(color);
  data->GetPointData()->AddArray(opacity);
  return data;
}

std::vector<double> Render(vtkPolyData* data, bool direct, vtkVolumeSplatMapper* mapper)
{
  if (!direct)
  {
    mapper->SetColorArrayName(nullptr);
    mapper->SetOpacityArrayName(nullptr);
  }
  mapper->SetInputData(data);
  const double rgb[3] = { 0.9, 0.6, 0.3 };
  auto property = splattest::ExtinctionProperty(8.0, 1.0, rgb);
  vtkNew<vtkRenderer> renderer;
  splattest::AddVolume(renderer, mapper, property);
  auto window = splattest::MakeRenderWindow(200, 200);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(1.5, 1.0, 2.5);
  camera->SetFocalPoint(0, 0, 0);
  renderer->ResetCameraClippingRange();
  window->Render();
  return splattest::ToRGB(splattest::Capture(window));
}
}

int main(int, char*[])
{
  for (bool direct : { false, true })
  {
    vtkNew<vtkVolumeSplatMapper> a, b;
    const std::vector<double> fromCovariance = Render(Kernels(true), direct, a);
    const std::vector<double> fromScale = Render(Kernels(false), direct, b);
    double largest = 0.0, brightest = 0.0;
    for (std::size_t i = 0; i < fromCovariance.size(); ++i)
    {
      largest = std::max(largest, std::abs(fromCovariance[i] - fromScale[i]));
      brightest = std::max(brightest, fromCovariance[i]);
    }
    std::printf("%s: covariance vs scale + rotation, largest difference %.4f (brightest %.3f), "
                "%lld kernels\n",
      direct ? "color and opacity arrays" : "transfer functions", largest, brightest,
      static_cast<long long>(a->GetNumberOfKernels()));
    Check(a->GetNumberOfKernels() == 7 && b->GetNumberOfKernels() == 7, "seven kernels");
    Check(brightest > 0.2, "the kernels are visible");
    // Identical up to one 8-bit step: the two float covariances differ in their last bits, which
    // may move a pixel across a rounding boundary.
    Check(largest <= 1.5 / 255.0, "covariance and scale + rotation render identically");
  }

  // Invalid and degenerate kernels.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  vtkNew<vtkPolyData> bad;
  vtkNew<vtkPoints> points;
  splattest::KernelSetArrays<vtkDoubleArray> arrays;
  auto add = [&](double x, double y, double z, double s0, double s1, double s2, double qw,
               double qx, double o)
  {
    points->InsertNextPoint(x, y, z);
    arrays.Scale->InsertNextTuple3(s0, s1, s2);
    arrays.Rotation->InsertNextTuple4(qw, qx, 0.0, 0.0);
    arrays.Opacity->InsertNextValue(o);
    arrays.Color->InsertNextTuple3(1.0, 0.5, 0.2);
  };
  add(nan, 0, 0, 0.1, 0.1, 0.1, 1, 0, 0.5);        // invalid: position
  add(0, inf, 0, 0.1, 0.1, 0.1, 1, 0, 0.5);        // invalid: position
  add(0, 0, 0, nan, 0.1, 0.1, 1, 0, 0.5);          // invalid: scale
  add(0, 0, 0, 0.1, 0.1, 0.1, 0, 0, 0.5);          // invalid: zero quaternion
  add(0, 0, 0, 0.1, 0.1, 0.1, nan, 0, 0.5);        // invalid: quaternion
  add(0, 0, 0, 0.1, 0.1, 0.1, 1, 0, nan);          // invalid: opacity
  add(0.2, 0, 0, 0.0, 0.0, 0.0, 1, 0, 0.8);        // degenerate: zero scales
  add(-0.2, 0, 0, 1e-6, 1.0, 1e-6, 0.9, 0.4, 0.8); // degenerate: variance ratio 1e12
  add(0, 0.2, 0, 0.1, 0.1, 0.1, 1, 0, 0.0);        // transparent
  add(0, 0, 20.0, 0.1, 0.1, 0.1, 1, 0, 0.8);       // behind the eye
  add(0, 0, 4.9, 0.3, 0.3, 0.3, 1, 0, 0.8);        // crossing the near plane
  add(0, -0.2, 0, 0.1, 0.2, 0.1, 1, 0, 0.8);       // valid
  bad->SetPoints(points);
  arrays.AddTo(bad);
  vtkNew<vtkVolumeSplatMapper> mapper;
  mapper->SetInputData(bad);
  vtkNew<vtkRenderer> renderer;
  splattest::AddVolume(renderer, mapper, nullptr);
  auto window = splattest::MakeRenderWindow(200, 200);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 0, 5);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetClippingRange(0.2, 50.0);
  window->Render();
  std::printf("invalid %lld, transparent %lld, kept %lld, near plane %lld, outside %lld\n",
    static_cast<long long>(mapper->GetNumberOfInvalidKernels()),
    static_cast<long long>(mapper->GetNumberOfTransparentKernels()),
    static_cast<long long>(mapper->GetNumberOfKernels()),
    static_cast<long long>(mapper->GetNumberOfNearPlaneKernels()),
    static_cast<long long>(mapper->GetNumberOfFrustumCulledKernels()));
  Check(mapper->GetNumberOfInvalidKernels() == 6, "six invalid kernels counted");
  Check(mapper->GetNumberOfTransparentKernels() == 1, "one transparent kernel left out");
  Check(mapper->GetNumberOfKernels() == 5, "five kernels in the lists");
  Check(mapper->GetNumberOfNearPlaneKernels() == 2, "behind the eye and crossing the near plane");
  const double* bounds = mapper->GetBounds();
  Check(std::isfinite(bounds[0]) && std::isfinite(bounds[5]), "finite bounds");
  for (double v : splattest::ToRGB(splattest::Capture(window)))
  {
    if (!std::isfinite(v))
    {
      Check(false, "no NaN pixel");
      break;
    }
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
