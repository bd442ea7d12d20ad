// SPDX-License-Identifier: BSD-3-Clause
// Every capture format vtkGaussianSplatReader reads, against converters nobody here wrote:
// PlayCanvas's splat-transform (.spz 4 and 3, compressed .ply, .sog and its folder form, .glb)
// and GaussianSplats3D's own generator (.ksplat levels 0 to 2, Testing/Tools/ply-to-ksplat.mjs),
// both installed by scripts/setup.sh under --tools DIR. Each source capture is written as an
// INRIA .ply (vtkGaussianSplatWriter for the synthetic ones), converted, and both files are read:
// - the same number of Gaussians and the spherical-harmonics degree the format keeps;
// - every Gaussian of the converted file matched to its source (by index where the format keeps
//   the order, else the best of the source Gaussians within the position bound), and each
//   quantity within the format's quantization bound (Bounds below, each with its reason),
//   after clipping the source to what the format can represent; formats whose codebooks are
//   k-means clusters (.sog) have no per-value bound (an outlier takes the nearest of 256
//   values): their median error is held to the codebook's resolution, and the image decides;
// - both drawn by vtkVolumeSplatMapper (CPU) from the same camera: PSNR at least the format's.
// The .glb is also written again as .gltf files (external and data-URI buffers, a node
// translation) that must read as the .glb does. The writer's own round trip (write, read) must
// give back the kernels to float precision.
// Sources: synthetic captures (the bench's torus) of SH degree 0 to 3, and with -D the shared
// data's two real captures. Skips when the converters are absent.
#include "SplatCaptureReference.h"
#include "SplatCaptureScene.h"
#include "SplatSphericalHarmonics.h"
#include "SplatTestUtilities.h"
#include "SplatVolumeTestUtilities.h"
#include "vtkGaussianSplatReader.h"
#include "vtkGaussianSplatWriter.h"
#include "vtkSplatBackend.h"
#include "vtkVolumeSplatMapper.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStaticPointLocator.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <json/json.h>
#include <vtksys/Base64.h>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using splattest::Check;

constexpr double C0 = 0.28209479177387814;
constexpr double Huge = 1e30;

// What a format keeps of a capture, and how far its values may be from the source's.
struct Bounds
{
  double Position;           // per axis: absolute, or a fraction of the capture's extent
  double LogScale;           // on the logarithms of the standard deviations
  double Rotation;           // per component of the unit quaternion, sign aligned
  double Opacity;            // peak opacity
  double Color;              // base color in [0, 1]
  double Rest;               // coefficients beyond the DC term
  double MinPSNR;            // the two files drawn from the same camera, dB
  bool Ordered = true;       // keeps the source's order
  bool Median = false;       // k-means codebooks: the bounds hold for the median Gaussian
  bool PositionOfExtent = false;
  double LogScaleRange[2] = { -Huge, Huge };
  double DCRange[2] = { -Huge, Huge };
  double RestRange[2] = { -Huge, Huge };
};

struct Format
{
  std::string Name;
  std::string Extension; // of the converted file
  std::vector<std::string> Options;
  int KSplatLevel = -1;  // a GaussianSplats3D conversion, level 2: SH bounds from its header
  int MaxDegree = 3;
  Bounds Limits;
};

// The formats, with the bounds their encodings allow (see the spec of each in
// Filters/SplatCapture*.cxx):
std::vector<Format> Formats()
{
  std::vector<Format> formats;
  // .spz: 24-bit fixed-point positions with 12 fractional bits (2^-13 = 1.2e-4 half a step),
  // log scales in 1/16 steps over [-10, 5.94] (1/32), smallest-three quaternions in 9 bits
  // (6.9e-4 each, 2e-3 on the largest, derived), 8-bit alpha (1/510) and colors with a 0.15 scale (DC within +-3.33, 0.0131 C0 in
  // color), SH bytes over [-1, 1) in 5-bit (degree 1) and 4-bit buckets (0.066).
  Bounds spz{ 1.23e-4, 1.0 / 32 + 1e-5, 2e-3, 1.0 / 510 + 1e-6, 0.0038, 0.0665, 36.0 };
  spz.LogScaleRange[0] = -10.0;
  spz.LogScaleRange[1] = 255.0 / 16 - 10.0;
  spz.DCRange[0] = -0.5 / 0.15;
  spz.DCRange[1] = 0.5 / 0.15;
  spz.RestRange[0] = -1.0;
  spz.RestRange[1] = 127.0 / 128;
  formats.push_back({ "spz", ".spz", {}, -1, 3, spz });
  formats.push_back({ "spz-v3", ".spz", { "--spz-version", "3" }, -1, 3, spz });
  // Compressed .ply: positions and log scales in 11-10-11 bits of each 256-Gaussian chunk's
  // range (a chunk spans at most the capture: half of 1/1023 of its extent), smallest three in
  // 10 bits, 8-bit colors in the chunk's range and alpha, SH bytes over [-4, 4] (8/512 = 0.0156
  // half a step, 0.031 at the ends); Morton order.
  Bounds compressed{ 1.0 / 2046, 0.02, 2e-3, 1.0 / 510 + 1e-6, 0.08, 0.032, 41.0, false };
  compressed.PositionOfExtent = true;
  compressed.LogScaleRange[0] = -20.0;
  compressed.LogScaleRange[1] = 20.0;
  compressed.RestRange[0] = -4.0;
  compressed.RestRange[1] = 4.0;
  formats.push_back({ "compressed-ply", ".compressed.ply", {}, -1, 3, compressed });
  // SOG: positions in 16-bit truncated steps of their log transform (about 2.5e-5 of the
  // extent), 8-bit quaternions (0.013), 256-entry k-means codebooks for log scales and DC, SH in
  // a k-means palette of at most N / 1024 rounded down to a power of two thousand sets: medians
  // (see above); Morton order. Its SH clustering runs on the CPU with -g cpu.
  Bounds sog{ 2.5e-5, 0.05, 0.013, 1.0 / 255 + 1e-6, 0.02, 0.1, 36.0, false, true };
  sog.PositionOfExtent = true;
  formats.push_back({ "sog", ".sog", { "-g", "cpu" }, -1, 3, sog });
  formats.push_back({ "sog-folder", "/meta.json", { "-g", "cpu" }, -1, 3, sog });
  // glTF: floats, linear scales and alpha (rounding of exp and logistic only).
  Bounds glb{ 1e-6, 1e-5, 1e-6, 1e-6, 1e-6, 1e-6, 60.0 };
  formats.push_back({ "glb", ".glb", {}, -1, 3, glb });
  // .ksplat: level 0 floats, levels 1-2 16-bit positions in 5-unit buckets (7.6e-5) and half
  // floats (2^-11 relative, more below the smallest normal half 6.1e-5: 0.004 on log scales);
  // colors and alpha truncated to 8 bits (1/255) for all levels; level 2 SH bytes truncated
  // over the header's range (ReadKSplatRange); the generator keeps degree 2 at most and orders
  // by bucket.
  Bounds ksplat0{ 1e-6, 1e-5, 1e-6, 1.0 / 255 + 1e-6, 1.0 / 255 + 1e-6, 1e-6, 35.0, false };
  Bounds ksplat1{ 8e-5, 0.004, 1e-3, 1.0 / 255 + 1e-6, 1.0 / 255 + 1e-6, 2e-3, 35.0, false };
  Bounds ksplat2 = ksplat1;
  formats.push_back({ "ksplat-0", ".ksplat", {}, 0, 2, ksplat0 });
  formats.push_back({ "ksplat-1", ".ksplat", {}, 1, 2, ksplat1 });
  formats.push_back({ "ksplat-2", ".ksplat", {}, 2, 2, ksplat2 });
  return formats;
}

std::string Quote(const std::string& s)
{
  return "'" + s + "'";
}

std::vector<char> ReadBytes(const std::string& path, std::size_t n)
{
  std::vector<char> bytes(n);
  std::ifstream(path, std::ios::binary).read(bytes.data(), static_cast<std::streamsize>(n));
  return bytes;
}

bool Run(const std::string& command, const std::string& log)
{
  return std::system((command + " >" + Quote(log) + " 2>&1").c_str()) == 0;
}

vtkSmartPointer<vtkPolyData> Read(const std::string& path, int& degree, bool spzFromRUB = false)
{
  vtkNew<vtkGaussianSplatReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetSPZFromRUB(spzFromRUB);
  reader->Update();
  degree = reader->GetSphericalHarmonicsDegree();
  return reader->GetOutput();
}

double Clip(double v, const double range[2])
{
  return std::min(std::max(v, range[0]), range[1]);
}

// The largest error of each quantity of converted Gaussian i against source Gaussian j.
struct Errors
{
  double Position = 0, LogScale = 0, Rotation = 0, Opacity = 0, Color = 0, Rest = 0;
  std::array<double, 6> Values() const
  {
    return { Position, LogScale, Rotation, Opacity, Color, Rest };
  }
};

class Comparison
{
public:
  Comparison(vtkPolyData* source, vtkPolyData* converted, const Bounds& bounds, int degree)
    : Source(source)
    , Converted(converted)
    , Limits(bounds)
    , Degree(degree)
  {
  }

  Errors Between(vtkIdType i, vtkIdType j) const
  {
    Errors e;
    double p[3], q[3];
    this->Converted->GetPoint(i, p);
    this->Source->GetPoint(j, q);
    for (int a = 0; a < 3; ++a)
    {
      e.Position = std::max(e.Position, std::abs(p[a] - q[a]));
    }
    const auto tuple = [](vtkPolyData* d, const char* name, vtkIdType k)
    { return d->GetPointData()->GetArray(name)->GetTuple(k); };
    std::array<double, 16> a{}, b{};
    auto get = [&](const char* name, int n)
    {
      std::copy_n(tuple(this->Converted, name, i), n, a.begin());
      std::copy_n(tuple(this->Source, name, j), n, b.begin());
    };
    get("Scale", 3);
    for (int c = 0; c < 3; ++c)
    {
      e.LogScale = std::max(e.LogScale,
        std::abs(std::log(a[c]) - Clip(std::log(b[c]), this->Limits.LogScaleRange)));
    }
    get("Rotation", 4);
    const double sign = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] < 0.0 ? -1.0 : 1.0;
    for (int c = 0; c < 4; ++c)
    {
      e.Rotation = std::max(e.Rotation, std::abs(a[c] - sign * b[c]));
    }
    get("Opacity", 1);
    e.Opacity = std::abs(a[0] - b[0]);
    get("Color", 3);
    for (int c = 0; c < 3; ++c)
    {
      // The source's color with its DC clipped to the format's range.
      const double dc = Clip((b[c] - 0.5) / C0, this->Limits.DCRange);
      e.Color = std::max(e.Color, std::abs(a[c] - std::clamp(0.5 + C0 * dc, 0.0, 1.0)));
    }
    if (this->Degree > 0)
    {
      const int components = 3 * (this->Degree + 1) * (this->Degree + 1);
      vtkDataArray* sa = this->Source->GetPointData()->GetArray("SphericalHarmonics");
      vtkDataArray* ca = this->Converted->GetPointData()->GetArray("SphericalHarmonics");
      for (int c = 3; c < components; ++c)
      {
        e.Rest = std::max(e.Rest,
          std::abs(ca->GetComponent(i, c) - Clip(sa->GetComponent(j, c), this->Limits.RestRange)));
      }
    }
    return e;
  }

  // Each converted Gaussian's errors against its source: the same index, or the best source
  // Gaussian near it.
  std::vector<Errors> Match() const
  {
    const vtkIdType n = this->Converted->GetNumberOfPoints();
    std::vector<Errors> out(n);
    vtkNew<vtkStaticPointLocator> locator;
    if (!this->Limits.Ordered)
    {
      locator->SetDataSet(this->Source);
      locator->BuildLocator();
    }
    vtkNew<vtkIdList> near;
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (this->Limits.Ordered)
      {
        out[i] = this->Between(i, i);
        continue;
      }
      double p[3];
      this->Converted->GetPoint(i, p);
      locator->FindPointsWithinRadius(2.0 * this->Limits.Position + 1e-9, p, near);
      if (near->GetNumberOfIds() == 0)
      {
        near->InsertNextId(locator->FindClosestPoint(p));
      }
      double best = Huge;
      for (vtkIdType k = 0; k < near->GetNumberOfIds(); ++k)
      {
        const Errors e = this->Between(i, near->GetId(k));
        const auto v = e.Values();
        const std::array<double, 6> limit = { this->Limits.Position, this->Limits.LogScale,
          this->Limits.Rotation, this->Limits.Opacity, this->Limits.Color, this->Limits.Rest };
        double worst = 0.0;
        for (int q = 0; q < 6; ++q)
        {
          worst = std::max(worst, v[q] / limit[q]);
        }
        if (worst < best)
        {
          best = worst;
          out[i] = e;
        }
      }
    }
    return out;
  }

private:
  vtkPolyData* Source;
  vtkPolyData* Converted;
  Bounds Limits;
  int Degree;
};

// The capture drawn by vtkVolumeSplatMapper (CPU) from `view`, 200 x 200 RGB.
std::vector<double> Draw(vtkPolyData* data, const splattest::CaptureView& view)
{
  vtkNew<vtkVolumeSplatMapper> mapper;
  mapper->SetBackend(vtkSplatBackend::CPU);
  return splattest::ToRGB(splattest::Capture(splattest::DrawVolume(
    mapper, data, view.Position.data(), view.FocalPoint.data(), view.Up.data(), 200)));
}

// The largest difference, over a spread of view directions d, between the view-dependent
// color of Gaussian i of `a` along d and that of Gaussian i of `b` along r d (before clamping).
double ColorTurnError(vtkPolyData* a, vtkPolyData* b, vtkIdType i, const double r[3][3], int degree)
{
  const int n = splat::SphericalHarmonicsCoefficients(degree);
  vtkDataArray* shA = a->GetPointData()->GetArray("SphericalHarmonics");
  vtkDataArray* shB = b->GetPointData()->GetArray("SphericalHarmonics");
  double worst = 0.0;
  for (int k = 0; k < 16; ++k)
  {
    const double z = 1.0 - (2.0 * k + 1.0) / 16.0, rho = std::sqrt(1.0 - z * z);
    const double d[3] = { rho * std::cos(2.4 * k), rho * std::sin(2.4 * k), z };
    double turned[3];
    vtkMath::Multiply3x3(r, d, turned);
    float basisA[16], basisB[16];
    splat::SphericalHarmonicsBasis(glm::vec3(d[0], d[1], d[2]), degree, basisA);
    splat::SphericalHarmonicsBasis(glm::vec3(turned[0], turned[1], turned[2]), degree, basisB);
    for (int c = 0; c < 3; ++c)
    {
      double colorA = 0.0, colorB = 0.0;
      for (int m = 0; m < n; ++m)
      {
        colorA += basisA[m] * shA->GetComponent(i, 3 * m + c);
        colorB += basisB[m] * shB->GetComponent(i, 3 * m + c);
      }
      worst = std::max(worst, std::abs(colorA - colorB));
    }
  }
  return worst;
}

// The covariance R S^2 R^T of Gaussian i of `data`.
void Covariance(vtkPolyData* data, vtkIdType i, double sigma[3][3])
{
  double q[4], s[3], r[3][3];
  data->GetPointData()->GetArray("Rotation")->GetTuple(i, q);
  data->GetPointData()->GetArray("Scale")->GetTuple(i, s);
  vtkMath::QuaternionToMatrix3x3(q, r);
  for (int j = 0; j < 3; ++j)
  {
    for (int k = 0; k < 3; ++k)
    {
      sigma[j][k] = 0.0;
      for (int m = 0; m < 3; ++m)
      {
        sigma[j][k] += r[j][m] * s[m] * s[m] * r[k][m];
      }
    }
  }
}

// Checks that `b` holds the Gaussians of `a` turned by the unit quaternion q (w first): their
// positions, their covariances (relative to the largest entry) and view-dependent colors.
void CheckTurned(const std::string& name, vtkPolyData* a, vtkPolyData* b, const double q[4],
  int degree)
{
  double r[3][3];
  vtkMath::QuaternionToMatrix3x3(q, r);
  bool same = a->GetNumberOfPoints() == b->GetNumberOfPoints();
  double position = 0.0, shape = 0.0, color = 0.0;
  for (vtkIdType i = 0; same && i < a->GetNumberOfPoints(); ++i)
  {
    double pa[3], pb[3], turned[3], sa[3][3], sb[3][3], rs[3][3], expected[3][3];
    a->GetPoint(i, pa);
    b->GetPoint(i, pb);
    vtkMath::Multiply3x3(r, pa, turned);
    position = std::max(position, std::sqrt(vtkMath::Distance2BetweenPoints(turned, pb)));
    Covariance(a, i, sa);
    Covariance(b, i, sb);
    vtkMath::Multiply3x3(r, sa, rs);
    double largest = 0.0, difference = 0.0;
    for (int j = 0; j < 3; ++j)
    {
      for (int k = 0; k < 3; ++k)
      {
        expected[j][k] = rs[j][0] * r[k][0] + rs[j][1] * r[k][1] + rs[j][2] * r[k][2];
        largest = std::max(largest, std::abs(expected[j][k]));
        difference = std::max(difference, std::abs(expected[j][k] - sb[j][k]));
      }
    }
    shape = std::max(shape, largest > 0.0 ? difference / largest : difference);
    if (degree > 0)
    {
      color = std::max(color, ColorTurnError(a, b, i, r, degree));
    }
  }
  std::printf("%-28s position %.2g, covariance %.2g, SH color %.2g\n", name.c_str(), position,
    shape, color);
  Check(same && position < 1e-4 && shape < 1e-5 && color < 1e-4,
    name + ": the Gaussians or their colors did not turn");
}

// The .glb's JSON with a node rotation: every Gaussian's position, orientation and
// view-dependent color must turn with it from those of the same file without it (gltf-bin). In
// the reader's (INRIA) frame the turn is H R H, H the half turn about z between the frames.
void TestGLTFRotated(const Json::Value& json, const std::string& work)
{
  int baseDegree = -1;
  vtkSmartPointer<vtkPolyData> source = Read(work + "/gltf-bin.gltf", baseDegree);
  const double axis[3] = { 0.48, 0.6, 0.64 }, angle = 1.1; // unit axis, radians
  const double q[4] = { std::cos(angle / 2), std::sin(angle / 2) * axis[0],
    std::sin(angle / 2) * axis[1], std::sin(angle / 2) * axis[2] };
  Json::Value edited = json;
  edited["buffers"][0]["uri"] = "variant.bin";
  for (int c : { 1, 2, 3, 0 }) // glTF stores x, y, z, w
  {
    edited["nodes"][0]["rotation"].append(q[c]);
  }
  const std::string path = work + "/gltf-rotated.gltf";
  std::ofstream(path) << Json::writeString(Json::StreamWriterBuilder(), edited);
  int degree = -1;
  vtkSmartPointer<vtkPolyData> data = Read(path, degree);
  const double inria[4] = { q[0], -q[1], -q[2], q[3] }; // H R H for H = diag(-1, -1, 1)
  CheckTurned("gltf-rotated", source, data, inria, degree);
}

// The .glb written again as .gltf files: its buffer in a .bin beside, or inline as a data URI,
// and with a node translation, which moves every Gaussian by it (in glTF's frame).
void TestGLTFVariants(const std::string& glb, vtkPolyData* source, const std::string& work)
{
  std::ifstream in(glb, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::uint32_t jsonLength = 0, binLength = 0;
  std::memcpy(&jsonLength, bytes.data() + 12, 4);
  std::memcpy(&binLength, bytes.data() + 20 + jsonLength, 4);
  const std::string binary = bytes.substr(28 + jsonLength, binLength);
  Json::Value json;
  std::istringstream text(bytes.substr(20, jsonLength));
  Json::parseFromStream(Json::CharReaderBuilder(), text, &json, nullptr);
  const std::string bin = work + "/variant.bin";
  std::ofstream(bin, std::ios::binary) << binary;
  std::string encoded(4 * binary.size() / 3 + 8, '\0');
  encoded.resize(vtksysBase64_Encode(reinterpret_cast<const unsigned char*>(binary.data()),
    binary.size(), reinterpret_cast<unsigned char*>(&encoded[0]), 0));

  const double shift[3] = { 0.5, -0.25, 1.0 };
  vtkNew<vtkPolyData> moved;
  moved->DeepCopy(source);
  for (vtkIdType i = 0; i < moved->GetNumberOfPoints(); ++i)
  {
    double p[3];
    moved->GetPoint(i, p);
    // glTF's x and y are the negated INRIA ones.
    moved->GetPoints()->SetPoint(i, p[0] - shift[0], p[1] - shift[1], p[2] + shift[2]);
  }
  struct Variant
  {
    const char* Name;
    std::string URI;
    bool Moved;
  };
  for (const Variant& variant : { Variant{ "gltf-bin", "variant.bin", false },
         Variant{ "gltf-data-uri", "data:application/octet-stream;base64," + encoded, false },
         Variant{ "gltf-translated", "variant.bin", true } })
  {
    Json::Value edited = json;
    edited["buffers"][0]["uri"] = variant.URI;
    if (variant.Moved)
    {
      for (double t : shift)
      {
        edited["nodes"][0]["translation"].append(t);
      }
    }
    const std::string path = work + "/" + variant.Name + ".gltf";
    std::ofstream(path) << Json::writeString(Json::StreamWriterBuilder(), edited);
    int degree = -1;
    vtkSmartPointer<vtkPolyData> data = Read(path, degree);
    vtkPolyData* expected = variant.Moved ? moved.Get() : source;
    Bounds exact{ 1e-6, 1e-5, 1e-6, 1e-6, 1e-6, 1e-6, 0.0 };
    bool same = data->GetNumberOfPoints() == expected->GetNumberOfPoints();
    for (const Errors& e : same ? Comparison(expected, data, exact, degree).Match() : std::vector<Errors>())
    {
      const auto v = e.Values();
      same = same && std::all_of(v.begin(), v.end(), [](double x) { return x <= 1e-5; });
    }
    std::printf("%-28s %s\n", variant.Name, same ? "as the .glb" : "differs");
    Check(same, std::string(variant.Name) + ": not the .glb's Gaussians");
  }
  TestGLTFRotated(json, work);
}

void TestFormat(const std::string& sourcePath, vtkPolyData* source, int degree,
  const Format& format, const std::string& tools, const std::string& script,
  const std::string& work)
{
  const std::string stem = vtksys::SystemTools::GetFilenameWithoutLastExtension(sourcePath);
  const std::string where = stem + " as " + format.Name;
  std::string converted = work + "/" + stem + "-" + format.Name + format.Extension;
  const std::string log = work + "/" + stem + "-" + format.Name + ".log";
  if (format.Extension == "/meta.json")
  {
    vtksys::SystemTools::MakeDirectory(work + "/" + stem + "-" + format.Name);
  }
  const int expected = std::min(degree, format.MaxDegree);
  std::string command;
  if (format.KSplatLevel >= 0)
  {
    command = "node " + Quote(script) + " " + Quote(tools + "/node_modules") + " " +
      Quote(sourcePath) + " " + Quote(converted) + " " + std::to_string(format.KSplatLevel) +
      " " + std::to_string(expected);
  }
  else
  {
    command = Quote(tools + "/node_modules/.bin/splat-transform") + " -q -w";
    for (const std::string& option : format.Options)
    {
      command += " " + option;
    }
    command += " " + Quote(sourcePath) + " " + Quote(converted);
  }
  if (!Run(command, log))
  {
    Check(false, where + ": the conversion failed, see " + log);
    return;
  }
  int readDegree = -1;
  vtkSmartPointer<vtkPolyData> data = Read(converted, readDegree);
  if (data->GetNumberOfPoints() != source->GetNumberOfPoints())
  {
    Check(false, where + ": " + std::to_string(data->GetNumberOfPoints()) + " Gaussians read, " +
        std::to_string(source->GetNumberOfPoints()) + " written");
    return;
  }
  Check(readDegree == expected,
    where + ": SH degree " + std::to_string(readDegree) + ", " + std::to_string(expected) +
      " expected");

  Bounds limits = format.Limits;
  if (limits.PositionOfExtent)
  {
    double b[6];
    source->GetBounds(b);
    limits.Position *= std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] }) * (1.0 + 1e-6);
  }
  if (format.KSplatLevel == 2)
  {
    // The coefficient range of the main header (bytes 36 and 40), truncated in 255 steps.
    const std::vector<char> head = ReadBytes(converted, 44);
    float range[2];
    std::memcpy(range, head.data() + 36, sizeof(range));
    limits.RestRange[0] = range[0];
    limits.RestRange[1] = range[1];
    limits.Rest = (range[1] - range[0]) / 255.0 + 1e-5;
  }
  const std::vector<Errors> errors =
    Comparison(source, data, limits, std::min(readDegree, expected)).Match();
  const char* names[] = { "position", "log scale", "rotation", "opacity", "color", "SH" };
  const double bounds[] = { limits.Position, limits.LogScale, limits.Rotation, limits.Opacity,
    limits.Color, limits.Rest };
  std::printf("%-28s", where.c_str());
  for (int q = 0; q < 6; ++q)
  {
    std::vector<double> values;
    for (const Errors& e : errors)
    {
      values.push_back(e.Values()[q]);
    }
    std::sort(values.begin(), values.end());
    const double worst = values.back();
    const double median = values[values.size() / 2];
    const double measured = limits.Median ? median : worst;
    std::printf(" %s %.3g/%.3g", names[q], measured, bounds[q]);
    if (limits.Median)
    {
      std::printf(" (max %.3g)", worst);
    }
    Check(measured <= bounds[q],
      where + ": " + names[q] + (limits.Median ? " median" : "") + " error " +
        std::to_string(measured) + " above its bound " + std::to_string(bounds[q]));
  }
  std::array<double, 3> center;
  double radius;
  splattest::RobustFrame(source, center, radius);
  const splattest::CaptureView view = splattest::CaptureViews(center, radius).front();
  const double psnr = splattest::PSNR(Draw(source, view), Draw(data, view));
  std::printf(" PSNR %.1f dB\n", psnr);
  if (format.Name == "glb" && stem == "torus-sh3")
  {
    TestGLTFVariants(converted, source, work);
  }
  if (format.Extension == ".spz" && stem == "torus-sh3")
  {
    // Read as Niantic's right-up-back frame: a half turn about x of what is stored.
    int rubDegree = -1;
    const double halfTurn[4] = { 0.0, 1.0, 0.0, 0.0 };
    CheckTurned(where + " from RUB", data, Read(converted, rubDegree, true), halfTurn, degree);
  }
  Check(psnr >= limits.MinPSNR,
    where + ": PSNR " + std::to_string(psnr) + " dB, below " + std::to_string(limits.MinPSNR));
}

// vtkGaussianSplatWriter's .ply read back: the kernels to float precision.
void TestWriter(vtkPolyData* source, int degree, const std::string& path)
{
  vtkNew<vtkGaussianSplatWriter> writer;
  writer->SetInputData(source);
  writer->SetFileName(path.c_str());
  writer->Write();
  int readDegree = -1;
  vtkSmartPointer<vtkPolyData> back = Read(path, readDegree);
  Check(back->GetNumberOfPoints() == source->GetNumberOfPoints() && readDegree == degree,
    path + ": the written capture does not read back whole");
  if (back->GetNumberOfPoints() != source->GetNumberOfPoints())
  {
    return;
  }
  // Positions and coefficients are copied; logarithms, logits and the normalization of the
  // quaternions round once in single precision.
  const std::array<double, 6> limit = { 0.0, 2e-6, 1e-6, 1e-6, 2e-6, 0.0 };
  Bounds exact{ limit[0], limit[1], limit[2], limit[3], limit[4], limit[5], 0.0 };
  int differing = 0;
  for (const Errors& e : Comparison(source, back, exact, degree).Match())
  {
    const auto v = e.Values();
    differing += !std::equal(v.begin(), v.end(), limit.begin(), std::less_equal<double>());
  }
  Check(differing == 0, path + ": " + std::to_string(differing) + " Gaussians read back differ");
}
}

int main(int argc, char* argv[])
{
  const std::string tools = splattest::Argument(argc, argv, "--tools");
  const std::string script = splattest::Argument(argc, argv, "--ksplat-script");
  const std::string work = splattest::Argument(argc, argv, "-T") + "/GaussianSplatFormats";
  vtksys::SystemTools::MakeDirectory(work);

  // Sources: synthetic captures of every degree (written by vtkGaussianSplatWriter, whose round
  // trip is checked on the way), and the real captures when present.
  std::vector<std::string> sources;
  for (int degree = 0; degree <= 3; ++degree)
  {
    auto capture = splatexample::SyntheticCapture(3000, degree, 7u + degree);
    const std::string path = work + "/torus-sh" + std::to_string(degree) + ".ply";
    TestWriter(capture, degree, path);
    sources.push_back(path);
  }
  const std::string data = splattest::Argument(argc, argv, "-D");
  for (const char* file : { "donut_fused.ply", "fruit_drops_minimal.ply" })
  {
    if (!data.empty() && splattest::FileExists(data + "/" + file))
    {
      sources.push_back(data + "/" + file);
    }
  }
  // The converters need Node.js, which a machine with an installed npm prefix may still lack
  // (the Debian 13 root of the second test leg sees the host's).
  if (tools.empty() || !splattest::FileExists(tools + "/node_modules/.bin/splat-transform") ||
    std::system("node --version > /dev/null 2>&1") != 0)
  {
    std::printf("the converters or Node.js are absent (%s): only the writer was tested\n",
      tools.c_str());
    return splattest::Failures() ? 1 : splattest::SkipReturnCode;
  }
  for (const std::string& path : sources)
  {
    int degree = -1;
    vtkSmartPointer<vtkPolyData> source = Read(path, degree);
    for (const Format& format : Formats())
    {
      TestFormat(path, source, degree, format, tools, script, work);
    }
  }
  return splattest::Failures() == 0 ? 0 : 1;
}
