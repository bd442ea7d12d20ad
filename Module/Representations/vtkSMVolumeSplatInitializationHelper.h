// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSMVolumeSplatInitializationHelper
 * @brief   Shows Gaussian kernel sets as Volume Splats, and fog as fog, on first Show
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
 * A fog (vtkOpenVDBReader's "DensityStatistics" field data: densities, none negative) then
 * gets the first view splat_render gives it (SplatFogOpacity.h): its opacity unit distance,
 * and, when its densities have no color map yet, a white one from 0 to the largest density
 * that is never rescaled (extinction linear in the density from zero), with the opacity
 * function that makes a typical cloud translucent but visible. ParaView's default, Cool to
 * Warm over the value range, would threshold the thin fringe away and tint smoke blue and red.
 * A color map the user already has for the array is left alone.
 *
 * @sa vtkVolumeSplatMapper vtkOpenVDBReader vtkVolumeSplatRepresentation
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
