// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkVolumeSplatRepresentation
 * @brief   ParaView's "Volume Splats": image data and Gaussian kernels drawn by
 *          vtkVolumeSplatMapper
 *
 * vtkVolumeSplatRepresentation is a volume representation (like vtkImageVolumeRepresentation)
 * whose mapper is vtkVolumeSplatMapper. It draws
 * - a vtkImageData: one kernel per voxel, the scalars of ColorArrayName through the color
 *   (LookupTable) and opacity (ScalarOpacityFunction) transfer functions;
 * - any other dataset, composite datasets included: its points, merged by vtkSplatPointsFilter,
 *   as 3D Gaussian kernels (covariance, or scale and rotation arrays: 3D Gaussian Splatting
 *   captures, OpenVDB fog kernels) with direct colors and opacities or the transfer functions.
 * The volume property's shading settings (Shade, Ambient, Diffuse, Specular, SpecularPower)
 * are forwarded; the mapper is set by the server-manager (SetSplatMapper), which exposes its
 * settings.
 *
 * In parallel, the ranks' images blend in visibility order (ordered compositing). Image data
 * stays where it is: pieces of a structured extent share their boundary plane of points, so
 * each rank draws the voxels of its extent up to, not including, a shared upper plane, and
 * gives the view the bounds of the voxels it owns (half a voxel around them) to order the
 * ranks. Point sets are redistributed by the view into a k-d tree of regions. Either way a
 * kernel reaching past its rank's region is blended with its rank's image, not in depth order
 * with the neighbor's kernels: within about two standard deviations of the region boundaries
 * the order is approximate (docs/paraview.md gives the measured difference from one rank).
 *
 * @sa vtkVolumeSplatMapper vtkSplatPointsFilter vtkSurfaceSplatRepresentation
 */
#ifndef vtkVolumeSplatRepresentation_h
#define vtkVolumeSplatRepresentation_h

#include "SplatRepresentationsModule.h" // For export macro
#include "vtkNew.h"                     // For vtkNew
#include "vtkSmartPointer.h"            // For vtkSmartPointer
#include "vtkVolumeRepresentation.h"

class vtkImageData;
class vtkPolyDataMapper;
class vtkSplatPointsFilter;
class vtkVolumeSplatMapper;

class SPLATREPRESENTATIONS_EXPORT vtkVolumeSplatRepresentation : public vtkVolumeRepresentation
{
public:
  static vtkVolumeSplatRepresentation* New();
  vtkTypeMacro(vtkVolumeSplatRepresentation, vtkVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(vtkInformationRequestKey* request_type, vtkInformation* inInfo,
    vtkInformation* outInfo) override;

  ///@{
  /**
   * The mapper that draws the kernels. The representation makes one; the server-manager sets
   * the one its proxy configures.
   */
  void SetSplatMapper(vtkVolumeSplatMapper* mapper);
  vtkVolumeSplatMapper* GetSplatMapper();
  ///@}

  ///@{
  /**
   * Forwarded to the vtkVolumeProperty.
   */
  void SetShade(bool shade);
  void SetAmbient(double value);
  void SetDiffuse(double value);
  void SetSpecular(double value);
  void SetSpecularPower(double value);
  ///@}

protected:
  vtkVolumeSplatRepresentation();
  ~vtkVolumeSplatRepresentation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;

  /**
   * The voxels of this rank's piece that no other piece has: the extent without the upper
   * planes it shares with the next pieces (those below the whole extent's upper bounds).
   */
  static vtkSmartPointer<vtkImageData> OwnedVoxels(vtkImageData* piece, const int wholeExtent[6]);

  /**
   * The scalar array and its association, and the actor's mapper, before each render.
   */
  void UpdateMapperParameters();

  vtkSmartPointer<vtkVolumeSplatMapper> Mapper;
  vtkNew<vtkPolyDataMapper> OutlineMapper;
  vtkNew<vtkSplatPointsFilter> PointsFilter;
  // What this process draws: its image voxels or its merged points.
  vtkSmartPointer<vtkDataObject> Cache;
  bool IsImage = false;
  // With image data: the bounds of the voxels this rank owns, half a voxel around them.
  double OwnedBounds[6];

private:
  vtkVolumeSplatRepresentation(const vtkVolumeSplatRepresentation&) = delete;
  void operator=(const vtkVolumeSplatRepresentation&) = delete;
};

#endif
