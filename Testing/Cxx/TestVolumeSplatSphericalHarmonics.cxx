// SPDX-License-Identifier: BSD-3-Clause
// View-dependent colors of vtkVolumeSplatMapper from spherical harmonics (the 3D Gaussian
// Splatting convention), on both backends:
// - one kernel with degree-1 coefficients seen from several camera positions, also through a
//   rotated vtkVolume: the center pixel is the color computed by hand for the view direction in
//   the data's coordinates, times the kernel's peak opacity (0.99) over the black background;
//   the views' colors differ, so a view-independent color fails;
// - a kernel off the view axis: colored for its own direction in a perspective projection, for
//   the view axis in a parallel one;
// - MaximumSphericalHarmonicsDegree 0: the view-independent color 0.5 + Y0 k0 from every view;
// - Shade on: the harmonic color lit like any other, (ambient + diffuse) times it;
// - a moved camera and a changed degree recolor the kernels without rebuilding the lists;
// - random kernels of degree 3: CPU and OpenGL agree within MAX_BACKEND_RMSE, and the image
//   differs from the degree-2 one by far more than that;
// - non-finite or out-of-range coefficients are skipped and counted; an array whose component
//   count is no degree is an error, and the color array colors the kernels, as it does when the
//   array name is unset.
// The bounds come from CMake (CMakeLists.txt) with the figures measured.
#include "SplatVolumeTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkMatrix4x4.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

namespace
{
constexpr int Size = 65; // odd: the center pixel is centered on the view axis
constexpr double Pi = 3.14159265358979323846;
const int Backends[2] = { vtkSplatBackend::CPU, vtkSplatBackend::OPENGL };
int failures = 0;

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::fprintf(stderr, "FAILED: %s\n", what.c_str());
    ++failures;
  }
}

std::string Name(int backend)
{
  return vtkSplatBackend::GetBackendAsString(backend);
}

// Degree-1 coefficients k0 .. k3, RGB each.
const double K[4][3] = { { 0.3, -0.2, 0.1 }, { 0.8, 0.0, -0.4 }, { 0.0, 0.8, 0.3 },
  { -0.4, 0.3, 0.8 } };

// The color by hand for the unit model direction d (eye to kernel), eval_sh of degree 0 or 1:
// 0.5 + Y0 k0 - Y1 y k1 + Y1 z k2 - Y1 x k3, clamped to [0, 1].
glm::dvec3 HandColor(const glm::dvec3& d, int degree)
{
  const double y0 = 0.5 / std::sqrt(Pi);
  const double y1 = degree > 0 ? std::sqrt(3.0 / (4.0 * Pi)) : 0.0;
  glm::dvec3 rgb;
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = 0.5 + y0 * K[0][c] - y1 * d.y * K[1][c] + y1 * d.z * K[2][c] - y1 * d.x * K[3][c];
  }
  return glm::clamp(rgb, 0.0, 1.0);
}

// Kernels with a Scale, Rotation, Opacity (1: peak 0.99) and a blue Color array, and
// `components` spherical-harmonic coefficients per kernel from `coefficients`.
vtkSmartPointer<vtkPolyData> Kernels(const std::vector<glm::dvec3>& positions, double scale,
  int components, const std::vector<double>& coefficients)
{
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> scales, rotations, opacities, colors, harmonics;
  scales->SetName("Scale");
  scales->SetNumberOfComponents(3);
  rotations->SetName("Rotation");
  rotations->SetNumberOfComponents(4);
  opacities->SetName("Opacity");
  colors->SetName("Color");
  colors->SetNumberOfComponents(3);
  harmonics->SetName("SphericalHarmonics");
  harmonics->SetNumberOfComponents(components);
  for (std::size_t i = 0; i < positions.size(); ++i)
  {
    points->InsertNextPoint(positions[i].x, positions[i].y, positions[i].z);
    scales->InsertNextTuple3(scale, scale, scale);
    rotations->InsertNextTuple4(1.0, 0.0, 0.0, 0.0);
    opacities->InsertNextTuple1(1.0);
    colors->InsertNextTuple3(0.0, 0.0, 1.0);
    harmonics->InsertNextTuple(coefficients.data() + components * i);
  }
  data->SetPoints(points);
  for (vtkDataArray* array :
    { scales.Get(), rotations.Get(), opacities.Get(), colors.Get(), harmonics.Get() })
  {
    data->GetPointData()->AddArray(array);
  }
  return data;
}

// One kernel of standard deviation 0.3 at the origin with the degree-1 coefficients K.
vtkSmartPointer<vtkPolyData> OneKernel()
{
  std::vector<double> coefficients(&K[0][0], &K[0][0] + 12);
  return Kernels({ glm::dvec3(0.0) }, 0.3, 12, coefficients);
}

struct Scene
{
  vtkNew<vtkVolumeSplatMapper> Mapper;
  vtkNew<vtkRenderer> Renderer;
  vtkSmartPointer<vtkRenderWindow> Window = splattest::MakeRenderWindow(Size, Size);
  vtkVolume* Volume;

  Scene(vtkDataSet* input, int backend, vtkVolumeProperty* property = nullptr)
  {
    this->Mapper->SetInputData(input);
    this->Mapper->SetBackend(backend);
    this->Volume = splattest::AddVolume(this->Renderer, this->Mapper, property);
    this->Window->AddRenderer(this->Renderer);
  }

  // The image from `eye` towards the origin, RGB in [0, 1].
  std::vector<double> View(const glm::dvec3& eye)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetPosition(eye.x, eye.y, eye.z);
    const bool vertical = std::abs(eye.y) > std::abs(eye.x) + std::abs(eye.z);
    camera->SetViewUp(vertical ? 1.0 : 0.0, vertical ? 0.0 : 1.0, 0.0);
    this->Renderer->ResetCameraClippingRange();
    this->Window->Render();
    return splattest::ToRGB(splattest::Capture(this->Window));
  }

  // The unit direction from the eye to the origin in the data's coordinates.
  glm::dvec3 ModelDirection(const glm::dvec3& eye)
  {
    vtkNew<vtkMatrix4x4> worldToModel;
    vtkMatrix4x4::Invert(this->Volume->GetMatrix(), worldToModel);
    double p[4] = { eye.x, eye.y, eye.z, 1.0 }, o[4] = { 0.0, 0.0, 0.0, 1.0 };
    worldToModel->MultiplyPoint(p, p);
    worldToModel->MultiplyPoint(o, o);
    return glm::normalize(glm::dvec3(o[0] - p[0], o[1] - p[1], o[2] - p[2]));
  }
};

glm::dvec3 CenterPixel(const std::vector<double>& image, int x = Size / 2)
{
  const std::size_t p = 3 * (static_cast<std::size_t>(Size / 2) * Size + x);
  return glm::dvec3(image[p], image[p + 1], image[p + 2]);
}

// Checks the pixel in column x of the center row against `expected` times the peak opacity;
// returns the difference.
double CheckCenter(const std::vector<double>& image, const glm::dvec3& expected,
  const std::string& what, int x = Size / 2)
{
  const glm::dvec3 center = CenterPixel(image, x);
  const glm::dvec3 wanted = 0.99 * expected;
  const double difference = glm::length(center - wanted) / std::sqrt(3.0);
  std::printf("%-44s center (%.4f %.4f %.4f), by hand (%.4f %.4f %.4f), RMS difference %.5f\n",
    what.c_str(), center.x, center.y, center.z, wanted.x, wanted.y, wanted.z, difference);
  Check(difference <= MAX_CENTER_DIFFERENCE, what + ": center pixel differs from the hand color");
  return difference;
}

const glm::dvec3 Eyes[4] = { glm::dvec3(0.0, 0.0, 4.0), glm::dvec3(4.0, 0.0, 0.0),
  glm::dvec3(0.0, -4.0, 0.0), glm::dvec3(2.3, 2.3, 2.3) };

void ViewDependence(int backend)
{
  Scene scene(OneKernel(), backend);
  glm::dvec3 first(0.0);
  for (int view = 0; view < 4; ++view)
  {
    const glm::dvec3 d = scene.ModelDirection(Eyes[view]);
    const std::vector<double> image = scene.View(Eyes[view]);
    Check(scene.Mapper->GetLastBackend() == backend, Name(backend) + " did not draw");
    CheckCenter(image, HandColor(d, 1), Name(backend) + " degree 1, view " + std::to_string(view));
    if (view == 0)
    {
      first = CenterPixel(image);
    }
    else
    {
      Check(glm::length(CenterPixel(image) - first) > 0.1,
        Name(backend) + ": the color does not change with the view");
    }
  }
  // Through a rotated volume the direction is the model's, not the world's. This pass builds
  // the lists its views need.
  scene.Volume->RotateX(40.0);
  scene.Volume->RotateZ(-65.0);
  for (int view = 0; view < 4; ++view)
  {
    CheckCenter(scene.View(Eyes[view]), HandColor(scene.ModelDirection(Eyes[view]), 1),
      Name(backend) + " degree 1, rotated volume, view " + std::to_string(view));
  }

  // Degree 0 from every view, then degree 3 (here 1) again: the camera moves and the degree
  // changes, the axis lists stay (a capture's default order, by depth, is sorted every frame).
  scene.Mapper->SetOrderingModeToBlended();
  scene.View(Eyes[0]);
  const vtkIdType builds = scene.Mapper->GetNumberOfListBuilds();
  scene.Mapper->SetMaximumSphericalHarmonicsDegree(0);
  for (int view = 0; view < 4; ++view)
  {
    CheckCenter(scene.View(Eyes[view]), HandColor(glm::dvec3(0.0), 0),
      Name(backend) + " degree 0, view " + std::to_string(view));
  }
  scene.Mapper->SetMaximumSphericalHarmonicsDegree(3);
  for (int view = 0; view < 4; ++view)
  {
    CheckCenter(scene.View(Eyes[view]), HandColor(scene.ModelDirection(Eyes[view]), 1),
      Name(backend) + " degree 1 again, view " + std::to_string(view));
  }
  // The OpenGL backend draws the CPU rasterizer's lists: one count for both.
  Check(builds > 0 && scene.Mapper->GetNumberOfListBuilds() == builds,
    Name(backend) + ": lists rebuilt on a camera or degree change: " + std::to_string(builds) +
      " then " + std::to_string(scene.Mapper->GetNumberOfListBuilds()));
}

// A kernel off the view axis: in a perspective projection colored for its own direction from
// the eye, in a parallel one for the view axis. Its center is 24 pixels right of the view's in
// both projections (depth 4).
void OffAxis(int backend)
{
  std::vector<double> coefficients(&K[0][0], &K[0][0] + 12);
  const glm::dvec3 center(0.8, 0.0, 0.0);
  Scene scene(Kernels({ center }, 0.3, 12, coefficients), backend);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  const double pixel = 0.8 / 24.0; // pixel size at depth 4
  camera->SetViewAngle(vtkMath::DegreesFromRadians(2.0 * std::atan(0.5 * Size * pixel / 4.0)));
  camera->SetParallelScale(0.5 * Size * pixel);
  for (bool parallel : { false, true })
  {
    camera->SetParallelProjection(parallel);
    const glm::dvec3 d = parallel ? glm::dvec3(0.0, 0.0, -1.0) : glm::normalize(center - Eyes[0]);
    CheckCenter(scene.View(Eyes[0]), HandColor(d, 1),
      Name(backend) + (parallel ? " off axis, parallel" : " off axis, perspective"),
      Size / 2 + 24);
  }
}

// Shade on, a normal facing the eye, the headlight: (ambient + diffuse) times the color.
void Shading(int backend)
{
  vtkSmartPointer<vtkPolyData> kernel = OneKernel();
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->InsertNextTuple3(0.0, 0.0, 1.0);
  kernel->GetPointData()->SetNormals(normals);
  vtkNew<vtkVolumeProperty> property;
  property->ShadeOn();
  property->SetAmbient(0.3);
  property->SetDiffuse(0.5);
  property->SetSpecular(0.0);
  Scene scene(kernel, backend, property);
  const glm::dvec3 d = scene.ModelDirection(Eyes[0]);
  CheckCenter(scene.View(Eyes[0]), 0.8 * HandColor(d, 1), Name(backend) + " degree 1, shaded");
}

// Random kernels of degree 3: the backends agree, and the third degree shows.
void DegreeThree()
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> position(-0.6, 0.6), coefficient(-0.5, 0.5);
  const int n = 40;
  std::vector<glm::dvec3> positions(n);
  std::vector<double> coefficients(48 * n);
  for (glm::dvec3& p : positions)
  {
    p = glm::dvec3(position(random), position(random), position(random));
  }
  for (double& c : coefficients)
  {
    c = coefficient(random);
  }
  vtkSmartPointer<vtkPolyData> kernels = Kernels(positions, 0.12, 48, coefficients);
  const glm::dvec3 eye(1.5, 2.0, 3.0);
  std::vector<double> images[2];
  for (int b = 0; b < 2; ++b)
  {
    Scene scene(kernels, Backends[b]);
    images[b] = scene.View(eye);
    if (b == 0)
    {
      scene.Mapper->SetMaximumSphericalHarmonicsDegree(2);
      const double rmse = splattest::RMSE(images[0], scene.View(eye));
      std::printf("degree 3 against degree 2 (CPU): RMSE %.4f\n", rmse);
      Check(rmse > MIN_DEGREE_THREE_RMSE, "the third degree changes nothing");
    }
  }
  const double rmse = splattest::RMSE(images[0], images[1]);
  std::printf("degree 3, CPU against OpenGL: RMSE %.5f (bound %.4f)\n", rmse, MAX_BACKEND_RMSE);
  Check(rmse <= MAX_BACKEND_RMSE, "degree 3: the backends differ");
}

// Invalid coefficients are skipped and counted; a component count that is no degree is an
// error, and the color array is used.
void InvalidInput()
{
  std::vector<double> coefficients;
  for (int i = 0; i < 3; ++i)
  {
    coefficients.insert(coefficients.end(), &K[0][0], &K[0][0] + 12);
  }
  coefficients[12 + 5] = std::numeric_limits<double>::quiet_NaN();
  coefficients[24 + 11] = 1e6;
  Scene scene(Kernels({ glm::dvec3(0.0), glm::dvec3(0.5, 0, 0), glm::dvec3(-0.5, 0, 0) }, 0.3,
                12, coefficients),
    vtkSplatBackend::CPU);
  scene.View(Eyes[0]);
  Check(scene.Mapper->GetNumberOfInvalidKernels() == 2 && scene.Mapper->GetNumberOfKernels() == 1,
    "NaN and out-of-range coefficients not skipped: " +
      std::to_string(scene.Mapper->GetNumberOfInvalidKernels()) + " invalid");

  std::vector<double> nine(9, 0.5);
  for (int backend : Backends)
  {
    Scene bad(Kernels({ glm::dvec3(0.0) }, 0.3, 9, nine), backend);
    vtkNew<vtkTest::ErrorObserver> errors;
    bad.Mapper->AddObserver(vtkCommand::ErrorEvent, errors);
    const std::vector<double> image = bad.View(Eyes[0]);
    Check(errors->GetError() != 0, "9 coefficients: no error");
    CheckCenter(image, glm::dvec3(0.0, 0.0, 1.0), Name(backend) + " 9 coefficients: Color array");
  }
  // Without an array name the harmonics are not used.
  Scene unnamed(OneKernel(), vtkSplatBackend::CPU);
  unnamed.Mapper->SetSphericalHarmonicsArrayName(nullptr);
  CheckCenter(unnamed.View(Eyes[0]), glm::dvec3(0.0, 0.0, 1.0), "CPU no array name: Color array");
}
}

int main()
{
  for (int backend : Backends)
  {
    ViewDependence(backend);
    OffAxis(backend);
    Shading(backend);
  }
  DegreeThree();
  InvalidInput();
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
