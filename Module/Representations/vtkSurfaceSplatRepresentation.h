// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSurfaceSplatRepresentation
 * @brief   ParaView's "Surface Splats": any dataset's points drawn by vtkSurfaceSplatMapper
 *
 * vtkSurfaceSplatRepresentation is ParaView's Surface representation
 * (vtkGeometryRepresentationWithFaces) with vtkSurfaceSplatMapper in place of the polygon
 * mapper. The surface that vtkPVGeometryFilter extracts (a mesh, a point cloud's vertices, a
 * volume's outer faces) goes through vtkSplatPointsFilter, in place of the superclass's
 * multiblock maker: normals and radii of the data when it has them, else estimated by
 * vtkSurfelGenerator, and the blocks of a composite dataset merged into one set of surfels,
 * which the mapper draws as one scene. Coloring (ColorArrayName, LookupTable, MapScalars), the
 * vtkProperty (colors, opacity, lighting, backface culling) and the actor's transform work as
 * for Surface. There is no level of detail: interactive renders draw the splats too.
 *
 * The mapper is set by the server-manager (SetSplatMapper), which exposes its settings; it can
 * be any vtkSurfaceSplatMapper. The surfel array names are set here (they decide which arrays
 * the data has and which must be estimated) and passed to the mapper.
 *
 * In parallel, each rank draws its piece and IceT composites the opaque splats by depth; an
 * opacity below 1, a translucent lookup table or an opacity array ask ParaView for ordered
 * compositing, which redistributes the surfels in a k-d tree so that the ranks' images blend
 * in visibility order.
 *
 * @sa vtkSurfaceSplatMapper vtkSplatPointsFilter vtkVolumeSplatRepresentation
 */
#ifndef vtkSurfaceSplatRepresentation_h
#define vtkSurfaceSplatRepresentation_h

#include "SplatRepresentationsModule.h" // For export macro
#include "vtkGeometryRepresentationWithFaces.h"
#include "vtkNew.h" // For vtkNew

class vtkSplatPointsFilter;
class vtkSurfaceSplatMapper;

class SPLATREPRESENTATIONS_EXPORT vtkSurfaceSplatRepresentation
  : public vtkGeometryRepresentationWithFaces
{
public:
  static vtkSurfaceSplatRepresentation* New();
  vtkTypeMacro(vtkSurfaceSplatRepresentation, vtkGeometryRepresentationWithFaces);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The mapper that draws the splats. The representation makes one; the server-manager sets
   * the one its proxy configures. The lookup table and color settings carry over.
   */
  void SetSplatMapper(vtkSurfaceSplatMapper* mapper);
  vtkSurfaceSplatMapper* GetSplatMapper();
  ///@}

  /**
   * Splats have no level of detail: always suppressed.
   */
  void SetSuppressLOD(bool) override { this->SuppressLOD = true; }

  ///@{
  /**
   * The surfel arrays, for the mapper and for deciding what to estimate: radii (default
   * "Radius") and the tangent axes of elliptical surfels (default "TangentAxis0",
   * "TangentAxis1").
   */
  void SetRadiusArrayName(const char* name);
  void SetTangentAxis0ArrayName(const char* name);
  void SetTangentAxis1ArrayName(const char* name);
  ///@}

  ///@{
  /**
   * Radius estimation for data without a radius array (vtkSurfelGenerator): on or off (then
   * the mapper's constant Radius), the factor on the neighbor spacing, the number of neighbors.
   */
  void SetEstimateRadii(bool estimate);
  void SetRadiusScale(double scale);
  void SetNumberOfNeighbors(int neighbors);
  ///@}

protected:
  vtkSurfaceSplatRepresentation();
  ~vtkSurfaceSplatRepresentation() override;

  /**
   * Translucent splats (an opacity array) need ordered compositing too.
   */
  bool NeedsOrderedCompositing() override;

  // In place of the superclass's multiblock maker: the mapper takes one vtkPolyData.
  vtkNew<vtkSplatPointsFilter> SurfelFilter;

private:
  vtkSurfaceSplatRepresentation(const vtkSurfaceSplatRepresentation&) = delete;
  void operator=(const vtkSurfaceSplatRepresentation&) = delete;
};

#endif
