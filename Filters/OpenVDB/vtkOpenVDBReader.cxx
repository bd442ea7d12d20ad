// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenVDBReader.h"

#include "SplatVolumeKernel.h" // For splat::VoxelCovariance

#include "vtkAOSDataArrayTemplate.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeTraits.h"
#include "vtksys/SystemTools.hxx"

#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/math/Operators.h>
#include <openvdb/math/Stencils.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/tools/Dense.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkOpenVDBReader);

namespace
{
using ScalarGrids = openvdb::TypeList<openvdb::FloatGrid, openvdb::DoubleGrid, openvdb::Int32Grid,
  openvdb::Int64Grid>;
using VectorGrids = openvdb::TypeList<openvdb::Vec3fGrid, openvdb::Vec3dGrid>;
using ValueGrids = ScalarGrids::Append<VectorGrids>;

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

/// The Jacobian of the index-to-world map at index position xyz: its columns are the index axes.
glm::dmat3 IndexJacobian(const openvdb::math::MapBase& map, const openvdb::Vec3d& xyz)
{
  glm::dmat3 A;
  for (int axis = 0; axis < 3; ++axis)
  {
    openvdb::Vec3d unit(0.0);
    unit[axis] = 1.0;
    const openvdb::Vec3d column = map.applyJacobian(unit, xyz);
    A[axis] = glm::dvec3(column[0], column[1], column[2]);
  }
  return A;
}

glm::dvec3 ToGlm(const openvdb::Vec3d& v)
{
  return glm::dvec3(v[0], v[1], v[2]);
}

/// Per value type: the number of components, the component type and finiteness.
template <typename T>
struct Channels
{
  using Component = T;
  static constexpr int Count = 1;
  static bool Finite(const T& v) { return std::isfinite(static_cast<double>(v)); }
  static const Component* Data(const T& v) { return &v; }
};

template <typename T>
struct Channels<openvdb::math::Vec3<T>>
{
  using Component = T;
  static constexpr int Count = 3;
  static bool Finite(const openvdb::math::Vec3<T>& v)
  {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
  }
  static const Component* Data(const openvdb::math::Vec3<T>& v) { return v.asPointer(); }
};

/// A new VTK array of the concrete class for T (vtkFloatArray, vtkIntArray, ...).
template <typename T>
vtkSmartPointer<vtkAOSDataArrayTemplate<T>> NewArray(
  const std::string& name, int components, vtkIdType tuples)
{
  vtkSmartPointer<vtkAOSDataArrayTemplate<T>> array;
  array.TakeReference(static_cast<vtkAOSDataArrayTemplate<T>*>(
    vtkDataArray::CreateDataArray(vtkTypeTraits<T>::VTK_TYPE_ID)));
  array->SetName(name.c_str());
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}

/// The grid's values as point data: scalars, or vectors and their magnitude as scalars.
template <typename ValueT>
struct ValueArrays
{
  using C = Channels<ValueT>;
  using Component = typename C::Component;
  vtkSmartPointer<vtkAOSDataArrayTemplate<Component>> Values;
  vtkSmartPointer<vtkAOSDataArrayTemplate<Component>> Magnitudes;

  ValueArrays(const std::string& gridName, vtkIdType n)
  {
    const std::string name = gridName.empty() ? "values" : gridName;
    this->Values = NewArray<Component>(name, C::Count, n);
    if (C::Count == 3)
    {
      this->Magnitudes = NewArray<Component>(name + "_magnitude", 1, n);
    }
  }

  void Set(vtkIdType id, const ValueT& value)
  {
    const Component* v = C::Data(value);
    std::copy_n(v, C::Count, this->Values->GetPointer(C::Count * id));
    if (this->Magnitudes)
    {
      double squared = 0.0;
      for (int c = 0; c < C::Count; ++c)
      {
        squared += static_cast<double>(v[c]) * v[c];
      }
      this->Magnitudes->SetValue(id, static_cast<Component>(std::sqrt(squared)));
    }
  }

  void AddTo(vtkPointData* pd)
  {
    if (this->Magnitudes)
    {
      pd->SetVectors(this->Values);
      pd->SetScalars(this->Magnitudes);
    }
    else
    {
      pd->SetScalars(this->Values);
    }
  }
};

/// One vertex cell per point.
void AddVertices(vtkPolyData* output)
{
  const vtkIdType n = output->GetNumberOfPoints();
  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  std::iota(offsets->GetPointer(0), offsets->GetPointer(0) + n + 1, vtkIdType(0));
  std::iota(connectivity->GetPointer(0), connectivity->GetPointer(0) + n, vtkIdType(0));
  vtkNew<vtkCellArray> vertices;
  vertices->SetData(offsets, connectivity);
  output->SetVerts(vertices);
}

/// The world box of a grid's transform: spacing, origin and direction of an image.
bool ImageGeometry(const openvdb::math::MapBase& map, vtkImageData* image)
{
  const glm::dmat3 A = IndexJacobian(map, openvdb::Vec3d(0.0));
  double spacing[3], direction[9];
  for (int axis = 0; axis < 3; ++axis)
  {
    spacing[axis] = glm::length(A[axis]);
    if (!(spacing[axis] > 0.0) || !std::isfinite(spacing[axis]))
    {
      return false;
    }
    for (int row = 0; row < 3; ++row)
    {
      direction[3 * row + axis] = A[axis][row] / spacing[axis];
    }
  }
  const openvdb::Vec3d origin = map.applyMap(openvdb::Vec3d(0.0));
  image->SetSpacing(spacing);
  image->SetOrigin(origin[0], origin[1], origin[2]);
  image->SetDirectionMatrix(direction);
  return true;
}
} // namespace

//------------------------------------------------------------------------------
struct vtkOpenVDBReader::Internals
{
  std::vector<GridInfo> Grids;
  std::string DefaultGrid; // the first supported grid
};

/**
 * Builds the outputs of one grid. Each builder fills the given outputs completely or throws.
 */
struct vtkOpenVDBReaderBuilder
{
  vtkOpenVDBReader* Reader;
  std::string GridName;

  /// Runs body(begin, end) over [0, count) in parallel, in 20 steps with progress events.
  template <typename Body>
  void ForLeaves(std::size_t count, double from, double to, Body&& body)
  {
    const vtkIdType n = static_cast<vtkIdType>(count);
    const vtkIdType step = std::max<vtkIdType>(1, (n + 19) / 20);
    for (vtkIdType begin = 0; begin < n; begin += step)
    {
      const vtkIdType end = std::min(n, begin + step);
      vtkSMPTools::For(begin, end, [&](vtkIdType b, vtkIdType e) { body(b, e); });
      this->Reader->UpdateProgress(from + (to - from) * end / n);
    }
  }

  //----------------------------------------------------------------------------
  template <typename GridT>
  void Kernels(const GridT& grid, vtkPolyData* output)
  {
    using ValueT = typename GridT::ValueType;
    using LeafT = typename GridT::TreeType::LeafNodeType;
    using C = Channels<ValueT>;
    const openvdb::math::MapBase& map = *grid.transform().baseMap();
    std::vector<const LeafT*> leaves;
    grid.tree().getNodes(leaves);

    // Count the finite values per leaf, then fill in leaf order.
    std::vector<vtkIdType> offsets(leaves.size() + 1, 0);
    this->ForLeaves(leaves.size(), 0.0, 0.2,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType l = begin; l < end; ++l)
        {
          for (auto it = leaves[l]->cbeginValueOn(); it; ++it)
          {
            offsets[l + 1] += C::Finite(*it) ? 1 : 0;
          }
        }
      });
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    const vtkIdType voxels = offsets.back();

    // Active tiles: every value iterator position above the leaf level.
    std::vector<std::pair<openvdb::CoordBBox, ValueT>> tiles;
    vtkIdType skipped = grid.tree().activeLeafVoxelCount() - voxels;
    auto tile = grid.cbeginValueOn();
    tile.setMaxDepth(decltype(tile)::LEAF_DEPTH - 1);
    for (; tile; ++tile)
    {
      openvdb::CoordBBox box;
      tile.getBoundingBox(box);
      if (C::Finite(*tile))
      {
        tiles.emplace_back(box, *tile);
      }
      else
      {
        skipped += static_cast<vtkIdType>(box.volume());
      }
    }
    const int k = this->Reader->TileSubdivision;
    const vtkIdType n = voxels + static_cast<vtkIdType>(tiles.size()) * k * k * k;
    if (n == 0)
    {
      throw std::runtime_error("it has no finite active values");
    }

    vtkNew<vtkPoints> points;
    points->SetDataTypeToFloat();
    points->SetNumberOfPoints(n);
    float* positions = static_cast<vtkFloatArray*>(points->GetData())->GetPointer(0);
    vtkNew<vtkFloatArray> covariances;
    covariances->SetName("Covariance");
    covariances->SetNumberOfComponents(6);
    covariances->SetNumberOfTuples(n);
    vtkNew<vtkFloatArray> volumes;
    volumes->SetName("SampleVolume");
    volumes->SetNumberOfTuples(n);
    ValueArrays<ValueT> values(this->GridName, n);
    // A kernel of a cell `cell` voxels wide centered at index position xyz.
    auto setKernel = [&](vtkIdType id, const openvdb::Vec3d& xyz, double cell, const ValueT& value)
    {
      const glm::dmat3 A = cell * IndexJacobian(map, xyz);
      const glm::dvec3 p = ToGlm(map.applyMap(xyz));
      const glm::dmat3 V = splat::VoxelCovariance(A);
      const double components[6] = { V[0][0], V[1][0], V[2][0], V[1][1], V[2][1], V[2][2] };
      std::copy_n(components, 6, covariances->GetPointer(6 * id));
      for (int c = 0; c < 3; ++c)
      {
        positions[3 * id + c] = static_cast<float>(p[c]);
      }
      volumes->SetValue(id, static_cast<float>(std::abs(glm::determinant(A))));
      values.Set(id, value);
    };
    this->ForLeaves(leaves.size(), 0.2, 0.9,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType l = begin; l < end; ++l)
        {
          vtkIdType id = offsets[l];
          for (auto it = leaves[l]->cbeginValueOn(); it; ++it)
          {
            if (C::Finite(*it))
            {
              setKernel(id++, it.getCoord().asVec3d(), 1.0, *it);
            }
          }
        }
      });
    // Each tile as a coarse grid of k^3 cells (few tiles: serial).
    vtkIdType id = voxels;
    for (const auto& t : tiles)
    {
      const double cell = static_cast<double>(t.first.dim()[0]) / k;
      const openvdb::Vec3d corner = t.first.min().asVec3d() - openvdb::Vec3d(0.5);
      for (int c = 0; c < k * k * k; ++c)
      {
        const openvdb::Vec3d sub(c % k + 0.5, (c / k) % k + 0.5, c / (k * k) + 0.5);
        setKernel(id++, corner + cell * sub, cell, t.second);
      }
    }
    this->Reader->UpdateProgress(1.0);

    output->SetPoints(points);
    output->GetPointData()->AddArray(covariances);
    output->GetPointData()->AddArray(volumes);
    values.AddTo(output->GetPointData());
    this->Reader->NumberOfVoxelKernels = voxels;
    this->Reader->NumberOfTileKernels = n - voxels;
    this->Reader->NumberOfTiles = static_cast<vtkIdType>(tiles.size());
    this->Reader->NumberOfSkippedValues = skipped;
  }

  //----------------------------------------------------------------------------
  template <typename GridT>
  void Surfels(const GridT& grid, vtkPolyData* output)
  {
    using LeafT = typename GridT::TreeType::LeafNodeType;
    using Stencil = openvdb::math::GradStencil<GridT>;
    const openvdb::math::MapBase& map = *grid.transform().baseMap();
    std::vector<const LeafT*> leaves;
    grid.tree().getNodes(leaves);

    // The voxel's surfel (point, normal, radius) when it borders the zero crossing, or 0 when it
    // does not, or -1 when its value or gradient is not usable.
    const double radiusScale = this->Reader->SurfelRadiusScale;
    auto surfel = [&](Stencil& stencil, const openvdb::Coord& ijk, glm::dvec3* point,
                    glm::dvec3* normal, double* radius) -> int
    {
      stencil.moveTo(ijk);
      if (!stencil.zeroCrossing())
      {
        return 0;
      }
      const openvdb::Vec3d xyz = ijk.asVec3d();
      const double phi = stencil.template getValue<0, 0, 0>();
      const openvdb::Vec3d indexGradient =
        openvdb::math::ISGradient<openvdb::math::CD_2ND>::result(stencil);
      const glm::dvec3 g = ToGlm(map.applyIJT(indexGradient, xyz));
      const double g2 = glm::dot(g, g);
      if (!(g2 > 0.0) || !std::isfinite(g2) || !std::isfinite(phi))
      {
        return -1;
      }
      if (point)
      {
        const glm::dmat3 A = IndexJacobian(map, xyz);
        *point = ToGlm(map.applyMap(xyz)) - (phi / g2) * g;
        *normal = g / std::sqrt(g2);
        *radius = radiusScale *
          std::max({ glm::length(A[0]), glm::length(A[1]), glm::length(A[2]) });
      }
      return 1;
    };

    std::vector<vtkIdType> offsets(leaves.size() + 1, 0);
    std::vector<vtkIdType> skipped(leaves.size(), 0);
    this->ForLeaves(leaves.size(), 0.0, 0.4,
      [&](vtkIdType begin, vtkIdType end)
      {
        Stencil stencil(grid);
        for (vtkIdType l = begin; l < end; ++l)
        {
          for (auto it = leaves[l]->cbeginValueOn(); it; ++it)
          {
            const int found = surfel(stencil, it.getCoord(), nullptr, nullptr, nullptr);
            offsets[l + 1] += found > 0 ? 1 : 0;
            skipped[l] += found < 0 ? 1 : 0;
          }
        }
      });
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    const vtkIdType n = offsets.back();
    if (n == 0)
    {
      throw std::runtime_error("its level set has no zero crossing");
    }
    vtkNew<vtkPoints> points;
    points->SetDataTypeToFloat();
    points->SetNumberOfPoints(n);
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(n);
    vtkNew<vtkFloatArray> radii;
    radii->SetName("Radius");
    radii->SetNumberOfTuples(n);
    float* positions = static_cast<vtkFloatArray*>(points->GetData())->GetPointer(0);
    this->ForLeaves(leaves.size(), 0.4, 1.0,
      [&](vtkIdType begin, vtkIdType end)
      {
        Stencil stencil(grid);
        for (vtkIdType l = begin; l < end; ++l)
        {
          vtkIdType id = offsets[l];
          for (auto it = leaves[l]->cbeginValueOn(); it; ++it)
          {
            glm::dvec3 p, normal;
            double radius;
            if (surfel(stencil, it.getCoord(), &p, &normal, &radius) > 0)
            {
              for (int c = 0; c < 3; ++c)
              {
                positions[3 * id + c] = static_cast<float>(p[c]);
                normals->SetValue(3 * id + c, static_cast<float>(normal[c]));
              }
              radii->SetValue(id++, static_cast<float>(radius));
            }
          }
        }
      });
    output->SetPoints(points);
    output->GetPointData()->SetNormals(normals);
    output->GetPointData()->AddArray(radii);
    AddVertices(output);
    this->Reader->NumberOfVoxelKernels = n;
    this->Reader->NumberOfSkippedValues =
      std::accumulate(skipped.begin(), skipped.end(), vtkIdType(0));
  }

  //----------------------------------------------------------------------------
  /// Copies attribute `name` of type T (stride components) of every leaf into a VTK array.
  template <typename T>
  vtkSmartPointer<vtkDataArray> Attribute(const std::string& name,
    const std::vector<const openvdb::points::PointDataTree::LeafNodeType*>& leaves,
    const std::vector<vtkIdType>& offsets)
  {
    using C = Channels<T>;
    const openvdb::Index stride = leaves[0]->constAttributeArray(name).stride();
    auto array = NewArray<typename C::Component>(name, C::Count * stride, offsets.back());
    vtkSMPTools::For(0, static_cast<vtkIdType>(leaves.size()),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType l = begin; l < end; ++l)
        {
          openvdb::points::AttributeHandle<T> handle(leaves[l]->constAttributeArray(name));
          if (handle.stride() != stride)
          {
            throw std::runtime_error("attribute '" + name + "' changes its stride");
          }
          for (openvdb::Index i = 0; i < handle.size(); ++i)
          {
            for (openvdb::Index m = 0; m < stride; ++m)
            {
              std::copy_n(C::Data(handle.get(i, m)), C::Count,
                array->GetPointer(C::Count * (stride * (offsets[l] + i) + m)));
            }
          }
        }
      });
    return array;
  }

  void Points(const openvdb::points::PointDataGrid& grid, vtkPolyData* output)
  {
    using LeafT = openvdb::points::PointDataTree::LeafNodeType;
    std::vector<const LeafT*> leaves;
    grid.tree().getNodes(leaves);
    std::vector<vtkIdType> offsets(leaves.size() + 1, 0);
    for (std::size_t l = 0; l < leaves.size(); ++l)
    {
      offsets[l + 1] = offsets[l] + static_cast<vtkIdType>(leaves[l]->pointCount());
    }
    const vtkIdType n = offsets.back();
    if (n == 0)
    {
      throw std::runtime_error("it holds no points");
    }
    const openvdb::math::Transform& transform = grid.transform();
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(n);
    double* positions = static_cast<vtkDoubleArray*>(points->GetData())->GetPointer(0);
    this->ForLeaves(leaves.size(), 0.0, 0.5,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType l = begin; l < end; ++l)
        {
          openvdb::points::AttributeHandle<openvdb::Vec3f> local(
            leaves[l]->constAttributeArray("P"));
          for (auto index = leaves[l]->beginIndexAll(); index; ++index)
          {
            const openvdb::Vec3d p = transform.indexToWorld(
              index.getCoord().asVec3d() + openvdb::Vec3d(local.get(*index)));
            std::copy_n(p.asPointer(), 3, positions + 3 * (offsets[l] + *index));
          }
        }
      });
    output->SetPoints(points);
    const auto& descriptor = leaves[0]->attributeSet().descriptor();
    for (const auto& entry : descriptor.map())
    {
      const openvdb::NamePair& type = descriptor.type(entry.second);
      if (entry.first == "P" || type.second == openvdb::points::GroupCodec::name())
      {
        continue;
      }
      vtkSmartPointer<vtkDataArray> array;
      if (type.first == "float")
        array = this->Attribute<float>(entry.first, leaves, offsets);
      else if (type.first == "double")
        array = this->Attribute<double>(entry.first, leaves, offsets);
      else if (type.first == "int32")
        array = this->Attribute<int32_t>(entry.first, leaves, offsets);
      else if (type.first == "int64")
        array = this->Attribute<int64_t>(entry.first, leaves, offsets);
      else if (type.first == "vec3s")
        array = this->Attribute<openvdb::Vec3f>(entry.first, leaves, offsets);
      else if (type.first == "vec3d")
        array = this->Attribute<openvdb::Vec3d>(entry.first, leaves, offsets);
      if (array)
      {
        output->GetPointData()->AddArray(array);
      }
      else
      {
        vtkWarningWithObjectMacro(this->Reader, "Attribute '" << entry.first << "' of type "
          << type.first << " of grid '" << this->GridName << "' is not read.");
      }
    }
    AddVertices(output);
    this->Reader->UpdateProgress(1.0);
    this->Reader->NumberOfVoxelKernels = n;
  }

  //----------------------------------------------------------------------------
  template <typename GridT>
  void Dense(const GridT& grid, const openvdb::CoordBBox& box, vtkImageData* image)
  {
    using ValueT = typename GridT::ValueType;
    if (!grid.transform().isLinear() || !ImageGeometry(*grid.transform().baseMap(), image))
    {
      throw std::runtime_error("a dense image needs a linear, non-degenerate transform");
    }
    const openvdb::Coord dim = box.dim();
    if (box.empty() || static_cast<double>(dim[0]) * dim[1] * dim[2] >
        static_cast<double>(this->Reader->MaximumDenseVoxels))
    {
      std::ostringstream message;
      message << "the dense box " << box << " is empty or exceeds MaximumDenseVoxels ("
              << this->Reader->MaximumDenseVoxels << ")";
      throw std::runtime_error(message.str());
    }
    image->SetExtent(box.min()[0], box.max()[0], box.min()[1], box.max()[1], box.min()[2],
      box.max()[2]);
    const vtkIdType n = image->GetNumberOfPoints();
    ValueArrays<ValueT> values(this->GridName, n);
    openvdb::tools::Dense<ValueT, openvdb::tools::LayoutXYZ> dense(
      box, reinterpret_cast<ValueT*>(values.Values->GetPointer(0)));
    openvdb::tools::copyToDense(grid, dense);
    if (values.Magnitudes)
    {
      vtkSMPTools::For(0, n,
        [&](vtkIdType begin, vtkIdType end)
        {
          for (vtkIdType i = begin; i < end; ++i)
          {
            values.Set(i, dense.getValue(static_cast<std::size_t>(i)));
          }
        });
    }
    values.AddTo(image->GetPointData());
  }
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
    vtkErrorMacro("Cannot read the grid list of the OpenVDB file '" << this->FileName
                                                                     << "': " << e.what());
    return 0;
  }

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
