// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSplatPointsFilter
 * @brief   the points of any dataset or composite dataset as one vtkPolyData of vertices
 *
 * vtkSplatPointsFilter prepares the data of the splat representations. Its output is one
 * vtkPolyData holding the points of every leaf of its input (any vtkDataSet, or a composite
 * dataset of them) with their point data (the arrays all leaves share), and one vertex cell per
 * point. The splat mappers draw points, not cells; the vertex cells are there so that ParaView's
 * ordered compositing, which moves cells between ranks, moves every point.
 *
 * With GenerateSurfels on (the Surface Splats representation), each leaf that lacks normals (or
 * the two tangent-axis arrays of elliptical surfels) or a radius array first goes through
 * vtkSurfelGenerator, before the leaves are merged so that meshes still have their polygons:
 * normals of the data when present, else polygon or PCA normals; radii from the neighbor
 * spacing times RadiusScale. With EstimateRadii off, leaves without a radius array get no
 * radius array, and vtkSurfaceSplatMapper gives their splats its constant Radius.
 *
 * @sa vtkSurfelGenerator vtkSurfaceSplatRepresentation vtkVolumeSplatRepresentation
 */
#ifndef vtkSplatPointsFilter_h
#define vtkSplatPointsFilter_h

#include "SplatRepresentationsModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // For vtkSmartPointer

class vtkDataSet;
class vtkPolyData;

class SPLATREPRESENTATIONS_EXPORT vtkSplatPointsFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkSplatPointsFilter* New();
  vtkTypeMacro(vtkSplatPointsFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Complete each leaf's surfels (normals, radii) with vtkSurfelGenerator. Default off.
   */
  vtkSetMacro(GenerateSurfels, bool);
  vtkGetMacro(GenerateSurfels, bool);
  vtkBooleanMacro(GenerateSurfels, bool);
  ///@}

  ///@{
  /**
   * Estimate the radii of leaves without a radius array (GenerateSurfels only). Default on.
   */
  vtkSetMacro(EstimateRadii, bool);
  vtkGetMacro(EstimateRadii, bool);
  vtkBooleanMacro(EstimateRadii, bool);
  ///@}

  ///@{
  /**
   * vtkSurfelGenerator's settings: the factor on the neighbor spacing (default 1) and the
   * number of neighbors (default 6).
   */
  vtkSetClampMacro(RadiusScale, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RadiusScale, double);
  vtkSetClampMacro(NumberOfNeighbors, int, 1, 256);
  vtkGetMacro(NumberOfNeighbors, int);
  ///@}

  ///@{
  /**
   * The surfel arrays looked for, and the name of the radii written: vtkSurfaceSplatMapper's
   * names (defaults "Radius", "TangentAxis0", "TangentAxis1").
   */
  vtkSetStringMacro(RadiusArrayName);
  vtkGetStringMacro(RadiusArrayName);
  vtkSetStringMacro(TangentAxis0ArrayName);
  vtkGetStringMacro(TangentAxis0ArrayName);
  vtkSetStringMacro(TangentAxis1ArrayName);
  vtkGetStringMacro(TangentAxis1ArrayName);
  ///@}

protected:
  vtkSplatPointsFilter();
  ~vtkSplatPointsFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * The leaf with normals and radii: itself when it has them, else vtkSurfelGenerator's output.
   */
  vtkSmartPointer<vtkDataSet> CompleteSurfels(vtkDataSet* leaf);

  bool GenerateSurfels = false;
  bool EstimateRadii = true;
  double RadiusScale = 1.0;
  int NumberOfNeighbors = 6;
  char* RadiusArrayName = nullptr;
  char* TangentAxis0ArrayName = nullptr;
  char* TangentAxis1ArrayName = nullptr;

private:
  vtkSplatPointsFilter(const vtkSplatPointsFilter&) = delete;
  void operator=(const vtkSplatPointsFilter&) = delete;
};

#endif
