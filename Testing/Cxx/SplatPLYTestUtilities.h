// SPDX-License-Identifier: BSD-3-Clause
// A small PLY writer for the reader tests: elements of scalar and list properties of any PLY
// type, written from double values (exact for every PLY type) in any of the three encodings.
#ifndef SplatPLYTestUtilities_h
#define SplatPLYTestUtilities_h

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace splattest
{
struct PLYProperty
{
  std::string Name;
  std::string Type;      // char, uchar, short, ushort, int, uint, float, double, or int8 ...
  std::string CountType; // empty for a scalar property
};

struct PLYElement
{
  std::string Name;
  std::vector<PLYProperty> Properties;
  // Per record, per property: one value for a scalar, the items for a list.
  std::vector<std::vector<std::vector<double>>> Records;
};

/// The vertex properties of a 3D Gaussian Splatting capture in the INRIA layout, all float:
/// x y z nx ny nz f_dc_0..2 f_rest_0..(rest - 1) opacity scale_0..2 rot_0..3.
inline std::vector<PLYProperty> GaussianCaptureProperties(int rest)
{
  std::vector<std::string> names = { "x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1",
    "f_dc_2" };
  for (int j = 0; j < rest; ++j)
  {
    names.push_back("f_rest_" + std::to_string(j));
  }
  for (const char* name :
    { "opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3" })
  {
    names.push_back(name);
  }
  std::vector<PLYProperty> properties;
  for (const std::string& name : names)
  {
    properties.push_back({ name, "float", "" });
  }
  return properties;
}

/// Bytes of one value of a PLY type; 0 for an unknown name.
inline int PLYTypeSize(const std::string& type)
{
  const char* names[][3] = { { "char", "int8", "1" }, { "uchar", "uint8", "1" },
    { "short", "int16", "2" }, { "ushort", "uint16", "2" }, { "int", "int32", "4" },
    { "uint", "uint32", "4" }, { "float", "float32", "4" }, { "double", "float64", "8" } };
  for (const auto& n : names)
  {
    if (type == n[0] || type == n[1])
    {
      return n[2][0] - '0';
    }
  }
  return 0;
}

/// Appends `value` as PLY type `type`, in the given byte order.
inline void PutBinary(std::string& out, const std::string& type, double value, bool bigEndian)
{
  char bytes[8];
  const int size = PLYTypeSize(type);
  const bool real = type == "float" || type == "float32" || type == "double" ||
    type == "float64";
  if (real && size == 4)
  {
    const float v = static_cast<float>(value);
    std::memcpy(bytes, &v, 4);
  }
  else if (real)
  {
    std::memcpy(bytes, &value, 8);
  }
  else
  {
    // Two's complement: the low bytes of the 64-bit integer (little-endian host assumed by
    // the copy below, reversed for big-endian files).
    const std::int64_t v = static_cast<std::int64_t>(value);
    std::memcpy(bytes, &v, 8);
  }
  if (bigEndian)
  {
    std::reverse(bytes, bytes + size);
  }
  out.append(bytes, size);
}

/// A PLY file of `elements` in `format` (ascii, binary_little_endian, binary_big_endian).
inline std::string PLYFile(const std::vector<PLYElement>& elements, const std::string& format)
{
  std::ostringstream header;
  header << "ply\nformat " << format << " 1.0\ncomment written by the Splat tests\n";
  for (const PLYElement& element : elements)
  {
    header << "element " << element.Name << " " << element.Records.size() << "\n";
    for (const PLYProperty& p : element.Properties)
    {
      header << "property " << (p.CountType.empty() ? "" : "list " + p.CountType + " ")
             << p.Type << " " << p.Name << "\n";
    }
  }
  header << "obj_info after the elements\nend_header\n";
  std::string data;
  const bool ascii = format == "ascii";
  const bool big = format == "binary_big_endian";
  for (const PLYElement& element : elements)
  {
    for (const auto& record : element.Records)
    {
      for (std::size_t i = 0; i < element.Properties.size(); ++i)
      {
        const PLYProperty& p = element.Properties[i];
        const std::vector<double>& values = record[i];
        if (ascii)
        {
          char text[64];
          if (!p.CountType.empty())
          {
            data += std::to_string(values.size()) + " ";
          }
          for (double v : values)
          {
            std::snprintf(text, sizeof(text), "%.17g ", v);
            data += text;
          }
        }
        else
        {
          if (!p.CountType.empty())
          {
            PutBinary(data, p.CountType, static_cast<double>(values.size()), big);
          }
          for (double v : values)
          {
            PutBinary(data, p.Type, v, big);
          }
        }
      }
      if (ascii)
      {
        data.back() = '\n';
      }
    }
  }
  return header.str() + data;
}

inline void WriteBytes(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out)
  {
    throw std::runtime_error("cannot write '" + path + "'");
  }
}
}

#endif
