// SPDX-License-Identifier: BSD-3-Clause
#include "vtkGaussianSplatWriter.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkGaussianSplatWriter);

namespace
{
constexpr double C0 = 0.28209479177387814;

void Put(std::vector<char>& out, double value)
{
  const float f = static_cast<float>(value);
  char bytes[4];
  std::memcpy(bytes, &f, 4);
#if VTK_WORDS_BIGENDIAN
  std::reverse(bytes, bytes + 4);
#endif
  out.insert(out.end(), bytes, bytes + 4);
}
}

//------------------------------------------------------------------------------
vtkGaussianSplatWriter::vtkGaussianSplatWriter() = default;

//------------------------------------------------------------------------------
vtkGaussianSplatWriter::~vtkGaussianSplatWriter()
{
  this->SetFileName(nullptr);
}

//------------------------------------------------------------------------------
int vtkGaussianSplatWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  auto* input = vtkPointSet::SafeDownCast(this->GetInput());
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro("No FileName given.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  const vtkIdType n = input ? input->GetNumberOfPoints() : 0;
  vtkPointData* pointData = input ? input->GetPointData() : nullptr;
  // The arrays a kernel set must have, with their sizes.
  auto array = [&](const char* name, int components, bool required) -> vtkDataArray*
  {
    vtkDataArray* a = pointData ? pointData->GetArray(name) : nullptr;
    if (a && (a->GetNumberOfComponents() != components || a->GetNumberOfTuples() != n))
    {
      vtkErrorMacro(<< this->FileName << ": the array '" << name << "' has "
                    << a->GetNumberOfComponents() << " components, " << components
                    << " are needed");
      return nullptr;
    }
    if (!a && required)
    {
      vtkErrorMacro(<< this->FileName << ": the input has no point array '" << name
                    << "' (not a 3D Gaussian Splatting kernel set)");
    }
    return a;
  };
  vtkDataArray* harmonics = pointData ? pointData->GetArray("SphericalHarmonics") : nullptr;
  int degree = 0;
  if (harmonics)
  {
    const int components = harmonics->GetNumberOfComponents();
    while (degree < 3 && 3 * (degree + 1) * (degree + 1) < components)
    {
      ++degree;
    }
    harmonics = array("SphericalHarmonics", 3 * (degree + 1) * (degree + 1), true);
  }
  vtkDataArray* scale = array("Scale", 3, true);
  vtkDataArray* rotation = array("Rotation", 4, true);
  vtkDataArray* opacity = array("Opacity", 1, true);
  vtkDataArray* color = harmonics ? nullptr : array("Color", 3, true);
  if (!input || !scale || !rotation || !opacity || !(harmonics || color))
  {
    this->SetErrorCode(vtkErrorCode::FileFormatError);
    return;
  }

  std::ofstream out(this->FileName, std::ios::binary);
  if (!out)
  {
    vtkErrorMacro(<< this->FileName << ": cannot open the file for writing");
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return;
  }
  const int perChannel = (degree + 1) * (degree + 1) - 1;
  std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex " +
    std::to_string(n) + "\n";
  std::vector<std::string> names = { "x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1",
    "f_dc_2" };
  for (int k = 0; k < 3 * perChannel; ++k)
  {
    names.push_back("f_rest_" + std::to_string(k));
  }
  for (const char* name : { "opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1",
         "rot_2", "rot_3" })
  {
    names.emplace_back(name);
  }
  for (const std::string& name : names)
  {
    header += "property float " + name + "\n";
  }
  header += "end_header\n";
  out.write(header.data(), static_cast<std::streamsize>(header.size()));

  std::vector<char> block;
  const vtkIdType batch = 1 << 14;
  for (vtkIdType first = 0; first < n && out; first += batch)
  {
    block.clear();
    for (vtkIdType i = first; i < std::min(n, first + batch); ++i)
    {
      double p[3];
      input->GetPoint(i, p);
      for (double v : { p[0], p[1], p[2], 0.0, 0.0, 0.0 })
      {
        Put(block, v);
      }
      for (int c = 0; c < 3; ++c)
      {
        Put(block,
          harmonics ? harmonics->GetComponent(i, c) : (color->GetComponent(i, c) - 0.5) / C0);
      }
      // INRIA stores the coefficients channel-major; the arrays interleave the channels.
      for (int c = 0; c < 3; ++c)
      {
        for (int k = 1; k <= perChannel; ++k)
        {
          Put(block, harmonics->GetComponent(i, 3 * k + c));
        }
      }
      const double o = std::clamp(opacity->GetComponent(i, 0), 1e-7, 1.0 - 1e-7);
      Put(block, std::log(o / (1.0 - o)));
      for (int c = 0; c < 3; ++c)
      {
        Put(block, std::log(scale->GetComponent(i, c)));
      }
      for (int c = 0; c < 4; ++c)
      {
        Put(block, rotation->GetComponent(i, c));
      }
    }
    out.write(block.data(), static_cast<std::streamsize>(block.size()));
    this->UpdateProgress(static_cast<double>(std::min(n, first + batch)) / n);
  }
  if (!out)
  {
    vtkErrorMacro(<< this->FileName << ": writing failed (disk full?)");
    this->SetErrorCode(vtkErrorCode::OutOfDiskSpaceError);
  }
}

//------------------------------------------------------------------------------
void vtkGaussianSplatWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}
