// SPDX-License-Identifier: BSD-3-Clause
#include "vtkVolumeSplatRepresentation.h"

#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkOutlineSource.h"
#include "vtkPVLODVolume.h"
#include "vtkPVRenderView.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderer.h"
#include "vtkSplatPointsFilter.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkVolumeProperty.h"
#include "vtkVolumeSplatMapper.h"

#include <cmath>

vtkStandardNewMacro(vtkVolumeSplatRepresentation);

namespace
{
// The image blocks of a composite dataset: their number, and the block when it is the only
// non-empty block (a reader's or a filter's multiblock holding one volume).
vtkImageData* SoleImageBlock(vtkDataObject* input, int& imageBlocks)
{
  imageBlocks = 0;
  auto* composite = vtkCompositeDataSet::SafeDownCast(input);
  if (!composite)
  {
    return nullptr;
  }
  vtkImageData* image = nullptr;
  int blocks = 0;
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(composite->NewIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    auto* block = vtkDataSet::SafeDownCast(it->GetCurrentDataObject());
    if (block && block->GetNumberOfPoints() > 0)
    {
      ++blocks;
      if (auto* blockImage = vtkImageData::SafeDownCast(block))
      {
        ++imageBlocks;
        image = blockImage;
      }
    }
  }
  return blocks == 1 ? image : nullptr;
}
}

//------------------------------------------------------------------------------
vtkVolumeSplatRepresentation::vtkVolumeSplatRepresentation()
{
  vtkMath::UninitializeBounds(this->OwnedBounds);
  this->Actor->SetLODMapper(this->OutlineMapper);
  vtkNew<vtkVolumeSplatMapper> mapper;
  this->SetSplatMapper(mapper);
}

//------------------------------------------------------------------------------
vtkVolumeSplatRepresentation::~vtkVolumeSplatRepresentation() = default;

//------------------------------------------------------------------------------
void vtkVolumeSplatRepresentation::SetSplatMapper(vtkVolumeSplatMapper* mapper)
{
  if (!mapper || mapper == this->Mapper)
  {
    return;
  }
  this->Mapper = mapper;
  this->Actor->SetMapper(mapper);
  this->MarkModified();
}

//------------------------------------------------------------------------------
vtkVolumeSplatMapper* vtkVolumeSplatRepresentation::GetSplatMapper()
{
  return this->Mapper;
}

//------------------------------------------------------------------------------
int vtkVolumeSplatRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  // No input on processes without data (the client, a render server).
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> vtkVolumeSplatRepresentation::OwnedVoxels(
  vtkImageData* piece, const int wholeExtent[6])
{
  auto owned = vtkSmartPointer<vtkImageData>::New();
  owned->ShallowCopy(piece);
  int extent[6];
  piece->GetExtent(extent);
  bool shared = false;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (extent[2 * axis + 1] < wholeExtent[2 * axis + 1] &&
      extent[2 * axis + 1] > extent[2 * axis])
    {
      --extent[2 * axis + 1];
      shared = true;
    }
  }
  if (shared)
  {
    owned->Crop(extent);
  }
  return owned;
}

//------------------------------------------------------------------------------
int vtkVolumeSplatRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkMath::UninitializeBounds(this->DataBounds);
  vtkMath::UninitializeBounds(this->OwnedBounds);
  this->DataSize = 0;
  this->Cache = nullptr;
  this->IsImage = false;
  if (inputVector[0]->GetNumberOfInformationObjects() == 1)
  {
    vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
    vtkDataObject* input = vtkDataObject::GetData(inInfo);
    vtkSmartPointer<vtkDataSet> cache;
    auto* image = vtkImageData::SafeDownCast(input);
    int imageBlocks = 0;
    vtkImageData* block = image ? nullptr : SoleImageBlock(input, imageBlocks);
    if (image || block)
    {
      image = image ? image : block;
      int wholeExtent[6];
      image->GetExtent(wholeExtent);
      if (!block && inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
      {
        inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent);
      }
      vtkSmartPointer<vtkImageData> owned = OwnedVoxels(image, wholeExtent);
      owned->GetBounds(this->OwnedBounds);
      const double* spacing = owned->GetSpacing();
      for (int axis = 0; axis < 3; ++axis)
      {
        this->OwnedBounds[2 * axis] -= 0.5 * std::abs(spacing[axis]);
        this->OwnedBounds[2 * axis + 1] += 0.5 * std::abs(spacing[axis]);
      }
      cache = owned;
      this->IsImage = true;
    }
    else if (imageBlocks > 0)
    {
      // Merged into one point set, images lose their grid and have no kernel shapes to draw.
      vtkErrorMacro("Volume Splats draws one image, or points with Gaussian kernel arrays; this "
                    "composite dataset holds "
        << imageBlocks << " image blocks among others: merge them into one image first "
                          "(for instance with Resample To Image).");
      cache = vtkSmartPointer<vtkPolyData>::New();
    }
    else
    {
      this->PointsFilter->SetInputDataObject(input);
      this->PointsFilter->Update();
      auto points = vtkSmartPointer<vtkPolyData>::New();
      points->ShallowCopy(this->PointsFilter->GetOutput());
      cache = points;
    }
    if (cache->GetNumberOfPoints() > 0)
    {
      this->OutlineSource->SetBounds(cache->GetBounds());
      this->OutlineSource->Update();
      this->OutlineSource->GetBounds(this->DataBounds);
    }
    this->DataSize = cache->GetActualMemorySize();
    this->Cache = cache;
    this->Actor->SetEnableLOD(0);
  }
  else
  {
    // A process without the data shows the outline.
    this->Mapper->RemoveAllInputs();
    this->Actor->SetEnableLOD(1);
  }
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkVolumeSplatRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request_type, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo))
  {
    return 0;
  }
  if (request_type == vtkPVView::REQUEST_UPDATE())
  {
    vtkPVRenderView::SetPiece(inInfo, this, this->Cache, this->DataSize, 0);
    vtkPVRenderView::SetPiece(inInfo, this, this->OutlineSource->GetOutputDataObject(0), 0, 1);
    // Kernels blend front to back: the ranks' images must too.
    outInfo->Set(vtkPVRenderView::NEED_ORDERED_COMPOSITING(), 1);
    // ParaView orders the ranks of USE_BOUNDS_FOR_REDISTRIBUTION data by these bounds, which
    // must tile space: an image piece's owned voxels grown by half a voxel, touching the next.
    vtkPVRenderView::SetGeometryBounds(
      inInfo, this, this->IsImage ? this->OwnedBounds : this->DataBounds);
    vtkPVRenderView::SetRequiresDistributedRendering(inInfo, this, true);
    if (this->IsImage)
    {
      // Too heavy to move, and already split into boxes: the view orders the ranks by them.
      vtkPVRenderView::SetOrderedCompositingConfiguration(
        inInfo, this, vtkPVRenderView::USE_BOUNDS_FOR_REDISTRIBUTION, this->OwnedBounds);
    }
    else
    {
      vtkPVRenderView::SetOrderedCompositingConfiguration(inInfo, this,
        vtkPVRenderView::DATA_IS_REDISTRIBUTABLE | vtkPVRenderView::USE_DATA_FOR_LOAD_BALANCING);
    }
  }
  else if (request_type == vtkPVView::REQUEST_UPDATE_LOD())
  {
    vtkPVRenderView::SetRequiresDistributedRenderingLOD(inInfo, this, true);
  }
  else if (request_type == vtkPVView::REQUEST_RENDER())
  {
    this->Mapper->SetInputConnection(vtkPVRenderView::GetPieceProducer(inInfo, this, 0));
    this->OutlineMapper->SetInputConnection(vtkPVRenderView::GetPieceProducer(inInfo, this, 1));
    this->UpdateMapperParameters();
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRepresentation::UpdateMapperParameters()
{
  const char* arrayName = nullptr;
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkInformation* info = this->GetInputArrayInformation(0);
  if (info && info->Has(vtkDataObject::FIELD_ASSOCIATION()) &&
    info->Has(vtkDataObject::FIELD_NAME()))
  {
    arrayName = info->Get(vtkDataObject::FIELD_NAME());
    association = info->Get(vtkDataObject::FIELD_ASSOCIATION());
  }
  const bool hasArray = arrayName && arrayName[0];
  if (hasArray)
  {
    this->Mapper->SelectScalarArray(arrayName);
    this->Mapper->SetScalarMode(association == vtkDataObject::FIELD_ASSOCIATION_CELLS
        ? VTK_SCALAR_MODE_USE_CELL_FIELD_DATA
        : VTK_SCALAR_MODE_USE_POINT_FIELD_DATA);
  }
  else
  {
    // Kernel sets may have direct colors and opacities; the active scalars otherwise.
    this->Mapper->SetScalarMode(VTK_SCALAR_MODE_DEFAULT);
  }
  this->Actor->SetMapper(this->Mapper);
  // Image voxels need scalars for the transfer functions ("Solid Color" hides them, as Volume
  // does); kernel sets may carry their own colors.
  this->Actor->SetVisibility(this->GetVisibility() && (hasArray || !this->IsImage));
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatRepresentation::AddToView(vtkView* view)
{
  if (auto* renderView = vtkPVRenderView::SafeDownCast(view))
  {
    renderView->GetRenderer()->AddActor(this->Actor);
    return this->Superclass::AddToView(view);
  }
  return false;
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatRepresentation::RemoveFromView(vtkView* view)
{
  if (auto* renderView = vtkPVRenderView::SafeDownCast(view))
  {
    renderView->GetRenderer()->RemoveActor(this->Actor);
    return this->Superclass::RemoveFromView(view);
  }
  return false;
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRepresentation::SetShade(bool shade)
{
  this->Property->SetShade(shade);
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRepresentation::SetAmbient(double value)
{
  this->Property->SetAmbient(value);
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRepresentation::SetDiffuse(double value)
{
  this->Property->SetDiffuse(value);
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRepresentation::SetSpecular(double value)
{
  this->Property->SetSpecular(value);
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRepresentation::SetSpecularPower(double value)
{
  this->Property->SetSpecularPower(value);
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "IsImage: " << this->IsImage << "\n";
  os << indent << "OwnedBounds: " << this->OwnedBounds[0] << " " << this->OwnedBounds[1] << " "
     << this->OwnedBounds[2] << " " << this->OwnedBounds[3] << " " << this->OwnedBounds[4] << " "
     << this->OwnedBounds[5] << "\n";
  os << indent << "SplatMapper: " << this->Mapper << "\n";
}
