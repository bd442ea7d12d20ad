// SPDX-License-Identifier: BSD-3-Clause
/**
 * @struct  vtkOpenVDBReaderBuilder
 * @brief   builds vtkOpenVDBReader's outputs from one OpenVDB grid (private to the reader)
 *
 * Kernels of scalar and vector grids (voxels and tiles), surfels of level sets, points of point
 * data grids and the dense image, each in parallel over the grid's leaves with the reader's
 * progress events. The helpers in namespace splatvdb convert OpenVDB's values, maps and
 * attributes to VTK arrays and image geometry.
 */
#ifndef vtkOpenVDBReaderBuilder_h
#define vtkOpenVDBReaderBuilder_h

#include "vtkOpenVDBReader.h"

#include "SplatVolumeKernel.h" // For splat::VoxelCovariance

#include "vtkAOSDataArrayTemplate.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkTypeTraits.h"

#include <openvdb/math/Operators.h>
#include <openvdb/math/Stencils.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/tools/Dense.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace splatvdb
{
using ScalarGrids = openvdb::TypeList<openvdb::FloatGrid, openvdb::DoubleGrid, openvdb::Int32Grid,
  openvdb::Int64Grid>;
using VectorGrids = openvdb::TypeList<openvdb::Vec3fGrid, openvdb::Vec3dGrid>;
using ValueGrids = ScalarGrids::Append<VectorGrids>;

/// The Jacobian of the index-to-world map at index position xyz: its columns are the index axes.
inline glm::dmat3 IndexJacobian(const openvdb::math::MapBase& map, const openvdb::Vec3d& xyz)
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

inline glm::dvec3 ToGlm(const openvdb::Vec3d& v)
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

/**
 * The field-data array "DensityStatistics" of kernels whose point scalars are densities (none
 * negative): the mean and the largest positive density and the volume ("SampleVolume") of the
 * kernels that hold them (splat::FogStatistics). Nothing when a scalar is negative.
 */
inline void AddDensityStatistics(vtkPolyData* output)
{
  vtkDataArray* densities = output->GetPointData()->GetScalars();
  vtkDataArray* volumes = output->GetPointData()->GetArray("SampleVolume");
  if (!densities || !volumes)
  {
    return;
  }
  double sum = 0.0, largest = 0.0, volume = 0.0;
  vtkIdType count = 0;
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
  {
    const double d = densities->GetComponent(i, 0);
    if (d < 0.0)
    {
      return;
    }
    if (d > 0.0)
    {
      sum += d;
      largest = std::max(largest, d);
      volume += volumes->GetComponent(i, 0);
      ++count;
    }
  }
  vtkNew<vtkDoubleArray> statistics;
  statistics->SetName("DensityStatistics");
  statistics->SetNumberOfComponents(3);
  statistics->SetComponentName(0, "Mean");
  statistics->SetComponentName(1, "Largest");
  statistics->SetComponentName(2, "Volume");
  const double tuple[3] = { count > 0 ? sum / count : 0.0, largest, volume };
  statistics->InsertNextTuple(tuple);
  output->GetFieldData()->AddArray(statistics);
}

/// One vertex cell per point, in 32-bit ids where they fit (8 bytes a point).
template <typename ArrayT>
void AddVertices(vtkPolyData* output)
{
  using Id = typename ArrayT::ValueType;
  const vtkIdType n = output->GetNumberOfPoints();
  vtkNew<ArrayT> offsets;
  vtkNew<ArrayT> connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  std::iota(offsets->GetPointer(0), offsets->GetPointer(0) + n + 1, Id(0));
  std::iota(connectivity->GetPointer(0), connectivity->GetPointer(0) + n, Id(0));
  vtkNew<vtkCellArray> vertices;
  vertices->SetData(offsets, connectivity);
  output->SetVerts(vertices);
}

inline void AddVertices(vtkPolyData* output)
{
  if (output->GetNumberOfPoints() < std::numeric_limits<vtkTypeInt32>::max())
  {
    AddVertices<vtkTypeInt32Array>(output);
  }
  else
  {
    AddVertices<vtkTypeInt64Array>(output);
  }
}

/// The world box of a grid's transform: spacing, origin and direction of an image.
inline bool ImageGeometry(const openvdb::math::MapBase& map, vtkImageData* image)
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
}

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
    using C = splatvdb::Channels<ValueT>;
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
    // Every kernel one voxel under a linear map: the kernels sit on the grid's lattice.
    const bool lattice = grid.transform().isLinear() &&
      std::all_of(tiles.begin(), tiles.end(), [k](const auto& t) { return t.first.dim()[0] == k; });
    vtkNew<vtkIntArray> indices;
    indices->SetName("VoxelIndex");
    indices->SetNumberOfComponents(3);
    indices->SetNumberOfTuples(lattice ? n : 0);

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
    splatvdb::ValueArrays<ValueT> values(this->GridName, n);
    // A kernel of a cell `cell` voxels wide centered at index position xyz.
    auto setKernel = [&](vtkIdType id, const openvdb::Vec3d& xyz, double cell, const ValueT& value)
    {
      const glm::dmat3 A = cell * splatvdb::IndexJacobian(map, xyz);
      const glm::dvec3 p = splatvdb::ToGlm(map.applyMap(xyz));
      const glm::dmat3 V = splat::VoxelCovariance(A);
      const double components[6] = { V[0][0], V[1][0], V[2][0], V[1][1], V[2][1], V[2][2] };
      std::copy_n(components, 6, covariances->GetPointer(6 * id));
      for (int c = 0; c < 3; ++c)
      {
        positions[3 * id + c] = static_cast<float>(p[c]);
      }
      volumes->SetValue(id, static_cast<float>(std::abs(glm::determinant(A))));
      values.Set(id, value);
      if (lattice)
      {
        for (int c = 0; c < 3; ++c)
        {
          indices->SetTypedComponent(id, c, static_cast<int>(std::lround(xyz[c])));
        }
      }
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
    // Vertex cells, although the kernels are drawn from the points: ParaView's default Surface
    // representation then shows them, and its volume opacity unit distance (the bounds'
    // diagonal over the cube root of the cells) comes out about a voxel.
    splatvdb::AddVertices(output);
    output->GetPointData()->AddArray(covariances);
    output->GetPointData()->AddArray(volumes);
    values.AddTo(output->GetPointData());
    splatvdb::AddDensityStatistics(output);
    if (lattice)
    {
      output->GetPointData()->AddArray(indices);
      vtkNew<vtkDoubleArray> indexToWorld;
      indexToWorld->SetName("IndexToWorld");
      indexToWorld->SetNumberOfComponents(16);
      indexToWorld->SetNumberOfTuples(1);
      const glm::dmat3 A = splatvdb::IndexJacobian(map, openvdb::Vec3d(0.0));
      const glm::dvec3 origin = splatvdb::ToGlm(map.applyMap(openvdb::Vec3d(0.0)));
      for (int row = 0; row < 4; ++row)
      {
        for (int column = 0; column < 4; ++column)
        {
          const double m = row == 3 ? (column == 3 ? 1.0 : 0.0)
                                    : (column == 3 ? origin[row] : A[column][row]);
          indexToWorld->SetTypedComponent(0, 4 * row + column, m);
        }
      }
      output->GetFieldData()->AddArray(indexToWorld);
    }
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
      const glm::dvec3 g = splatvdb::ToGlm(map.applyIJT(indexGradient, xyz));
      const double g2 = glm::dot(g, g);
      if (!(g2 > 0.0) || !std::isfinite(g2) || !std::isfinite(phi))
      {
        return -1;
      }
      if (point)
      {
        const glm::dmat3 A = splatvdb::IndexJacobian(map, xyz);
        *point = splatvdb::ToGlm(map.applyMap(xyz)) - (phi / g2) * g;
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
    splatvdb::AddVertices(output);
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
    using C = splatvdb::Channels<T>;
    const openvdb::Index stride = leaves[0]->constAttributeArray(name).stride();
    auto array = splatvdb::NewArray<typename C::Component>(name, C::Count * stride, offsets.back());
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
    splatvdb::AddVertices(output);
    this->Reader->UpdateProgress(1.0);
    this->Reader->NumberOfVoxelKernels = n;
  }

  //----------------------------------------------------------------------------
  template <typename GridT>
  void Dense(const GridT& grid, const openvdb::CoordBBox& box, vtkImageData* image)
  {
    using ValueT = typename GridT::ValueType;
    if (!grid.transform().isLinear() ||
      !splatvdb::ImageGeometry(*grid.transform().baseMap(), image))
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
    splatvdb::ValueArrays<ValueT> values(this->GridName, n);
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

#endif
