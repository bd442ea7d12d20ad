// SPDX-License-Identifier: BSD-3-Clause
#include "vtkGaussianSplatReader.h"

#include "vtkByteSwap.h"
#include "vtkErrorCode.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkSplatPLYReader.h"
#include "SplatCaptureFormats.h"
#include "vtkStringArray.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkGaussianSplatReader);

namespace
{
using namespace splatcapture;

// Bytes of one .splat record.
constexpr int SplatRecordSize = 32;

// The values of a one-component array as floats: the array itself when it is float.
vtkSmartPointer<vtkFloatArray> AsFloat(vtkDataArray* array)
{
  if (auto* floats = vtkFloatArray::FastDownCast(array))
  {
    return floats;
  }
  auto converted = vtkSmartPointer<vtkFloatArray>::New();
  converted->DeepCopy(array);
  return converted;
}
}

//------------------------------------------------------------------------------
vtkGaussianSplatReader::vtkGaussianSplatReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkGaussianSplatReader::~vtkGaussianSplatReader()
{
  this->SetFileName(nullptr);
}

//------------------------------------------------------------------------------
bool vtkGaussianSplatReader::IsGaussianSplatFile(const char* fileName)
{
  if (!fileName)
  {
    return false;
  }
  // The first bytes of the file hold this text (the JSON of a glTF or a SOG's meta.json).
  const auto mentions = [fileName](const char* text)
  {
    std::ifstream in(fileName, std::ios::binary);
    std::string head(1 << 20, '\0');
    in.read(&head[0], static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    return head.find(text) != std::string::npos;
  };
  switch (Identify(fileName))
  {
    case Format::Unknown:
      return false;
    case Format::GLTF:
      return mentions("KHR_gaussian_splatting"); // other glTF files are meshes
    case Format::SOG:
      return vtksys::SystemTools::LowerCase(
               vtksys::SystemTools::GetFilenameLastExtension(fileName)) == ".sog" ||
        mentions("\"means\"");
    case Format::Splat:
    {
      const unsigned long size = vtksys::SystemTools::FileLength(fileName);
      return size > 0 && size % SplatRecordSize == 0;
    }
    default:
      return true;
  }
}

//------------------------------------------------------------------------------
int vtkGaussianSplatReader::CanReadFile(const char* fileName)
{
  return vtkGaussianSplatReader::IsGaussianSplatFile(fileName) ? 1 : 0;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatReader::Fail(int errorCode, const std::string& what)
{
  vtkErrorMacro(<< this->FileName << ": " << what);
  this->SetErrorCode(errorCode);
}

//------------------------------------------------------------------------------
int vtkGaussianSplatReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  this->SetErrorCode(vtkErrorCode::NoError);
  this->SphericalHarmonicsDegree = -1;
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro("No FileName given.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return 0;
  }
  this->UpdateProgress(0.0);
  vtkNew<vtkPolyData> result;
  bool ok = true;
  try
  {
    const std::string name = this->FileName;
    const splatcapture::Progress progress = [this](double fraction) { this->UpdateProgress(fraction); };
    switch (Identify(name))
    {
      case Format::PLY:
        ok = this->ReadPLY(result);
        break;
      case Format::Splat:
        ok = this->ReadSplat(result);
        break;
      case Format::CompressedPLY:
        ReadCompressedPLY(name, result, progress);
        break;
      case Format::SPZ:
        ReadSPZ(name, this->SPZFromRUB, result, progress);
        break;
      case Format::SOG:
        ReadSOG(name, result, progress);
        break;
      case Format::GLTF:
        ReadGLTF(name, result, progress);
        break;
      case Format::KSplat:
        ReadKSplat(name, result, progress);
        break;
      default:
        ok = this->ReadPLY(result); // reports what the file lacks
    }
  }
  catch (const ReadError& error)
  {
    this->Fail(error.Code, error.what());
    ok = false;
  }
  catch (const std::bad_alloc&)
  {
    this->Fail(vtkErrorCode::UnknownError, "out of memory");
    ok = false;
  }
  catch (const std::exception& e)
  {
    // A library's own exception on corrupt data (jsoncpp's on a value of the wrong type).
    this->Fail(vtkErrorCode::FileFormatError, std::string("corrupt file: ") + e.what());
    ok = false;
  }
  if (!ok)
  {
    this->SphericalHarmonicsDegree = -1;
    return 0;
  }
  output->ShallowCopy(result);
  vtkDataArray* harmonics = output->GetPointData()->GetArray("SphericalHarmonics");
  this->SphericalHarmonicsDegree =
    harmonics ? static_cast<int>(std::lround(std::sqrt(harmonics->GetNumberOfComponents() / 3.0))) - 1
              : 0;
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkGaussianSplatReader::ReadPLY(vtkPolyData* output)
{
  // Reading the PLY file is most of the work; the conversion follows.
  vtkSmartPointer<vtkPolyData> vertices =
    ReadPLYFile(this->FileName, false, [this](double f) { this->UpdateProgress(0.8 * f); });
  vtkPointData* properties = vertices->GetPointData();
  // x, y and z are the points; the other properties are point-data arrays.
  for (auto name = std::begin(PLYProperties) + 3; name != std::end(PLYProperties);
       ++name)
  {
    if (!properties->GetArray(*name))
    {
      this->Fail(vtkErrorCode::FileFormatError,
        std::string("not a 3D Gaussian Splatting PLY file: the vertex element has no property '") +
          *name + "'");
      return false;
    }
  }
  // f_rest_0 .. f_rest_(n-1), with no gap and nothing beyond.
  int rest = 0;
  while (properties->GetArray(("f_rest_" + std::to_string(rest)).c_str()))
  {
    ++rest;
  }
  int named = 0;
  for (int i = 0; i < properties->GetNumberOfArrays(); ++i)
  {
    const char* name = properties->GetArrayName(i);
    named += name && std::string(name).rfind("f_rest_", 0) == 0;
  }
  int degree = 0;
  while (degree < 3 && 3 * ((degree + 1) * (degree + 1) - 1) < rest)
  {
    ++degree;
  }
  if (named != rest || 3 * ((degree + 1) * (degree + 1) - 1) != rest)
  {
    this->Fail(vtkErrorCode::FileFormatError,
      "the vertex element has " + std::to_string(named) +
        " f_rest properties; spherical harmonics of degree 1, 2 or 3 need f_rest_0 .. f_rest_8, "
        "f_rest_0 .. f_rest_23 or f_rest_0 .. f_rest_44");
    return false;
  }

  const vtkIdType n = vertices->GetNumberOfPoints();
  // The float values of each property (converted when stored in another type).
  std::vector<vtkSmartPointer<vtkFloatArray>> keep;
  auto column = [properties, &keep](const std::string& name)
  {
    keep.push_back(AsFloat(properties->GetArray(name.c_str())));
    return static_cast<const float*>(keep.back()->GetPointer(0));
  };
  std::vector<const float*> dc, scales, rotations, coefficients;
  for (int c = 0; c < 3; ++c)
  {
    dc.push_back(column("f_dc_" + std::to_string(c)));
    scales.push_back(column("scale_" + std::to_string(c)));
  }
  for (int c = 0; c < 4; ++c)
  {
    rotations.push_back(column("rot_" + std::to_string(c)));
  }
  for (int k = 0; k < rest; ++k)
  {
    coefficients.push_back(column("f_rest_" + std::to_string(k)));
  }
  const float* logit = column("opacity");

  vtkDataArray* points = vertices->GetPoints()->GetData();
  Kernels kernels(n, degree);
  const int perChannel = rest / 3;
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        double p[3];
        points->GetTuple(i, p);
        kernels.SetPosition(i, static_cast<float>(p[0]), static_cast<float>(p[1]),
          static_cast<float>(p[2]));
        kernels.SetRotation(i, rotations[0][i], rotations[1][i], rotations[2][i], rotations[3][i]);
        kernels.SetOpacityLogit(i, logit[i]);
        kernels.SetLogScale(i, scales[0][i], scales[1][i], scales[2][i]);
        kernels.SetDC(i, dc[0][i], dc[1][i], dc[2][i]);
        // The file stores f_rest channel-major.
        for (int c = 0; c < 3 && rest; ++c)
        {
          for (int k = 0; k < perChannel; ++k)
          {
            kernels.SetRest(i, k + 1, c, coefficients[c * perChannel + k][i]);
          }
        }
      }
    });
  kernels.MoveTo(output);
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianSplatReader::ReadSplat(vtkPolyData* output)
{
  std::ifstream in(this->FileName, std::ios::binary | std::ios::ate);
  if (!in)
  {
    this->Fail(vtkErrorCode::CannotOpenFileError, "cannot open the file");
    return false;
  }
  const std::streamoff size = in.tellg();
  if (size <= 0 || size % SplatRecordSize != 0)
  {
    this->Fail(vtkErrorCode::FileFormatError,
      "a .splat file holds 32-byte records, but its size is " + std::to_string(size) +
        " bytes (truncated?)");
    return false;
  }
  in.seekg(0);
  const vtkIdType n = static_cast<vtkIdType>(size / SplatRecordSize);
  Kernels kernels(n, 0);
  const vtkIdType batch = 1 << 16;
  std::vector<char> records;
  for (vtkIdType first = 0; first < n; first += batch)
  {
    const vtkIdType count = std::min(batch, n - first);
    records.resize(static_cast<std::size_t>(count) * SplatRecordSize);
    if (!in.read(records.data(), static_cast<std::streamsize>(records.size())))
    {
      this->Fail(vtkErrorCode::PrematureEndOfFileError,
        "byte " + std::to_string(first * SplatRecordSize + in.gcount()) +
          ": the file ends early (it was shorter than its size said)");
      return false;
    }
    for (vtkIdType r = 0; r < count; ++r)
    {
      const char* record = records.data() + r * SplatRecordSize;
      const vtkIdType i = first + r;
      float values[6];
      std::copy(record, record + sizeof(values), reinterpret_cast<char*>(values));
      vtkByteSwap::Swap4LERange(values, 6);
      kernels.SetPosition(i, values[0], values[1], values[2]);
      kernels.SetScale(i, values[3], values[4], values[5]);
      const auto* bytes = reinterpret_cast<const unsigned char*>(record + 24);
      kernels.SetColor(i, bytes[0] / 255.0f, bytes[1] / 255.0f, bytes[2] / 255.0f);
      kernels.SetOpacity(i, bytes[3] / 255.0f);
      kernels.SetRotation(i, (bytes[4] - 128.0f) / 128.0f, (bytes[5] - 128.0f) / 128.0f,
        (bytes[6] - 128.0f) / 128.0f, (bytes[7] - 128.0f) / 128.0f);
    }
    this->UpdateProgress(static_cast<double>(first + count) / n);
  }
  kernels.MoveTo(output);
  return true;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "SPZFromRUB: " << (this->SPZFromRUB ? "On" : "Off") << "\n";
  os << indent << "SphericalHarmonicsDegree: " << this->SphericalHarmonicsDegree << "\n";
}
