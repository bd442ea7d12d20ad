// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSplatPLYReader.h"
#include "SplatPLYFormat.h"

#include "vtkCellArray.h"
#include "vtkGaussianSplatReader.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSplatPLYReader);

namespace
{
using namespace splatply;

// The PLY header and the data reading.
class Parser
{
public:
  Format Encoding = Ascii;
  std::vector<Element> Elements;
  Input In;

  void ReadHeader(const char* fileName)
  {
    if (!this->In.Open(fileName))
    {
      throw ReadError(vtkErrorCode::CannotOpenFileError, "cannot open the file");
    }
    std::string line;
    if (!this->In.ReadLine(line) || line != "ply")
    {
      throw ReadError(vtkErrorCode::UnrecognizedFileTypeError,
        "not a PLY file (the first line must be 'ply')");
    }
    bool formatSeen = false;
    for (;;)
    {
      if (!this->In.ReadLine(line))
      {
        throw ReadError(vtkErrorCode::PrematureEndOfFileError,
          "header line " + std::to_string(this->In.Line()) +
            ": the file ends inside the header (no end_header)");
      }
      std::istringstream words(line);
      std::string keyword;
      words >> keyword;
      if (keyword.empty() || keyword == "comment" || keyword == "obj_info")
      {
        continue;
      }
      if (keyword == "end_header")
      {
        break;
      }
      std::vector<std::string> fields;
      for (std::string word; words >> word;)
      {
        fields.push_back(word);
      }
      if (keyword == "format")
      {
        this->ParseFormat(fields, formatSeen);
        formatSeen = true;
      }
      else if (keyword == "element")
      {
        this->ParseElement(fields);
      }
      else if (keyword == "property")
      {
        this->ParseProperty(fields);
      }
      else
      {
        throw this->HeaderError(
          vtkErrorCode::FileFormatError, "unknown header keyword '" + keyword + "'");
      }
    }
    if (!formatSeen)
    {
      throw this->HeaderError(vtkErrorCode::FileFormatError, "no format line in the header");
    }
    for (Element& element : this->Elements)
    {
      this->Layout(element);
    }
    this->Swap = this->Encoding != Ascii &&
      (this->Encoding == BinaryLittleEndian) != HostIsLittleEndian();
  }

  const Element* Find(const std::string& name) const
  {
    for (const Element& element : this->Elements)
    {
      if (element.Name == name)
      {
        return &element;
      }
    }
    return nullptr;
  }

  // Reads the data of every element into `output`: the vertices as points and point data, the
  // faces as polygons and cell data. `progress` is called with the fraction of the file read.
  // Reads the scalar properties of every element into field-data arrays of `output` named
  // element.property; `progress` as above.
  template <typename Progress>
  void ReadAllElements(vtkPolyData* output, Progress&& progress)
  {
    for (const Element& element : this->Elements)
    {
      if (element.Properties.empty())
      {
        continue;
      }
      this->CheckFits(element);
      std::vector<Sink> sinks(element.Properties.size());
      for (std::size_t i = 0; i < element.Properties.size(); ++i)
      {
        const Property& property = element.Properties[i];
        if (property.CountType < 0)
        {
          sinks[i].Array = NewArray(output->GetFieldData(), Types[property.Type].VTKType,
            (element.Name + "." + property.Name).c_str(), 1, element.Count);
        }
      }
      this->ReadElement(element, sinks, -1, 0, output, progress);
    }
  }

  template <typename Progress>
  void ReadData(vtkPolyData* output, Progress&& progress)
  {
    const Element* vertex = this->Find("vertex");
    if (!vertex)
    {
      throw ReadError(vtkErrorCode::FileFormatError, "the header has no vertex element");
    }
    for (const char* axis : { "x", "y", "z" })
    {
      if (vertex->Find(axis) < 0)
      {
        throw ReadError(vtkErrorCode::FileFormatError,
          "header line " + std::to_string(vertex->Line) +
            ": the vertex element has no scalar property " + axis);
      }
    }
    for (const Element& element : this->Elements)
    {
      if (element.Properties.empty())
      {
        continue; // nothing to read, whatever its count
      }
      this->CheckFits(element); // before anything is allocated for it
      std::vector<Sink> sinks(element.Properties.size());
      int indices = -1;
      if (&element == vertex)
      {
        this->VertexSinks(element, output, sinks);
      }
      else if (element.Name == "face")
      {
        indices = this->FaceIndices(element);
        if (indices >= 0)
        {
          this->AttributeSinks(element, output->GetCellData(), sinks);
        }
      }
      this->ReadElement(element, sinks, indices, vertex->Count, output, progress);
    }
  }

private:
  // The number of the header line just read.
  int HeaderLine() const { return this->In.Line() - 1; }

  ReadError HeaderError(int code, const std::string& what) const
  {
    return ReadError(code, "header line " + std::to_string(this->HeaderLine()) + ": " + what);
  }

  int ParseType(const std::string& name) const
  {
    for (int type = Int8; type <= Float64; ++type)
    {
      if (name == Types[type].Name || name == Types[type].SizedName)
      {
        return type;
      }
    }
    throw this->HeaderError(vtkErrorCode::FileFormatError, "unknown property type '" + name + "'");
  }

  void ParseFormat(const std::vector<std::string>& fields, bool seen)
  {
    if (seen || !this->Elements.empty())
    {
      throw this->HeaderError(
        vtkErrorCode::FileFormatError, "the format line must come once, before the elements");
    }
    const char* names[] = { "ascii", "binary_little_endian", "binary_big_endian" };
    for (int format = Ascii; format <= BinaryBigEndian; ++format)
    {
      if (fields.size() == 2 && fields[0] == names[format] && fields[1] == "1.0")
      {
        this->Encoding = static_cast<Format>(format);
        return;
      }
    }
    throw this->HeaderError(vtkErrorCode::FileFormatError,
      "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  }

  void ParseElement(const std::vector<std::string>& fields)
  {
    Element element;
    const char* last = fields.size() == 2 ? fields[1].data() + fields[1].size() : nullptr;
    const auto parsed =
      last ? std::from_chars(fields[1].data(), last, element.Count) : std::from_chars_result{};
    if (!last || parsed.ptr != last || parsed.ec != std::errc() || element.Count < 0)
    {
      throw this->HeaderError(
        vtkErrorCode::FileFormatError, "expected 'element NAME COUNT' with a count >= 0");
    }
    element.Name = fields[0];
    element.Line = this->HeaderLine();
    if (this->Find(element.Name))
    {
      throw this->HeaderError(
        vtkErrorCode::FileFormatError, "a second element named '" + element.Name + "'");
    }
    this->Elements.push_back(element);
  }

  void ParseProperty(const std::vector<std::string>& fields)
  {
    if (this->Elements.empty())
    {
      throw this->HeaderError(vtkErrorCode::FileFormatError, "a property before any element");
    }
    Property property;
    if (fields.size() == 4 && fields[0] == "list")
    {
      property.CountType = this->ParseType(fields[1]);
      property.Type = this->ParseType(fields[2]);
      if (!IsInteger(property.CountType))
      {
        throw this->HeaderError(vtkErrorCode::FileFormatError,
          "the length of list '" + fields[3] + "' must have an integer type");
      }
    }
    else if (fields.size() == 2 && fields[0] != "list")
    {
      property.Type = this->ParseType(fields[0]);
    }
    else
    {
      throw this->HeaderError(vtkErrorCode::FileFormatError,
        "expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
    }
    property.Name = fields.back();
    property.Line = this->HeaderLine();
    Element& element = this->Elements.back();
    for (const Property& other : element.Properties)
    {
      if (other.Name == property.Name)
      {
        throw this->HeaderError(vtkErrorCode::FileFormatError,
          "a second property '" + property.Name + "' in element '" + element.Name + "'");
      }
    }
    element.Properties.push_back(property);
  }

  // Scalar offsets in the packed record of the element's scalars, and the record sizes.
  static void Layout(Element& element)
  {
    for (Property& property : element.Properties)
    {
      if (property.CountType >= 0)
      {
        element.HasLists = true;
        element.MinimumSize += Types[property.CountType].Size;
      }
      else
      {
        property.Offset = element.ScalarSize;
        element.ScalarSize += Types[property.Type].Size;
        element.MinimumSize += Types[property.Type].Size;
      }
    }
  }

  // The list of a face element holding its vertex indices, or -1.
  int FaceIndices(const Element& element) const
  {
    for (std::size_t i = 0; i < element.Properties.size(); ++i)
    {
      const Property& property = element.Properties[i];
      if (property.CountType >= 0 &&
        (property.Name == "vertex_indices" || property.Name == "vertex_index"))
      {
        if (!IsInteger(property.Type))
        {
          throw ReadError(vtkErrorCode::FileFormatError,
            "header line " + std::to_string(property.Line) + ": the face list '" +
              property.Name + "' must have an integer type");
        }
        return static_cast<int>(i);
      }
    }
    return -1;
  }

  // A new array of `count` tuples added to `attributes`.
  static vtkDataArray* NewArray(vtkFieldData* attributes, int vtkType, const char* name,
    int components, vtkIdType count)
  {
    vtkSmartPointer<vtkDataArray> array =
      vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(vtkType));
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(count);
    attributes->AddArray(array);
    return array;
  }

  // Sinks for the named properties `names` (all scalars of `element`) as the components of
  // one new array; null when any is missing.
  static vtkDataArray* Group(const Element& element, std::vector<Sink>& sinks,
    std::initializer_list<const char*> names, vtkDataSetAttributes* attributes, int vtkType,
    const char* arrayName, bool color = false)
  {
    std::vector<int> found;
    for (const char* name : names)
    {
      found.push_back(element.Find(name));
      if (found.back() < 0 || sinks[found.back()].Array)
      {
        return nullptr;
      }
    }
    vtkDataArray* array = NewArray(
      attributes, vtkType, arrayName, static_cast<int>(names.size()), element.Count);
    for (std::size_t c = 0; c < found.size(); ++c)
    {
      sinks[found[c]] = Sink{ array, static_cast<int>(c), color };
    }
    return array;
  }

  // Colors, normals, texture coordinates and named arrays for the scalars of `element`.
  static void AttributeSinks(
    const Element& element, vtkDataSetAttributes* attributes, std::vector<Sink>& sinks)
  {
    if (vtkDataArray* rgba = Group(element, sinks, { "red", "green", "blue", "alpha" },
          attributes, VTK_UNSIGNED_CHAR, "RGBA", true))
    {
      attributes->SetScalars(rgba);
    }
    else if (vtkDataArray* rgb = Group(element, sinks, { "red", "green", "blue" }, attributes,
               VTK_UNSIGNED_CHAR, "RGB", true))
    {
      attributes->SetScalars(rgb);
    }
    if (vtkDataArray* normals =
          Group(element, sinks, { "nx", "ny", "nz" }, attributes, VTK_FLOAT, "Normals"))
    {
      attributes->SetNormals(normals);
    }
    vtkDataArray* tcoords =
      Group(element, sinks, { "u", "v" }, attributes, VTK_FLOAT, "TCoords");
    tcoords = tcoords ? tcoords
                      : Group(element, sinks, { "s", "t" }, attributes, VTK_FLOAT, "TCoords");
    tcoords = tcoords ? tcoords
                      : Group(element, sinks, { "texture_u", "texture_v" }, attributes,
                          VTK_FLOAT, "TCoords");
    if (tcoords)
    {
      attributes->SetTCoords(tcoords);
    }
    for (std::size_t i = 0; i < element.Properties.size(); ++i)
    {
      const Property& property = element.Properties[i];
      if (property.CountType < 0 && !sinks[i].Array)
      {
        sinks[i].Array = NewArray(attributes, Types[property.Type].VTKType,
          property.Name.c_str(), 1, element.Count);
      }
    }
  }

  static void VertexSinks(const Element& element, vtkPolyData* output, std::vector<Sink>& sinks)
  {
    const int axes[] = { element.Find("x"), element.Find("y"), element.Find("z") };
    vtkNew<vtkPoints> points;
    const bool isDouble = std::any_of(
      axes, axes + 3, [&](int i) { return element.Properties[i].Type == Float64; });
    points->SetDataType(isDouble ? VTK_DOUBLE : VTK_FLOAT);
    points->SetNumberOfPoints(element.Count);
    output->SetPoints(points);
    for (int c = 0; c < 3; ++c)
    {
      sinks[axes[c]] = Sink{ points->GetData(), c, false };
    }
    AttributeSinks(element, output->GetPointData(), sinks);
  }

  std::string Where() const
  {
    return this->Encoding == Ascii ? "line " + std::to_string(this->In.Line())
                                   : "byte " + std::to_string(this->In.Offset());
  }

  ReadError Truncated(const Element& element, vtkTypeInt64 record) const
  {
    return ReadError(vtkErrorCode::PrematureEndOfFileError,
      this->Where() + ": the file ends inside " + element.Name + " " + std::to_string(record) +
        " of " + std::to_string(element.Count));
  }

  // Checks before allocating that the element's records fit in the rest of the file: binary
  // records of at least MinimumSize bytes (empty lists), ascii ones of at least two characters
  // a value (the last one of the file may lack its separator).
  void CheckFits(const Element& element) const
  {
    const vtkTypeInt64 remaining = this->In.Remaining();
    const vtkTypeInt64 least = this->Encoding == Ascii
      ? 2 * static_cast<vtkTypeInt64>(element.Properties.size())
      : static_cast<vtkTypeInt64>(element.MinimumSize);
    if (least > 0 && element.Count > (remaining + (this->Encoding == Ascii)) / least)
    {
      throw ReadError(vtkErrorCode::PrematureEndOfFileError,
        this->Where() + ": the header announces " + std::to_string(element.Count) + " " +
          element.Name + " elements of at least " + std::to_string(least) +
          (this->Encoding == Ascii ? " characters" : " bytes") + " each, but only " +
          std::to_string(remaining) + " bytes follow");
    }
  }

  // The next ascii value of `type` stored natively at `out`.
  void ParseValue(int type, char* out, const Element& element, vtkTypeInt64 record)
  {
    const char* token;
    std::size_t length;
    if (!this->In.Token(token, length))
    {
      throw this->Truncated(element, record);
    }
    const char* end = token + length;
    const bool ok = WithType(type,
      [&](auto v)
      {
        using T = decltype(v);
        bool valid;
        // from_chars takes no '+' sign.
        const char* start = token + (length > 1 && token[0] == '+');
        if constexpr (std::is_floating_point<T>::value)
        {
          double value = 0.0;
          const auto parsed = std::from_chars(start, end, value);
          valid = parsed.ptr == end && parsed.ec == std::errc();
          // Values beyond the type's range are errors; NaN and infinities are passed on.
          valid = valid &&
            !(std::isfinite(value) && std::abs(value) > std::numeric_limits<T>::max());
          v = valid ? static_cast<T>(value) : T{};
        }
        else
        {
          long long value = 0;
          const auto parsed = std::from_chars(start, end, value);
          valid = parsed.ptr == end && parsed.ec == std::errc() &&
            value >= std::numeric_limits<T>::lowest() && value <= std::numeric_limits<T>::max();
          v = valid ? static_cast<T>(value) : T{};
        }
        std::memcpy(out, &v, sizeof(T));
        return valid;
      });
    if (!ok)
    {
      throw ReadError(vtkErrorCode::FileFormatError,
        this->Where() + ": '" + std::string(token, length) + "' is not a " + Types[type].Name +
          " (" + element.Name + " " + std::to_string(record) + ")");
    }
  }

  // The next value of integer `type` (a list length or index), in ascii or binary.
  long long ReadInteger(int type, const Element& element, vtkTypeInt64 record)
  {
    char value[8];
    const char* p = value;
    if (this->Encoding == Ascii)
    {
      this->ParseValue(type, value, element, record);
    }
    else
    {
      p = this->In.Need(Types[type].Size);
      if (!p)
      {
        throw this->Truncated(element, record);
      }
    }
    const bool swap = this->Encoding != Ascii && this->Swap;
    const long long result = WithType(
      type, [&](auto v) { return static_cast<long long>(Load<decltype(v)>(p, swap)); });
    if (this->Encoding != Ascii)
    {
      this->In.Consume(Types[type].Size);
    }
    return result;
  }

  // Reads one record of an element with lists: its scalars packed into `scalars`, the vertex
  // indices of list `indices` appended to `connectivity`, the other lists skipped.
  void ReadListRecord(const Element& element, vtkTypeInt64 record, char* scalars, int indices,
    vtkTypeInt64 vertices, vtkIdTypeArray* connectivity)
  {
    for (std::size_t i = 0; i < element.Properties.size(); ++i)
    {
      const Property& property = element.Properties[i];
      const int size = Types[property.Type].Size;
      if (property.CountType < 0)
      {
        this->ReadScalar(property, scalars + property.Offset, element, record);
        continue;
      }
      const long long length = this->ReadInteger(property.CountType, element, record);
      const vtkTypeInt64 room = this->Encoding == Ascii ? (this->In.Remaining() + 1) / 2
                                                        : this->In.Remaining() / size;
      if (length < 0 || length > room)
      {
        throw ReadError(vtkErrorCode::FileFormatError,
          this->Where() + ": list '" + property.Name + "' of " + element.Name + " " +
            std::to_string(record) + " has length " + std::to_string(length) +
            (length < 0 ? "" : ", more than the rest of the file holds"));
      }
      if (static_cast<int>(i) == indices)
      {
        for (long long k = 0; k < length; ++k)
        {
          const long long index = this->ReadInteger(property.Type, element, record);
          if (index < 0 || index >= vertices)
          {
            throw ReadError(vtkErrorCode::FileFormatError,
              this->Where() + ": vertex index " + std::to_string(index) + " of " +
                element.Name + " " + std::to_string(record) + " is outside [0, " +
                std::to_string(vertices) + ")");
          }
          connectivity->InsertNextValue(static_cast<vtkIdType>(index));
        }
      }
      else if (this->Encoding == Ascii)
      {
        char ignored[8];
        for (long long k = 0; k < length; ++k)
        {
          this->ParseValue(property.Type, ignored, element, record);
        }
      }
      else
      {
        // Within the file: checked against the room above.
        for (vtkTypeInt64 left = length * size; left > 0;)
        {
          const std::size_t step =
            this->In.Fill(static_cast<std::size_t>(std::min<vtkTypeInt64>(left, 1 << 20)));
          if (step == 0)
          {
            throw this->Truncated(element, record);
          }
          this->In.Consume(step);
          left -= static_cast<vtkTypeInt64>(step);
        }
      }
    }
  }

  void ReadScalar(const Property& property, char* out, const Element& element, vtkTypeInt64 record)
  {
    if (this->Encoding == Ascii)
    {
      this->ParseValue(property.Type, out, element, record);
      return;
    }
    const int size = Types[property.Type].Size;
    const char* p = this->In.Need(size);
    if (!p)
    {
      throw this->Truncated(element, record);
    }
    std::memcpy(out, p, size);
    this->In.Consume(size);
  }

  template <typename Progress>
  void ReadElement(const Element& element, const std::vector<Sink>& sinks, int indices,
    vtkTypeInt64 vertices, vtkPolyData* output, Progress& progress)
  {
    vtkNew<vtkIdTypeArray> offsets, connectivity;
    if (indices >= 0)
    {
      offsets->SetNumberOfValues(element.Count + 1);
      offsets->SetValue(0, 0);
    }
    const std::size_t size = std::max<std::size_t>(element.ScalarSize, 1);
    const vtkTypeInt64 batch = element.HasLists
      ? 1 << 16
      : std::max<vtkTypeInt64>(1, static_cast<vtkTypeInt64>((256 << 10) / size));
    // Binary records without lists are decoded from the file's bytes; the others are packed
    // into `packed` first (binary values in the file's byte order, ascii ones in the machine's,
    // for which Swap is false).
    const bool direct = this->Encoding != Ascii && !element.HasLists;
    std::vector<char> packed;
    for (vtkTypeInt64 first = 0; first < element.Count; first += batch)
    {
      const vtkTypeInt64 n = std::min(batch, element.Count - first);
      const char* records;
      if (direct)
      {
        records = this->In.Need(static_cast<std::size_t>(n) * element.ScalarSize);
        if (!records)
        {
          const vtkTypeInt64 complete = this->In.Remaining() / element.ScalarSize;
          throw ReadError(vtkErrorCode::PrematureEndOfFileError,
            "byte " + std::to_string(this->In.FileSize()) + ": the file ends inside " +
              element.Name + " " + std::to_string(first + complete) + " of " +
              std::to_string(element.Count) + " (which starts at byte " +
              std::to_string(this->In.Offset() + complete * element.ScalarSize) + ")");
        }
      }
      else
      {
        packed.resize(static_cast<std::size_t>(n) * element.ScalarSize);
        for (vtkTypeInt64 r = 0; r < n; ++r)
        {
          char* record = packed.data() + r * element.ScalarSize;
          if (element.HasLists)
          {
            this->ReadListRecord(
              element, first + r, record, indices, vertices, connectivity);
            if (indices >= 0)
            {
              offsets->SetValue(first + r + 1, connectivity->GetNumberOfValues());
            }
          }
          else
          {
            for (const Property& property : element.Properties)
            {
              this->ReadScalar(property, record + property.Offset, element, first + r);
            }
          }
        }
        records = packed.data();
      }
      for (std::size_t i = 0; i < element.Properties.size(); ++i)
      {
        if (sinks[i].Array)
        {
          Decode(records + element.Properties[i].Offset, element.ScalarSize,
            static_cast<std::size_t>(n), this->Swap, element.Properties[i].Type, sinks[i], first);
        }
      }
      if (direct)
      {
        this->In.Consume(static_cast<std::size_t>(n) * element.ScalarSize);
      }
      progress(static_cast<double>(this->In.Offset()) / std::max<vtkTypeInt64>(
        this->In.FileSize(), 1));
    }
    if (indices >= 0)
    {
      vtkNew<vtkCellArray> polys;
      polys->SetData(offsets, connectivity);
      output->SetPolys(polys);
    }
  }

  bool Swap = false; // binary data in the other byte order than the machine's
};
}

//------------------------------------------------------------------------------
vtkSplatPLYReader::vtkSplatPLYReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkSplatPLYReader::~vtkSplatPLYReader()
{
  this->SetFileName(nullptr);
}

//------------------------------------------------------------------------------
bool vtkSplatPLYReader::CanReadFile(const char* fileName)
{
  Parser parser;
  try
  {
    parser.ReadHeader(fileName);
    return !vtkGaussianSplatReader::IsGaussianSplatFile(fileName);
  }
  catch (const std::exception&)
  {
    return false;
  }
}

//------------------------------------------------------------------------------
bool vtkSplatPLYReader::GetVertexPropertyNames(const char* fileName, vtkStringArray* names)
{
  names->Initialize();
  Parser parser;
  try
  {
    parser.ReadHeader(fileName);
  }
  catch (const std::exception&)
  {
    return false;
  }
  const Element* vertex = parser.Find("vertex");
  if (!vertex)
  {
    return false;
  }
  for (const Property& property : vertex->Properties)
  {
    names->InsertNextValue(property.Name);
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkSplatPLYReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  this->SetErrorCode(vtkErrorCode::NoError);
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro("No FileName given.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return 0;
  }
  this->UpdateProgress(0.0);
  vtkNew<vtkPolyData> result;
  Parser parser;
  try
  {
    parser.ReadHeader(this->FileName);
    const auto progress = [this](double fraction) { this->UpdateProgress(fraction); };
    if (this->ReadAllElements)
    {
      parser.ReadAllElements(result, progress);
    }
    else
    {
      parser.ReadData(result, progress);
    }
  }
  catch (const ReadError& error)
  {
    vtkErrorMacro(<< this->FileName << ": " << error.what());
    this->SetErrorCode(error.Code);
    return 0;
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro(<< this->FileName << ": out of memory");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return 0;
  }
  output->ShallowCopy(result);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkSplatPLYReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ReadAllElements: " << (this->ReadAllElements ? "On" : "Off") << "\n";
}
