// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSurfelSphereSource
 * @brief   surfels spread uniformly over a sphere
 *
 * vtkSurfelSphereSource produces NumberOfPoints points on a sphere of the given Radius and
 * Center, placed on a Fibonacci lattice (nearly uniform, no poles), as vertices with outward
 * point normals and a "Radius" point-data array equal to the sampling spacing
 * sqrt(4 pi Radius^2 / NumberOfPoints), at which vtkSurfaceSplatMapper's kernels cover the sphere
 * as a partition of unity. It is the splatting counterpart of vtkSphereSource for tests and
 * benchmarks: any number of points, no mesh.
 */
#ifndef vtkSurfelSphereSource_h
#define vtkSurfelSphereSource_h

#include "SplatFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class SPLATFILTERS_EXPORT vtkSurfelSphereSource : public vtkPolyDataAlgorithm
{
public:
  static vtkSurfelSphereSource* New();
  vtkTypeMacro(vtkSurfelSphereSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of points. Default 10000.
   */
  vtkSetClampMacro(NumberOfPoints, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(NumberOfPoints, vtkIdType);
  ///@}

  ///@{
  /**
   * The sphere's radius (default 0.5, as vtkSphereSource) and center (default the origin).
   */
  vtkSetClampMacro(Radius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Radius, double);
  vtkSetVector3Macro(Center, double);
  vtkGetVector3Macro(Center, double);
  ///@}

protected:
  vtkSurfelSphereSource();
  ~vtkSurfelSphereSource() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkIdType NumberOfPoints = 10000;
  double Radius = 0.5;
  double Center[3] = { 0.0, 0.0, 0.0 };

private:
  vtkSurfelSphereSource(const vtkSurfelSphereSource&) = delete;
  void operator=(const vtkSurfelSphereSource&) = delete;
};

#endif
