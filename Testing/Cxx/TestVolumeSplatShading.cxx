// SPDX-License-Identifier: BSD-3-Clause
// Shading of vtkVolumeSplatMapper (volume property Shade on), on both backends, against images
// whose shading is known exactly:
// - a slab whose scalar ramps along z, seen down z in a parallel projection: every voxel's
//   normal is the gradient's direction (two-sided, towards the eye), so the shaded image must
//   equal the unshaded image of a color transfer function scaled by the lighting factor:
//   ambient + diffuse (headlight), ambient + diffuse cos 60 (a camera light 60 degrees off the
//   view direction) and ambient + diffuse plus the white specular term (headlight, the mirror
//   direction is the view direction);
// - point-set kernels with point normals facing the eye and edge-on: their centers' colors are
//   (ambient + diffuse) and ambient times the unshaded ones; without a normals array they are
//   drawn unshaded.
// The bound MAX_SHADING_RMSE (CMakeLists.txt) is a fraction of the 8-bit step; each case also
// checks that the shaded image is far from the unshaded one, so that missing shading fails.
#include "SplatVolumeTestUtilities.h"
#include "vtkSplatBackend.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkDoubleArray.h"
#include "vtkLight.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cstdio>
#include <string>

namespace
{
constexpr int Size = 128;
int failures = 0;

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::fprintf(stderr, "FAILED: %s\n", what.c_str());
    ++failures;
  }
}

// The image of `input` through the mapper on `backend`, seen down -z in a parallel projection,
// lit by the headlight or, with `light`, by that light only.
std::vector<double> Render(
  vtkDataSet* input, vtkVolumeProperty* property, int backend, vtkLight* light = nullptr)
{
  vtkNew<vtkVolumeSplatMapper> mapper;
  mapper->SetInputData(input);
  mapper->SetBackend(backend);
  vtkNew<vtkRenderer> renderer;
  splattest::AddVolume(renderer, mapper, property);
  if (light)
  {
    renderer->AddLight(light);
  }
  auto window = splattest::MakeRenderWindow(Size, Size);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetParallelScale(0.8);
  camera->SetPosition(0.0, 0.0, 4.0);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  renderer->ResetCameraClippingRange();
  window->Render();
  return splattest::ToRGB(splattest::Capture(window));
}

// A property with constant color `rgb` and constant opacity per unit distance over [0, 3].
vtkSmartPointer<vtkVolumeProperty> ConstantProperty(const double rgb[3], double alpha)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, alpha);
  opacity->AddPoint(3.0, alpha);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, rgb[0], rgb[1], rgb[2]);
  color->AddRGBPoint(3.0, rgb[0], rgb[1], rgb[2]);
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetScalarOpacityUnitDistance(1.0 / 16.0);
  return property;
}

// 32^3 voxels of spacing 1/16 centered at the origin; the scalar ramps from 1 to 2 along z.
vtkSmartPointer<vtkImageData> RampSlab()
{
  const int n = 32;
  const double h = 1.0 / 16.0, o = -0.5 * (n - 1) * h;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(h, h, h);
  image->SetOrigin(o, o, o);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetNumberOfTuples(n * n * n);
  for (vtkIdType id = 0; id < n * n * n; ++id)
  {
    scalars->SetValue(id, static_cast<float>(1.0 + static_cast<double>(id / (n * n)) / (n - 1)));
  }
  image->GetPointData()->SetScalars(scalars);
  return image;
}

void CheckRamp(int backend, const std::string& backendName)
{
  auto slab = RampSlab();
  const double rgb[3] = { 0.9, 0.7, 0.5 };
  const double ambient = 0.2, diffuse = 0.5;
  struct Case
  {
    std::string Name;
    double Specular;
    double Factor;       // the lighting factor of the transfer function's color
    bool SixtyDegrees;   // lit by a camera light 60 degrees off the view direction
  };
  const Case cases[] = {
    { "headlight", 0.0, ambient + diffuse, false },
    { "light at 60 degrees", 0.0, ambient + 0.5 * diffuse, true },
    { "headlight with specular", 0.3, ambient + diffuse, false },
  };
  for (const Case& c : cases)
  {
    auto shadedProperty = ConstantProperty(rgb, 0.15);
    shadedProperty->ShadeOn();
    shadedProperty->SetAmbient(ambient);
    shadedProperty->SetDiffuse(diffuse);
    shadedProperty->SetSpecular(c.Specular);
    shadedProperty->SetSpecularPower(1.0);
    vtkNew<vtkLight> light;
    light->SetLightTypeToCameraLight();
    light->SetPosition(std::sin(vtkMath::Pi() / 3.0), 0.0, std::cos(vtkMath::Pi() / 3.0));
    light->SetFocalPoint(0.0, 0.0, 0.0);
    const std::vector<double> shaded =
      Render(slab, shadedProperty, backend, c.SixtyDegrees ? light.Get() : nullptr);
    // The same lighting as an unshaded color: factor times the color, plus the specular white.
    double lit[3];
    for (int i = 0; i < 3; ++i)
    {
      lit[i] = c.Factor * rgb[i] + c.Specular;
    }
    const std::vector<double> expected = Render(slab, ConstantProperty(lit, 0.15), backend);
    const std::vector<double> unshaded = Render(slab, ConstantProperty(rgb, 0.15), backend);
    const double error = splattest::RMSE(shaded, expected);
    const double unshadedError = splattest::RMSE(unshaded, expected);
    std::printf("%s ramp, %s: RMSE %.5f against the lit colors (unshaded: %.5f)\n",
      backendName.c_str(), c.Name.c_str(), error, unshadedError);
    Check(error <= MAX_SHADING_RMSE, backendName + " ramp " + c.Name + " within the bound");
    Check(unshadedError > 20.0 * MAX_SHADING_RMSE,
      backendName + " ramp " + c.Name + ": the unshaded image differs");
  }
}

// Two kernels side by side, normals facing the eye (left) and edge-on (right), with direct
// color and peak opacity; with `normals` off, no normals array.
vtkSmartPointer<vtkPolyData> TwoKernels(bool normals)
{
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(-0.4, 0.0, 0.0);
  points->InsertNextPoint(0.4, 0.0, 0.0);
  data->SetPoints(points);
  auto array = [&](const char* name, int components, std::initializer_list<double> values)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(components);
    for (double v : values)
    {
      a->InsertNextValue(v);
    }
    data->GetPointData()->AddArray(a);
    return a.Get();
  };
  const double s = 0.1 * 0.1;
  array("Covariance", 6, { s, 0, 0, s, 0, s, s, 0, 0, s, 0, s });
  array("Color", 3, { 0.9, 0.7, 0.5, 0.9, 0.7, 0.5 });
  array("Opacity", 1, { 0.9, 0.9 });
  if (normals)
  {
    data->GetPointData()->SetNormals(array("Normals", 3, { 0, 0, 1, 1, 0, 0 }));
  }
  return data;
}

void CheckPointNormals(int backend, const std::string& backendName)
{
  const double rgb[3] = { 1.0, 1.0, 1.0 };
  auto property = ConstantProperty(rgb, 0.5);
  const std::vector<double> unshaded = Render(TwoKernels(true), property, backend);
  property->ShadeOn();
  property->SetAmbient(0.2);
  property->SetDiffuse(0.5);
  property->SetSpecular(0.0);
  const std::vector<double> shaded = Render(TwoKernels(true), property, backend);
  const std::vector<double> withoutNormals = Render(TwoKernels(false), property, backend);
  // The kernels' centers: x = -0.4 and 0.4 of the parallel scale 0.8 around the image center.
  const int y = Size / 2;
  const int columns[2] = { Size / 4, 3 * Size / 4 };
  const double factors[2] = { 0.7, 0.2 };
  for (int k = 0; k < 2; ++k)
  {
    const std::size_t p = 3 * (static_cast<std::size_t>(y) * Size + columns[k]);
    const double ratio = shaded[p] / unshaded[p];
    std::printf("%s point normals, kernel %d: shaded/unshaded %.3f (expected %.3f)\n",
      backendName.c_str(), k, ratio, factors[k]);
    Check(unshaded[p] > 0.5 && std::abs(ratio - factors[k]) < 0.02,
      backendName + " point kernel " + std::to_string(k) + " lit by its normal");
  }
  Check(splattest::RMSE(withoutNormals, unshaded) < MAX_SHADING_RMSE,
    backendName + " point set without normals drawn unshaded");
}
}

int main(int, char*[])
{
  CheckRamp(vtkSplatBackend::CPU, "CPU");
  CheckRamp(vtkSplatBackend::OPENGL, "OpenGL");
  CheckPointNormals(vtkSplatBackend::CPU, "CPU");
  CheckPointNormals(vtkSplatBackend::OPENGL, "OpenGL");
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
