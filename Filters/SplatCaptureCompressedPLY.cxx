// SPDX-License-Identifier: BSD-3-Clause
// PlayCanvas's compressed .ply: chunks of 256 Gaussians, each with the ranges of its positions,
// log scales and colors, and per Gaussian four packed 32-bit words (position and scale 11-10-11
// bits, rotation as the smallest three, color and opacity 8 bits each) and, optionally, the
// spherical harmonics as one byte per INRIA f_rest value.
#include "SplatCaptureFormats.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedIntArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <cmath>

namespace splatcapture
{
namespace
{
constexpr vtkIdType ChunkSize = 256;

// Bits `bits` wide at `shift` of `word`, as a fraction of their largest value.
float Unorm(std::uint32_t word, int shift, int bits)
{
  const std::uint32_t mask = (1u << bits) - 1;
  return static_cast<float>((word >> shift) & mask) / static_cast<float>(mask);
}

float Lerp(float a, float b, float t)
{
  return a * (1.0f - t) + b * t;
}

// The properties of the file's elements, by element.property name.
class Columns
{
public:
  explicit Columns(vtkFieldData* fields)
    : Fields(fields)
  {
  }

  // The values of `name`, which must be there, of type T, with `count` records.
  template <typename ArrayT>
  const typename ArrayT::ValueType* Get(const std::string& name, vtkIdType count) const
  {
    vtkDataArray* array = this->Fields->GetArray(name.c_str());
    if (!array)
    {
      throw ReadError(vtkErrorCode::FileFormatError,
        "not a compressed 3DGS PLY file: it has no property '" + name + "'");
    }
    auto* typed = ArrayT::FastDownCast(array);
    if (!typed || array->GetNumberOfTuples() != count)
    {
      vtkNew<ArrayT> expected;
      throw ReadError(vtkErrorCode::FileFormatError,
        "the property '" + name + "' has " + std::to_string(array->GetNumberOfTuples()) + " " +
          array->GetDataTypeAsString() + " values where " + std::to_string(count) + " " +
          expected->GetDataTypeAsString() + " were expected");
    }
    return typed->GetPointer(0);
  }

  bool Has(const std::string& name) const { return this->Fields->GetArray(name.c_str()); }

private:
  vtkFieldData* Fields;
};
}

//------------------------------------------------------------------------------
void ReadCompressedPLY(const std::string& fileName, vtkPolyData* output, const Progress& progress)
{
  vtkSmartPointer<vtkPolyData> elements =
    ReadPLYFile(fileName, true, [&progress](double f) { progress(0.6 * f); });
  progress(0.6);
  const Columns columns(elements->GetFieldData());
  vtkDataArray* positions = elements->GetFieldData()->GetArray("vertex.packed_position");
  const vtkIdType n = positions ? positions->GetNumberOfTuples() : 0;
  const vtkIdType chunks = (n + ChunkSize - 1) / ChunkSize;
  std::vector<const std::uint32_t*> words;
  for (const char* name : { "position", "rotation", "scale", "color" })
  {
    words.push_back(columns.Get<vtkUnsignedIntArray>(std::string("vertex.packed_") + name, n));
  }
  // Minimum and maximum of position, log scale and color per axis. Older files have no color
  // range: their colors are the bytes themselves.
  const bool colorRange = columns.Has("chunk.min_r");
  const char* const axes[] = { "x", "y", "z", "scale_x", "scale_y", "scale_z", "r", "g", "b" };
  std::vector<const float*> minimum, maximum;
  for (int a = 0; a < (colorRange ? 9 : 6); ++a)
  {
    minimum.push_back(columns.Get<vtkFloatArray>(std::string("chunk.min_") + axes[a], chunks));
    maximum.push_back(columns.Get<vtkFloatArray>(std::string("chunk.max_") + axes[a], chunks));
  }
  // The spherical harmonics: 9, 24 or 45 bytes in the INRIA order.
  int rest = 0;
  while (columns.Has("sh.f_rest_" + std::to_string(rest)))
  {
    ++rest;
  }
  int degree = 0;
  while (degree < 3 && 3 * RestCoefficients(degree) < rest)
  {
    ++degree;
  }
  if (3 * RestCoefficients(degree) != rest)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "the sh element has " + std::to_string(rest) +
        " f_rest properties; degree 1, 2 or 3 needs 9, 24 or 45");
  }
  std::vector<const unsigned char*> harmonics;
  for (int k = 0; k < rest; ++k)
  {
    harmonics.push_back(columns.Get<vtkUnsignedCharArray>("sh.f_rest_" + std::to_string(k), n));
  }

  Kernels kernels(n, degree);
  const int perChannel = RestCoefficients(degree);
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const vtkIdType chunk = i / ChunkSize;
        const auto range = [&](int axis, float t)
        { return Lerp(minimum[axis][chunk], maximum[axis][chunk], t); };
        const std::uint32_t position = words[0][i];
        kernels.SetPosition(i, range(0, Unorm(position, 21, 11)),
          range(1, Unorm(position, 11, 10)), range(2, Unorm(position, 0, 11)));
        const std::uint32_t scale = words[2][i];
        kernels.SetLogScale(i, range(3, Unorm(scale, 21, 11)), range(4, Unorm(scale, 11, 10)),
          range(5, Unorm(scale, 0, 11)));
        // The smallest three of (w, x, y, z), the largest's index in the top two bits.
        const std::uint32_t rotation = words[1][i];
        const int largest = static_cast<int>(rotation >> 30);
        float q[4];
        double sum = 0.0;
        for (int c = 0, shift = 20; c < 4; ++c)
        {
          if (c != largest)
          {
            q[c] = (Unorm(rotation, shift, 10) - 0.5f) * 1.41421356237309515f;
            sum += static_cast<double>(q[c]) * q[c];
            shift -= 10;
          }
        }
        q[largest] = static_cast<float>(std::sqrt(std::max(0.0, 1.0 - sum)));
        kernels.SetRotation(i, q[0], q[1], q[2], q[3]);
        const std::uint32_t color = words[3][i];
        float rgb[3];
        for (int c = 0; c < 3; ++c)
        {
          const float t = Unorm(color, 24 - 8 * c, 8);
          rgb[c] = colorRange ? range(6 + c, t) : t;
        }
        kernels.SetColor(i, rgb[0], rgb[1], rgb[2]);
        kernels.SetOpacity(i, Unorm(color, 0, 8));
        for (int c = 0; c < 3 && rest; ++c)
        {
          for (int k = 0; k < perChannel; ++k)
          {
            const double b = harmonics[c * perChannel + k][i];
            const double unit = b == 0.0 ? 0.0 : b == 255.0 ? 1.0 : (b + 0.5) / 256.0;
            kernels.SetRest(i, k + 1, c, static_cast<float>((unit - 0.5) * 8.0));
          }
        }
      }
    });
  kernels.MoveTo(output);
}
}
