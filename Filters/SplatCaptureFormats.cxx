// SPDX-License-Identifier: BSD-3-Clause
#include "SplatCaptureFormats.h"
#include "SplatSphericalHarmonics.h"

#include "vtkCallbackCommand.h"
#include "vtkErrorCode.h"
#include "vtkExecutive.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkSplatPLYReader.h"

#include <Eigen/Dense>
#include <vtksys/SystemTools.hxx>
#include <zlib.h>

#include <array>
#include <cmath>
#include <fstream>

namespace splatcapture
{
namespace
{
vtkSmartPointer<vtkFloatArray> NewArray(const char* name, int components, vtkIdType tuples)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}

bool HasExtension(const std::string& fileName, const char* extension)
{
  return vtksys::SystemTools::StringEndsWith(
    vtksys::SystemTools::LowerCase(fileName), extension);
}

// The vertex properties of the compressed layout.
const char* const CompressedPLYProperties[] = { "packed_position", "packed_rotation",
  "packed_scale", "packed_color" };

template <std::size_t N>
bool HasAll(vtkStringArray* names, const char* const (&required)[N])
{
  return std::all_of(std::begin(required), std::end(required),
    [names](const char* name) { return names->LookupValue(name) >= 0; });
}

Format IdentifyPLY(const std::string& fileName)
{
  vtkNew<vtkStringArray> names;
  if (!vtkSplatPLYReader::GetVertexPropertyNames(fileName.c_str(), names))
  {
    return Format::Unknown;
  }
  return HasAll(names, PLYProperties) ? Format::PLY
    : HasAll(names, CompressedPLYProperties) ? Format::CompressedPLY
                                             : Format::Unknown;
}
}

//------------------------------------------------------------------------------
Format Identify(const std::string& fileName)
{
  std::ifstream in(fileName, std::ios::binary);
  std::array<char, 16> head{};
  if (!in || !in.read(head.data(), head.size()))
  {
    head.fill(0); // shorter than 16 bytes: only a .splat of nothing could be; none is
  }
  const std::string start(head.data(), head.size());
  if (start.compare(0, 4, "ply\n") == 0 || start.compare(0, 5, "ply\r\n") == 0)
  {
    return IdentifyPLY(fileName);
  }
  if (start.compare(0, 4, "NGSP") == 0 ||
    (static_cast<unsigned char>(head[0]) == 0x1f && static_cast<unsigned char>(head[1]) == 0x8b &&
      HasExtension(fileName, ".spz")))
  {
    return Format::SPZ;
  }
  if (start.compare(0, 4, "PK\3\4") == 0 && HasExtension(fileName, ".sog"))
  {
    return Format::SOG;
  }
  if (start.compare(0, 4, "glTF") == 0 || HasExtension(fileName, ".gltf"))
  {
    return Format::GLTF;
  }
  if (HasExtension(fileName, ".json"))
  {
    return Format::SOG; // the meta.json of an unbundled SOG
  }
  if (HasExtension(fileName, ".ksplat"))
  {
    return Format::KSplat;
  }
  if (HasExtension(fileName, ".splat"))
  {
    return Format::Splat;
  }
  return Format::Unknown;
}

//------------------------------------------------------------------------------
const char* FormatName(Format format)
{
  switch (format)
  {
    case Format::PLY:
      return "3D Gaussian Splatting PLY";
    case Format::CompressedPLY:
      return "compressed PLY";
    case Format::Splat:
      return ".splat";
    case Format::SPZ:
      return "SPZ";
    case Format::SOG:
      return "SOG";
    case Format::GLTF:
      return "glTF";
    case Format::KSplat:
      return ".ksplat";
    default:
      return "unknown";
  }
}

//------------------------------------------------------------------------------
HarmonicsTurn::HarmonicsTurn(const double q[3][3], int degree)
  : Degree(degree)
{
  // A Fibonacci spiral of directions: every band's basis has full rank on it.
  constexpr int Directions = 64;
  const int n = splat::SphericalHarmonicsCoefficients(degree);
  Eigen::MatrixXd at(Directions, n), turned(Directions, n);
  float basis[splat::MaximumSphericalHarmonicsCoefficients];
  for (int i = 0; i < Directions; ++i)
  {
    const double z = 1.0 - (2.0 * i + 1.0) / Directions;
    const double r = std::sqrt(1.0 - z * z), phi = 2.399963229728653 * i;
    const double d[3] = { r * std::cos(phi), r * std::sin(phi), z };
    splat::SphericalHarmonicsBasis(glm::vec3(d[0], d[1], d[2]), degree, basis);
    at.row(i) = Eigen::Map<Eigen::RowVectorXf>(basis, n).cast<double>();
    glm::vec3 back; // Q^T d
    for (int c = 0; c < 3; ++c)
    {
      back[c] = static_cast<float>(q[0][c] * d[0] + q[1][c] * d[1] + q[2][c] * d[2]);
    }
    splat::SphericalHarmonicsBasis(back, degree, basis);
    turned.row(i) = Eigen::Map<Eigen::RowVectorXf>(basis, n).cast<double>();
  }
  for (int l = 1; l <= degree; ++l)
  {
    const int first = l * l, size = 2 * l + 1;
    const Eigen::MatrixXd block = at.middleCols(first, size)
                                    .colPivHouseholderQr()
                                    .solve(turned.middleCols(first, size));
    for (int r = 0; r < size; ++r)
    {
      for (int c = 0; c < size; ++c)
      {
        // Coefficient r of the turned band is the sum over c of block(r, c) times the old c.
        // Entries within float noise of 0 or +-1 are snapped, so axis turns stay exact.
        const double v = block(r, c), nearest = std::round(v);
        this->Blocks.push_back(static_cast<float>(std::abs(v - nearest) < 1e-6 ? nearest : v));
      }
    }
  }
}

//------------------------------------------------------------------------------
void HarmonicsTurn::Apply(float* rest) const
{
  float turned[3 * splat::MaximumSphericalHarmonicsCoefficients];
  const float* block = this->Blocks.data();
  for (int l = 1, first = 0; l <= this->Degree; first += 2 * l + 1, ++l)
  {
    const int size = 2 * l + 1;
    for (int r = 0; r < size; ++r, block += size)
    {
      for (int channel = 0; channel < 3; ++channel)
      {
        float sum = 0.0f;
        for (int c = 0; c < size; ++c)
        {
          sum += block[c] * rest[3 * (first + c) + channel];
        }
        turned[3 * (first + r) + channel] = sum;
      }
    }
  }
  std::copy(turned, turned + 3 * RestCoefficients(this->Degree), rest);
}

//------------------------------------------------------------------------------
Kernels::Kernels(vtkIdType count, int degree)
  : NumberOfGaussians(count)
  , SHDegree(degree)
  , PerChannel(RestCoefficients(degree))
{
  this->Points = NewArray("Points", 3, count);
  this->Scale = NewArray("Scale", 3, count);
  this->Rotation = NewArray("Rotation", 4, count);
  this->Opacity = NewArray("Opacity", 1, count);
  this->Color = NewArray("Color", 3, count);
  if (degree > 0)
  {
    this->SH = NewArray("SphericalHarmonics", 3 * (this->PerChannel + 1), count);
    this->SH->FillValue(0.0f); // for files whose parts have lower degrees
    this->Harmonics = this->SH->GetPointer(0);
  }
}

void Kernels::SetPosition(vtkIdType i, float x, float y, float z)
{
  float* p = this->Points->GetPointer(3 * i);
  p[0] = x;
  p[1] = y;
  p[2] = z;
}

void Kernels::SetScale(vtkIdType i, float sx, float sy, float sz)
{
  float* s = this->Scale->GetPointer(3 * i);
  s[0] = sx;
  s[1] = sy;
  s[2] = sz;
}

void Kernels::SetLogScale(vtkIdType i, float lx, float ly, float lz)
{
  this->SetScale(i, std::exp(lx), std::exp(ly), std::exp(lz));
}

void Kernels::SetRotation(vtkIdType i, float w, float x, float y, float z)
{
  const double norm = std::sqrt(static_cast<double>(w) * w + static_cast<double>(x) * x +
    static_cast<double>(y) * y + static_cast<double>(z) * z);
  const double scale = norm > 0.0 && std::isfinite(norm) ? 1.0 / norm : 1.0;
  float* q = this->Rotation->GetPointer(4 * i);
  q[0] = static_cast<float>(w * scale);
  q[1] = static_cast<float>(x * scale);
  q[2] = static_cast<float>(y * scale);
  q[3] = static_cast<float>(z * scale);
}

void Kernels::SetOpacity(vtkIdType i, float opacity)
{
  this->Opacity->SetValue(i, opacity);
}

void Kernels::SetOpacityLogit(vtkIdType i, float logit)
{
  this->Opacity->SetValue(i, static_cast<float>(1.0 / (1.0 + std::exp(-static_cast<double>(logit)))));
}

void Kernels::SetDC(vtkIdType i, float r, float g, float b)
{
  const float dc[3] = { r, g, b };
  float* color = this->Color->GetPointer(3 * i);
  for (int c = 0; c < 3; ++c)
  {
    color[c] = static_cast<float>(std::clamp(0.5 + C0 * dc[c], 0.0, 1.0));
    if (this->Harmonics)
    {
      this->SetRest(i, 0, c, dc[c]);
    }
  }
}

void Kernels::SetColor(vtkIdType i, float r, float g, float b)
{
  this->SetDC(i, static_cast<float>((r - 0.5) / C0), static_cast<float>((g - 0.5) / C0),
    static_cast<float>((b - 0.5) / C0));
}

void Kernels::SetFlag(const char* name, int value)
{
  this->Flags.emplace_back(name, value);
}

void Kernels::MoveTo(vtkPolyData* output)
{
  vtkNew<vtkPoints> points;
  points->SetData(this->Points);
  output->SetPoints(points);
  vtkPointData* pointData = output->GetPointData();
  for (vtkFloatArray* array : { this->Scale.Get(), this->Rotation.Get(), this->Opacity.Get(),
         this->Color.Get(), this->SH.Get() })
  {
    if (array)
    {
      pointData->AddArray(array);
    }
  }
  for (const auto& flag : this->Flags)
  {
    vtkNew<vtkIntArray> value;
    value->SetName(flag.first.c_str());
    value->InsertNextValue(flag.second);
    output->GetFieldData()->AddArray(value);
  }
}

//------------------------------------------------------------------------------
const std::uint8_t* Bytes::Take(std::size_t n, const char* item)
{
  if (n > this->Remaining())
  {
    throw ReadError(vtkErrorCode::PrematureEndOfFileError,
      this->What + " ends at byte " + std::to_string(this->Size) + ", inside the " + item +
        " (" + std::to_string(n) + " bytes from byte " + std::to_string(this->Position) + ")");
  }
  const std::uint8_t* p = this->Data + this->Position;
  this->Position += n;
  return p;
}

//------------------------------------------------------------------------------
std::vector<std::uint8_t> ReadFile(const std::string& fileName, std::size_t limit)
{
  std::ifstream in(fileName, std::ios::binary | std::ios::ate);
  if (!in)
  {
    throw ReadError(vtkErrorCode::CannotOpenFileError, "cannot open the file");
  }
  const std::streamoff size = in.tellg();
  if (size < 0 || static_cast<std::uint64_t>(size) > limit)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "the file has " + std::to_string(size) + " bytes, more than the " + std::to_string(limit) +
        " this format can hold");
  }
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), size))
  {
    throw ReadError(vtkErrorCode::PrematureEndOfFileError, "the file could not be read whole");
  }
  return bytes;
}

//------------------------------------------------------------------------------
std::vector<std::uint8_t> Gunzip(
  const std::uint8_t* data, std::size_t size, std::size_t limit, bool prefix)
{
  z_stream stream{};
  // 15 window bits + 32: gzip or zlib headers, detected.
  if (inflateInit2(&stream, 15 + 32) != Z_OK)
  {
    throw ReadError(vtkErrorCode::UnknownError, "zlib could not be initialized");
  }
  std::vector<std::uint8_t> out;
  stream.next_in = const_cast<Bytef*>(data);
  stream.avail_in = static_cast<uInt>(std::min<std::size_t>(size, UINT32_MAX));
  int status = Z_OK;
  while (status == Z_OK)
  {
    if (out.size() == limit)
    {
      inflateEnd(&stream);
      if (prefix)
      {
        return out;
      }
      throw ReadError(vtkErrorCode::FileFormatError,
        "the compressed data inflates to more than " + std::to_string(limit) +
          " bytes, more than its header allows");
    }
    const std::size_t done = out.size();
    out.resize(std::min(limit, std::max<std::size_t>(2 * done, 1 << 20)));
    stream.next_out = out.data() + done;
    stream.avail_out = static_cast<uInt>(std::min<std::size_t>(out.size() - done, UINT32_MAX));
    status = inflate(&stream, Z_NO_FLUSH);
    out.resize(done + (stream.next_out - (out.data() + done)));
    if (status == Z_BUF_ERROR && stream.avail_in > 0)
    {
      status = Z_OK; // the output was full
    }
  }
  inflateEnd(&stream);
  if (status != Z_STREAM_END)
  {
    throw ReadError(status == Z_BUF_ERROR ? vtkErrorCode::PrematureEndOfFileError
                                          : vtkErrorCode::FileFormatError,
      status == Z_BUF_ERROR ? "the compressed data ends early (truncated file)"
                            : std::string("the compressed data is corrupt (zlib: ") +
          (stream.msg ? stream.msg : "error") + ")");
  }
  return out;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> ReadPLYFile(
  const std::string& fileName, bool allElements, const Progress& progress)
{
  vtkNew<vtkSplatPLYReader> ply;
  ply->SetFileName(fileName.c_str());
  ply->SetReadAllElements(allElements);
  vtkNew<vtkCallbackCommand> forward;
  forward->SetCallback([](vtkObject* caller, unsigned long, void* clientData, void*)
    { (*static_cast<const Progress*>(clientData))(vtkAlgorithm::SafeDownCast(caller)->GetProgress()); });
  forward->SetClientData(const_cast<Progress*>(&progress));
  ply->AddObserver(vtkCommand::ProgressEvent, forward);
  // The first error message of the reader or its executive, without VTK's prefix.
  std::string message;
  vtkNew<vtkCallbackCommand> errors;
  errors->SetCallback([](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      auto* kept = static_cast<std::string*>(clientData);
      if (kept->empty())
      {
        const std::string text = static_cast<const char*>(callData);
        const std::size_t start = text.find("): ");
        *kept = start == std::string::npos ? text : text.substr(start + 3);
        kept->erase(kept->find_last_not_of(" \n") + 1);
      }
    });
  errors->SetClientData(&message);
  ply->AddObserver(vtkCommand::ErrorEvent, errors);
  ply->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  ply->Update();
  if (ply->GetErrorCode() != vtkErrorCode::NoError)
  {
    // vtkSplatPLYReader's message names the file, the place and the problem.
    const std::string prefix = fileName + ": ";
    throw ReadError(ply->GetErrorCode(),
      message.compare(0, prefix.size(), prefix) == 0 ? message.substr(prefix.size()) : message);
  }
  return ply->GetOutput();
}

//------------------------------------------------------------------------------
float HalfToFloat(std::uint16_t half)
{
  const int exponent = (half >> 10) & 0x1f;
  const int mantissa = half & 0x3ff;
  const float sign = (half & 0x8000) ? -1.0f : 1.0f;
  if (exponent == 0)
  {
    return sign * std::ldexp(static_cast<float>(mantissa), -24);
  }
  if (exponent == 31)
  {
    return mantissa ? std::nanf("") : sign * INFINITY;
  }
  return sign * std::ldexp(static_cast<float>(mantissa | 0x400), exponent - 25);
}
}
