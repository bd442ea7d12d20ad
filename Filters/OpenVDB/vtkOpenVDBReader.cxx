// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenVDBReader.h"
#include "vtkOpenVDBArchiveCheck.h"
#include "vtkOpenVDBReaderBuilder.h"

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtksys/SystemTools.hxx"

#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointDataGrid.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkOpenVDBReader);

namespace
{
using splatvdb::ValueGrids;

/// One grid of the file's listing (metadata only).
struct GridInfo
{
  std::string Name;
  std::string Class;
  std::string ValueType;
  std::string TransformType;
  vtkIdType ActiveVoxels = -1;
  bool Linear = false;
  double IndexToWorld[16] = {};
  bool HasBounds = false; // the file's active voxel bounding box
  openvdb::CoordBBox Bounds;
  bool Supported = false;
};

bool IsSupported(const openvdb::GridBase& grid)
{
  return grid.isType<openvdb::points::PointDataGrid>() ||
    grid.apply<ValueGrids>([](const auto&) {});
}

} // namespace

//------------------------------------------------------------------------------
struct vtkOpenVDBReader::Internals
{
  std::vector<GridInfo> Grids;
  std::string DefaultGrid; // the first supported grid
  std::string ListingError; // why RequestInformation could not list the grids, if it could not
  vtkNew<vtkStringArray> SupportedGridNames;
};

//------------------------------------------------------------------------------
vtkOpenVDBReader::vtkOpenVDBReader()
  : Internal(new Internals)
{
  openvdb::initialize();
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
}

//------------------------------------------------------------------------------
vtkOpenVDBReader::~vtkOpenVDBReader()
{
  this->SetFileName(nullptr);
  this->SetGridName(nullptr);
}

//------------------------------------------------------------------------------
int vtkOpenVDBReader::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
vtkImageData* vtkOpenVDBReader::GetDenseOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
int vtkOpenVDBReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  Internals& internal = *this->Internal;
  internal.Grids.clear();
  internal.DefaultGrid.clear();
  internal.SupportedGridNames->Initialize();
  internal.ListingError = "no such file";
  // A failed update must not leave the previous grid's outputs behind.
  vtkPolyData::GetData(outputVector, 0)->Initialize();
  vtkImageData::GetData(outputVector, 1)->Initialize();
  if (!this->FileName || !vtksys::SystemTools::FileExists(this->FileName, true))
  {
    vtkErrorMacro("Cannot open the OpenVDB file '" << (this->FileName ? this->FileName : "")
                                                    << "': no such file.");
    return 0;
  }
  try
  {
    splatvdb::ArchiveCheck{ this->FileName };
    openvdb::io::File file(this->FileName);
    file.open(false);
    openvdb::GridPtrVecPtr grids = file.readAllGridMetadata();
    file.close();
    for (const openvdb::GridBase::Ptr& grid : *grids)
    {
      GridInfo info;
      info.Name = grid->getName();
      info.Class = openvdb::GridBase::gridClassToString(grid->getGridClass());
      info.ValueType = grid->valueType();
      const openvdb::math::MapBase& map = *grid->transform().baseMap();
      info.TransformType = map.type();
      info.Linear = map.isLinear();
      if (info.Linear)
      {
        const openvdb::Mat4d M = map.getAffineMap()->getMat4();
        for (int row = 0; row < 4; ++row)
        {
          for (int column = 0; column < 4; ++column)
          {
            info.IndexToWorld[4 * row + column] = M(column, row); // OpenVDB: row vectors
          }
        }
      }
      if (auto count = grid->getMetadata<openvdb::Int64Metadata>(
            openvdb::GridBase::META_FILE_VOXEL_COUNT))
      {
        info.ActiveVoxels = static_cast<vtkIdType>(count->value());
      }
      using BoxCorner = openvdb::Vec3IMetadata;
      auto low = grid->getMetadata<BoxCorner>(openvdb::GridBase::META_FILE_BBOX_MIN);
      auto high = grid->getMetadata<BoxCorner>(openvdb::GridBase::META_FILE_BBOX_MAX);
      if (low && high)
      {
        info.HasBounds = true;
        info.Bounds =
          openvdb::CoordBBox(openvdb::Coord(low->value()), openvdb::Coord(high->value()));
      }
      info.Supported = IsSupported(*grid);
      if (info.Supported)
      {
        internal.SupportedGridNames->InsertNextValue(info.Name);
      }
      if (info.Supported && internal.DefaultGrid.empty())
      {
        internal.DefaultGrid = info.Name;
      }
      internal.Grids.push_back(info);
    }
  }
  catch (const std::exception& e)
  {
    internal.Grids.clear();
    internal.DefaultGrid.clear();
    internal.SupportedGridNames->Initialize();
    internal.ListingError = e.what();
    vtkErrorMacro("Cannot read the grid list of the OpenVDB file '" << this->FileName
                                                                     << "': " << e.what());
    return 0;
  }
  internal.ListingError.clear();

  // The dense image's extent and geometry, when the file records them.
  const std::string selected =
    this->GridName && *this->GridName ? this->GridName : internal.DefaultGrid;
  vtkInformation* imageInfo = outputVector->GetInformationObject(1);
  imageInfo->Remove(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  for (const GridInfo& info : internal.Grids)
  {
    if (info.Name != selected || !this->ProduceDenseOutput || !info.Linear)
    {
      continue;
    }
    const int* b = this->DenseIndexBounds;
    const bool userBox = b[0] <= b[1] && b[2] <= b[3] && b[4] <= b[5];
    if (userBox || info.HasBounds)
    {
      const openvdb::CoordBBox& box = info.Bounds;
      const int extent[6] = { userBox ? b[0] : box.min()[0], userBox ? b[1] : box.max()[0],
        userBox ? b[2] : box.min()[1], userBox ? b[3] : box.max()[1],
        userBox ? b[4] : box.min()[2], userBox ? b[5] : box.max()[2] };
      imageInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
    }
    break;
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkOpenVDBReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkImageData* image = vtkImageData::GetData(outputVector, 1);
  output->Initialize();
  image->Initialize();
  this->NumberOfVoxelKernels = this->NumberOfTileKernels = this->NumberOfTiles = 0;
  this->NumberOfSkippedValues = 0;
  const std::string fileName = this->FileName ? this->FileName : "";
  const std::string gridName =
    this->GridName && *this->GridName ? this->GridName : this->Internal->DefaultGrid;
  // VTK 9.1 runs RequestData after a failed RequestInformation: the update fails with its cause.
  if (!this->Internal->ListingError.empty())
  {
    vtkErrorMacro("Cannot read the OpenVDB file '" << fileName
                                                   << "': " << this->Internal->ListingError);
    return 0;
  }
  if (this->Internal->Grids.empty())
  {
    vtkErrorMacro("The OpenVDB file '" << fileName << "' has no grids.");
    return 0;
  }
  if (gridName.empty())
  {
    std::ostringstream types;
    for (const GridInfo& info : this->Internal->Grids)
    {
      types << " '" << info.Name << "' (" << info.ValueType << ")";
    }
    vtkErrorMacro("The OpenVDB file '" << fileName << "' has no grid of a supported type:"
                                       << types.str() << ".");
    return 0;
  }

  vtkNew<vtkPolyData> kernels;
  vtkNew<vtkImageData> dense;
  vtkOpenVDBReaderBuilder builder{ this, gridName };
  try
  {
    // The stream reader reads every grid; with stream exceptions a short read stops it.
    splatvdb::ArchiveCheck{ fileName };
    std::ifstream stream(fileName, std::ios::in | std::ios::binary);
    stream.exceptions(std::ios::failbit | std::ios::badbit);
    openvdb::io::Stream vdb(stream, false);
    openvdb::GridBase::Ptr grid;
    const openvdb::GridPtrVecPtr grids = vdb.getGrids();
    for (const openvdb::GridBase::Ptr& candidate : *grids)
    {
      if (candidate->getName() == gridName)
      {
        grid = candidate;
        break;
      }
    }
    if (!grid)
    {
      std::ostringstream names;
      for (const GridInfo& info : this->Internal->Grids)
      {
        names << " '" << info.Name << "'";
      }
      throw std::runtime_error("no such grid; the file has" + names.str());
    }
    const bool levelSet = grid->getGridClass() == openvdb::GRID_LEVEL_SET;
    bool built;
    if (auto points = openvdb::gridConstPtrCast<openvdb::points::PointDataGrid>(grid))
    {
      builder.Points(*points, kernels);
      built = true;
    }
    else if (levelSet)
    {
      built = grid->apply<openvdb::TypeList<openvdb::FloatGrid, openvdb::DoubleGrid>>(
        [&](const auto& g) { builder.Surfels(g, kernels); });
    }
    else
    {
      built = grid->apply<ValueGrids>([&](const auto& g) { builder.Kernels(g, kernels); });
    }
    if (!built)
    {
      throw std::runtime_error("its type (" + grid->valueType() + ", " +
        openvdb::GridBase::gridClassToString(grid->getGridClass()) + ") is not supported");
    }
    if (this->ProduceDenseOutput)
    {
      const int* b = this->DenseIndexBounds;
      const openvdb::CoordBBox box = b[0] <= b[1] && b[2] <= b[3] && b[4] <= b[5]
        ? openvdb::CoordBBox(b[0], b[2], b[4], b[1], b[3], b[5])
        : grid->evalActiveVoxelBoundingBox();
      if (!grid->apply<ValueGrids>([&](const auto& g) { builder.Dense(g, box, dense); }))
      {
        throw std::runtime_error("it has no values for a dense image");
      }
    }
  }
  catch (const std::exception& e)
  {
    this->NumberOfVoxelKernels = this->NumberOfTileKernels = this->NumberOfTiles = 0;
    this->NumberOfSkippedValues = 0;
    vtkErrorMacro("Cannot read grid '" << gridName << "' of the OpenVDB file '" << fileName
                                       << "': " << e.what());
    return 0;
  }
  output->ShallowCopy(kernels);
  image->ShallowCopy(dense);
  if (this->NumberOfSkippedValues > 0)
  {
    vtkWarningMacro("Grid '" << gridName << "' of '" << fileName << "': "
                             << this->NumberOfSkippedValues
                             << " values with a non-finite value or gradient were skipped.");
  }
  return 1;
}

//------------------------------------------------------------------------------
namespace
{
const GridInfo* Info(const std::vector<GridInfo>& grids, int index)
{
  return index >= 0 && index < static_cast<int>(grids.size()) ? &grids[index] : nullptr;
}
}

int vtkOpenVDBReader::GetNumberOfGrids()
{
  return static_cast<int>(this->Internal->Grids.size());
}

const char* vtkOpenVDBReader::GetGridName(int index)
{
  const GridInfo* info = Info(this->Internal->Grids, index);
  return info ? info->Name.c_str() : nullptr;
}

const char* vtkOpenVDBReader::GetGridClass(int index)
{
  const GridInfo* info = Info(this->Internal->Grids, index);
  return info ? info->Class.c_str() : nullptr;
}

const char* vtkOpenVDBReader::GetGridValueType(int index)
{
  const GridInfo* info = Info(this->Internal->Grids, index);
  return info ? info->ValueType.c_str() : nullptr;
}

const char* vtkOpenVDBReader::GetGridTransformType(int index)
{
  const GridInfo* info = Info(this->Internal->Grids, index);
  return info ? info->TransformType.c_str() : nullptr;
}

vtkIdType vtkOpenVDBReader::GetGridActiveVoxelCount(int index)
{
  const GridInfo* info = Info(this->Internal->Grids, index);
  return info ? info->ActiveVoxels : -1;
}

vtkStringArray* vtkOpenVDBReader::GetSupportedGridNames()
{
  return this->Internal->SupportedGridNames;
}

bool vtkOpenVDBReader::GetGridIndexToWorld(int index, double matrix[16])
{
  const GridInfo* info = Info(this->Internal->Grids, index);
  if (!info || !info->Linear)
  {
    return false;
  }
  std::copy_n(info->IndexToWorld, 16, matrix);
  return true;
}

//------------------------------------------------------------------------------
void vtkOpenVDBReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "GridName: " << (this->GridName ? this->GridName : "(none)") << "\n";
  os << indent << "TileSubdivision: " << this->TileSubdivision << "\n";
  os << indent << "SurfelRadiusScale: " << this->SurfelRadiusScale << "\n";
  os << indent << "ProduceDenseOutput: " << this->ProduceDenseOutput << "\n";
  const int* b = this->DenseIndexBounds;
  os << indent << "DenseIndexBounds: " << b[0] << " " << b[1] << " " << b[2] << " " << b[3]
     << " " << b[4] << " " << b[5] << "\n";
  os << indent << "MaximumDenseVoxels: " << this->MaximumDenseVoxels << "\n";
  os << indent << "NumberOfVoxelKernels: " << this->NumberOfVoxelKernels << "\n";
  os << indent << "NumberOfTileKernels: " << this->NumberOfTileKernels << "\n";
  os << indent << "NumberOfTiles: " << this->NumberOfTiles << "\n";
  os << indent << "NumberOfSkippedValues: " << this->NumberOfSkippedValues << "\n";
  os << indent << "Grids: " << this->Internal->Grids.size() << "\n";
  for (const GridInfo& info : this->Internal->Grids)
  {
    os << indent.GetNextIndent() << "'" << info.Name << "': " << info.Class << ", "
       << info.ValueType << ", " << info.ActiveVoxels << " active voxels, "
       << info.TransformType;
    if (info.Linear)
    {
      os << " [";
      for (int i = 0; i < 12; ++i)
      {
        os << info.IndexToWorld[i] << (i % 4 == 3 ? (i == 11 ? "" : "; ") : " ");
      }
      os << "]";
    }
    os << (info.Supported ? "" : " (not supported)") << "\n";
  }
}
