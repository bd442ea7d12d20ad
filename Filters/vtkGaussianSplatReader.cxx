// SPDX-License-Identifier: BSD-3-Clause
#include "vtkGaussianSplatReader.h"

#include "vtkByteSwap.h"
#include "vtkCallbackCommand.h"
#include "vtkErrorCode.h"
#include "vtkExecutive.h"
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
// The degree-0 real spherical harmonic, 1 / (2 sqrt(pi)).
constexpr double C0 = 0.28209479177387814;
// Bytes of one .splat record.
constexpr int SplatRecordSize = 32;

// The vertex properties every 3DGS .ply has, in the groups of the output arrays.
const char* const RequiredProperties[] = { "x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2",
  "opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3" };

bool IsSplatName(const char* fileName)
{
  return vtksys::SystemTools::LowerCase(
           vtksys::SystemTools::GetFilenameLastExtension(fileName)) == ".splat";
}

vtkSmartPointer<vtkFloatArray> NewArray(const char* name, int components, vtkIdType tuples)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}

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

// Writes q / |q| (w, x, y, z) to `out`; a zero or non-finite quaternion is passed on as it is,
// for the mapper to skip and count.
void Normalize(const float q[4], float* out)
{
  const double norm = std::sqrt(static_cast<double>(q[0]) * q[0] +
    static_cast<double>(q[1]) * q[1] + static_cast<double>(q[2]) * q[2] +
    static_cast<double>(q[3]) * q[3]);
  const double scale = norm > 0.0 && std::isfinite(norm) ? 1.0 / norm : 1.0;
  for (int c = 0; c < 4; ++c)
  {
    out[c] = static_cast<float>(q[c] * scale);
  }
}

float BaseColor(float dc)
{
  return static_cast<float>(std::clamp(0.5 + C0 * dc, 0.0, 1.0));
}

void ForwardProgress(vtkObject* caller, unsigned long, void* clientData, void*)
{
  auto* reader = static_cast<vtkGaussianSplatReader*>(clientData);
  // Reading the PLY file is most of the work; the conversion follows.
  reader->UpdateProgress(0.8 * vtkAlgorithm::SafeDownCast(caller)->GetProgress());
}

// Keeps the first error message of vtkSplatPLYReader (or its executive) in the std::string
// `clientData`, without VTK's prefix, for this reader to report as its own.
void KeepError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* message = static_cast<std::string*>(clientData);
  if (message->empty())
  {
    const std::string text = static_cast<const char*>(callData);
    const std::size_t start = text.find("): ");
    *message = start == std::string::npos ? text : text.substr(start + 3);
    message->erase(message->find_last_not_of(" \n") + 1);
  }
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
  if (IsSplatName(fileName))
  {
    const unsigned long size = vtksys::SystemTools::FileLength(fileName);
    return size > 0 && size % SplatRecordSize == 0;
  }
  vtkNew<vtkStringArray> names;
  if (!vtkSplatPLYReader::GetVertexPropertyNames(fileName, names))
  {
    return false;
  }
  return std::all_of(std::begin(RequiredProperties), std::end(RequiredProperties),
    [&names](const char* name) { return names->LookupValue(name) >= 0; });
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
  bool ok;
  try
  {
    ok = IsSplatName(this->FileName) ? this->ReadSplat(result) : this->ReadPLY(result);
  }
  catch (const std::bad_alloc&)
  {
    this->Fail(vtkErrorCode::UnknownError, "out of memory");
    ok = false;
  }
  if (!ok)
  {
    this->SphericalHarmonicsDegree = -1;
    return 0;
  }
  output->ShallowCopy(result);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkGaussianSplatReader::ReadPLY(vtkPolyData* output)
{
  vtkNew<vtkSplatPLYReader> ply;
  ply->SetFileName(this->FileName);
  vtkNew<vtkCallbackCommand> progress;
  progress->SetCallback(ForwardProgress);
  progress->SetClientData(this);
  ply->AddObserver(vtkCommand::ProgressEvent, progress);
  std::string message;
  vtkNew<vtkCallbackCommand> errors;
  errors->SetCallback(KeepError);
  errors->SetClientData(&message);
  ply->AddObserver(vtkCommand::ErrorEvent, errors);
  ply->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  ply->Update();
  if (ply->GetErrorCode() != vtkErrorCode::NoError)
  {
    // vtkSplatPLYReader's message names the file, the place and the problem.
    const std::string prefix = std::string(this->FileName) + ": ";
    this->Fail(ply->GetErrorCode(),
      message.compare(0, prefix.size(), prefix) == 0 ? message.substr(prefix.size()) : message);
    return false;
  }
  vtkPolyData* vertices = ply->GetOutput();
  vtkPointData* properties = vertices->GetPointData();
  // x, y and z are the points; the other properties are point-data arrays.
  for (auto name = std::begin(RequiredProperties) + 3; name != std::end(RequiredProperties);
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

  auto scale = NewArray("Scale", 3, n);
  auto rotation = NewArray("Rotation", 4, n);
  auto opacity = NewArray("Opacity", 1, n);
  auto color = NewArray("Color", 3, n);
  const int perChannel = rest / 3;
  vtkSmartPointer<vtkFloatArray> harmonics =
    rest ? NewArray("SphericalHarmonics", 3 * (perChannel + 1), n) : nullptr;
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        float q[4];
        for (int c = 0; c < 4; ++c)
        {
          q[c] = rotations[c][i];
        }
        Normalize(q, rotation->GetPointer(4 * i));
        opacity->SetValue(i, static_cast<float>(1.0 / (1.0 + std::exp(-logit[i]))));
        for (int c = 0; c < 3; ++c)
        {
          scale->SetValue(3 * i + c, std::exp(scales[c][i]));
          color->SetValue(3 * i + c, BaseColor(dc[c][i]));
        }
        if (harmonics)
        {
          // The file stores f_rest channel-major; the output interleaves the channels.
          float* out = harmonics->GetPointer(3 * (perChannel + 1) * i);
          for (int c = 0; c < 3; ++c)
          {
            out[c] = dc[c][i];
            for (int k = 0; k < perChannel; ++k)
            {
              out[3 * (k + 1) + c] = coefficients[c * perChannel + k][i];
            }
          }
        }
      }
    });
  output->SetPoints(vertices->GetPoints());
  vtkPointData* pointData = output->GetPointData();
  for (vtkFloatArray* array : { scale.Get(), rotation.Get(), opacity.Get(), color.Get() })
  {
    pointData->AddArray(array);
  }
  if (harmonics)
  {
    pointData->AddArray(harmonics);
  }
  this->SphericalHarmonicsDegree = degree;
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
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(n);
  auto* position = vtkFloatArray::FastDownCast(points->GetData());
  auto scale = NewArray("Scale", 3, n);
  auto rotation = NewArray("Rotation", 4, n);
  auto opacity = NewArray("Opacity", 1, n);
  auto color = NewArray("Color", 3, n);

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
      std::copy(values, values + 3, position->GetPointer(3 * i));
      std::copy(values + 3, values + 6, scale->GetPointer(3 * i));
      const auto* bytes = reinterpret_cast<const unsigned char*>(record + 24);
      for (int c = 0; c < 3; ++c)
      {
        color->SetValue(3 * i + c, bytes[c] / 255.0f);
      }
      opacity->SetValue(i, bytes[3] / 255.0f);
      float q[4];
      for (int c = 0; c < 4; ++c)
      {
        q[c] = (bytes[4 + c] - 128.0f) / 128.0f;
      }
      Normalize(q, rotation->GetPointer(4 * i));
    }
    this->UpdateProgress(static_cast<double>(first + count) / n);
  }
  output->SetPoints(points);
  vtkPointData* pointData = output->GetPointData();
  for (vtkFloatArray* array : { scale.Get(), rotation.Get(), opacity.Get(), color.Get() })
  {
    pointData->AddArray(array);
  }
  this->SphericalHarmonicsDegree = 0;
  return true;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "SphericalHarmonicsDegree: " << this->SphericalHarmonicsDegree << "\n";
}
