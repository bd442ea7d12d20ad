// SPDX-License-Identifier: BSD-3-Clause
#include "vtkDifferentialPointGenerator.h"

#include "SplatDifferentialPointGeometry.h"
#include "SplatDifferentialPointSetCover.h"
#include "SplatDifferentialPointSimplifier.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPCANormalEstimation.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <tuple>
#include <vector>

vtkStandardNewMacro(vtkDifferentialPointGenerator);

namespace
{
using splat::DifferentialPoint;
using Rings = std::vector<std::vector<std::int64_t>>;

// A point cloud's stand-in for a mesh vertex's 1-ring (rectangle enlargement, simplification
// neighbors): its 8 nearest points, the samples around a point of a regular grid.
constexpr int CloudRingSize = 8;

// The finite input points, the samples of the surface.
struct Samples
{
  std::vector<vtkIdType> InputIds;
  std::vector<Eigen::Vector3d> Positions;
  Rings Ring;                                            // 1-ring or nearest points, symmetric
  std::vector<std::vector<Eigen::Vector3d>> RingNormals; // a mesh edge's averaged polygon normals
  std::vector<Eigen::Vector3d> FrameNormals;             // zero where unknown
  vtkSmartPointer<vtkCellArray> Polygons;                // a mesh's, over the samples' ids
  bool Mesh = false;
};

vtkSmartPointer<vtkPolyData> MakeCloud(const std::vector<Eigen::Vector3d>& positions)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(positions.size()));
  for (std::size_t i = 0; i < positions.size(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), positions[i].data());
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  return cloud;
}

Eigen::Vector3d ToEigen(vtkDataArray* array, vtkIdType id)
{
  double v[3];
  array->GetTuple(id, v);
  return { v[0], v[1], v[2] };
}

// A normal to use as the fit's frame: finite and not zero.
bool UsableNormal(const Eigen::Vector3d& n)
{
  return n.allFinite() && n.norm() > 1e-12;
}

// PCA: the direction of least spread of the neighbors about x; +z when they fix no plane.
Eigen::Vector3d PlaneNormal(const Eigen::Vector3d& x, const std::vector<Eigen::Vector3d>& neighbors)
{
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& q : neighbors)
  {
    covariance += (q - x) * (q - x).transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  if (neighbors.size() < 2 || solver.info() != Eigen::Success || solver.eigenvalues()[1] <= 0.0)
  {
    return Eigen::Vector3d::UnitZ();
  }
  return solver.eigenvectors().col(0);
}

// The mesh's polygons over the finite samples (polygons touching a non-finite point are left
// out), their consistently oriented vertex normals and the 1-rings with each edge's averaged
// polygon normals. Returns false when no polygon is left.
bool BuildMesh(vtkPolyData* mesh, const std::vector<vtkIdType>& sampleOf, Samples& samples)
{
  vtkNew<vtkCellArray> polys;
  auto iter = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  std::vector<vtkIdType> ids;
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* cell;
    iter->GetCurrentCell(size, cell);
    ids.clear();
    for (vtkIdType i = 0; i < size; ++i)
    {
      if (cell[i] < 0 || cell[i] >= static_cast<vtkIdType>(sampleOf.size()) ||
        sampleOf[cell[i]] < 0)
      {
        break;
      }
      ids.push_back(sampleOf[cell[i]]);
    }
    if (size >= 3 && static_cast<vtkIdType>(ids.size()) == size)
    {
      polys->InsertNextCell(size, ids.data());
    }
  }
  if (polys->GetNumberOfCells() == 0)
  {
    return false;
  }
  vtkSmartPointer<vtkPolyData> clean = MakeCloud(samples.Positions);
  clean->SetPolys(polys);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(clean);
  normals->ComputePointNormalsOn();
  normals->ComputeCellNormalsOn();
  normals->SplittingOff();
  normals->ConsistencyOn();
  normals->Update();
  vtkPolyData* oriented = normals->GetOutput();
  vtkDataArray* pointNormals = oriented->GetPointData()->GetNormals();
  vtkDataArray* cellNormals = oriented->GetCellData()->GetNormals();
  const std::size_t n = samples.Positions.size();
  if (!pointNormals || !cellNormals ||
    pointNormals->GetNumberOfTuples() != static_cast<vtkIdType>(n))
  {
    return false;
  }

  // Directed edges (a, b, polygon), sorted to merge each edge's polygons.
  std::vector<std::tuple<std::int64_t, std::int64_t, vtkIdType>> edges;
  auto cells = vtk::TakeSmartPointer(oriented->GetPolys()->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* cell;
    cells->GetCurrentCell(size, cell);
    for (vtkIdType i = 0; i < size; ++i)
    {
      const vtkIdType a = cell[i], b = cell[(i + 1) % size];
      if (a != b)
      {
        edges.emplace_back(a, b, cells->GetCurrentCellId());
        edges.emplace_back(b, a, cells->GetCurrentCellId());
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  samples.Ring.assign(n, {});
  samples.RingNormals.assign(n, {});
  for (std::size_t i = 0; i < edges.size(); ++i)
  {
    const auto [a, b, cell] = edges[i];
    if (i == 0 || std::get<0>(edges[i - 1]) != a || std::get<1>(edges[i - 1]) != b)
    {
      samples.Ring[a].push_back(b);
      samples.RingNormals[a].push_back(Eigen::Vector3d::Zero());
    }
    samples.RingNormals[a].back() += ToEigen(cellNormals, cell);
  }
  samples.FrameNormals.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    samples.FrameNormals[i] = ToEigen(pointNormals, static_cast<vtkIdType>(i));
  }
  samples.Polygons = oriented->GetPolys();
  samples.Mesh = true;
  return true;
}

// A point cloud's rings: the CloudRingSize nearest points, made symmetric. Normals from PCA
// oriented by graph traversal.
void BuildCloud(vtkPolyData* cloud, vtkStaticPointLocator* locator, Samples& samples)
{
  const vtkIdType n = cloud->GetNumberOfPoints();
  Rings nearest(n);
  vtkSMPThreadLocalObject<vtkIdList> lists;
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      vtkIdList* found = lists.Local();
      for (vtkIdType p = begin; p < end; ++p)
      {
        locator->FindClosestNPoints(CloudRingSize + 1, samples.Positions[p].data(), found);
        for (vtkIdType i = 0; i < found->GetNumberOfIds(); ++i)
        {
          if (found->GetId(i) != p && static_cast<int>(nearest[p].size()) < CloudRingSize)
          {
            nearest[p].push_back(found->GetId(i));
          }
        }
      }
    });
  samples.Ring.assign(n, {});
  for (vtkIdType p = 0; p < n; ++p)
  {
    for (std::int64_t q : nearest[p])
    {
      samples.Ring[p].push_back(q);
      samples.Ring[q].push_back(p);
    }
  }
  for (auto& ring : samples.Ring)
  {
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  }
  samples.FrameNormals.assign(n, Eigen::Vector3d::Zero());
}

// The set cover's samples of the surface, weighted by the area each stands for: a mesh's used
// vertices and polygon centroids (a polygon's area half to its centroid, half shared by its
// vertices), a cloud's points and the midpoints to their ring neighbors (a point's area, the mean
// squared distance to its ring, half to itself and half shared by its ring's midpoints). A
// centroid or midpoint takes the averaged normal of its points; none is made where they cancel.
std::vector<splat::CoverSample> CoverSamples(
  const Samples& samples, const std::vector<DifferentialPoint>& points)
{
  const std::size_t n = points.size();
  std::vector<splat::CoverSample> result;
  std::vector<double> weights(n, 0.0);
  auto addAverage = [&](const Eigen::Vector3d& position, const Eigen::Vector3d& normalSum,
                      double weight)
  {
    if (normalSum.norm() > 1e-6)
    {
      result.push_back({ position, normalSum.normalized(), weight });
    }
  };
  if (samples.Mesh)
  {
    auto cells = vtk::TakeSmartPointer(samples.Polygons->NewIterator());
    for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
    {
      vtkIdType size;
      const vtkIdType* cell;
      cells->GetCurrentCell(size, cell);
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), normalSum = Eigen::Vector3d::Zero();
      double area = 0.0;
      for (vtkIdType i = 0; i < size; ++i)
      {
        centroid += points[cell[i]].Position / static_cast<double>(size);
        normalSum += points[cell[i]].Normal;
        if (i >= 2)
        {
          area += 0.5 *
            (points[cell[i - 1]].Position - points[cell[0]].Position)
              .cross(points[cell[i]].Position - points[cell[0]].Position)
              .norm();
        }
      }
      for (vtkIdType i = 0; i < size; ++i)
      {
        weights[cell[i]] += 0.5 * area / static_cast<double>(size);
      }
      addAverage(centroid, normalSum, 0.5 * area);
    }
  }
  else
  {
    for (std::size_t p = 0; p < n; ++p)
    {
      const auto& ring = samples.Ring[p];
      double area = 0.0;
      for (std::int64_t q : ring)
      {
        area += (points[q].Position - points[p].Position).squaredNorm() / ring.size();
      }
      weights[p] = 0.5 * area;
    }
    for (std::size_t p = 0; p < n; ++p)
    {
      for (std::int64_t q : samples.Ring[p])
      {
        if (static_cast<std::size_t>(q) > p && points[p].Normal.dot(points[q].Normal) > 0.0)
        {
          addAverage(0.5 * (points[p].Position + points[q].Position),
            points[p].Normal + points[q].Normal,
            weights[p] / samples.Ring[p].size() + weights[q] / samples.Ring[q].size());
        }
      }
    }
  }
  for (std::size_t p = 0; p < n; ++p)
  {
    if (!samples.Ring[p].empty())
    {
      result.push_back({ points[p].Position, points[p].Normal, weights[p] });
    }
  }
  return result;
}

// The output: the kept points' coordinates and input point data, their differential geometry
// as named arrays and one vertex each.
void WriteOutput(vtkPointSet* input, const std::vector<vtkIdType>& keptInput,
  const std::vector<DifferentialPoint>& keptPoints, vtkPolyData* output)
{
  const auto m = static_cast<vtkIdType>(keptInput.size());
  vtkNew<vtkIdList> source;
  source->SetNumberOfIds(m);
  std::copy(keptInput.begin(), keptInput.end(), source->begin());
  vtkNew<vtkIdList> destination;
  destination->SetNumberOfIds(m);
  std::iota(destination->begin(), destination->end(), 0);
  vtkNew<vtkPoints> outputPoints;
  if (input->GetPoints())
  {
    outputPoints->SetDataType(input->GetPoints()->GetDataType());
    outputPoints->SetNumberOfPoints(m);
    outputPoints->InsertPoints(destination, source, input->GetPoints());
  }
  output->SetPoints(outputPoints);
  vtkPointData* outputData = output->GetPointData();
  outputData->CopyAllocate(input->GetPointData(), m);
  outputData->CopyData(input->GetPointData(), source, destination);

  auto makeArray = [m](const char* name, int components)
  {
    vtkNew<vtkFloatArray> array;
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(m);
    return vtkSmartPointer<vtkFloatArray>(array);
  };
  auto normals = makeArray("Normals", 3);
  auto directionU = makeArray("PrincipalDirectionU", 3);
  auto directionV = makeArray("PrincipalDirectionV", 3);
  auto curvatures = makeArray("PrincipalCurvatures", 2);
  auto extents = makeArray("Extents", 2);
  for (vtkIdType i = 0; i < m; ++i)
  {
    const DifferentialPoint& point = keptPoints[i];
    normals->SetTuple(i, point.Normal.data());
    directionU->SetTuple(i, point.U.data());
    directionV->SetTuple(i, point.V.data());
    const double curvature[2] = { point.CurvatureU, point.CurvatureV };
    curvatures->SetTuple(i, curvature);
    const double extent[2] = { point.ExtentU, point.ExtentV };
    extents->SetTuple(i, extent);
  }
  outputData->SetNormals(normals);
  outputData->AddArray(directionU);
  outputData->AddArray(directionV);
  outputData->AddArray(curvatures);
  outputData->AddArray(extents);

  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfTuples(m);
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfTuples(m + 1);
  for (vtkIdType i = 0; i <= m; ++i)
  {
    if (i < m)
    {
      connectivity->SetValue(i, i);
    }
    offsets->SetValue(i, i);
  }
  vtkNew<vtkCellArray> vertices;
  vertices->SetData(offsets, connectivity);
  output->SetVerts(vertices);
}
}

//------------------------------------------------------------------------------
int vtkDifferentialPointGenerator::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkDifferentialPointGenerator::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("The input must be a vtkPointSet.");
    return 0;
  }
  this->NumberOfKeptPoints = 0;
  this->NumberOfSkippedPoints = 0;
  const vtkIdType numberOfInputPoints = input->GetNumberOfPoints();

  Samples samples;
  std::vector<vtkIdType> sampleOf(numberOfInputPoints, -1);
  for (vtkIdType i = 0; i < numberOfInputPoints; ++i)
  {
    Eigen::Vector3d x;
    input->GetPoint(i, x.data());
    if (x.allFinite())
    {
      sampleOf[i] = static_cast<vtkIdType>(samples.Positions.size());
      samples.InputIds.push_back(i);
      samples.Positions.push_back(x);
    }
  }
  const vtkIdType n = static_cast<vtkIdType>(samples.Positions.size());
  this->NumberOfSkippedPoints = numberOfInputPoints - n;
  if (n == 0)
  {
    WriteOutput(input, {}, {}, output);
    return 1;
  }

  vtkSmartPointer<vtkPolyData> cloud = MakeCloud(samples.Positions);
  vtkNew<vtkStaticPointLocator> locator;
  auto* mesh = vtkPolyData::SafeDownCast(input);
  if (!mesh || mesh->GetNumberOfPolys() == 0 || !BuildMesh(mesh, sampleOf, samples))
  {
    locator->SetDataSet(cloud);
    locator->BuildLocator();
    BuildCloud(cloud, locator, samples);
    if (n >= 3 && !input->GetPointData()->GetNormals())
    {
      vtkNew<vtkPCANormalEstimation> pca;
      pca->SetInputData(cloud);
      pca->SetSampleSize(this->NumberOfNeighbors);
      pca->SetNormalOrientation(vtkPCANormalEstimation::GRAPH_TRAVERSAL);
      pca->Update();
      if (vtkDataArray* normals = pca->GetOutput()->GetPointData()->GetNormals())
      {
        for (vtkIdType p = 0; p < n; ++p)
        {
          samples.FrameNormals[p] = ToEigen(normals, p);
        }
      }
    }
  }
  vtkDataArray* inputNormals = input->GetPointData()->GetNormals();
  if (inputNormals && inputNormals->GetNumberOfComponents() == 3)
  {
    for (vtkIdType p = 0; p < n; ++p)
    {
      const Eigen::Vector3d normal = ToEigen(inputNormals, samples.InputIds[p]);
      if (UsableNormal(normal))
      {
        samples.FrameNormals[p] = normal;
      }
    }
  }
  this->UpdateProgress(0.2);

  double delta = this->MaximumPrincipalWidth;
  if (delta <= 0.0)
  {
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& x : samples.Positions)
    {
      box.extend(x);
    }
    delta = box.diagonal().norm() / 20.0;
  }
  const double epsilon = this->MaximumPrincipalError;
  // Below this curvature the error bound leaves the extent at delta: the point is flat.
  const double flatCurvature = delta > 0.0 ? std::sqrt(2.0 * epsilon - epsilon * epsilon) / delta
                                           : std::numeric_limits<double>::infinity();
  const int k = static_cast<int>(std::min<vtkIdType>(this->NumberOfNeighbors + 1, n));

  std::vector<DifferentialPoint> points(n);
  vtkSMPThreadLocalObject<vtkIdList> lists;
  vtkSMPThreadLocal<std::vector<Eigen::Vector3d>> neighborhoods;
  vtkSMPThreadLocal<std::vector<std::int64_t>> twoRings;
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<Eigen::Vector3d>& neighborhood = neighborhoods.Local();
      std::vector<std::int64_t>& twoRing = twoRings.Local();
      vtkIdList* found = lists.Local();
      for (vtkIdType p = begin; p < end; ++p)
      {
        const Eigen::Vector3d& x = samples.Positions[p];
        neighborhood.clear();
        if (samples.Mesh)
        {
          twoRing.clear();
          for (std::int64_t q : samples.Ring[p])
          {
            twoRing.push_back(q);
            twoRing.insert(twoRing.end(), samples.Ring[q].begin(), samples.Ring[q].end());
          }
          std::sort(twoRing.begin(), twoRing.end());
          twoRing.erase(std::unique(twoRing.begin(), twoRing.end()), twoRing.end());
          for (std::int64_t q : twoRing)
          {
            if (q != p)
            {
              neighborhood.push_back(samples.Positions[q]);
            }
          }
        }
        else
        {
          locator->FindClosestNPoints(k, x.data(), found);
          for (vtkIdType i = 0; i < found->GetNumberOfIds(); ++i)
          {
            if (found->GetId(i) != p)
            {
              neighborhood.push_back(samples.Positions[found->GetId(i)]);
            }
          }
        }
        Eigen::Vector3d frame = samples.FrameNormals[p];
        frame = UsableNormal(frame) ? frame.normalized() : PlaneNormal(x, neighborhood);

        DifferentialPoint& point = points[p];
        point.Position = x;
        splat::FitDifferentialPoint(neighborhood, frame, flatCurvature, point);
        point.ExtentU = splat::ErrorBoundedExtent(point.CurvatureU, epsilon, delta);
        point.ExtentV = splat::ErrorBoundedExtent(point.CurvatureV, epsilon, delta);
        // Section IV-B: the rectangle holds the midpoints of the edges to the neighbors,
        // projected onto the tangent plane along the edge's normal (orthographically for a cloud
        // and where that normal lies nearly in the plane, at a crease).
        for (std::size_t i = 0; i < samples.Ring[p].size(); ++i)
        {
          const Eigen::Vector3d middle = 0.5 * (x + samples.Positions[samples.Ring[p][i]]);
          Eigen::Vector3d along = point.Normal;
          if (samples.Mesh && UsableNormal(samples.RingNormals[p][i]))
          {
            const Eigen::Vector3d edgeNormal = samples.RingNormals[p][i].normalized();
            if (std::abs(edgeNormal.dot(point.Normal)) > 0.1)
            {
              along = edgeNormal;
            }
          }
          const Eigen::Vector3d projected =
            middle - ((middle - x).dot(point.Normal) / along.dot(point.Normal)) * along;
          const Eigen::Vector2d uv = point.Local(projected);
          point.ExtentU = std::max(point.ExtentU, std::abs(uv.x()));
          point.ExtentV = std::max(point.ExtentV, std::abs(uv.y()));
        }
      }
    });
  this->UpdateProgress(0.5);

  // A mesh's vertices that no polygon uses are not samples of its surface.
  std::vector<bool> kept(n, true);
  if (samples.Mesh)
  {
    for (vtkIdType p = 0; p < n; ++p)
    {
      kept[p] = !samples.Ring[p].empty();
    }
  }
  if (this->Simplify && n > 1)
  {
    const auto progress = [this](double fraction)
    {
      this->UpdateProgress(0.5 + 0.45 * fraction);
      return !this->GetAbortExecute();
    };
    std::vector<bool> simplified;
    if (this->SimplificationMode == SET_COVER)
    {
      splat::DifferentialPointSetCover cover(points, this->SimplificationMargin, epsilon);
      simplified = cover.Run(CoverSamples(samples, points), kept, progress);
    }
    else
    {
      splat::DifferentialPointSimplifier simplifier(points, this->SimplificationMargin);
      simplified = simplifier.Run(samples.Ring, progress);
    }
    for (vtkIdType p = 0; p < n; ++p)
    {
      kept[p] = kept[p] && simplified[p];
    }
  }

  std::vector<vtkIdType> keptInput;
  std::vector<DifferentialPoint> keptPoints;
  for (vtkIdType p = 0; p < n; ++p)
  {
    if (kept[p])
    {
      keptInput.push_back(samples.InputIds[p]);
      keptPoints.push_back(points[p]);
    }
  }
  WriteOutput(input, keptInput, keptPoints, output);
  this->NumberOfKeptPoints = static_cast<vtkIdType>(keptInput.size());
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
const char* vtkDifferentialPointGenerator::GetSimplificationModeAsString()
{
  return this->SimplificationMode == SET_COVER ? "SET_COVER" : "GREEDY_ENCLOSURE";
}

//------------------------------------------------------------------------------
void vtkDifferentialPointGenerator::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumPrincipalError: " << this->MaximumPrincipalError << "\n";
  os << indent << "MaximumPrincipalWidth: " << this->MaximumPrincipalWidth << "\n";
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "Simplify: " << (this->Simplify ? "On" : "Off") << "\n";
  os << indent << "SimplificationMode: " << this->GetSimplificationModeAsString() << "\n";
  os << indent << "SimplificationMargin: " << this->SimplificationMargin << "\n";
  os << indent << "NumberOfKeptPoints: " << this->NumberOfKeptPoints << "\n";
  os << indent << "NumberOfSkippedPoints: " << this->NumberOfSkippedPoints << "\n";
}
