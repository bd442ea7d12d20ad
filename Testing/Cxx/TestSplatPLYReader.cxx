// SPDX-License-Identifier: BSD-3-Clause
// vtkSplatPLYReader:
// - files written by the test in all three encodings, with scalar and list properties of every
//   PLY type in the vertex and face elements and an unknown element between them, read back
//   with every value equal, points as double when stored as double, float colors scaled;
// - corrupt headers and data (counts, sizes, types, list lengths, indices, ascii tokens,
//   truncations) each give an error naming the file and the place, and an empty output;
// - progress events rise from 0 to 1;
// - with --bunny: ../shared/data/bunny.ply (skipped when absent) gives what VTK's vtkPLYReader
//   gives, 35947 points and 69451 triangles.
#include "SplatPLYTestUtilities.h"
#include "SplatTestUtilities.h"
#include "vtkSplatPLYReader.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkIdTypeArray.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
using splattest::Check;

using splattest::PLYElement;

// Vertices with every scalar type, normals, RGBA, texture coordinates and a list to skip;
// an unknown element; faces with an index list, a scalar and another list. `real` is the type
// of x, y, z; `colorType` that of the colors (uchar, or float in [0, 1]).
std::vector<PLYElement> Elements(const std::string& real, const std::string& colorType)
{
  PLYElement vertex{ "vertex",
    { { "x", real, "" }, { "y", real, "" }, { "z", real, "" }, { "nx", "float32", "" },
      { "ny", "float32", "" }, { "nz", "float32", "" }, { "red", colorType, "" },
      { "green", colorType, "" }, { "blue", colorType, "" }, { "alpha", colorType, "" },
      { "u", "float", "" }, { "v", "float", "" }, { "i8", "char", "" }, { "u8", "uint8", "" },
      { "i16", "short", "" }, { "u16", "ushort", "" }, { "i32", "int", "" },
      { "u32", "uint32", "" }, { "f64", "double", "" },
      { "neighbors", "int", "uchar" } },
    {} };
  const int n = 7;
  for (int i = 0; i < n; ++i)
  {
    auto color = [&](int c)
    { return colorType == "uchar" ? (37 * i + 90 * c) % 256 : c * 0.125 + i / 16.0; };
    const double z = real == "double" ? 1e6 + 0.1 * i : 2.0 * i;
    vertex.Records.push_back({ { 0.5 * i - 1.0 }, { 1e-3 * i * i }, { z },
      { 0.0 }, { 0.6 }, { -0.8 }, { color(0) }, { color(1) }, { color(2) }, { color(0) },
      { 0.125 * i }, { 1.0 - 0.125 * i }, { -128.0 + 40 * i }, { 255.0 - 40 * i },
      { -32768.0 + 9000 * i }, { 65535.0 - 9000 * i }, { -2147483648.0 + 7e8 * i },
      { 4294967295.0 - 6e8 * i }, { 1.0 / 3.0 + i },
      std::vector<double>(i % 3, static_cast<double>(i)) });
  }
  PLYElement material{ "material", { { "shine", "float", "" }, { "name", "uchar", "int" } },
    { { { 0.5 }, { 1, 2, 3 } }, { { 0.25 }, {} } } };
  PLYElement face{ "face",
    { { "tag", "int16", "" }, { "vertex_indices", "int", "uchar" },
      { "weights", "float", "ushort" } },
    { { { -3 }, { 0, 1, 2 }, { 0.5 } }, { { 7 }, { 2, 3, 4, 5 }, {} },
      { { 300 }, { 6, 5, 0 }, { 0.25, 0.75 } } } };
  return { vertex, material, face };
}

vtkSmartPointer<vtkPolyData> Read(const std::string& path, int* errorCode, std::string* message)
{
  vtkNew<vtkSplatPLYReader> reader;
  reader->SetFileName(path.c_str());
  // Keeps the reader's error messages for the checks instead of printing them.
  vtkNew<vtkCallbackCommand> errors;
  errors->SetClientData(message);
  errors->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    { *static_cast<std::string*>(clientData) += static_cast<const char*>(callData); });
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->Update();
  *errorCode = reader->GetErrorCode();
  return reader->GetOutput();
}

// Whether component c of tuple t of `array` is `expected` (as the array's own type stores it).
bool Equal(vtkDataArray* array, vtkIdType t, int c, double expected)
{
  return array && array->GetComponent(t, c) == expected;
}

void CheckRoundTrip(const std::string& folder, const std::string& format, const std::string& real,
  const std::string& colorType)
{
  const std::vector<PLYElement> elements = Elements(real, colorType);
  const std::string path = folder + "/TestSplatPLYReader_" + format + "_" + real + ".ply";
  splattest::WriteBytes(path, splattest::PLYFile(elements, format));
  int code;
  std::string message;
  vtkSmartPointer<vtkPolyData> data = Read(path, &code, &message);
  const std::string what = format + " (" + real + " points, " + colorType + " colors): ";
  Check(code == vtkErrorCode::NoError && message.empty(), what + "read without error " + message);
  const PLYElement& vertex = elements[0];
  const vtkIdType n = static_cast<vtkIdType>(vertex.Records.size());
  Check(data->GetNumberOfPoints() == n, what + "number of points");
  if (data->GetNumberOfPoints() != n)
  {
    return;
  }
  Check(data->GetPoints()->GetDataType() == (real == "double" ? VTK_DOUBLE : VTK_FLOAT),
    what + "points stored as " + real);
  vtkPointData* pd = data->GetPointData();
  Check(pd->GetNormals() && std::string(pd->GetNormals()->GetName()) == "Normals",
    what + "Normals");
  Check(pd->GetScalars() && std::string(pd->GetScalars()->GetName()) == "RGBA" &&
      pd->GetScalars()->GetDataType() == VTK_UNSIGNED_CHAR,
    what + "RGBA unsigned char scalars");
  Check(pd->GetTCoords() && pd->GetTCoords()->GetNumberOfComponents() == 2, what + "TCoords");
  Check(!pd->GetArray("neighbors") && !pd->GetArray("x"), what + "no arrays for lists or xyz");
  const std::vector<std::pair<const char*, int>> typed = { { "i8", VTK_SIGNED_CHAR },
    { "u8", VTK_UNSIGNED_CHAR }, { "i16", VTK_SHORT }, { "u16", VTK_UNSIGNED_SHORT },
    { "i32", VTK_INT }, { "u32", VTK_UNSIGNED_INT }, { "f64", VTK_DOUBLE } };
  for (const auto& [name, type] : typed)
  {
    Check(pd->GetArray(name) && pd->GetArray(name)->GetDataType() == type,
      what + "array " + name + " of its PLY type");
  }
  int wrong = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const auto& r = vertex.Records[i];
    double p[3];
    data->GetPoint(i, p);
    const bool asFloat = real != "double";
    for (int c = 0; c < 3; ++c)
    {
      wrong += p[c] != (asFloat ? static_cast<float>(r[c][0]) : r[c][0]);
      wrong += !Equal(pd->GetNormals(), i, c, static_cast<float>(r[3 + c][0]));
    }
    for (int c = 0; c < 4; ++c)
    {
      const double v = r[6 + c][0];
      wrong += !Equal(pd->GetScalars(), i, c,
        colorType == "uchar" ? v : std::round(static_cast<float>(v) * 255.0));
    }
    wrong += !Equal(pd->GetTCoords(), i, 0, r[10][0]) + !Equal(pd->GetTCoords(), i, 1, r[11][0]);
    for (std::size_t k = 0; k < typed.size(); ++k)
    {
      wrong += !Equal(pd->GetArray(typed[k].first), i, 0, r[12 + k][0]);
    }
  }
  Check(wrong == 0, what + std::to_string(wrong) + " vertex values differ");

  const PLYElement& face = elements[2];
  vtkCellArray* polys = data->GetPolys();
  Check(polys->GetNumberOfCells() == 3, what + "three faces");
  vtkDataArray* tag = data->GetCellData()->GetArray("tag");
  Check(tag && tag->GetDataType() == VTK_SHORT, what + "face scalar as a short cell array");
  wrong = 0;
  for (vtkIdType f = 0; f < polys->GetNumberOfCells() && f < 3; ++f)
  {
    vtkNew<vtkIdList> ids;
    polys->GetCellAtId(f, ids);
    const std::vector<double>& expected = face.Records[f][1];
    wrong += ids->GetNumberOfIds() != static_cast<vtkIdType>(expected.size());
    for (vtkIdType k = 0; k < ids->GetNumberOfIds() && k < vtkIdType(expected.size()); ++k)
    {
      wrong += ids->GetId(k) != expected[k];
    }
    wrong += !Equal(tag, f, 0, face.Records[f][0][0]);
  }
  Check(wrong == 0, what + std::to_string(wrong) + " face values differ");
}

// Each variant of a valid file must give an error naming the file and a place, and no points.
void CheckCorrupt(const std::string& folder)
{
  const std::string good = splattest::PLYFile(Elements("float", "uchar"), "binary_little_endian");
  const std::string ascii = splattest::PLYFile(Elements("float", "uchar"), "ascii");
  const std::size_t data = good.find("end_header\n") + 11;
  auto replace = [](std::string text, const std::string& from, const std::string& to)
  {
    const std::size_t at = text.find(from);
    return at == std::string::npos ? std::string() : text.replace(at, from.size(), to);
  };
  // The first face record: tag (2 bytes) then the uchar index count at this offset.
  const std::size_t faceCount = good.size() - (2 + 1 + 12 + 2 + 4) - (2 + 1 + 16 + 2) -
    (2 + 1 + 12 + 2 + 8) + 2;
  std::string badLength = good, badIndex = good;
  badLength[faceCount] = static_cast<char>(200);
  badIndex[faceCount + 1] = 9; // vertex 9 of 7
  const std::vector<std::pair<std::string, std::string>> variants = {
    { "no ply magic", replace(good, "ply\n", "plx\n") },
    { "unknown format", replace(good, "binary_little_endian", "binary_middle_endian") },
    { "huge vertex count", replace(good, "element vertex 7", "element vertex 999999999999") },
    { "count overflowing int64",
      replace(good, "element vertex 7", "element vertex 99999999999999999999") },
    { "negative count", replace(good, "element vertex 7", "element vertex -7") },
    { "count with letters", replace(good, "element vertex 7", "element vertex 7x") },
    { "unknown type", replace(good, "property float32 nx", "property float128 nx") },
    { "float list length",
      replace(good, "list uchar int vertex_indices", "list float int vertex_indices") },
    { "float vertex indices",
      replace(good, "list uchar int vertex_indices", "list uchar float vertex_indices") },
    { "property before element",
      replace(good, "element vertex 7\n", "property float w\nelement vertex 7\n") },
    { "no z", replace(good, "property float z\n", "property float w\n") },
    { "duplicate property", replace(good, "property float32 nx", "property float32 ny") },
    { "no end_header", good.substr(0, data - 11) },
    { "truncated in the vertices", good.substr(0, data + 100) },
    { "truncated in the faces", good.substr(0, good.size() - 7) },
    { "list length beyond the file", badLength },
    { "vertex index out of range", badIndex },
    { "ascii: a letter for a float",
      replace(ascii, "end_header\n-1 0 ", "end_header\n-1 zero ") },
    { "ascii: a fraction for an int", replace(ascii, " -128 ", " -128.5 ") },
    { "ascii: out of range uchar", replace(ascii, " 255 -32768 ", " 256 -32768 ") },
    { "ascii: truncated", ascii.substr(0, ascii.size() - 9) },
  };
  for (const auto& [name, bytes] : variants)
  {
    Check(!bytes.empty() && bytes != good && bytes != ascii, "variant '" + name + "' made");
    const std::string path = folder + "/TestSplatPLYReader_corrupt.ply";
    splattest::WriteBytes(path, bytes);
    int code;
    std::string message;
    vtkSmartPointer<vtkPolyData> output = Read(path, &code, &message);
    // The message after vtkErrorMacro's prefix (which names the source line).
    const std::size_t prefix = message.find("): ");
    const std::string text = prefix == std::string::npos ? message : message.substr(prefix + 3);
    const bool placed = text.find("line ") != std::string::npos ||
      text.find("byte ") != std::string::npos || name == "no ply magic";
    std::printf("%-30s -> %s", name.c_str(), text.c_str());
    Check(code != vtkErrorCode::NoError && output->GetNumberOfPoints() == 0 &&
        message.find(path) != std::string::npos && placed,
      "'" + name + "' gives an error naming the file and the place, and no points");
  }
}

int CompareBunny(const std::string& path)
{
  if (!splattest::FileExists(path))
  {
    std::printf("%s is absent: skipped\n", path.c_str());
    return splattest::SkipReturnCode;
  }
  vtkNew<vtkPLYReader> vtkReader;
  vtkReader->SetFileName(path.c_str());
  vtkReader->Update();
  vtkPolyData* expected = vtkReader->GetOutput();
  int code;
  std::string message;
  vtkSmartPointer<vtkPolyData> data = Read(path, &code, &message);
  std::printf("bunny: %lld points, %lld polygons (vtkPLYReader: %lld, %lld)\n",
    static_cast<long long>(data->GetNumberOfPoints()),
    static_cast<long long>(data->GetNumberOfPolys()),
    static_cast<long long>(expected->GetNumberOfPoints()),
    static_cast<long long>(expected->GetNumberOfPolys()));
  Check(code == vtkErrorCode::NoError, "bunny read without error");
  Check(data->GetNumberOfPoints() == 35947 && data->GetNumberOfPolys() == 69451,
    "35947 points and 69451 polygons");
  Check(expected->GetNumberOfPoints() == data->GetNumberOfPoints() &&
      expected->GetNumberOfPolys() == data->GetNumberOfPolys(),
    "the counts of vtkPLYReader");
  if (splattest::Failures())
  {
    return EXIT_FAILURE;
  }
  vtkIdType differences = 0;
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    double a[3], b[3];
    data->GetPoint(i, a);
    expected->GetPoint(i, b);
    differences += a[0] != b[0] || a[1] != b[1] || a[2] != b[2];
  }
  vtkNew<vtkIdTypeArray> ours, theirs;
  data->GetPolys()->ExportLegacyFormat(ours);
  expected->GetPolys()->ExportLegacyFormat(theirs);
  Check(ours->GetNumberOfValues() == theirs->GetNumberOfValues(), "same connectivity size");
  for (vtkIdType i = 0; i < ours->GetNumberOfValues() && i < theirs->GetNumberOfValues(); ++i)
  {
    differences += ours->GetValue(i) != theirs->GetValue(i);
  }
  Check(differences == 0, std::to_string(differences) + " point or index values differ");
  for (const char* name : { "confidence", "intensity" })
  {
    Check(data->GetPointData()->GetArray(name) != nullptr,
      std::string("the vertex property '") + name + "' as an array");
  }
  return splattest::Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}
}

int main(int argc, char* argv[])
{
  if (std::string(argv[argc - 1]) == "--bunny")
  {
    return CompareBunny(splattest::Argument(argc, argv, "-D") + "/bunny.ply");
  }
  const std::string folder = splattest::Argument(argc, argv, "-T");
  for (const char* format : { "ascii", "binary_little_endian", "binary_big_endian" })
  {
    CheckRoundTrip(folder, format, "float", "uchar");
    CheckRoundTrip(folder, format, "double", "float");
  }
  vtkNew<vtkStringArray> names;
  Check(vtkSplatPLYReader::GetVertexPropertyNames(
          (folder + "/TestSplatPLYReader_ascii_float.ply").c_str(), names) &&
      names->GetNumberOfValues() == 20 && names->GetValue(19) == "neighbors",
    "GetVertexPropertyNames lists the 20 vertex properties");
  CheckCorrupt(folder);

  // Progress events from 0 to 1.
  std::vector<double> progress;
  vtkNew<vtkSplatPLYReader> reader;
  reader->SetFileName((folder + "/TestSplatPLYReader_binary_big_endian_double.ply").c_str());
  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(&progress);
  observer->SetCallback([](vtkObject*, unsigned long, void* clientData, void* callData)
    { static_cast<std::vector<double>*>(clientData)->push_back(*static_cast<double*>(callData)); });
  reader->AddObserver(vtkCommand::ProgressEvent, observer);
  reader->Update();
  Check(progress.size() >= 3 && progress.front() == 0.0 && progress.back() == 1.0 &&
      std::is_sorted(progress.begin(), progress.end()),
    "progress events rising from 0 to 1");
  return splattest::Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}
