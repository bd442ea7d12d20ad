// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSurfelGenerator.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkMath.h"
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
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"

#include <algorithm>
#include <numeric>

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkSurfelGenerator);

namespace
{
// Point normals for a point set without them: mesh normals when it has polygons, PCA otherwise.
vtkSmartPointer<vtkDataArray> EstimateNormals(vtkPointSet* points, int neighbors)
{
  auto* polyData = vtkPolyData::SafeDownCast(points);
  if (polyData && polyData->GetNumberOfPolys() > 0)
  {
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(polyData);
    normals->ComputePointNormalsOn();
    normals->ComputeCellNormalsOff();
    normals->SplittingOff();
    normals->ConsistencyOn();
    normals->Update();
    return normals->GetOutput()->GetPointData()->GetNormals();
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points->GetPoints());
  vtkNew<vtkPCANormalEstimation> pca;
  pca->SetInputData(cloud);
  pca->SetSampleSize(std::max(neighbors, 8));
  pca->SetNormalOrientation(vtkPCANormalEstimation::GRAPH_TRAVERSAL);
  pca->Update();
  return pca->GetOutput()->GetPointData()->GetNormals();
}
}

//------------------------------------------------------------------------------
vtkSurfelGenerator::vtkSurfelGenerator()
{
  this->SetRadiusArrayName("Radius");
}

//------------------------------------------------------------------------------
vtkSurfelGenerator::~vtkSurfelGenerator()
{
  this->SetRadiusArrayName(nullptr);
}

//------------------------------------------------------------------------------
int vtkSurfelGenerator::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkSurfelGenerator::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || !output)
  {
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  if (n == 0)
  {
    return 1;
  }
  if (!this->RadiusArrayName || !*this->RadiusArrayName)
  {
    vtkErrorMacro("RadiusArrayName must be a non-empty name.");
    return 0;
  }

  // Non-finite points stay in the output (their data is kept) but take no part in the
  // neighborhoods, and get radius 0 so that the mapper skips and counts them.
  std::vector<vtkIdType> finiteIds;
  finiteIds.reserve(n);
  vtkNew<vtkPoints> finitePoints;
  finitePoints->SetDataTypeToDouble();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      finiteIds.push_back(i);
      finitePoints->InsertNextPoint(p);
    }
  }
  this->UpdateProgress(0.1);

  vtkSmartPointer<vtkDataArray> normals = input->GetPointData()->GetNormals();
  if (!normals || normals->GetNumberOfComponents() != 3)
  {
    normals = EstimateNormals(input, this->NumberOfNeighbors);
    if (!normals)
    {
      vtkErrorMacro("Could not estimate normals for the input points.");
      return 0;
    }
  }
  this->UpdateProgress(0.5);

  vtkNew<vtkFloatArray> radius;
  radius->SetName(this->RadiusArrayName);
  radius->SetNumberOfTuples(n);
  radius->Fill(0.0);
  auto* mesh = vtkPolyData::SafeDownCast(input);
  if (mesh && mesh->GetNumberOfPolys() > 0)
  {
    this->MeshRadii(mesh, radius);
  }
  else
  {
    this->NeighborRadii(finitePoints, finiteIds, radius);
  }
  this->UpdateProgress(0.9);

  vtkNew<vtkPointData> surfelData;
  surfelData->PassData(input->GetPointData());
  surfelData->SetNormals(normals);
  surfelData->AddArray(radius);

  // A mesh's vertices that no polygon uses (radius 0) do not sample its surface: left out.
  vtkNew<vtkIdList> kept;
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (!mesh || mesh->GetNumberOfPolys() == 0 || radius->GetValue(i) > 0.0f)
    {
      kept->InsertNextId(i);
    }
  }
  const vtkIdType m = kept->GetNumberOfIds();
  if (m == n)
  {
    output->SetPoints(input->GetPoints());
    output->GetPointData()->ShallowCopy(surfelData);
  }
  else
  {
    vtkNew<vtkIdList> destination;
    destination->SetNumberOfIds(m);
    std::iota(destination->begin(), destination->end(), 0);
    vtkNew<vtkPoints> points;
    points->SetDataType(input->GetPoints()->GetDataType());
    points->SetNumberOfPoints(m);
    points->InsertPoints(destination, kept, input->GetPoints());
    output->SetPoints(points);
    output->GetPointData()->CopyAllocate(surfelData, m);
    output->GetPointData()->CopyData(surfelData, kept, destination);
  }

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
  return 1;
}

//------------------------------------------------------------------------------
void vtkSurfelGenerator::MeshRadii(vtkPolyData* mesh, vtkFloatArray* radius)
{
  vtkCellArray* polys = mesh->GetPolys();
  auto iter = vtk::TakeSmartPointer(polys->NewIterator());
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    iter->GetCurrentCell(size, ids);
    for (vtkIdType e = 0; e < size; ++e)
    {
      const vtkIdType a = ids[e];
      const vtkIdType b = ids[(e + 1) % size];
      double p[3], q[3];
      mesh->GetPoint(a, p);
      mesh->GetPoint(b, q);
      const double length = std::sqrt(vtkMath::Distance2BetweenPoints(p, q));
      if (!std::isfinite(length))
      {
        continue;
      }
      const float scaled = static_cast<float>(this->RadiusScale * length);
      radius->SetValue(a, std::max(radius->GetValue(a), scaled));
      radius->SetValue(b, std::max(radius->GetValue(b), scaled));
    }
  }
}

//------------------------------------------------------------------------------
void vtkSurfelGenerator::NeighborRadii(
  vtkPoints* points, const std::vector<vtkIdType>& ids, vtkFloatArray* radius)
{
  const vtkIdType count = points->GetNumberOfPoints();
  if (count < 2)
  {
    return;
  }
  vtkNew<vtkPolyData> pointSet;
  pointSet->SetPoints(points);
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(pointSet);
  locator->BuildLocator();
  const int k = static_cast<int>(std::min<vtkIdType>(this->NumberOfNeighbors, count - 1));
  const double scale = this->RadiusScale;
  vtkSMPTools::For(0, count,
    [&](vtkIdType begin, vtkIdType end)
    {
      // One list per range of points (a few per thread) rather than per thread.
      vtkNew<vtkIdList> neighbors;
      for (vtkIdType j = begin; j < end; ++j)
      {
        double p[3], q[3];
        points->GetPoint(j, p);
        locator->FindClosestNPoints(k + 1, p, neighbors);
        double sum = 0.0;
        int found = 0;
        for (vtkIdType m = 0; m < neighbors->GetNumberOfIds() && found < k; ++m)
        {
          if (neighbors->GetId(m) != j)
          {
            points->GetPoint(neighbors->GetId(m), q);
            sum += std::sqrt(vtkMath::Distance2BetweenPoints(p, q));
            ++found;
          }
        }
        radius->SetValue(ids[j], found > 0 ? static_cast<float>(scale * sum / found) : 0.0f);
      }
    });
}

//------------------------------------------------------------------------------
void vtkSurfelGenerator::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "RadiusArrayName: " << (this->RadiusArrayName ? this->RadiusArrayName : "(none)")
     << "\n";
}
