// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSurfelGenerator
 * @brief   turns a point cloud or a mesh's vertices into surfels: points with normals and radii
 *
 * vtkSurfelGenerator prepares any vtkPointSet for vtkSurfaceSplatMapper. Its output is a
 * vtkPolyData with one vertex per input point, the input's point data, point normals and a
 * per-point radius array (RadiusArrayName, default "Radius"). A polygonal mesh's vertices that
 * no polygon uses are not samples of its surface and are left out.
 *
 * Normals: the input's point normals when it has them; otherwise, for a polygonal mesh, the
 * averaged polygon normals (vtkPolyDataNormals); otherwise, for a point cloud, a PCA fit over the
 * nearest neighbors, consistently oriented by graph traversal (vtkPCANormalEstimation).
 *
 * Radius: for a polygonal mesh, RadiusScale times the longest edge at each vertex, so that the
 * splats cover every polygon however anisotropic the sampling; for a point cloud, RadiusScale
 * times the mean distance to the NumberOfNeighbors nearest points (vtkStaticPointLocator). On a
 * regular grid of spacing h with 4 neighbors this is h, the radius at which
 * vtkSurfaceSplatMapper's kernels form a partition of unity.
 *
 * Points with non-finite coordinates are kept but get a radius of 0 so that the mapper skips them.
 */
#ifndef vtkSurfelGenerator_h
#define vtkSurfelGenerator_h

#include "SplatFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <vector> // For std::vector

class vtkFloatArray;
class vtkPoints;

class SPLATFILTERS_EXPORT vtkSurfelGenerator : public vtkPolyDataAlgorithm
{
public:
  static vtkSurfelGenerator* New();
  vtkTypeMacro(vtkSurfelGenerator, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of nearest neighbors whose mean distance sets each point cloud radius (and over
   * which point cloud normals are fitted, at least 8 of them). Default 6.
   */
  vtkSetClampMacro(NumberOfNeighbors, int, 1, 256);
  vtkGetMacro(NumberOfNeighbors, int);
  ///@}

  ///@{
  /**
   * Factor applied to the neighbor spacing to make the radius. Default 1.
   */
  vtkSetClampMacro(RadiusScale, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RadiusScale, double);
  ///@}

  ///@{
  /**
   * Name of the radius array written to the output. Default "Radius".
   */
  vtkSetStringMacro(RadiusArrayName);
  vtkGetStringMacro(RadiusArrayName);
  ///@}

protected:
  vtkSurfelGenerator();
  ~vtkSurfelGenerator() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  void MeshRadii(vtkPolyData* mesh, vtkFloatArray* radius);
  void NeighborRadii(vtkPoints* points, const std::vector<vtkIdType>& ids, vtkFloatArray* radius);

  int NumberOfNeighbors = 6;
  double RadiusScale = 1.0;
  char* RadiusArrayName = nullptr;

private:
  vtkSurfelGenerator(const vtkSurfelGenerator&) = delete;
  void operator=(const vtkSurfelGenerator&) = delete;
};

#endif
