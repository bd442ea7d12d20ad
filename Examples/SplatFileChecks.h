// SPDX-License-Identifier: BSD-3-Clause
// Checks run before a file is handed to a VTK 9.1 reader that crashes, hangs or allocates
// without bound on some corrupt files (found by Testing/Cxx/TestReaderFuzz.cxx):
// - vtkXMLPolyDataReader and vtkXMLImageDataReader trust the counts, extents, component counts,
//   types, offsets and binary block headers of the file (String arrays, a zero block size, a
//   swapped header word or a wrong offset crash; huge counts hang or throw std::bad_alloc);
//   CheckXMLFile checks them, with VTK's own XML parser, against what the file holds.
// - MetaIO (vtkMetaImageReader) loops without end on a negative NDims; CheckMetaImageHeader
//   checks the header lines it sizes its reads with.
// - vtkNIFTIImageReader crashes in RequestInformation on an unknown datatype;
//   CheckNIFTIDataType checks it.
// Each throws std::runtime_error naming the file.
#ifndef SplatFileChecks_h
#define SplatFileChecks_h

#include "vtkBase64Utilities.h"
#include "vtkNew.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"
#include "vtk_zlib.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace splatexample
{
/// Byte sizes of the VTK XML and MetaImage element types the example programs accept.
inline int XMLTypeSize(const std::string& type)
{
  for (const auto& [name, size] : std::vector<std::pair<std::string, int>>{ { "Int8", 1 },
         { "UInt8", 1 }, { "Int16", 2 }, { "UInt16", 2 }, { "Int32", 4 }, { "UInt32", 4 },
         { "Int64", 8 }, { "UInt64", 8 }, { "Float32", 4 }, { "Float64", 8 } })
  {
    if (type == name)
    {
      return size;
    }
  }
  return 0;
}

/// Whether `text` is a whole decimal integer in [low, high] (stored in `value`): VTK's attribute
/// parsing takes "1e308" as 1 and wraps values past the type's range.
inline bool ParseInteger(const char* text, long long low, long long high, long long& value)
{
  if (!text || !*text)
  {
    return false;
  }
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(text, &end, 10);
  return errno == 0 && *end == '\0' && value >= low && value <= high;
}

/// The most bytes that `stored` bytes can decompress to: deflate's limit is 1032:1 and LZ4's
/// 255:1; LZMA has no fixed limit, so it gets a generous one.
inline double MaxExpansion(const std::string& compressor)
{
  if (compressor.empty())
  {
    return 1;
  }
  return compressor == "vtkLZ4DataCompressor" ? 255 : compressor == "vtkLZMADataCompressor"
      ? 65536
      : 1032;
}

/// Checks a VTK XML PolyData or ImageData file (`type`) before vtkXMLReader reads it.
class XMLFileCheck
{
public:
  XMLFileCheck(const std::string& path, const std::string& type)
    : Path(path)
  {
    this->FileSize = static_cast<double>(vtksys::SystemTools::FileLength(path));
    this->Parser->SetFileName(path.c_str());
    vtkXMLDataElement* root = this->Parser->Parse() ? this->Parser->GetRootElement() : nullptr;
    if (!root || !root->GetAttribute("type") || type != root->GetAttribute("type"))
    {
      this->Fail("is not a well-formed VTK XML " + type + " file");
    }
    const std::string byteOrder = Attribute(root, "byte_order", "LittleEndian");
    const std::string header = Attribute(root, "header_type", "UInt32");
    this->Compressor = Attribute(root, "compressor", "");
    if ((byteOrder != "LittleEndian" && byteOrder != "BigEndian") ||
      (header != "UInt32" && header != "UInt64") || MaxExpansion(this->Compressor) == 1032 &&
        this->Compressor != "vtkZLibDataCompressor")
    {
      this->Fail("has an unknown byte_order, header_type or compressor");
    }
    this->BigEndian = byteOrder == "BigEndian";
    this->HeaderWidth = header == "UInt64" ? 8 : 4;
    vtkXMLDataElement* dataset = root->FindNestedElementWithName(type.c_str());
    if (!dataset)
    {
      this->Fail("has no " + type + " element");
    }
    if (type == "ImageData")
    {
      this->WholeExtent = this->Extent(dataset, "WholeExtent", this->WholeExtent);
    }
    for (int p = 0; p < dataset->GetNumberOfNestedElements(); ++p)
    {
      vtkXMLDataElement* piece = dataset->GetNestedElement(p);
      if (std::strcmp(piece->GetName(), "Piece") == 0)
      {
        this->CheckPiece(piece, type == "ImageData");
      }
    }
  }

private:
  // What CheckArray learned of an array: its value size, its byte count, and where its values
  // start in the file when they are stored raw and uncompressed (-1 otherwise).
  struct ArrayData
  {
    int ValueSize;
    double Total;
    double RawValues = -1;
  };

  static std::string Attribute(vtkXMLDataElement* e, const char* name, const char* fallback)
  {
    const char* value = e->GetAttribute(name);
    return value ? value : fallback;
  }

  [[noreturn]] void Fail(const std::string& what) const
  {
    throw std::runtime_error("'" + this->Path + "' " + what);
  }

  // An extent attribute: three ranges low <= high within [-2^30, 2^30] and within `outer`.
  std::vector<long long> Extent(
    vtkXMLDataElement* e, const char* name, const std::vector<long long>& outer) const
  {
    std::istringstream text(Attribute(e, name, ""));
    std::vector<long long> extent(6);
    for (int axis = 0; axis < 3; ++axis)
    {
      long long& low = extent[2 * axis];
      long long& high = extent[2 * axis + 1];
      if (!(text >> low >> high) || low > high || low < outer[2 * axis] ||
        high > outer[2 * axis + 1])
      {
        this->Fail(std::string("has an invalid ") + name);
      }
    }
    return extent;
  }

  long long Count(vtkXMLDataElement* e, const char* name) const
  {
    long long value = 0;
    if (e->GetAttribute(name) &&
      !ParseInteger(e->GetAttribute(name), 0, (1LL << 53), value))
    {
      this->Fail(std::string("has an invalid ") + name + " '" + e->GetAttribute(name) + "'");
    }
    return value;
  }

  void CheckPiece(vtkXMLDataElement* piece, bool image)
  {
    long long points = 0, cells = 0;
    std::map<std::string, long long> cellCounts;
    if (image)
    {
      const std::vector<long long> extent = this->Extent(piece, "Extent", this->WholeExtent);
      points = 1;
      cells = 1;
      for (int axis = 0; axis < 3; ++axis)
      {
        points *= extent[2 * axis + 1] - extent[2 * axis] + 1;
        cells *= std::max(extent[2 * axis + 1] - extent[2 * axis], 1LL);
      }
    }
    else
    {
      points = this->Count(piece, "NumberOfPoints");
      for (const char* name : { "Verts", "Lines", "Strips", "Polys" })
      {
        cellCounts[name] = this->Count(piece, ("NumberOf" + std::string(name)).c_str());
        cells += cellCounts[name];
      }
    }
    for (int g = 0; g < piece->GetNumberOfNestedElements(); ++g)
    {
      vtkXMLDataElement* group = piece->GetNestedElement(g);
      const std::string name = group->GetName();
      const long long tuples = name == "PointData" || name == "Points" ? points
        : name == "CellData"                                           ? cells
                                                                       : -1;
      std::map<std::string, ArrayData> cellArrays;
      for (int a = 0; a < group->GetNumberOfNestedElements(); ++a)
      {
        // A cell group's offsets hold one value per cell; its connectivity any number.
        vtkXMLDataElement* array = group->GetNestedElement(a);
        const std::string arrayName = Attribute(array, "Name", "");
        const bool offsets = cellCounts.count(name) && arrayName == "offsets";
        if (std::strcmp(array->GetName(), "DataArray") == 0)
        {
          cellArrays.emplace(arrayName,
            this->CheckArray(array, offsets ? cellCounts[name] : tuples,
              cellCounts.count(name) && cellCounts[name] > 0));
        }
      }
      if (cellCounts.count(name) && cellCounts[name] > 0)
      {
        this->CheckLastOffset(cellArrays, name);
      }
    }
  }

  // vtkXMLPolyDataReader sizes a cell group's connectivity by its last offset: where that value
  // can be read without decoding the array (raw, uncompressed), it must be the connectivity's
  // length.
  void CheckLastOffset(const std::map<std::string, ArrayData>& arrays, const std::string& group)
  {
    const auto offsets = arrays.find("offsets"), connectivity = arrays.find("connectivity");
    if (offsets == arrays.end() || connectivity == arrays.end() ||
      offsets->second.RawValues < 0 || offsets->second.ValueSize > 8)
    {
      return;
    }
    const ArrayData& o = offsets->second;
    const std::string bytes = this->ReadAt(o.RawValues + o.Total - o.ValueSize, o.ValueSize);
    std::uint64_t last = 0;
    for (int b = 0; b < o.ValueSize && bytes.size() == std::size_t(o.ValueSize); ++b)
    {
      last = (last << 8) |
        static_cast<unsigned char>(bytes[this->BigEndian ? b : o.ValueSize - 1 - b]);
    }
    if (double(last) * connectivity->second.ValueSize != connectivity->second.Total)
    {
      this->Fail("has " + group + " whose last offset is not the length of their connectivity");
    }
  }

  // One DataArray holding `tuples` tuples (-1: a cell array whose length the data gives; not
  // empty for a group with cells).
  ArrayData CheckArray(vtkXMLDataElement* array, long long tuples, bool nonEmpty)
  {
    const std::string name = Attribute(array, "Name", "");
    const int size = XMLTypeSize(Attribute(array, "type", ""));
    long long components = 1;
    if (size == 0 ||
      (array->GetAttribute("NumberOfComponents") &&
        !ParseInteger(array->GetAttribute("NumberOfComponents"), 1, 1 << 16, components)))
    {
      this->Fail("has array '" + name + "' of an unsupported type or number of components");
    }
    const double bytes = tuples < 0 ? -1 : double(tuples) * components * size;
    const std::string format = Attribute(array, "format", "");
    ArrayData data{ size, bytes };
    if (format == "ascii")
    {
      // An ascii value takes at least a digit and a separator.
      if (bytes > 4 * this->FileSize)
      {
        this->Fail("has fewer values in array '" + name + "' than its size says");
      }
      return data;
    }
    double start; // where the array's (encoded) block starts in the file
    bool raw = false;
    if (format == "binary")
    {
      // Inline base64 text follows the end of the DataArray's start tag.
      start = static_cast<double>(this->Find('>', static_cast<double>(array->GetXMLByteIndex())));
      start = static_cast<double>(this->SkipSpace(start + 1));
    }
    else if (format == "appended")
    {
      long long offset;
      if (!ParseInteger(array->GetAttribute("offset"), 0, 1LL << 62, offset))
      {
        this->Fail("has an invalid offset for array '" + name + "'");
      }
      // The parser stops at the appended section's marker: its position starts the data.
      start = this->Parser->GetAppendedDataPosition() + double(offset);
      const vtkXMLDataElement* appended = this->Parser->GetRootElement()
                                            ->FindNestedElementWithName("AppendedData");
      raw = !appended || Attribute(const_cast<vtkXMLDataElement*>(appended), "encoding",
                           "base64") == "raw";
    }
    else
    {
      this->Fail("has array '" + name + "' in an unknown format '" + format + "'");
    }
    const std::string encoded = this->ReadAt(start, 4096);
    const double available = (this->FileSize - start) * (raw ? 1 : 0.75);
    data.Total = this->CheckBlocks(raw, encoded, available, bytes, nonEmpty, name);
    if (raw && this->Compressor.empty())
    {
      data.RawValues = start + double(this->HeaderWidth);
    }
    return data;
  }

  // Up to `count` bytes of the file from `start` on.
  std::string ReadAt(double start, std::size_t count) const
  {
    std::ifstream in(this->Path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(std::clamp(start, 0.0, this->FileSize)));
    std::string bytes(static_cast<std::size_t>(std::clamp(this->FileSize - start, 0.0,
                        static_cast<double>(count))),
      '\0');
    in.read(&bytes[0], static_cast<std::streamsize>(bytes.size()));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
    return bytes;
  }

  // The position of the first `c` at or after `from` (the file's size when there is none).
  double Find(char c, double from) const
  {
    for (double at = from; at < this->FileSize; at += 4096)
    {
      const std::string chunk = this->ReadAt(at, 4096);
      const std::size_t found = chunk.find(c);
      if (found != std::string::npos)
      {
        return at + double(found);
      }
    }
    return this->FileSize;
  }

  double SkipSpace(double from) const
  {
    const std::string chunk = this->ReadAt(from, 4096);
    const std::size_t found = chunk.find_first_not_of(" \t\r\n");
    return found == std::string::npos ? from + double(chunk.size()) : from + double(found);
  }

  // The binary header: the byte count, or (compressed) the block count, block size, last block
  // size and the compressed block sizes; they must fit the file and give `bytes` (if >= 0).
  // Returns the array's byte count.
  double CheckBlocks(bool raw, const std::string& encoded, double available, double bytes,
    bool nonEmpty, const std::string& name)
  {
    const bool compressed = !this->Compressor.empty();
    std::vector<double> words = this->Words(raw, encoded, 1);
    if (compressed && !words.empty() && words[0] < 4096)
    {
      words = this->Words(raw, encoded, 3 + static_cast<int>(words[0]));
    }
    const std::size_t needed = compressed ? (words.empty() ? 3 : 3 + std::size_t(words[0])) : 1;
    double total = words.empty() ? -1 : words[0], stored = total;
    if (compressed && words.size() == needed)
    {
      const double blocks = words[0], blockSize = words[1], last = words[2];
      total = blocks == 0 ? 0 : (blocks - 1) * blockSize + (last > 0 ? last : blockSize);
      stored = 0;
      for (std::size_t b = 3; b < words.size(); ++b)
      {
        stored += words[b];
        if (words[b] == 0) // a compressed block is never empty
        {
          this->Fail("has an empty compressed block in array '" + name + "'");
        }
      }
      if (blocks > 0 && (blockSize <= 0 || last > blockSize))
      {
        this->Fail("has an invalid compression header in array '" + name + "'");
      }
    }
    const double header = double(needed) * this->HeaderWidth;
    if (words.size() != needed || stored + header > available + 4 ||
      (bytes >= 0 && total != bytes) || (nonEmpty && total <= 0) || total > MaxExpansion(this->Compressor) * stored + 64)
    {
      this->Fail("has array '" + name + "' whose data is missing or not of its declared size");
    }
    return total;
  }

  // The first `count` header words, decoded from raw bytes or base64 text.
  std::vector<double> Words(bool raw, const std::string& encoded, int count) const
  {
    const std::size_t width = this->HeaderWidth, size = count * width;
    std::string bytes = encoded.substr(0, size);
    if (!raw)
    {
      const std::size_t chars = std::min(encoded.size(), (size + 2) / 3 * 4);
      bytes.assign(chars, '\0');
      bytes.resize(vtkBase64Utilities::DecodeSafely(
        reinterpret_cast<const unsigned char*>(encoded.data()), chars,
        reinterpret_cast<unsigned char*>(&bytes[0]), bytes.size()));
    }
    std::vector<double> words;
    for (std::size_t at = 0; at + width <= std::min(bytes.size(), size); at += width)
    {
      std::uint64_t word = 0;
      for (std::size_t b = 0; b < width; ++b)
      {
        const auto byte = static_cast<unsigned char>(bytes[at + (this->BigEndian ? b : width - 1 - b)]);
        word = (word << 8) | byte;
      }
      words.push_back(static_cast<double>(word));
    }
    return words;
  }

  std::string Path;
  std::string Compressor;
  double FileSize = 0;
  std::vector<long long> WholeExtent = { -(1LL << 30), 1LL << 30, -(1LL << 30), 1LL << 30,
    -(1LL << 30), 1LL << 30 };
  bool BigEndian = false;
  std::size_t HeaderWidth = 4;
  vtkNew<vtkXMLDataParser> Parser;
};

inline std::string Trim(const std::string& text)
{
  const std::size_t first = text.find_first_not_of(" \t\r");
  return first == std::string::npos
    ? std::string()
    : text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

/// Checks the header lines of a MetaImage (.mhd, .mha) that MetaIO sizes its reads with: NDims
/// (1 to 3, and before the fields that have NDims values), DimSize and
/// ElementNumberOfChannels; the data size they imply against the data file's size.
inline void CheckMetaImageHeader(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  auto fail = [&](const std::string& what)
  { return std::runtime_error("'" + path + "' " + what); };
  long long dims = 0, channels = 1;
  double voxels = 1, typeSize = 0;
  bool compressed = false;
  long long compressedSize = -1;
  std::string line, dataFile;
  double headerSize = 0;
  while (dataFile.empty() && std::getline(in, line))
  {
    headerSize += line.size() + 1;
    const std::size_t equals = line.find('=');
    if (equals == std::string::npos)
    {
      continue;
    }
    const std::string key = Trim(line.substr(0, equals));
    const std::string value = Trim(line.substr(equals + 1));
    std::istringstream values(value);
    if (key == "NDims" && !ParseInteger(value.c_str(), 1, 3, dims))
    {
      throw fail("has NDims '" + value + "' (1 to 3 are read)");
    }
    else if (key == "DimSize")
    {
      for (long long d = 0, n; d < dims; ++d)
      {
        std::string number;
        values >> number;
        if (!ParseInteger(number.c_str(), 1, 1LL << 31, n))
        {
          throw fail("has an invalid DimSize '" + value + "'");
        }
        voxels *= n;
      }
    }
    else if (key == "ElementNumberOfChannels" &&
      !ParseInteger(value.c_str(), 1, 1 << 16, channels))
    {
      throw fail("has an invalid ElementNumberOfChannels '" + value + "'");
    }
    else if (key == "ElementType")
    {
      typeSize = value == "MET_CHAR" || value == "MET_UCHAR" ? 1
        : value == "MET_SHORT" || value == "MET_USHORT"     ? 2
        : value == "MET_INT" || value == "MET_UINT" || value == "MET_FLOAT" ? 4
        : value == "MET_DOUBLE" || value == "MET_LONG_LONG" || value == "MET_ULONG_LONG" ? 8
                                                                                      : 0;
    }
    else if (key == "CompressedDataSize" &&
      !ParseInteger(value.c_str(), 1, 1LL << 62, compressedSize))
    {
      throw fail("has an invalid CompressedDataSize '" + value + "'");
    }
    else if (key == "CompressedData")
    {
      compressed = value == "True";
    }
    else if (key == "ElementDataFile")
    {
      dataFile = value;
    }
    else if (dims == 0 && (key == "TransformMatrix" || key == "Offset" ||
                            key == "ElementSpacing" || key == "CenterOfRotation"))
    {
      throw fail("has " + key + " before NDims");
    }
  }
  if (dims == 0 || typeSize == 0 || dataFile.empty())
  {
    throw fail("lacks NDims, DimSize, a known ElementType or ElementDataFile");
  }
  const std::string data = dataFile == "LOCAL"
    ? path
    : vtksys::SystemTools::GetFilenamePath(path) + "/" + dataFile;
  // MetaIO reads what a truncated data file holds and says so only on std::cerr.
  const double stored = static_cast<double>(vtksys::SystemTools::FileLength(data)) -
    (dataFile == "LOCAL" ? headerSize : 0.0);
  const double bytes = voxels * channels * typeSize;
  if (compressed ? compressedSize > stored || bytes > 1032 * stored : bytes > stored)
  {
    throw fail("declares more data than '" + data + "' holds");
  }
}

/// Checks the datatype of a NIFTI-1 or NIFTI-2 header (gzipped or not) against the types
/// vtkNIFTIImageReader reads.
inline void CheckNIFTIDataType(const std::string& path)
{
  unsigned char header[16] = {};
  gzFile in = gzopen(path.c_str(), "rb");
  const int read = in ? gzread(in, header, sizeof(header)) : 0;
  if (in)
  {
    gzclose(in);
  }
  // sizeof_hdr is 348 (NIFTI-1, datatype at byte 70) or 540 (NIFTI-2, at byte 12), in either
  // byte order; datatype is 16 bits in the same order.
  const bool little = header[0] == 0x5c || header[0] == 0x1c;
  const bool nifti2 = header[0] == 0x1c || header[3] == 0x1c;
  unsigned char type[2] = { header[12], header[13] };
  if (!nifti2 && read == sizeof(header))
  {
    in = gzopen(path.c_str(), "rb");
    gzseek(in, 70, SEEK_SET);
    const int n = gzread(in, type, 2);
    gzclose(in);
    if (n != 2)
    {
      type[0] = type[1] = 0;
    }
  }
  const int datatype = little ? type[0] | (type[1] << 8) : type[1] | (type[0] << 8);
  for (int known : { 2, 4, 8, 16, 32, 64, 128, 256, 512, 768, 1024, 1280, 1792, 2304 })
  {
    if (read == sizeof(header) && datatype == known)
    {
      return;
    }
  }
  throw std::runtime_error(
    "'" + path + "' has NIFTI datatype " + std::to_string(datatype) + ", which is not read");
}
}

#endif