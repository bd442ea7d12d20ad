// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSMVolumeSplatInitializationHelper.h"

#include "vtkObjectFactory.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSourceProxy.h"

vtkStandardNewMacro(vtkSMVolumeSplatInitializationHelper);

namespace
{
// Whether `attributes` hold an array `name` of `components` components.
bool HasArray(vtkPVDataSetAttributesInformation* attributes, const char* name, int components)
{
  vtkPVArrayInformation* array = attributes ? attributes->GetArrayInformation(name) : nullptr;
  return array && array->GetNumberOfComponents() == components;
}
}

//------------------------------------------------------------------------------
void vtkSMVolumeSplatInitializationHelper::PostInitializeProxy(
  vtkSMProxy* proxy, vtkPVXMLElement*, vtkMTimeType initializationTimeStamp)
{
  vtkSMProperty* representation = proxy->GetProperty("Representation");
  vtkSMProperty* input = proxy->GetProperty("Input");
  if (!representation || !input || representation->GetMTime() > initializationTimeStamp)
  {
    return;
  }
  vtkSMPropertyHelper inputHelper(input);
  auto* source = vtkSMSourceProxy::SafeDownCast(inputHelper.GetAsProxy());
  if (!source)
  {
    return;
  }
  vtkPVDataSetAttributesInformation* points =
    source->GetDataInformation(inputHelper.GetOutputPort())->GetPointDataInformation();
  if (HasArray(points, "Covariance", 6) ||
    (HasArray(points, "Scale", 3) && HasArray(points, "Rotation", 4)))
  {
    vtkSMPropertyHelper(representation).Set("Volume Splats");
  }
}

//------------------------------------------------------------------------------
void vtkSMVolumeSplatInitializationHelper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
