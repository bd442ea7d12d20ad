// SPDX-License-Identifier: BSD-3-Clause
// GaussianSplats3D's .ksplat: a 4096-byte header, 1024-byte section headers, then per section
// the bucket sizes and centers and the Gaussians, as floats (compression level 0) or as
// positions relative to their bucket's center in 16 bits with half floats (level 1) and byte
// spherical harmonics (level 2).
#include "SplatCaptureFormats.h"

#include "vtkErrorCode.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

namespace splatcapture
{
namespace
{
constexpr std::size_t HeaderSize = 4096;
constexpr std::size_t SectionHeaderSize = 1024;
constexpr std::uint32_t MaxGaussians = 1u << 28;

struct Section
{
  std::uint32_t Count, Capacity, BucketSize, Buckets, FullBuckets, PartialBuckets;
  float BlockSize;
  std::uint32_t BucketBytes, ScaleRange;
  int Degree;
};

// Bytes per Gaussian of a compression level with `rest` spherical-harmonic values.
std::size_t RecordSize(int level, int rest)
{
  return level == 0 ? 44 + 4 * rest : level == 1 ? 24 + 2 * rest : 24 + rest;
}

// Stored index i of the coefficients (band by band, channel-major in a band) as the INRIA
// coefficient (1-based) and channel.
void Coefficient(int i, int& k, int& channel)
{
  const int band = i < 9 ? 1 : i < 24 ? 2 : 3;
  const int first = band == 1 ? 0 : band == 2 ? 9 : 24;
  const int width = 2 * band + 1;
  channel = (i - first) / width;
  k = band * band + (i - first) % width; // 1 + (l^2 - 1) + m
}
}

//------------------------------------------------------------------------------
void ReadKSplat(const std::string& fileName, vtkPolyData* output, const Progress& progress)
{
  const std::vector<std::uint8_t> file = ReadFile(fileName, std::size_t(16) << 30);
  Bytes header(file.data(), file.size(), "the file");
  const int major = header.Read<std::uint8_t>("version");
  const int minor = header.Read<std::uint8_t>("version");
  if (major != 0 || minor < 1)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "not a .ksplat file of version 0.1 or later (version " + std::to_string(major) + "." +
        std::to_string(minor) + ")");
  }
  header.Skip(2, "header");
  const std::uint32_t sections = header.Read<std::uint32_t>("section count");
  header.Skip(8, "header");
  const std::uint32_t count = header.Read<std::uint32_t>("Gaussian count");
  const int level = header.Read<std::uint16_t>("compression level");
  header.Skip(2 + 12, "header");
  float shMin = header.Read<float>("coefficient range");
  float shMax = header.Read<float>("coefficient range");
  shMin = shMin == 0.0f ? -1.5f : shMin;
  shMax = shMax == 0.0f ? 1.5f : shMax;
  if (level > 2 || count > MaxGaussians || sections > (file.size() - HeaderSize) / SectionHeaderSize)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "the header announces " + std::to_string(count) + " Gaussians in " +
        std::to_string(sections) + " sections at compression level " + std::to_string(level) +
        ", which the file cannot hold");
  }
  std::vector<Section> layout(sections);
  int degree = 0;
  std::uint64_t total = 0;
  for (std::uint32_t s = 0; s < sections; ++s)
  {
    Bytes in(file.data() + HeaderSize + s * SectionHeaderSize, SectionHeaderSize, "a section header");
    Section& section = layout[s];
    section.Count = in.Read<std::uint32_t>("count");
    section.Capacity = in.Read<std::uint32_t>("capacity");
    section.BucketSize = in.Read<std::uint32_t>("bucket size");
    section.Buckets = in.Read<std::uint32_t>("bucket count");
    section.BlockSize = in.Read<float>("block size");
    section.BucketBytes = in.Read<std::uint16_t>("bucket storage");
    in.Skip(2, "padding");
    section.ScaleRange = in.Read<std::uint32_t>("scale range");
    in.Skip(4, "padding");
    section.FullBuckets = in.Read<std::uint32_t>("full buckets");
    section.PartialBuckets = in.Read<std::uint32_t>("partial buckets");
    section.Degree = in.Read<std::uint16_t>("degree");
    if (section.ScaleRange == 0)
    {
      section.ScaleRange = level == 0 ? 1 : 32767;
    }
    if (section.Degree > 3 || section.Count > section.Capacity ||
      section.PartialBuckets > section.Buckets ||
      (level > 0 && section.Buckets > 0 && section.BucketBytes < 12))
    {
      throw ReadError(vtkErrorCode::FileFormatError,
        "section " + std::to_string(s) + "'s header is corrupt");
    }
    degree = std::max(degree, section.Degree);
    total += section.Count;
  }
  if (total != count)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "the sections hold " + std::to_string(total) + " Gaussians, the header announces " +
        std::to_string(count));
  }

  Kernels kernels(count, degree);
  Bytes data(file.data(), file.size(), "the file");
  data.Skip(HeaderSize + static_cast<std::size_t>(sections) * SectionHeaderSize, "section headers");
  vtkIdType next = 0;
  for (std::uint32_t s = 0; s < sections; ++s)
  {
    const Section& section = layout[s];
    const int rest = 3 * RestCoefficients(section.Degree);
    std::vector<std::uint32_t> partial(section.PartialBuckets);
    for (std::uint32_t& size : partial)
    {
      size = data.Read<std::uint32_t>("bucket sizes");
    }
    const std::uint8_t* centers =
      data.Take(static_cast<std::size_t>(section.BucketBytes) * section.Buckets, "bucket centers");
    const std::size_t record = RecordSize(level, rest);
    const std::uint8_t* records =
      data.Take(record * section.Capacity, "Gaussians");
    const float unit = section.BlockSize / 2.0f / static_cast<float>(section.ScaleRange);
    // The end of each bucket's Gaussians: full buckets first, then the partial ones in order.
    std::vector<std::uint64_t> bucketEnds;
    for (std::uint64_t b = 0, end = 0; level > 0 && b < section.Buckets; ++b)
    {
      end += b < section.FullBuckets ? section.BucketSize
        : b - section.FullBuckets < partial.size() ? partial[b - section.FullBuckets]
                                                   : 0;
      bucketEnds.push_back(end);
    }
    if (level > 0 && (bucketEnds.empty() || bucketEnds.back() < section.Count))
    {
      throw ReadError(vtkErrorCode::FileFormatError,
        "section " + std::to_string(s) + " has more Gaussians than its buckets hold");
    }
    const vtkIdType first = next;
    vtkSMPTools::For(0, section.Count,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType j = begin; j < end; ++j)
        {
          const vtkIdType at = first + j;
          const auto bucket = level > 0 ? std::upper_bound(bucketEnds.begin(), bucketEnds.end(),
                                            static_cast<std::uint64_t>(j)) -
              bucketEnds.begin()
                                        : 0;
          Bytes in(records + record * j, record, "a Gaussian");
          float p[3], scale[3], q[4];
          if (level == 0)
          {
            for (float& v : p)
            {
              v = in.Read<float>("position");
            }
            for (float& v : scale)
            {
              v = in.Read<float>("scale");
            }
            for (float& v : q)
            {
              v = in.Read<float>("rotation");
            }
          }
          else
          {
            for (int a = 0; a < 3; ++a)
            {
              float center;
              std::memcpy(&center, centers + section.BucketBytes * bucket + 4 * a, 4);
              const int u = in.Read<std::uint16_t>("position");
              p[a] = (u - static_cast<float>(section.ScaleRange)) * unit + center;
            }
            for (float& v : scale)
            {
              v = HalfToFloat(in.Read<std::uint16_t>("scale"));
            }
            for (float& v : q)
            {
              v = HalfToFloat(in.Read<std::uint16_t>("rotation"));
            }
          }
          kernels.SetPosition(at, p[0], p[1], p[2]);
          kernels.SetScale(at, scale[0], scale[1], scale[2]);
          kernels.SetRotation(at, q[0], q[1], q[2], q[3]);
          const std::uint8_t* rgba = in.Take(4, "color");
          kernels.SetColor(at, rgba[0] / 255.0f, rgba[1] / 255.0f, rgba[2] / 255.0f);
          kernels.SetOpacity(at, rgba[3] / 255.0f);
          for (int i = 0; i < rest; ++i)
          {
            const float value = level == 0 ? in.Read<float>("coefficients")
              : level == 1
              ? HalfToFloat(in.Read<std::uint16_t>("coefficients"))
              : shMin + in.Read<std::uint8_t>("coefficients") / 255.0f * (shMax - shMin);
            int k, channel;
            Coefficient(i, k, channel);
            kernels.SetRest(at, k, channel, value);
          }
        }
      });
    next += section.Count;
    progress(static_cast<double>(s + 1) / sections);
  }
  kernels.MoveTo(output);
}
}
