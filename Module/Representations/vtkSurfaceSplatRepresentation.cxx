// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSurfaceSplatRepresentation.h"

#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSplatPointsFilter.h"
#include "vtkSurfaceSplatMapper.h"

vtkStandardNewMacro(vtkSurfaceSplatRepresentation);

//------------------------------------------------------------------------------
vtkSurfaceSplatRepresentation::vtkSurfaceSplatRepresentation()
{
  this->SurfelFilter->GenerateSurfelsOn();
  // The superclass deletes MultiBlockMaker: it holds a reference of its own.
  this->MultiBlockMaker->Delete();
  this->MultiBlockMaker = this->SurfelFilter;
  this->MultiBlockMaker->Register(this);
  this->SuppressLOD = true;
  vtkNew<vtkSurfaceSplatMapper> mapper;
  this->SetSplatMapper(mapper);
}

//------------------------------------------------------------------------------
vtkSurfaceSplatRepresentation::~vtkSurfaceSplatRepresentation() = default;

//------------------------------------------------------------------------------
vtkSurfaceSplatMapper* vtkSurfaceSplatRepresentation::GetSplatMapper()
{
  return vtkSurfaceSplatMapper::SafeDownCast(this->Mapper);
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRepresentation::SetSplatMapper(vtkSurfaceSplatMapper* mapper)
{
  if (!mapper || mapper == this->Mapper)
  {
    return;
  }
  // What the representation forwards to its mapper only when it changes.
  mapper->SetLookupTable(this->Mapper->GetLookupTable());
  mapper->SetColorMode(this->Mapper->GetColorMode());
  mapper->SetInterpolateScalarsBeforeMapping(this->Mapper->GetInterpolateScalarsBeforeMapping());
  mapper->SetStatic(this->Mapper->GetStatic());
  mapper->SetRadiusArrayName(this->SurfelFilter->GetRadiusArrayName());
  mapper->SetTangentAxis0ArrayName(this->SurfelFilter->GetTangentAxis0ArrayName());
  mapper->SetTangentAxis1ArrayName(this->SurfelFilter->GetTangentAxis1ArrayName());
  mapper->Register(this);
  this->Mapper->UnRegister(this);
  this->Mapper = mapper;
  // Connects the new mapper to the actor (and the superclass's selection to the mapper).
  this->SetupDefaults();
  this->MarkModified();
}

//------------------------------------------------------------------------------
bool vtkSurfaceSplatRepresentation::NeedsOrderedCompositing()
{
  if (this->Superclass::NeedsOrderedCompositing())
  {
    return true;
  }
  const char* opacityName = this->GetSplatMapper()->GetOpacityArrayName();
  auto* surfels = vtkPolyData::SafeDownCast(this->SurfelFilter->GetOutputDataObject(0));
  return surfels && opacityName && surfels->GetPointData()->GetArray(opacityName);
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRepresentation::SetRadiusArrayName(const char* name)
{
  this->GetSplatMapper()->SetRadiusArrayName(name);
  this->SurfelFilter->SetRadiusArrayName(name);
  this->MarkModified();
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRepresentation::SetTangentAxis0ArrayName(const char* name)
{
  this->GetSplatMapper()->SetTangentAxis0ArrayName(name);
  this->SurfelFilter->SetTangentAxis0ArrayName(name);
  this->MarkModified();
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRepresentation::SetTangentAxis1ArrayName(const char* name)
{
  this->GetSplatMapper()->SetTangentAxis1ArrayName(name);
  this->SurfelFilter->SetTangentAxis1ArrayName(name);
  this->MarkModified();
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRepresentation::SetEstimateRadii(bool estimate)
{
  this->SurfelFilter->SetEstimateRadii(estimate);
  this->MarkModified();
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRepresentation::SetRadiusScale(double scale)
{
  this->SurfelFilter->SetRadiusScale(scale);
  this->MarkModified();
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRepresentation::SetNumberOfNeighbors(int neighbors)
{
  this->SurfelFilter->SetNumberOfNeighbors(neighbors);
  this->MarkModified();
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SurfelFilter:\n";
  this->SurfelFilter->PrintSelf(os, indent.GetNextIndent());
  os << indent << "SplatMapper: " << this->Mapper << "\n";
}
