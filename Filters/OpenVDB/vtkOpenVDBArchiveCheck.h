// SPDX-License-Identifier: BSD-3-Clause
// Checks the layout of an OpenVDB file before OpenVDB reads it. OpenVDB 10's io::File and
// io::Stream read counts, string lengths and offsets without checking them or their stream, so
// a truncated or corrupt header makes them loop without end over a failed stream or allocate
// gigabytes for one string (found by Testing/Cxx/TestPointReaderFuzz.cxx). This walks what
// they read before a grid's tree, in the order Archive::readHeader, MetaMap::readMeta,
// GridDescriptor::read and Archive::readGridMetadata read it: the header, the file metadata,
// each grid's descriptor, compression flags, metadata and transform type, each count, length
// and offset against the bytes the file holds. The trees are read by the reader with stream
// exceptions, so a short read there stops it.
#ifndef vtkOpenVDBArchiveCheck_h
#define vtkOpenVDBArchiveCheck_h

#include <openvdb/version.h>

#include <cctype>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

namespace splatvdb
{
class ArchiveCheck
{
public:
  /// Throws std::runtime_error saying what is wrong and where ("the file has ...").
  explicit ArchiveCheck(const std::string& path)
    : In(path, std::ios::binary | std::ios::ate)
  {
    if (!this->In)
    {
      this->Fail("cannot be opened");
    }
    this->Size = static_cast<std::uint64_t>(this->In.tellg());
    this->In.seekg(0);
    if (this->Read<std::int64_t>() != 0x56444220) // OPENVDB_MAGIC
    {
      this->Fail("is not an OpenVDB file (wrong magic number)");
    }
    const auto version = this->Read<std::uint32_t>();
    if (version < openvdb::OPENVDB_FILE_VERSION_SELECTIVE_COMPRESSION ||
      version > openvdb::OPENVDB_FILE_VERSION)
    {
      this->Fail("has file format version " + std::to_string(version) + " (" +
        std::to_string(openvdb::OPENVDB_FILE_VERSION_SELECTIVE_COMPRESSION) + " to " +
        std::to_string(openvdb::OPENVDB_FILE_VERSION) + " are read)");
    }
    this->Skip(8); // library major and minor version
    const bool hasGridOffsets = this->Read<char>() != 0;
    if (version < openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION)
    {
      this->Skip(1); // the file-wide compression flag
    }
    this->CheckUuid();
    this->CheckMetaMap("file metadata");
    const auto grids = this->Read<std::int32_t>();
    if (grids < 0 || std::uint64_t(grids) > this->Remaining() / 36)
    {
      this->Fail("has an invalid grid count " + std::to_string(grids));
    }
    // A file written to a stream has no grid offsets: its grids follow one another and only
    // a full read finds where each ends.
    for (std::int32_t g = 0; g < grids && hasGridOffsets; ++g)
    {
      this->CheckGrid(version);
    }
  }

private:
  template <typename T>
  T Read()
  {
    T value{};
    this->Require(sizeof(T), "a field");
    this->In.read(reinterpret_cast<char*>(&value), sizeof(T));
    this->Position += sizeof(T);
    return value;
  }

  void Skip(std::uint64_t bytes, const char* what = "a field")
  {
    this->Require(bytes, what);
    this->Position += bytes;
    this->In.seekg(static_cast<std::streamoff>(this->Position));
  }

  void Seek(std::uint64_t position)
  {
    this->Position = position;
    this->In.seekg(static_cast<std::streamoff>(position));
  }

  std::uint64_t Remaining() const { return this->Size - this->Position; }

  void Require(std::uint64_t bytes, const std::string& what)
  {
    if (!this->In || bytes > this->Remaining())
    {
      this->Fail("ends within " + what);
    }
  }

  [[noreturn]] void Fail(const std::string& what) const
  {
    throw std::runtime_error("the file " + what + " (at byte " +
      std::to_string(this->Position) + " of " + std::to_string(this->Size) + ")");
  }

  // A length-prefixed string (readString); returns its text.
  std::string String(const char* what)
  {
    const auto length = this->Read<std::uint32_t>();
    this->Require(length, what);
    std::string text(length, '\0');
    this->In.read(&text[0], length);
    this->Position += length;
    return text;
  }

  // The UUID, 36 characters 8-4-4-4-12 that boost's operator>> parses.
  void CheckUuid()
  {
    this->Require(36, "the file's UUID");
    char uuid[36];
    this->In.read(uuid, 36);
    for (int i = 0; i < 36; ++i)
    {
      const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
      if (dash ? uuid[i] != '-' : !std::isxdigit(static_cast<unsigned char>(uuid[i])))
      {
        this->Fail("has an invalid UUID");
      }
    }
    this->Position += 36;
  }

  // MetaMap::readMeta: a count, then per item a name, a type name and a sized value.
  void CheckMetaMap(const char* what)
  {
    const auto count = this->Read<std::uint32_t>();
    if (count > this->Remaining() / 12)
    {
      this->Fail("has an invalid " + std::string(what) + " count " + std::to_string(count));
    }
    for (std::uint32_t i = 0; i < count; ++i)
    {
      this->String(what);
      this->String(what);
      this->Skip(this->Read<std::uint32_t>(), what);
    }
  }

  // A grid descriptor, then at its grid position what the metadata pass reads, then on to its
  // end, where the next descriptor starts.
  void CheckGrid(std::uint32_t version)
  {
    const std::string name = this->String("a grid descriptor");
    this->String("a grid descriptor"); // the grid type
    if (version >= openvdb::OPENVDB_FILE_VERSION_GRID_INSTANCING)
    {
      this->String("a grid descriptor"); // the instance parent
    }
    const auto gridPos = this->Read<std::int64_t>();
    const auto blockPos = this->Read<std::int64_t>();
    const auto endPos = this->Read<std::int64_t>();
    if (gridPos != std::int64_t(this->Position) || blockPos > endPos || endPos < gridPos ||
      std::uint64_t(endPos) > this->Size)
    {
      this->Fail("has grid '" + name + "' at offsets outside the file");
    }
    if (version >= openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION)
    {
      this->Skip(4, "a grid's compression flags");
    }
    this->CheckMetaMap("grid metadata");
    this->String("a grid's transform");
    this->Seek(std::uint64_t(endPos));
  }

  std::ifstream In;
  std::uint64_t Size = 0;
  std::uint64_t Position = 0;
};
}

#endif
