// SPDX-License-Identifier: BSD-3-Clause
// Niantic's .spz: versions 2 and 3 (one gzip stream) and 4 (a plain header, a table of contents
// and one zstd stream per attribute). The values are taken as stored, in the frame of the
// INRIA .ply, as splat-transform and the web viewers write and read them, or, on request, as
// the right-up-back frame the format's README names, turned into the .ply's.
#include "SplatCaptureFormats.h"

#include "vtkErrorCode.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <zstd.h>

#include <cmath>

namespace splatcapture
{
namespace
{
constexpr std::uint32_t Magic = 0x5053474e; // "NGSP"
// More Gaussians than any capture has; bounds what a corrupt count could allocate.
constexpr std::uint32_t MaxGaussians = 1u << 28;
constexpr int LegacyHeaderSize = 16;

struct Header
{
  std::uint32_t Version = 0;
  std::uint32_t Count = 0;
  int Degree = 0;
  int FractionalBits = 0;
  int Flags = 0;
};

// Bytes per Gaussian of each attribute stream, in file order: positions, alphas, colors,
// scales, rotations, spherical harmonics.
std::array<std::size_t, 6> StreamSizes(const Header& header)
{
  const std::size_t rest = static_cast<std::size_t>(RestCoefficients(header.Degree)) * 3;
  return { 9, 1, 3, 3, header.Version >= 3 ? 4u : 3u, rest };
}

Header ReadHeader(Bytes& in)
{
  if (in.Read<std::uint32_t>("magic number") != Magic)
  {
    throw ReadError(vtkErrorCode::UnrecognizedFileTypeError, "not an SPZ file (no NGSP magic number)");
  }
  Header header;
  header.Version = in.Read<std::uint32_t>("version");
  header.Count = in.Read<std::uint32_t>("number of Gaussians");
  header.Degree = in.Read<std::uint8_t>("spherical-harmonics degree");
  header.FractionalBits = in.Read<std::uint8_t>("fractional bits");
  header.Flags = in.Read<std::uint8_t>("flags");
  if (header.Version < 2 || header.Version > 4)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "SPZ version " + std::to_string(header.Version) + " (versions 2 to 4 are read)");
  }
  if (header.Degree > 3)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "spherical harmonics of degree " + std::to_string(header.Degree) + " (0 to 3 are read)");
  }
  if (header.FractionalBits > 24)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      std::to_string(header.FractionalBits) + " fractional bits in 24-bit positions");
  }
  if (header.Count > MaxGaussians)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "the header announces " + std::to_string(header.Count) + " Gaussians, more than " +
        std::to_string(MaxGaussians));
  }
  return header;
}

// The attribute streams of a version 4 file, each decompressed and checked against its size.
std::vector<std::vector<std::uint8_t>> ReadStreams(Bytes& in, const Header& header)
{
  const int streams = in.Read<std::uint8_t>("number of streams");
  const std::uint32_t tocOffset = in.Read<std::uint32_t>("table of contents offset");
  const auto sizes = StreamSizes(header);
  const int expected = header.Degree > 0 ? 6 : 5;
  if (streams != expected)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      std::to_string(streams) + " attribute streams where " + std::to_string(expected) +
        " were expected");
  }
  if (tocOffset < 32 || tocOffset > in.Offset() + in.Remaining())
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "the table of contents offset " + std::to_string(tocOffset) + " is outside the file");
  }
  in.Skip(tocOffset - in.Offset(), "header extensions");
  std::vector<std::pair<std::uint64_t, std::uint64_t>> toc(streams);
  for (auto& entry : toc)
  {
    entry.first = in.Read<std::uint64_t>("table of contents");
    entry.second = in.Read<std::uint64_t>("table of contents");
  }
  std::vector<std::vector<std::uint8_t>> out(6);
  for (int s = 0; s < streams; ++s)
  {
    const std::uint64_t size = sizes[s] * header.Count;
    if (toc[s].second != size || toc[s].first > in.Remaining())
    {
      throw ReadError(vtkErrorCode::FileFormatError,
        "stream " + std::to_string(s) + " holds " + std::to_string(toc[s].second) + " bytes in " +
          std::to_string(toc[s].first) + " compressed ones, where " + std::to_string(size) +
          " bytes in at most " + std::to_string(in.Remaining()) + " were expected");
    }
    const std::uint8_t* compressed = in.Take(toc[s].first, "attribute stream");
    out[s].resize(size);
    const std::size_t got = ZSTD_decompress(out[s].data(), size, compressed, toc[s].first);
    if (ZSTD_isError(got) || got != size)
    {
      throw ReadError(vtkErrorCode::FileFormatError,
        "stream " + std::to_string(s) + " does not decompress to its " + std::to_string(size) +
          " bytes" + (ZSTD_isError(got) ? std::string(" (zstd: ") + ZSTD_getErrorName(got) + ")" : ""));
    }
  }
  return out;
}


void Decode(const Header& header, const std::array<const std::uint8_t*, 6>& streams,
  bool fromRUB, Kernels& kernels, const Progress& progress)
{
  // RUB to the .ply's right-down-forward: a half turn about x. An orientation may take it on
  // either side (Q R or Q R Q^T draw the same Gaussian for a diagonal Q); the latter keeps w.
  const float flip = fromRUB ? -1.0f : 1.0f;
  const double halfTurn[3][3] = { { 1, 0, 0 }, { 0, -1, 0 }, { 0, 0, -1 } };
  const HarmonicsTurn colorTurn(halfTurn, header.Degree);
  const float unit = 1.0f / static_cast<float>(1 << header.FractionalBits);
  const int perChannel = RestCoefficients(header.Degree);
  const vtkIdType n = header.Count;
  const vtkIdType block = 1 << 16;
  for (vtkIdType first = 0; first < n; first += block)
  {
    vtkSMPTools::For(first, std::min(n, first + block),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          float p[3];
          for (int c = 0; c < 3; ++c)
          {
            const std::uint8_t* b = streams[0] + 9 * i + 3 * c;
            std::int32_t v = b[0] | (b[1] << 8) | (b[2] << 16);
            v = (v & 0x800000) ? v - (1 << 24) : v;
            p[c] = static_cast<float>(v) * unit;
          }
          kernels.SetPosition(i, p[0], flip * p[1], flip * p[2]);
          kernels.SetOpacity(i, streams[1][i] / 255.0f);
          const std::uint8_t* color = streams[2] + 3 * i;
          kernels.SetDC(i, (color[0] / 255.0f - 0.5f) / 0.15f, (color[1] / 255.0f - 0.5f) / 0.15f,
            (color[2] / 255.0f - 0.5f) / 0.15f);
          const std::uint8_t* scale = streams[3] + 3 * i;
          kernels.SetLogScale(
            i, scale[0] / 16.0f - 10.0f, scale[1] / 16.0f - 10.0f, scale[2] / 16.0f - 10.0f);
          float q[4]; // x, y, z, w
          if (header.Version >= 3)
          {
            // The smallest three: the largest component's index in the top two bits, then
            // the others, first at the highest bits, as sign and 9-bit magnitude.
            const std::uint8_t* r = streams[4] + 4 * i;
            std::uint32_t bits = r[0] | (r[1] << 8) | (r[2] << 16) | (std::uint32_t(r[3]) << 24);
            const int largest = static_cast<int>(bits >> 30);
            double sum = 0.0;
            for (int c = 3; c >= 0; --c)
            {
              if (c != largest)
              {
                const float magnitude = (bits & 511) / 511.0f * 0.70710678118654752f;
                q[c] = (bits & 512) ? -magnitude : magnitude;
                sum += static_cast<double>(q[c]) * q[c];
                bits >>= 10;
              }
            }
            q[largest] = static_cast<float>(std::sqrt(std::max(0.0, 1.0 - sum)));
          }
          else
          {
            const std::uint8_t* r = streams[4] + 3 * i;
            double sum = 0.0;
            for (int c = 0; c < 3; ++c)
            {
              q[c] = r[c] / 127.5f - 1.0f;
              sum += static_cast<double>(q[c]) * q[c];
            }
            q[3] = static_cast<float>(std::sqrt(std::max(0.0, 1.0 - sum)));
          }
          kernels.SetRotation(i, q[3], q[0], flip * q[1], flip * q[2]);
          // Coefficient-major with the channels inside, as the output.
          const std::uint8_t* sh = streams[5] + static_cast<std::size_t>(3 * perChannel) * i;
          for (int k = 0; k < perChannel; ++k)
          {
            for (int c = 0; c < 3; ++c)
            {
              kernels.SetRest(i, k + 1, c, (sh[3 * k + c] - 128.0f) / 128.0f);
            }
          }
          if (fromRUB)
          {
            kernels.TurnRest(i, colorTurn);
          }
        }
      });
    progress(0.3 + 0.7 * static_cast<double>(std::min(n, first + block)) / std::max<vtkIdType>(n, 1));
  }
}
}

//------------------------------------------------------------------------------
void ReadSPZ(
  const std::string& fileName, bool fromRUB, vtkPolyData* output, const Progress& progress)
{
  // The largest file of MaxGaussians Gaussians (under 100 bytes each) fits in 32 GiB.
  const std::vector<std::uint8_t> file = ReadFile(fileName, std::size_t(32) << 30);
  progress(0.1);
  std::vector<std::uint8_t> inflated;
  std::vector<std::vector<std::uint8_t>> streams;
  Header header;
  std::array<const std::uint8_t*, 6> starts{};
  if (file.size() >= 2 && file[0] == 0x1f && file[1] == 0x8b)
  {
    // Versions 2 and 3: the header's count bounds what the stream may inflate to.
    std::vector<std::uint8_t> head = Gunzip(file.data(), file.size(), LegacyHeaderSize, true);
    Bytes headerBytes(head.data(), head.size(), "the SPZ header");
    header = ReadHeader(headerBytes);
    if (header.Version == 4)
    {
      throw ReadError(vtkErrorCode::FileFormatError, "a gzip-compressed SPZ of version 4");
    }
    headerBytes.Skip(1, "reserved byte");
    std::size_t total = LegacyHeaderSize;
    for (std::size_t size : StreamSizes(header))
    {
      total += size * header.Count;
    }
    inflated = Gunzip(file.data(), file.size(), total, false);
    if (inflated.size() < total)
    {
      throw ReadError(vtkErrorCode::PrematureEndOfFileError,
        "the data inflates to " + std::to_string(inflated.size()) + " bytes, " +
          "less than the " + std::to_string(total) + " its header announces (truncated file)");
    }
    std::size_t offset = LegacyHeaderSize;
    const auto sizes = StreamSizes(header);
    for (int s = 0; s < 6; ++s)
    {
      starts[s] = inflated.data() + offset;
      offset += sizes[s] * header.Count;
    }
  }
  else
  {
    Bytes in(file.data(), file.size(), "the file");
    header = ReadHeader(in);
    if (header.Version != 4)
    {
      throw ReadError(vtkErrorCode::FileFormatError,
        "an SPZ of version " + std::to_string(header.Version) + " without gzip compression");
    }
    streams = ReadStreams(in, header);
    for (int s = 0; s < 6; ++s)
    {
      starts[s] = streams[s].data();
    }
  }
  progress(0.3);
  Kernels kernels(header.Count, header.Degree);
  Decode(header, starts, fromRUB, kernels, progress);
  kernels.SetFlag("Antialiased", header.Flags & 1);
  kernels.MoveTo(output);
}
}
