// SPDX-License-Identifier: BSD-3-Clause
// PlayCanvas's SOG: lossless WebP images with one texel per Gaussian (row-major) and a
// meta.json with their ranges and codebooks, either as a folder or bundled in a .sog zip
// archive. meta.json versions 1 (ranges) and 2 (codebooks, "version": 2) are read.
#include "SplatCaptureFormats.h"

#include "vtkErrorCode.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <json/json.h>
#include <minizip/unzip.h>
#include <vtksys/SystemTools.hxx>
#include <webp/decode.h>

#include <cmath>
#include <map>
#include <memory>
#include <sstream>

namespace splatcapture
{
namespace
{
// Bounds what a corrupt header could make us allocate: far beyond any capture.
constexpr std::size_t MaxFileBytes = std::size_t(4) << 30;
constexpr std::int64_t MaxGaussians = std::int64_t(1) << 28;

// The files of a SOG, from its folder or its archive.
class Source
{
public:
  explicit Source(const std::string& fileName)
  {
    if (vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(fileName)) ==
      ".json")
    {
      this->Folder = vtksys::SystemTools::GetFilenamePath(fileName);
      this->MetaName = vtksys::SystemTools::GetFilenameName(fileName);
      return;
    }
    this->Archive = unzOpen64(fileName.c_str());
    if (!this->Archive)
    {
      throw ReadError(vtkErrorCode::FileFormatError, "not a zip archive (a .sog is one)");
    }
    this->MetaName = "meta.json";
  }

  ~Source()
  {
    if (this->Archive)
    {
      unzClose(this->Archive);
    }
  }

  Source(const Source&) = delete;
  Source& operator=(const Source&) = delete;

  const std::string& Meta() const { return this->MetaName; }

  // The bytes of the file `name` of the SOG.
  std::vector<std::uint8_t> Read(const std::string& name) const
  {
    if (name.empty() || name.find("..") != std::string::npos || name[0] == '/')
    {
      throw ReadError(vtkErrorCode::FileFormatError, "meta.json names the file '" + name + "'");
    }
    if (!this->Archive)
    {
      const std::string path = this->Folder.empty() ? name : this->Folder + "/" + name;
      try
      {
        return ReadFile(path, MaxFileBytes);
      }
      catch (const ReadError& error)
      {
        throw ReadError(error.Code, name + ": " + error.what());
      }
    }
    unz_file_info64 info;
    if (unzLocateFile(this->Archive, name.c_str(), 1) != UNZ_OK ||
      unzGetCurrentFileInfo64(this->Archive, &info, nullptr, 0, nullptr, 0, nullptr, 0) != UNZ_OK)
    {
      throw ReadError(vtkErrorCode::FileFormatError, "the archive has no file '" + name + "'");
    }
    if (info.uncompressed_size > MaxFileBytes)
    {
      throw ReadError(vtkErrorCode::FileFormatError,
        "the archive's '" + name + "' announces " + std::to_string(info.uncompressed_size) +
          " bytes");
    }
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(info.uncompressed_size));
    if (unzOpenCurrentFile(this->Archive) != UNZ_OK)
    {
      throw ReadError(vtkErrorCode::FileFormatError, "the archive's '" + name + "' cannot be opened");
    }
    const int got = bytes.empty()
      ? 0
      : unzReadCurrentFile(this->Archive, bytes.data(), static_cast<unsigned>(bytes.size()));
    const int closed = unzCloseCurrentFile(this->Archive); // checks the CRC
    if (got != static_cast<int>(bytes.size()) || closed != UNZ_OK)
    {
      throw ReadError(vtkErrorCode::PrematureEndOfFileError,
        "the archive's '" + name + "' is truncated or corrupt");
    }
    return bytes;
  }

private:
  unzFile Archive = nullptr;
  std::string Folder;
  std::string MetaName;
};

// An RGBA image decoded from WebP.
struct Image
{
  int Width = 0;
  int Height = 0;
  std::unique_ptr<std::uint8_t, void (*)(void*)> Pixels{ nullptr, WebPFree };

  const std::uint8_t* Texel(std::int64_t i) const { return this->Pixels.get() + 4 * i; }
};

Image Decode(const Source& source, const std::string& name, std::int64_t leastTexels)
{
  const std::vector<std::uint8_t> bytes = source.Read(name);
  Image image;
  if (!WebPGetInfo(bytes.data(), bytes.size(), &image.Width, &image.Height))
  {
    throw ReadError(vtkErrorCode::FileFormatError, "'" + name + "' is not a WebP image");
  }
  const std::int64_t texels = static_cast<std::int64_t>(image.Width) * image.Height;
  if (texels < leastTexels)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "'" + name + "' has " + std::to_string(texels) + " pixels, fewer than the " +
        std::to_string(leastTexels) + " needed");
  }
  image.Pixels.reset(WebPDecodeRGBA(bytes.data(), bytes.size(), &image.Width, &image.Height));
  if (!image.Pixels)
  {
    throw ReadError(vtkErrorCode::FileFormatError, "'" + name + "' is a corrupt WebP image");
  }
  return image;
}

// The JSON helpers: the members meta.json must have, with the types they must have.
const Json::Value& Member(const Json::Value& object, const char* name)
{
  if (!object.isObject() || !object.isMember(name))
  {
    throw ReadError(vtkErrorCode::FileFormatError, std::string("meta.json has no '") + name + "'");
  }
  return object[name];
}

std::vector<float> Floats(const Json::Value& object, const char* name, unsigned count)
{
  const Json::Value& values = Member(object, name);
  if (!values.isArray() || values.size() != count)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      std::string("meta.json's '") + name + "' is not " + std::to_string(count) + " numbers");
  }
  std::vector<float> out;
  for (const Json::Value& value : values)
  {
    if (!value.isNumeric())
    {
      throw ReadError(vtkErrorCode::FileFormatError,
        std::string("meta.json's '") + name + "' holds a value that is not a number");
    }
    out.push_back(value.asFloat());
  }
  return out;
}

std::string FileAt(const Json::Value& object, unsigned index)
{
  const Json::Value& files = Member(object, "files");
  if (!files.isArray() || files.size() <= index || !files[index].isString())
  {
    throw ReadError(vtkErrorCode::FileFormatError, "meta.json lists too few files");
  }
  return files[index].asString();
}

std::int64_t Integer(const Json::Value& value, const char* what)
{
  if (!value.isIntegral())
  {
    throw ReadError(
      vtkErrorCode::FileFormatError, std::string("meta.json's ") + what + " is not an integer");
  }
  return value.asInt64();
}

// A byte's value: a codebook entry (version 2) or a linear range (version 1).
class Dequantizer
{
public:
  static Dequantizer Codebook(const Json::Value& object)
  {
    Dequantizer d;
    d.Table = Floats(object, "codebook", 256);
    return d;
  }

  static Dequantizer Range(float minimum, float maximum)
  {
    Dequantizer d;
    for (int b = 0; b < 256; ++b)
    {
      d.Table.push_back(minimum + (maximum - minimum) * b / 255.0f);
    }
    return d;
  }

  float operator()(std::uint8_t b) const { return this->Table[b]; }

private:
  std::vector<float> Table;
};

}

//------------------------------------------------------------------------------
void ReadSOG(const std::string& fileName, vtkPolyData* output, const Progress& progress)
{
  const Source source(fileName);
  const std::vector<std::uint8_t> metaBytes = source.Read(source.Meta());
  Json::Value meta;
  {
    Json::CharReaderBuilder builder;
    std::string errors;
    std::istringstream text(std::string(metaBytes.begin(), metaBytes.end()));
    if (!Json::parseFromStream(builder, text, &meta, &errors) || !meta.isObject())
    {
      throw ReadError(vtkErrorCode::FileFormatError, "meta.json is not valid JSON: " + errors);
    }
  }
  const bool codebooks = meta.isMember("version");
  if (codebooks && Integer(meta["version"], "version") != 2)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "SOG version " + meta["version"].toStyledString() + " (versions 1 and 2 are read)");
  }
  const Json::Value& means = Member(meta, "means");
  const std::int64_t count = codebooks ? Integer(Member(meta, "count"), "count")
                                       : Integer(Member(means, "shape")[0], "means.shape");
  if (count < 0 || count > MaxGaussians)
  {
    throw ReadError(vtkErrorCode::FileFormatError,
      "meta.json announces " + std::to_string(count) + " Gaussians");
  }
  const std::vector<float> meanMin = Floats(means, "mins", 3), meanMax = Floats(means, "maxs", 3);
  const Json::Value& scales = Member(meta, "scales");
  const Json::Value& sh0 = Member(meta, "sh0");
  std::vector<Dequantizer> scale, dc;
  Dequantizer opacity = Dequantizer::Range(0.0f, 1.0f);
  if (codebooks)
  {
    scale.assign(3, Dequantizer::Codebook(scales));
    dc.assign(3, Dequantizer::Codebook(sh0));
  }
  else
  {
    const std::vector<float> low = Floats(scales, "mins", 3), high = Floats(scales, "maxs", 3);
    const std::vector<float> dcLow = Floats(sh0, "mins", 4), dcHigh = Floats(sh0, "maxs", 4);
    for (int c = 0; c < 3; ++c)
    {
      scale.push_back(Dequantizer::Range(low[c], high[c]));
      dc.push_back(Dequantizer::Range(dcLow[c], dcHigh[c]));
    }
    // Version 1 stores the opacity's logit in a range.
    opacity = Dequantizer::Range(dcLow[3], dcHigh[3]);
  }

  // Spherical harmonics: a palette of coefficient sets and a 16-bit label per Gaussian.
  int degree = 0;
  const Json::Value* shN = meta.isMember("shN") ? &meta["shN"] : nullptr;
  Image centroids, labels;
  Dequantizer coefficient = Dequantizer::Range(0.0f, 0.0f);
  std::int64_t paletteSize = 0;
  if (shN)
  {
    centroids = Decode(source, FileAt(*shN, 0), 1);
    if (codebooks)
    {
      degree = static_cast<int>(Integer(Member(*shN, "bands"), "shN.bands"));
      coefficient = Dequantizer::Codebook(*shN);
    }
    else
    {
      // Version 1: the degree from the palette's width, 64 sets a row.
      for (int d = 1; d <= 3; ++d)
      {
        degree = centroids.Width == 64 * RestCoefficients(d) ? d : degree;
      }
      const Json::Value& low = Member(*shN, "mins");
      const Json::Value& high = Member(*shN, "maxs");
      if (!low.isNumeric() || !high.isNumeric())
      {
        throw ReadError(vtkErrorCode::FileFormatError, "meta.json's shN range is not numbers");
      }
      coefficient = Dequantizer::Range(low.asFloat(), high.asFloat());
    }
    if (degree < 1 || degree > 3 || centroids.Width != 64 * RestCoefficients(degree))
    {
      throw ReadError(vtkErrorCode::FileFormatError,
        "the spherical-harmonics palette is " + std::to_string(centroids.Width) +
          " pixels wide, which fits no degree from 1 to 3");
    }
    paletteSize = static_cast<std::int64_t>(centroids.Height) * 64;
    if (codebooks)
    {
      paletteSize = std::min(paletteSize, Integer(Member(*shN, "count"), "shN.count"));
    }
    labels = Decode(source, FileAt(*shN, 1), count);
  }
  progress(0.2);
  const Image low = Decode(source, FileAt(means, 0), count);
  const Image high = Decode(source, FileAt(means, 1), count);
  const Image quats = Decode(source, FileAt(Member(meta, "quats"), 0), count);
  const Image scaleImage = Decode(source, FileAt(scales, 0), count);
  const Image colors = Decode(source, FileAt(sh0, 0), count);
  progress(0.8);

  Kernels kernels(count, degree);
  const int perChannel = RestCoefficients(degree);
  vtkSMPTools::For(0, count,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        float p[3];
        for (int a = 0; a < 3; ++a)
        {
          const int u = low.Texel(i)[a] | (high.Texel(i)[a] << 8);
          const float range = meanMax[a] - meanMin[a];
          const float t = meanMin[a] + (range != 0.0f ? range : 1.0f) * u / 65535.0f;
          // The positions were stored as sign(p) log(|p| + 1).
          p[a] = std::copysign(std::expm1(std::abs(t)), t);
        }
        kernels.SetPosition(i, p[0], p[1], p[2]);
        // The smallest three of (w, x, y, z), the largest's index in the alpha as 252 + index.
        const std::uint8_t* q = quats.Texel(i);
        float r[4] = { 1.0f, 0.0f, 0.0f, 0.0f };
        if (q[3] >= 252)
        {
          const int largest = q[3] - 252;
          double sum = 0.0;
          for (int c = 0, byte = 0; c < 4; ++c)
          {
            if (c != largest)
            {
              r[c] = (q[byte++] / 255.0f * 2.0f - 1.0f) * 0.70710678118654752f;
              sum += static_cast<double>(r[c]) * r[c];
            }
          }
          r[largest] = static_cast<float>(std::sqrt(std::max(0.0, 1.0 - sum)));
        }
        kernels.SetRotation(i, r[0], r[1], r[2], r[3]);
        const std::uint8_t* s = scaleImage.Texel(i);
        kernels.SetLogScale(i, scale[0](s[0]), scale[1](s[1]), scale[2](s[2]));
        const std::uint8_t* c = colors.Texel(i);
        kernels.SetDC(i, dc[0](c[0]), dc[1](c[1]), dc[2](c[2]));
        if (codebooks)
        {
          kernels.SetOpacity(i, c[3] / 255.0f);
        }
        else
        {
          kernels.SetOpacityLogit(i, opacity(c[3]));
        }
        if (degree > 0)
        {
          const std::uint8_t* l = labels.Texel(i);
          const std::int64_t label = l[0] | (l[1] << 8);
          for (int k = 0; k < perChannel; ++k)
          {
            const std::uint8_t* set = label < paletteSize
              ? centroids.Texel((label / 64) * centroids.Width + (label % 64) * perChannel + k)
              : nullptr;
            for (int ch = 0; ch < 3; ++ch)
            {
              kernels.SetRest(i, k + 1, ch, set ? coefficient(set[ch]) : 0.0f);
            }
          }
        }
      }
    });
  kernels.MoveTo(output);
}
}
