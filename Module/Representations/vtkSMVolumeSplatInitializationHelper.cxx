// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSMVolumeSplatInitializationHelper.h"

#include "SplatFogOpacity.h"

#include "vtkDataSetAttributes.h"
#include "vtkObjectFactory.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkSMCoreUtilities.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMTransferFunctionManager.h"

#include <string>
#include <vector>

vtkStandardNewMacro(vtkSMVolumeSplatInitializationHelper);

namespace
{
// Whether `attributes` hold an array `name` of `components` components.
bool HasArray(vtkPVDataSetAttributesInformation* attributes, const char* name, int components)
{
  vtkPVArrayInformation* array = attributes ? attributes->GetArrayInformation(name) : nullptr;
  return array && array->GetNumberOfComponents() == components;
}

// A fog's first view (the reader's "DensityStatistics"): the opacity unit distance of
// SplatFogOpacity.h unless set, and, when its densities have no color map yet, a white one
// over 0 to the largest density, never rescaled, with that file's opacity function.
void SetUpFog(vtkSMProxy* representation, vtkPVDataInformation* data, vtkMTimeType timeStamp)
{
  vtkPVArrayInformation* statistics =
    data->GetFieldDataInformation()->GetArrayInformation("DensityStatistics");
  vtkPVArrayInformation* densities =
    data->GetPointDataInformation()->GetAttributeInformation(vtkDataSetAttributes::SCALARS);
  if (!statistics || statistics->GetNumberOfComponents() != 3 || !densities ||
    !densities->GetName())
  {
    return;
  }
  const splat::FogStatistics fog{ statistics->GetComponentRange(0)[0],
    statistics->GetComponentRange(1)[0], statistics->GetComponentRange(2)[0] };
  splat::FogOpacity opacity;
  if (!splat::MakeFogOpacity(fog, opacity))
  {
    return;
  }
  vtkSMProperty* unitDistance = representation->GetProperty("ScalarOpacityUnitDistance");
  if (unitDistance && unitDistance->GetMTime() <= timeStamp)
  {
    vtkSMPropertyHelper(unitDistance).Set(opacity.UnitDistance);
  }
  vtkSMSessionProxyManager* pxm = representation->GetSessionProxyManager();
  const std::string name = vtkSMCoreUtilities::SanitizeName(densities->GetName());
  if (pxm->GetProxy("lookup_tables", (name + ".PVLookupTable").c_str()))
  {
    return; // the densities' color map is the user's (or an earlier file's)
  }
  vtkNew<vtkSMTransferFunctionManager> manager;
  vtkSMProxy* colors = manager->GetColorTransferFunction(densities->GetName(), pxm);
  vtkSMProxy* opacities = manager->GetOpacityTransferFunction(densities->GetName(), pxm);
  if (!colors || !opacities)
  {
    return;
  }
  const double white[8] = { 0.0, 1.0, 1.0, 1.0, fog.Largest, 1.0, 1.0, 1.0 };
  vtkSMPropertyHelper(colors, "RGBPoints").Set(white, 8);
  vtkSMPropertyHelper(colors, "AutomaticRescaleRangeMode")
    .Set(vtkSMTransferFunctionManager::NEVER);
  std::vector<double> points; // x, alpha, midpoint, sharpness
  for (int i = 0; i < splat::FogOpacity::Samples; ++i)
  {
    points.insert(points.end(), { opacity.Density[i], opacity.Alpha[i], 0.5, 0.0 });
  }
  vtkSMPropertyHelper(opacities, "Points")
    .Set(points.data(), static_cast<unsigned int>(points.size()));
  colors->UpdateVTKObjects();
  opacities->UpdateVTKObjects();
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
  vtkPVDataInformation* data = source->GetDataInformation(inputHelper.GetOutputPort());
  vtkPVDataSetAttributesInformation* points = data->GetPointDataInformation();
  if (HasArray(points, "Covariance", 6) ||
    (HasArray(points, "Scale", 3) && HasArray(points, "Rotation", 4)))
  {
    vtkSMPropertyHelper(representation).Set("Volume Splats");
    SetUpFog(proxy, data, initializationTimeStamp);
  }
}

//------------------------------------------------------------------------------
void vtkSMVolumeSplatInitializationHelper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
