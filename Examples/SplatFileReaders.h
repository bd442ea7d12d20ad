// SPDX-License-Identifier: BSD-3-Clause
// The files the example programs read, by extension: meshes and point clouds (.ply, .vtp, .xyz,
// .off), 3D Gaussian Splatting captures (every format vtkGaussianSplatReader reads, by content)
// and volumes (.nii, .nii.gz, .vti, .mhd, .mha). Every reader throws std::runtime_error with a message naming the
// file when it cannot read it.
#ifndef SplatFileReaders_h
#define SplatFileReaders_h

#include "SplatFileChecks.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkErrorCode.h"
#include "vtkFloatArray.h"
#include "vtkGaussianSplatReader.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMetaImageReader.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkSplatPLYReader.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLPolyDataReader.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h> // mkdtemp

namespace splatexample
{
/// Whether the file name's last extension is `extension` (".ply"), in any letter case.
inline bool HasExtension(const std::string& path, const std::string& extension)
{
  return vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(path)) ==
    extension;
}

// Text point cloud: "x y z" or "x y z nx ny nz" per line, the same on every line; lines
// starting with # are comments.
inline vtkSmartPointer<vtkPolyData> ReadXYZ(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw std::runtime_error("cannot open '" + path + "'");
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  std::size_t columns = 0;
  std::string line;
  for (int lineNumber = 1; std::getline(in, line); ++lineNumber)
  {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#')
    {
      continue;
    }
    std::istringstream fields(line);
    std::vector<double> values;
    double value;
    while (fields >> value)
    {
      values.push_back(value);
    }
    const std::string where = path + ":" + std::to_string(lineNumber) + ": ";
    if (!fields.eof() || (values.size() != 3 && values.size() != 6))
    {
      throw std::runtime_error(where + "expected 'x y z' or 'x y z nx ny nz', got '" + line + "'");
    }
    if (columns != 0 && values.size() != columns)
    {
      throw std::runtime_error(where + std::to_string(values.size()) +
        " numbers where earlier lines have " + std::to_string(columns));
    }
    columns = values.size();
    points->InsertNextPoint(values.data());
    if (columns == 6)
    {
      normals->InsertNextTuple(values.data() + 3);
    }
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  if (columns == 6)
  {
    cloud->GetPointData()->SetNormals(normals);
  }
  return cloud;
}

// Object File Format mesh: "OFF", the counts "vertices faces edges", one "x y z" line per
// vertex, one "n i_0 ... i_n-1" line per face; # starts a comment. Values after those (colors)
// are ignored. VTK 9.1 has no OFF reader.
inline vtkSmartPointer<vtkPolyData> ReadOFF(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw std::runtime_error("cannot open '" + path + "'");
  }
  std::string line;
  int lineNumber = 0;
  std::istringstream fields;
  // Loads the next line holding data into `fields`.
  auto nextLine = [&]()
  {
    while (std::getline(in, line))
    {
      ++lineNumber;
      line.erase(std::min(line.find('#'), line.size()));
      if (line.find_first_not_of(" \t\r") != std::string::npos)
      {
        fields.clear();
        fields.str(line);
        return;
      }
    }
    throw std::runtime_error(path + ": the file ends early");
  };
  auto fail = [&](const std::string& what)
  { return std::runtime_error(path + ":" + std::to_string(lineNumber) + ": " + what); };

  nextLine();
  std::string keyword;
  fields >> keyword;
  if (keyword != "OFF")
  {
    throw fail("not an OFF file (the first line must be OFF)");
  }
  long long vertexCount, faceCount;
  if (!(fields >> vertexCount)) // the counts may follow the keyword on the same line
  {
    nextLine();
    fields >> vertexCount;
  }
  if (!(fields >> faceCount) || vertexCount <= 0 || faceCount < 0)
  {
    throw fail("expected the counts 'vertices faces edges'");
  }
  // A vertex line takes at least 6 bytes ("x y z\n") and a face line 8: counts the file cannot
  // hold are an error before anything is allocated for them.
  const double fileSize = static_cast<double>(vtksys::SystemTools::FileLength(path));
  if (6.0 * vertexCount + 8.0 * faceCount > fileSize)
  {
    throw fail("the counts " + std::to_string(vertexCount) + " vertices and " +
      std::to_string(faceCount) + " faces do not fit in the file");
  }

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->Allocate(vertexCount);
  for (long long i = 0; i < vertexCount; ++i)
  {
    nextLine();
    double p[3];
    if (!(fields >> p[0] >> p[1] >> p[2]))
    {
      throw fail("expected a vertex 'x y z'");
    }
    points->InsertNextPoint(p);
  }
  vtkNew<vtkCellArray> polys;
  std::vector<vtkIdType> ids;
  for (long long i = 0; i < faceCount; ++i)
  {
    nextLine();
    long long n;
    // Each index takes at least two characters of the line.
    if (!(fields >> n) || n < 3 || 2 * n > static_cast<long long>(line.size()))
    {
      throw fail("expected a face 'n i_0 ... i_n-1' with n >= 3");
    }
    ids.resize(n);
    for (auto& id : ids)
    {
      long long index;
      if (!(fields >> index) || index < 0 || index >= vertexCount)
      {
        throw fail("face vertex index missing or out of range");
      }
      id = static_cast<vtkIdType>(index);
    }
    polys->InsertNextCell(static_cast<vtkIdType>(n), ids.data());
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}

// Debian's libcgal-demo ships its sample data as one tarball: only the armadillo is unpacked,
// into a temporary folder removed after reading.
inline const char* const CgalData = "/usr/share/doc/libcgal-dev/data.tar.gz";

inline vtkSmartPointer<vtkPolyData> ReadCgalArmadillo()
{
  const std::string member = "data/meshes/armadillo.off";
  std::string folder;
  if (!vtksys::SystemTools::GetEnv("TMPDIR", folder) || folder.empty())
  {
    folder = "/tmp";
  }
  std::string pattern = folder + "/splat_cgal.XXXXXX";
  if (!mkdtemp(pattern.data()))
  {
    throw std::runtime_error("cannot create a temporary folder in " + folder);
  }
  struct RemoveOnExit
  {
    std::string Path;
    ~RemoveOnExit() { vtksys::SystemTools::RemoveADirectory(this->Path); }
  } temporary{ pattern };

  const std::string command =
    "tar -xzf '" + std::string(CgalData) + "' -C '" + temporary.Path + "' " + member;
  if (std::system(command.c_str()) != 0)
  {
    throw std::runtime_error("'" + command + "' failed");
  }
  return ReadOFF(temporary.Path + "/" + member);
}

inline void RequireFile(const std::string& path)
{
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    throw std::runtime_error("no such file: '" + path + "'");
  }
}

// Updates `reader` and throws with the reader's first error message (prefixed with the file's
// name when the message lacks it) when it reports one: this project's readers set an error
// code, and some of VTK's print an error and still hand over an output with ErrorCode unset
// (vtkMetaImageReader gives a one-voxel image for a file it cannot parse). The pipeline
// information is updated first, and `checkInformation` run on it, because a failed
// RequestInformation does not stop RequestData (vtkNIFTIImageReader then reads into no
// buffer). Exceptions thrown inside a reader come back as std::runtime_error naming the file.
inline void UpdateReader(vtkAlgorithm* reader, const std::string& path,
  const std::function<void()>& checkInformation = nullptr)
{
  std::string message;
  vtkNew<vtkCallbackCommand> errors;
  errors->SetClientData(&message);
  errors->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      auto* first = static_cast<std::string*>(clientData);
      if (first->empty()) // the reader's message; the executive's follows it
      {
        // After VTK's prefix "ERROR: In FILE, line N\nCLASS (ADDRESS): ".
        const std::string text = static_cast<const char*>(callData);
        const std::size_t start = text.find("): ");
        *first = start == std::string::npos ? text : text.substr(start + 3);
        first->erase(first->find_last_not_of(" \n") + 1);
      }
    });
  auto check = [&]()
  {
    if (reader->GetErrorCode() != vtkErrorCode::NoError || !message.empty())
    {
      reader->RemoveObservers(vtkCommand::ErrorEvent);
      reader->GetExecutive()->RemoveObservers(vtkCommand::ErrorEvent);
      throw std::runtime_error(message.find(path) != std::string::npos
          ? message
          : "reading '" + path + "' failed" + (message.empty() ? "" : ": " + message));
    }
  };
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  try
  {
    reader->UpdateInformation();
    check();
    if (checkInformation)
    {
      checkInformation();
    }
    reader->Update();
  }
  catch (const std::bad_alloc&)
  {
    throw;
  }
  catch (const std::runtime_error&)
  {
    throw;
  }
  catch (const std::exception& e)
  {
    message = e.what();
  }
  check();
  reader->RemoveObservers(vtkCommand::ErrorEvent);
  reader->GetExecutive()->RemoveObservers(vtkCommand::ErrorEvent);
}

// Throws unless every point-data array has one tuple per point and every cell's point ids are
// in range: what the mappers index without checking.
inline void CheckPolyData(vtkPolyData* data, const std::string& path)
{
  const vtkIdType n = data->GetNumberOfPoints();
  for (int a = 0; a < data->GetPointData()->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = data->GetPointData()->GetAbstractArray(a);
    if (array->GetNumberOfTuples() != n)
    {
      throw std::runtime_error("'" + path + "': point array '" +
        (array->GetName() ? array->GetName() : "") + "' does not have one value per point");
    }
  }
  for (vtkCellArray* cells :
    { data->GetVerts(), data->GetLines(), data->GetPolys(), data->GetStrips() })
  {
    double range[2];
    if (cells && cells->GetNumberOfConnectivityIds() > 0 &&
      (cells->GetConnectivityArray()->GetRange(range, 0), range[0] < 0 || range[1] >= n))
    {
      throw std::runtime_error("'" + path + "' has cells with point ids out of range");
    }
  }
}

// Reads a mesh or point cloud by its extension; throws with a readable message when it cannot.
inline vtkSmartPointer<vtkPolyData> ReadPolyData(const std::string& path)
{
  RequireFile(path);
  vtkSmartPointer<vtkPolyData> data;
  if (HasExtension(path, ".ply"))
  {
    vtkNew<vtkSplatPLYReader> reader;
    reader->SetFileName(path.c_str());
    UpdateReader(reader, path);
    data = reader->GetOutput();
  }
  else if (HasExtension(path, ".vtp"))
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    XMLFileCheck(path, "PolyData");
    reader->SetFileName(path.c_str());
    UpdateReader(reader, path);
    data = reader->GetOutput();
  }
  else if (HasExtension(path, ".xyz"))
  {
    data = ReadXYZ(path);
  }
  else if (HasExtension(path, ".off"))
  {
    data = ReadOFF(path);
  }
  else
  {
    throw std::runtime_error(
      "'" + path + "': unknown file type; splat_render reads .ply, .vtp, .xyz and .off (surfaces), "
      "3D Gaussian Splatting captures (.ply, .splat, .spz, .sog, meta.json, .ksplat, .glb, .gltf) "
      "and .nii, .nii.gz, .vti, .mhd and .mha (volumes)");
  }
  if (data->GetNumberOfPoints() == 0)
  {
    throw std::runtime_error("'" + path + "' holds no points");
  }
  CheckPolyData(data, path);
  return data;
}

// Whether `path` is a 3D Gaussian Splatting capture: named .splat, or a file
// vtkGaussianSplatReader::IsGaussianSplatFile recognizes by its first bytes (a .ply whose
// vertices have the 3DGS properties, .spz, .sog, .ksplat, a glTF using KHR_gaussian_splatting).
inline bool IsGaussianSplatFile(const std::string& path)
{
  return HasExtension(path, ".splat") || vtkGaussianSplatReader::IsGaussianSplatFile(path.c_str());
}

// A 3D Gaussian Splatting capture: the kernels and the degree of their spherical harmonics.
struct GaussianSplats
{
  vtkSmartPointer<vtkPolyData> Kernels;
  int Degree = 0;
};

// Reads a 3D Gaussian Splatting capture (a .spz as right-up-back with `spzFromRUB`); throws
// with a readable message when it cannot.
inline GaussianSplats ReadGaussianSplats(const std::string& path, bool spzFromRUB = false)
{
  RequireFile(path);
  vtkNew<vtkGaussianSplatReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetSPZFromRUB(spzFromRUB);
  UpdateReader(reader, path);
  if (reader->GetOutput()->GetNumberOfPoints() == 0)
  {
    throw std::runtime_error("'" + path + "' holds no Gaussians");
  }
  return { reader->GetOutput(), reader->GetSphericalHarmonicsDegree() };
}

// Whether `path` names a volume: image data read by VTK's NIFTI, XML image or MetaImage reader.
inline bool IsVolumeFile(const std::string& path)
{
  const std::string lower = vtksys::SystemTools::LowerCase(path);
  for (const std::string extension : { ".nii", ".nii.gz", ".vti", ".mhd", ".mha" })
  {
    if (vtksys::SystemTools::StringEndsWith(lower, extension.c_str()))
    {
      return true;
    }
  }
  return false;
}

// Reads a volume by its extension; throws with a readable message when it cannot.
inline vtkSmartPointer<vtkImageData> ReadVolume(const std::string& path)
{
  RequireFile(path);
  vtkSmartPointer<vtkAlgorithm> reader;
  std::function<void()> checkInformation;
  if (HasExtension(path, ".vti"))
  {
    XMLFileCheck(path, "ImageData");
    auto xml = vtkSmartPointer<vtkXMLImageDataReader>::New();
    xml->SetFileName(path.c_str());
    reader = xml;
  }
  else if (HasExtension(path, ".mhd") || HasExtension(path, ".mha"))
  {
    CheckMetaImageHeader(path);
    auto meta = vtkSmartPointer<vtkMetaImageReader>::New();
    meta->SetFileName(path.c_str());
    reader = meta;
  }
  else
  {
    auto nifti = vtkSmartPointer<vtkNIFTIImageReader>::New();
    if (!nifti->CanReadFile(path.c_str()))
    {
      throw std::runtime_error("'" + path + "' is not a NIFTI file");
    }
    CheckNIFTIDataType(path);
    nifti->SetFileName(path.c_str());
    reader = nifti;
    // The header's size, type and components against what the file (or, gzipped, at most
    // 1032 times its size: deflate's limit) can hold, before the reader allocates them.
    checkInformation = [&]()
    {
      vtkInformation* info = reader->GetOutputInformation(0);
      vtkInformation* scalars = vtkDataObject::GetActiveFieldInformation(
        info, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
      const int* extent = info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
      // An unknown NIFTI datatype leaves the scalar type unset: only numeric types are sized.
      const int type = scalars && scalars->Has(vtkDataObject::FIELD_ARRAY_TYPE())
        ? scalars->Get(vtkDataObject::FIELD_ARRAY_TYPE())
        : VTK_VOID;
      const bool numeric = (type >= VTK_CHAR && type <= VTK_DOUBLE) ||
        (type >= VTK_SIGNED_CHAR && type <= VTK_UNSIGNED_LONG_LONG);
      double bytes = numeric ? vtkAbstractArray::GetDataTypeSize(type) *
          double(scalars->Get(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS()))
                             : 0;
      for (int axis = 0; axis < 3 && extent; ++axis)
      {
        bytes *= double(extent[2 * axis + 1]) - extent[2 * axis] + 1;
      }
      const double stored = static_cast<double>(vtksys::SystemTools::FileLength(path));
      if (!extent || !(bytes > 0) || bytes > stored * (HasExtension(path, ".gz") ? 1032 : 1))
      {
        throw std::runtime_error("'" + path + "': the NIFTI header's dimensions or data type "
                                              "do not fit the file");
      }
    };
  }
  UpdateReader(reader, path, checkInformation);
  auto* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!image || image->GetNumberOfPoints() == 0 || !image->GetPointData()->GetScalars())
  {
    throw std::runtime_error("reading '" + path + "' gave no image with point scalars");
  }
  return image;
}
}

#endif
