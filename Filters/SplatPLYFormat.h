// SPDX-License-Identifier: BSD-3-Clause
// The byte level of vtkSplatPLYReader (private to SplatFilters): the PLY types and the header's
// description of elements and properties, buffered file input with byte, line and token
// positions, and the decoding of one property over a block of records into a VTK array.
#ifndef SplatPLYFormat_h
#define SplatPLYFormat_h

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkType.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace splatply
{
// The PLY scalar types, in the order of Types below.
enum PlyType
{
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Float32,
  Float64
};

struct TypeInfo
{
  const char* Name;
  const char* SizedName;
  int Size;
  int VTKType;
};

constexpr TypeInfo Types[] = { { "char", "int8", 1, VTK_SIGNED_CHAR },
  { "uchar", "uint8", 1, VTK_UNSIGNED_CHAR }, { "short", "int16", 2, VTK_SHORT },
  { "ushort", "uint16", 2, VTK_UNSIGNED_SHORT }, { "int", "int32", 4, VTK_INT },
  { "uint", "uint32", 4, VTK_UNSIGNED_INT }, { "float", "float32", 4, VTK_FLOAT },
  { "double", "float64", 8, VTK_DOUBLE } };

inline bool IsInteger(int type)
{
  return type != Float32 && type != Float64;
}

struct Property
{
  std::string Name;
  int Type = Float32;   // the value type (the item type of a list)
  int CountType = -1;   // the list length's type; -1 for a scalar property
  std::size_t Offset{}; // byte offset in the record of the element's scalar properties
  int Line = 0;         // in the header
};

struct Element
{
  std::string Name;
  vtkTypeInt64 Count = 0;
  int Line = 0; // in the header
  std::vector<Property> Properties;
  bool HasLists = false;
  std::size_t ScalarSize = 0; // bytes of one record's scalar properties, packed
  std::size_t MinimumSize = 0; // bytes of one binary record with empty lists

  int Find(const std::string& name) const
  {
    for (std::size_t i = 0; i < this->Properties.size(); ++i)
    {
      if (this->Properties[i].Name == name && this->Properties[i].CountType < 0)
      {
        return static_cast<int>(i);
      }
    }
    return -1;
  }
};

enum Format
{
  Ascii,
  BinaryLittleEndian,
  BinaryBigEndian
};

struct ReadError : std::runtime_error
{
  ReadError(int code, const std::string& message)
    : std::runtime_error(message)
    , Code(code)
  {
  }
  int Code;
};

inline bool HostIsLittleEndian()
{
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// Decodes one value of type T stored at `p`, swapping its bytes when `swap`.
template <typename T>
T Load(const char* p, bool swap)
{
  char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (swap)
  {
    std::reverse(bytes, bytes + sizeof(T));
  }
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

template <typename F>
auto WithType(int type, F&& f)
{
  switch (type)
  {
    case Int8:
      return f(std::int8_t{});
    case UInt8:
      return f(std::uint8_t{});
    case Int16:
      return f(std::int16_t{});
    case UInt16:
      return f(std::uint16_t{});
    case Int32:
      return f(std::int32_t{});
    case UInt32:
      return f(std::uint32_t{});
    case Float32:
      return f(float{});
    default:
      return f(double{});
  }
}

// A color component: integers clamped to [0, 255], floating point values taken as [0, 1].
template <typename S>
unsigned char ToColor(S v)
{
  if constexpr (std::is_floating_point<S>::value)
  {
    const double scaled = std::round(static_cast<double>(v) * 255.0);
    return scaled >= 255.0 ? 255 : (scaled > 0.0 ? static_cast<unsigned char>(scaled) : 0);
  }
  else
  {
    return static_cast<unsigned char>(std::min<long long>(std::max<long long>(v, 0), 255));
  }
}

// Where one scalar property's values go: a component of a data array, optionally as a color.
struct Sink
{
  vtkDataArray* Array = nullptr;
  int Component = 0;
  bool Color = false;
};

// Copies `n` values of type S at `records + offset`, one per `stride` bytes, into component
// sink.Component of tuples first .. first + n - 1 of sink.Array.
template <typename S, typename D>
void DecodeColumn(const char* records, std::size_t stride, std::size_t n, bool swap,
  const Sink& sink, vtkIdType first, D* data)
{
  const int components = sink.Array->GetNumberOfComponents();
  D* out = data + first * components + sink.Component;
  auto copy = [&](auto convert)
  {
    if (swap)
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        out[i * components] = convert(Load<S>(records + i * stride, true));
      }
    }
    else
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        out[i * components] = convert(Load<S>(records + i * stride, false));
      }
    }
  };
  if (sink.Color)
  {
    copy([](S v) { return static_cast<D>(ToColor(v)); });
  }
  else
  {
    copy([](S v) { return static_cast<D>(v); });
  }
}

inline void Decode(const char* records, std::size_t stride, std::size_t n, bool swap, int type,
  const Sink& sink, vtkIdType first)
{
  switch (sink.Array->GetDataType())
  {
    vtkTemplateMacro(WithType(type,
      [&](auto s)
      {
        DecodeColumn<decltype(s)>(records, stride, n, swap, sink, first,
          static_cast<VTK_TT*>(sink.Array->GetVoidPointer(0)));
      }));
  }
}

// Buffered reading of the file with the position of every byte, line and token.
class Input
{
public:
  ~Input()
  {
    if (this->File)
    {
      std::fclose(this->File);
    }
  }

  bool Open(const char* fileName)
  {
    this->File = std::fopen(fileName, "rb");
    if (!this->File || std::fseek(this->File, 0, SEEK_END) != 0)
    {
      return false;
    }
    const long size = std::ftell(this->File);
    this->Size = size;
    return size >= 0 && std::fseek(this->File, 0, SEEK_SET) == 0;
  }

  vtkTypeInt64 Offset() const { return this->Consumed; }
  vtkTypeInt64 Remaining() const { return this->Size - this->Consumed; }
  vtkTypeInt64 FileSize() const { return this->Size; }
  int Line() const { return this->LineNumber; }

  // Makes min(n, what is left) bytes from the current position available; returns how many.
  std::size_t Fill(std::size_t n)
  {
    if (this->End - this->Begin < n)
    {
      // A block, or what is left of a smaller file: a vector's resize zeroes all it grows by.
      const std::size_t block = static_cast<std::size_t>(
        std::min<vtkTypeInt64>(BlockSize, std::max<vtkTypeInt64>(this->Remaining(), 0)));
      if (this->Buffer.size() < std::max(n, block))
      {
        this->Buffer.resize(std::max(n, block));
      }
      std::memmove(this->Buffer.data(), this->Buffer.data() + this->Begin, this->End - this->Begin);
      this->End -= this->Begin;
      this->Begin = 0;
      this->End += std::fread(
        this->Buffer.data() + this->End, 1, this->Buffer.size() - this->End, this->File);
    }
    return std::min(n, this->End - this->Begin);
  }

  // The next n bytes, or null when the file ends before.
  const char* Need(std::size_t n)
  {
    return this->Fill(n) == n ? this->Buffer.data() + this->Begin : nullptr;
  }

  void Consume(std::size_t n)
  {
    this->Begin += n;
    this->Consumed += static_cast<vtkTypeInt64>(n);
  }

  // One header line without its end of line; false when the file ends before the line does.
  bool ReadLine(std::string& line)
  {
    line.clear();
    while (this->Fill(1) == 1)
    {
      const char c = this->Buffer[this->Begin];
      this->Consume(1);
      if (c == '\n')
      {
        ++this->LineNumber;
        if (!line.empty() && line.back() == '\r')
        {
          line.pop_back();
        }
        return true;
      }
      if (line.size() >= MaxHeaderLine)
      {
        throw ReadError(vtkErrorCode::FileFormatError,
          "line " + std::to_string(this->LineNumber) + ": a header line longer than " +
            std::to_string(MaxHeaderLine) + " characters (not a PLY header)");
      }
      line += c;
    }
    return false;
  }

  // The next whitespace-separated ascii token; false at the end of the file.
  bool Token(const char*& begin, std::size_t& length)
  {
    for (;;)
    {
      if (this->Fill(1) == 0)
      {
        return false;
      }
      const char c = this->Buffer[this->Begin];
      if (c != ' ' && c != '\t' && c != '\r' && c != '\n')
      {
        break;
      }
      this->LineNumber += c == '\n';
      this->Consume(1);
    }
    const std::size_t available = this->Fill(MaxToken + 1);
    const char* p = this->Buffer.data() + this->Begin;
    length = 0;
    while (length < available && !std::strchr(" \t\r\n", p[length]))
    {
      ++length;
    }
    if (length > MaxToken)
    {
      throw ReadError(vtkErrorCode::FileFormatError,
        "line " + std::to_string(this->LineNumber) + ": a value longer than " +
          std::to_string(MaxToken) + " characters");
    }
    begin = p;
    this->Consume(length);
    return true;
  }

private:
  static constexpr std::size_t BlockSize = 8 << 20;
  static constexpr std::size_t MaxHeaderLine = 1 << 16;
  static constexpr std::size_t MaxToken = 64;
  std::FILE* File = nullptr;
  std::vector<char> Buffer;
  std::size_t Begin = 0;
  std::size_t End = 0;
  vtkTypeInt64 Size = 0;
  vtkTypeInt64 Consumed = 0;
  int LineNumber = 1; // of the current position
};
}

#endif
