// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSMVolumeSplatInitializationHelper
 * @brief   Shows Gaussian kernel sets as Volume Splats on first Show
 *
 * ParaView picks a dataset's first representation from its type and the producer's hints,
 * never from its arrays, so a point set of Gaussian kernels (an OpenVDB fog read by
 * vtkOpenVDBReader: a vertex cell and a 6-component "Covariance" per voxel) would first show as
 * Surface: its points, not its volume. The plugin names this class as GeometryRepresentation's
 * initialization helper (SplatRepresentations.xml), and when the representation's input has
 * the point arrays vtkVolumeSplatMapper draws kernels from by default (a 6-component
 * "Covariance", or a 3-component "Scale" with a 4-component "Rotation"), it sets the
 * representation to "Volume Splats", unless the caller already chose one. Level sets, point
 * grids, meshes and point clouds keep ParaView's choice.
 *
 * @sa vtkVolumeSplatMapper vtkOpenVDBReader
 */
#ifndef vtkSMVolumeSplatInitializationHelper_h
#define vtkSMVolumeSplatInitializationHelper_h

#include "SplatRepresentationsModule.h" // For export macro
#include "vtkSMProxyInitializationHelper.h"

class SPLATREPRESENTATIONS_EXPORT vtkSMVolumeSplatInitializationHelper
  : public vtkSMProxyInitializationHelper
{
public:
  static vtkSMVolumeSplatInitializationHelper* New();
  vtkTypeMacro(vtkSMVolumeSplatInitializationHelper, vtkSMProxyInitializationHelper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void PostInitializeProxy(
    vtkSMProxy* proxy, vtkPVXMLElement* xml, vtkMTimeType initializationTimeStamp) override;

protected:
  vtkSMVolumeSplatInitializationHelper() = default;
  ~vtkSMVolumeSplatInitializationHelper() override = default;

private:
  vtkSMVolumeSplatInitializationHelper(const vtkSMVolumeSplatInitializationHelper&) = delete;
  void operator=(const vtkSMVolumeSplatInitializationHelper&) = delete;
};

#endif
