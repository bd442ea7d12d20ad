// SPDX-License-Identifier: BSD-3-Clause
// vtkGaussianSplatReader on a 3D Gaussian Splatting .ply (INRIA layout, degree-1 spherical
// harmonics) and a .splat file written by the test from known Gaussians:
// - the output arrays equal the values the 3DGS model defines (exp of the log scales, logistic
//   of the opacity logits, normalized quaternions, 0.5 + C0 f_dc, the coefficients reordered
//   coefficient-major), and for .splat the decoded 8-bit quantization;
// - drawn by vtkVolumeSplatMapper they give the image of the same kernels given directly as
//   arrays (RMSE bound below);
// - IsGaussianSplatFile tells captures from meshes; a wrong number of f_rest properties and a
//   truncated .splat give errors.
#include "SplatPLYTestUtilities.h"
#include "SplatVolumeTestUtilities.h"
#include "vtkGaussianSplatReader.h"
#include "vtkSplatBackend.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkErrorCode.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace
{
using splattest::Check;

constexpr double C0 = 0.28209479177387814;
constexpr int Count = 6;

// The known Gaussians as a 3DGS .ply stores them.
struct Gaussian
{
  double Position[3];
  double LogScale[3];
  double Quaternion[4]; // w, x, y, z, not normalized
  double Logit;
  double DC[3];
  double Rest[3][3]; // per channel (r, g, b), the three degree-1 coefficients
};

std::vector<Gaussian> Gaussians()
{
  std::vector<Gaussian> g(Count);
  for (int i = 0; i < Count; ++i)
  {
    const double a = 2.0 * 3.14159265358979 * i / Count;
    g[i] = { { 0.4 * std::cos(a), 0.4 * std::sin(a), 0.1 * i - 0.25 },
      { std::log(0.05 + 0.02 * i), std::log(0.12 - 0.01 * i), std::log(0.04 + 0.03 * (i % 3)) },
      { 1.0 + 0.5 * i, 0.3 * i - 0.6, 0.2, -0.4 + 0.15 * i }, -1.5 + 0.7 * i,
      { 1.2 - 0.4 * i, 0.3 * i - 0.8, 0.5 * std::sin(a) },
      { { 0.1 * i, -0.2, 0.05 }, { 0.3, 0.1 - 0.05 * i, -0.1 }, { -0.15, 0.2, 0.04 * i } } };
  }
  return g;
}

// The arrays the 3DGS model defines for `g`: Scale, Rotation, Opacity, Color and, when
// `harmonics`, SphericalHarmonics (12 components: DC then the degree-1 coefficients, RGB
// interleaved).
vtkSmartPointer<vtkPolyData> Kernels(const std::vector<Gaussian>& g, bool harmonics)
{
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  splattest::KernelSetArrays<vtkFloatArray> arrays;
  vtkFloatArray* scale = arrays.Scale;
  vtkFloatArray* rotation = arrays.Rotation;
  vtkFloatArray* opacity = arrays.Opacity;
  vtkFloatArray* color = arrays.Color;
  vtkNew<vtkFloatArray> sh;
  sh->SetName("SphericalHarmonics");
  sh->SetNumberOfComponents(12);
  for (const Gaussian& k : g)
  {
    points->InsertNextPoint(k.Position);
    scale->InsertNextTuple3(
      std::exp(k.LogScale[0]), std::exp(k.LogScale[1]), std::exp(k.LogScale[2]));
    const double* q = k.Quaternion;
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    rotation->InsertNextTuple4(q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm);
    opacity->InsertNextValue(static_cast<float>(1.0 / (1.0 + std::exp(-k.Logit))));
    double rgb[3], coefficients[12];
    for (int c = 0; c < 3; ++c)
    {
      rgb[c] = std::min(1.0, std::max(0.0, 0.5 + C0 * k.DC[c]));
      coefficients[c] = k.DC[c];
      for (int j = 0; j < 3; ++j)
      {
        coefficients[3 * (j + 1) + c] = k.Rest[c][j];
      }
    }
    color->InsertNextTuple(rgb);
    sh->InsertNextTuple(coefficients);
  }
  data->SetPoints(points);
  arrays.AddTo(data);
  if (harmonics)
  {
    data->GetPointData()->AddArray(sh);
  }
  return data;
}

// The INRIA layout: x y z nx ny nz f_dc_0..2 f_rest_0..(rest - 1) opacity scale_0..2 rot_0..3.
std::string PLY(const std::vector<Gaussian>& g, int rest)
{
  splattest::PLYElement vertex{ "vertex", splattest::GaussianCaptureProperties(rest), {} };
  for (const Gaussian& k : g)
  {
    std::vector<double> values(k.Position, k.Position + 3);
    values.insert(values.end(), { 0.0, 0.0, 0.0, k.DC[0], k.DC[1], k.DC[2] });
    for (int j = 0; j < rest; ++j)
    {
      values.push_back(k.Rest[j / 3][j % 3]); // channel-major: red's, green's, blue's
    }
    values.push_back(k.Logit);
    values.insert(values.end(), k.LogScale, k.LogScale + 3);
    values.insert(values.end(), k.Quaternion, k.Quaternion + 4);
    std::vector<std::vector<double>> record;
    for (double v : values)
    {
      record.push_back({ v });
    }
    vertex.Records.push_back(record);
  }
  return splattest::PLYFile({ vertex }, "binary_little_endian");
}

// The antimatter15 layout, and in `decoded` the kernels its 8-bit fields stand for.
std::string Splat(const std::vector<Gaussian>& g, std::vector<Gaussian>& decoded)
{
  std::string bytes;
  decoded = g;
  auto byte = [](double v)
  { return static_cast<unsigned char>(std::lround(std::min(255.0, std::max(0.0, v)))); };
  for (std::size_t i = 0; i < g.size(); ++i)
  {
    const Gaussian& k = g[i];
    float floats[6];
    for (int c = 0; c < 3; ++c)
    {
      floats[c] = static_cast<float>(k.Position[c]);
      floats[3 + c] = static_cast<float>(std::exp(k.LogScale[c]));
    }
    bytes.append(reinterpret_cast<const char*>(floats), sizeof(floats));
    unsigned char fields[8];
    const double alpha = 1.0 / (1.0 + std::exp(-k.Logit));
    const double* q = k.Quaternion;
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int c = 0; c < 3; ++c)
    {
      fields[c] = byte((0.5 + C0 * k.DC[c]) * 255.0);
      // f_dc such that 0.5 + C0 f_dc is the quantized color.
      decoded[i].DC[c] = (fields[c] / 255.0 - 0.5) / C0;
    }
    fields[3] = byte(alpha * 255.0);
    decoded[i].Logit = std::log(fields[3] / (255.0 - fields[3]));
    for (int c = 0; c < 4; ++c)
    {
      fields[4 + c] = byte(q[c] / norm * 128.0 + 128.0);
      decoded[i].Quaternion[c] = (fields[4 + c] - 128.0) / 128.0;
    }
    bytes.append(reinterpret_cast<const char*>(fields), sizeof(fields));
  }
  return bytes;
}

// The largest difference between the same-named arrays of `a` and `b`, relative to 1 or the
// value's size.
double LargestDifference(vtkPolyData* a, vtkPolyData* b, const char* name)
{
  vtkDataArray* x = a->GetPointData()->GetArray(name);
  vtkDataArray* y = b->GetPointData()->GetArray(name);
  if (!x || !y || x->GetNumberOfTuples() != y->GetNumberOfTuples() ||
    x->GetNumberOfComponents() != y->GetNumberOfComponents())
  {
    return HUGE_VAL;
  }
  double largest = 0.0;
  const int n = x->GetNumberOfComponents();
  for (vtkIdType i = 0; i < x->GetNumberOfValues(); ++i)
  {
    const double u = x->GetComponent(i / n, i % n);
    const double v = y->GetComponent(i / n, i % n);
    largest = std::max(largest, std::abs(u - v) / std::max(1.0, std::abs(v)));
  }
  return largest;
}

std::vector<double> Render(vtkPolyData* kernels)
{
  vtkNew<vtkVolumeSplatMapper> mapper;
  mapper->SetBackend(vtkSplatBackend::CPU);
  mapper->SetInputData(kernels);
  vtkNew<vtkRenderer> renderer;
  splattest::AddVolume(renderer, mapper, nullptr);
  auto window = splattest::MakeRenderWindow(200, 200);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.6, 0.8, 2.5);
  camera->SetFocalPoint(0, 0, 0);
  renderer->ResetCameraClippingRange();
  window->Render();
  Check(mapper->GetNumberOfKernels() == Count, "every kernel drawn");
  return splattest::ToRGB(splattest::Capture(window));
}

vtkSmartPointer<vtkPolyData> Read(const std::string& path, int* code, int* degree)
{
  vtkNew<vtkGaussianSplatReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  *code = reader->GetErrorCode();
  *degree = reader->GetSphericalHarmonicsDegree();
  return reader->GetOutput();
}

// Reads `path` and compares it with `expected`, array by array and drawn.
void CheckFile(const std::string& path, vtkPolyData* expected, int expectedDegree,
  const char* what, double maxRMSE)
{
  int code, degree;
  vtkSmartPointer<vtkPolyData> data = Read(path, &code, &degree);
  Check(code == vtkErrorCode::NoError && data->GetNumberOfPoints() == Count,
    std::string(what) + ": read without error");
  Check(degree == expectedDegree, std::string(what) + ": spherical harmonics degree");
  Check(vtkGaussianSplatReader::IsGaussianSplatFile(path.c_str()),
    std::string(what) + ": IsGaussianSplatFile");
  Check(vtkGaussianSplatReader::CanReadFile(path.c_str()) == 1,
    std::string(what) + ": CanReadFile");
  if (data->GetNumberOfPoints() != Count)
  {
    return;
  }
  double position = 0.0;
  for (vtkIdType i = 0; i < Count; ++i)
  {
    double p[3], q[3];
    data->GetPoint(i, p);
    expected->GetPoint(i, q);
    position = std::max({ position, std::abs(p[0] - q[0]), std::abs(p[1] - q[1]),
      std::abs(p[2] - q[2]) });
  }
  Check(position == 0.0, std::string(what) + ": positions");
  for (const char* name : { "Scale", "Rotation", "Opacity", "Color", "SphericalHarmonics" })
  {
    if (!expected->GetPointData()->GetArray(name))
    {
      Check(!data->GetPointData()->GetArray(name), std::string(what) + ": no " + name);
      continue;
    }
    const double difference = LargestDifference(data, expected, name);
    std::printf("%s: %s largest relative difference %.2g\n", what, name, difference);
    // Float arithmetic against the test's double arithmetic: a few float epsilons (measured at
    // most 6e-8).
    Check(difference <= 1e-6, std::string(what) + ": " + name + " equals the model's values");
  }
  const std::vector<double> image = Render(data);
  const double brightest = *std::max_element(image.begin(), image.end());
  // Measured brightest 0.72 (.ply) and 0.62 (.splat).
  Check(brightest > 0.2, std::string(what) + ": the kernels are visible");
  const double rmse = splattest::RMSE(image, Render(expected));
  std::printf("%s: image RMSE against the kernels given as arrays %.6f (brightest %.3f)\n", what,
    rmse, brightest);
  Check(rmse <= maxRMSE, std::string(what) + ": the same image as the kernels given as arrays");
}
}

int main(int argc, char* argv[])
{
  const std::string folder = splattest::Argument(argc, argv, "-T");
  const std::vector<Gaussian> gaussians = Gaussians();

  // The same arithmetic in float and double: identical up to rounding, which moves no pixel
  // across an 8-bit step (measured RMSE 0).
  const std::string ply = folder + "/TestGaussianSplatReader.ply";
  splattest::WriteBytes(ply, PLY(gaussians, 9));
  CheckFile(ply, Kernels(gaussians, true), 1, ".ply", 0.5 / 255.0);

  std::vector<Gaussian> decoded;
  const std::string splat = folder + "/TestGaussianSplatReader.splat";
  splattest::WriteBytes(splat, Splat(gaussians, decoded));
  CheckFile(splat, Kernels(decoded, false), 0, ".splat", 0.5 / 255.0);

  // A mesh is not a capture; wrong f_rest counts and truncated files are errors.
  splattest::PLYElement mesh{ "vertex",
    { { "x", "float", "" }, { "y", "float", "" }, { "z", "float", "" } },
    { { { 0 }, { 0 }, { 0 } } } };
  const std::string meshPath = folder + "/TestGaussianSplatReader_mesh.ply";
  splattest::WriteBytes(meshPath, splattest::PLYFile({ mesh }, "ascii"));
  Check(!vtkGaussianSplatReader::IsGaussianSplatFile(meshPath.c_str()), "a mesh is no capture");
  Check(vtkGaussianSplatReader::CanReadFile(meshPath.c_str()) == 0, "CanReadFile declines a mesh");
  const std::string bad = folder + "/TestGaussianSplatReader_bad.ply";
  splattest::WriteBytes(bad, PLY(gaussians, 5));
  const std::string shortSplat = folder + "/TestGaussianSplatReader_short.splat";
  splattest::WriteBytes(shortSplat, Splat(gaussians, decoded).substr(0, 5 * 32 + 7));
  Check(!vtkGaussianSplatReader::IsGaussianSplatFile(shortSplat.c_str()),
    "a .splat of 167 bytes is no capture");
  for (const std::string& path : { meshPath, bad, shortSplat })
  {
    int code, degree;
    vtkSmartPointer<vtkPolyData> data = Read(path, &code, &degree);
    Check(code != vtkErrorCode::NoError && data->GetNumberOfPoints() == 0 && degree == -1,
      path + " gives an error and no points");
  }
  return splattest::Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}
