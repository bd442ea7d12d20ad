// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSplatPointsFilter.h"

#include "vtkCellArray.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSet.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSurfelGenerator.h"

#include <numeric>
#include <vector>

vtkStandardNewMacro(vtkSplatPointsFilter);

namespace
{
bool HasArray(vtkDataSet* data, const char* name, int components)
{
  vtkDataArray* array = name ? data->GetPointData()->GetArray(name) : nullptr;
  return array && array->GetNumberOfComponents() == components;
}

// The non-empty leaves of a dataset or composite dataset.
std::vector<vtkSmartPointer<vtkDataSet>> LeavesOf(vtkDataObject* input)
{
  std::vector<vtkSmartPointer<vtkDataSet>> leaves;
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    auto iter = vtk::TakeSmartPointer(composite->NewIterator());
    iter->SkipEmptyNodesOn();
    for (iter->InitTraversal(); !iter->IsDoneWithTraversal(); iter->GoToNextItem())
    {
      auto* leaf = vtkDataSet::SafeDownCast(iter->GetCurrentDataObject());
      if (leaf && leaf->GetNumberOfPoints() > 0)
      {
        leaves.emplace_back(leaf);
      }
    }
  }
  else if (auto* data = vtkDataSet::SafeDownCast(input))
  {
    if (data->GetNumberOfPoints() > 0)
    {
      leaves.emplace_back(data);
    }
  }
  return leaves;
}
}

//------------------------------------------------------------------------------
vtkSplatPointsFilter::vtkSplatPointsFilter()
{
  this->SetRadiusArrayName("Radius");
  this->SetTangentAxis0ArrayName("TangentAxis0");
  this->SetTangentAxis1ArrayName("TangentAxis1");
}

//------------------------------------------------------------------------------
vtkSplatPointsFilter::~vtkSplatPointsFilter()
{
  this->SetRadiusArrayName(nullptr);
  this->SetTangentAxis0ArrayName(nullptr);
  this->SetTangentAxis1ArrayName(nullptr);
}

//------------------------------------------------------------------------------
int vtkSplatPointsFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDataSet> vtkSplatPointsFilter::CompleteSurfels(vtkDataSet* leaf)
{
  const bool hasAxes = HasArray(leaf, this->TangentAxis0ArrayName, 3) &&
    HasArray(leaf, this->TangentAxis1ArrayName, 3);
  vtkDataArray* normals = leaf->GetPointData()->GetNormals();
  const bool hasNormals = hasAxes || (normals && normals->GetNumberOfComponents() == 3);
  const bool hasRadii = hasAxes || HasArray(leaf, this->RadiusArrayName, 1);
  auto* pointSet = vtkPointSet::SafeDownCast(leaf);
  if ((hasNormals && (hasRadii || !this->EstimateRadii)) || !pointSet)
  {
    return leaf;
  }
  vtkNew<vtkSurfelGenerator> generator;
  generator->SetInputData(pointSet);
  generator->SetNumberOfNeighbors(this->NumberOfNeighbors);
  generator->SetRadiusScale(this->RadiusScale);
  // The leaf's own radii are kept: the estimates go into a scratch array when it has them.
  const bool keepRadii = hasRadii || !this->EstimateRadii;
  generator->SetRadiusArrayName(keepRadii ? "vtkSplatPointsFilterRadius" : this->RadiusArrayName);
  generator->Update();
  vtkSmartPointer<vtkDataSet> surfels = generator->GetOutput();
  if (keepRadii)
  {
    surfels->GetPointData()->RemoveArray("vtkSplatPointsFilterRadius");
  }
  return surfels;
}

//------------------------------------------------------------------------------
int vtkSplatPointsFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!output)
  {
    return 0;
  }
  std::vector<vtkSmartPointer<vtkDataSet>> leaves = LeavesOf(input);
  if (this->GenerateSurfels)
  {
    for (std::size_t i = 0; i < leaves.size(); ++i)
    {
      leaves[i] = this->CompleteSurfels(leaves[i]);
      this->UpdateProgress(0.8 * (i + 1) / leaves.size());
    }
  }
  if (leaves.empty())
  {
    return 1;
  }

  // Points in double when any leaf has them (data far from the origin), else in float.
  vtkIdType total = 0;
  int pointType = VTK_FLOAT;
  for (const auto& leaf : leaves)
  {
    total += leaf->GetNumberOfPoints();
    auto* pointSet = vtkPointSet::SafeDownCast(leaf);
    if (!pointSet || pointSet->GetPoints()->GetDataType() == VTK_DOUBLE)
    {
      pointType = VTK_DOUBLE;
    }
  }
  vtkNew<vtkPoints> points;
  points->SetDataType(pointType);
  points->SetNumberOfPoints(total);

  vtkDataSetAttributes::FieldList fields(static_cast<int>(leaves.size()));
  for (const auto& leaf : leaves)
  {
    fields.IntersectFieldList(leaf->GetPointData());
  }
  vtkPointData* outputData = output->GetPointData();
  outputData->CopyAllocate(fields, total);
  outputData->SetNumberOfTuples(total);
  vtkIdType offset = 0;
  for (std::size_t i = 0; i < leaves.size(); ++i)
  {
    vtkDataSet* leaf = leaves[i];
    const vtkIdType n = leaf->GetNumberOfPoints();
    if (auto* pointSet = vtkPointSet::SafeDownCast(leaf))
    {
      points->InsertPoints(offset, n, 0, pointSet->GetPoints());
    }
    else
    {
      for (vtkIdType p = 0; p < n; ++p)
      {
        points->SetPoint(offset + p, leaf->GetPoint(p));
      }
    }
    outputData->CopyData(fields, leaf->GetPointData(), static_cast<int>(i), offset, n, 0);
    offset += n;
  }
  output->SetPoints(points);

  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfTuples(total + 1);
  std::iota(offsets->GetPointer(0), offsets->GetPointer(0) + total + 1, vtkIdType(0));
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfTuples(total);
  std::iota(connectivity->GetPointer(0), connectivity->GetPointer(0) + total, vtkIdType(0));
  vtkNew<vtkCellArray> vertices;
  vertices->SetData(offsets, connectivity);
  output->SetVerts(vertices);
  return 1;
}

//------------------------------------------------------------------------------
void vtkSplatPointsFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  auto name = [](const char* s) { return s ? s : "(none)"; };
  os << indent << "GenerateSurfels: " << this->GenerateSurfels << "\n";
  os << indent << "EstimateRadii: " << this->EstimateRadii << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "RadiusArrayName: " << name(this->RadiusArrayName) << "\n";
  os << indent << "TangentAxis0ArrayName: " << name(this->TangentAxis0ArrayName) << "\n";
  os << indent << "TangentAxis1ArrayName: " << name(this->TangentAxis1ArrayName) << "\n";
}
