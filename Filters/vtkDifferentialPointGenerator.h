// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkDifferentialPointGenerator
 * @brief   turns a mesh's vertices or a point cloud into differential points
 *
 * vtkDifferentialPointGenerator builds the differential points of Kalaiah and Varshney,
 * *Modeling and Rendering of Points with Local Geometry* (IEEE TVCG 9(1), 2003): per point the
 * normal, the principal directions and curvatures, and a rectangle on the tangent plane over
 * which that second-order description stands for the surface. A vtkPolyData with polygons is a
 * mesh; any other vtkPointSet is a point cloud.
 *
 * Curvature: a quadric z = a x^2 + b xy + c y^2 + d x + e y is fitted by least squares (Eigen)
 * in a tangent frame at each point, over the mesh vertex's 2-ring or the point cloud's
 * NumberOfNeighbors nearest points (vtkStaticPointLocator); the shape operator of the fitted
 * graph at the point (fundamental forms I and II, a 2x2 generalized eigenproblem) gives the
 * curvatures and directions, and its normal the output normal. This replaces Taubin's tensor
 * (the paper's choice), whose estimates depend on the mesh's valence and edge lengths and stay
 * biased on irregular meshes however fine; the fit's error shrinks with the spacing on any
 * sampling, needs no connectivity (point clouds use the same code) and its normal's linear
 * terms absorb a frame normal that is slightly off (measured: 0.1 to 3% curvature error on the
 * test's spheres, cylinders and saddles, TestDifferentialPointGenerator). The
 * frame's normal comes from the input's normals when it has them, else from the mesh
 * (vtkPolyDataNormals, consistently oriented) or from PCA (vtkPCANormalEstimation, oriented by
 * graph traversal). Neighborhoods too small or too degenerate for the full fit fall back to the
 * three curvature terms alone, then to a flat point.
 *
 * Extents (paper, section IV-A): half-widths u_eps = min(delta, sqrt(2 eps - eps^2)/|lambda_u|)
 * and the same along v, with eps the MaximumPrincipalError and delta the
 * MaximumPrincipalWidth; flat and zero-curvature points get delta. Section IV-B: each rectangle
 * is enlarged to contain the midpoints of the edges to its neighbors (projected along the edge's
 * averaged polygon normals onto the tangent plane), so that sparse samples in curved areas
 * leave no holes; a point cloud uses its 8 nearest neighbors as a mesh vertex its 1-ring.
 *
 * Simplification (SimplifyOn by default) keeps a subset of the points whose rectangles, scaled
 * down by SimplificationMargin, still cover the surface. GetNumberOfKeptPoints() says how many.
 * - SET_COVER (the default): the surface is sampled (a mesh's vertices and polygon centroids, a
 *   cloud's points and the midpoints to their ring neighbors, weighted by area); a point covers
 *   the samples its rectangle holds on its tangent plane, within a tolerance of its quadric along
 *   the normal and with a normal its eq. 10 prediction matches within twice the error bound; a
 *   greedy set cover (most uncovered area first) picks the points, then drops those left
 *   redundant. Every input point stays covered. It keeps 1.3x (an even cloud on a
 *   sphere) to 5x (the bunny) fewer points than the paper's (TestDifferentialPointGenerator).
 * - GREEDY_ENCLOSURE (section IV-C): points are pruned greedily, most redundant first (eq. 6: how
 *   well the curvature at a point predicts its neighbors' normals and the reverse), when the
 *   rectangles of their overlapping neighbors cover sampled line segments of their own rectangle
 *   (the paper's eight and the rectangle's border); the neighbors of a pruned point that overlap
 *   become neighbors.
 *
 * Output: one vertex per kept point, the input's point data of that point, and the arrays
 * - "Normals" (float, 3 components, the active normals): the fitted surface's normal;
 * - "PrincipalDirectionU" (float, 3): the direction of maximum |curvature|;
 * - "PrincipalDirectionV" (float, 3): the other, PrincipalDirectionU x PrincipalDirectionV =
 * Normals;
 * - "PrincipalCurvatures" (float, 2): lambda_u and lambda_v, |lambda_u| >= |lambda_v|, signed as
 *   in the paper (dN(u) = -lambda_u u): negative where the surface bends away from its normal,
 *   -1/R on a sphere of radius R with outward normals;
 * - "Extents" (float, 2): the rectangle's half-widths along PrincipalDirectionU and
 *   PrincipalDirectionV.
 * At umbilic and flat points PrincipalDirectionU is the projection of the x, y or z axis
 * (whichever is longest) onto the tangent plane, as in the paper; points whose curvatures differ
 * by less than 5% of the larger one (or of the curvature whose bound is delta) count as such,
 * because their fitted directions follow noise and would turn neighboring rectangles every
 * which way.
 *
 * Points with a NaN or infinite coordinate are left out and counted
 * (GetNumberOfSkippedPoints()); they take no part in any neighborhood. A mesh's vertices that no
 * polygon uses are not samples of its surface and are left out too. Every output value is finite.
 */
#ifndef vtkDifferentialPointGenerator_h
#define vtkDifferentialPointGenerator_h

#include "SplatFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class SPLATFILTERS_EXPORT vtkDifferentialPointGenerator : public vtkPolyDataAlgorithm
{
public:
  static vtkDifferentialPointGenerator* New();
  vtkTypeMacro(vtkDifferentialPointGenerator, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Maximum principal error eps of the paper, in [0, 1]: the largest deviation, scaled by the
   * curvature, of the point's osculating circles from its tangent plane along the principal
   * directions. Smaller values give smaller rectangles. Default 0.01.
   */
  vtkSetClampMacro(MaximumPrincipalError, double, 0.0, 1.0);
  vtkGetMacro(MaximumPrincipalError, double);
  ///@}

  ///@{
  /**
   * Maximum principal width delta of the paper: the largest half-width of a rectangle from the
   * curvature bound, in the input's units. 0 (the default) takes one twentieth of the diagonal
   * of the finite points' bounding box. Scans with open boundaries, thin parts or noise render
   * better with less: at one fiftieth no point of the Stanford bunny sticks out of its
   * silhouette.
   */
  vtkSetClampMacro(MaximumPrincipalWidth, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumPrincipalWidth, double);
  ///@}

  ///@{
  /**
   * Number of nearest neighbors over which a point cloud's quadric is fitted. Default 16.
   */
  vtkSetClampMacro(NumberOfNeighbors, int, 5, 256);
  vtkGetMacro(NumberOfNeighbors, int);
  ///@}

  ///@{
  /**
   * Whether redundant points are pruned (paper, section IV-C). Default on.
   */
  vtkSetMacro(Simplify, vtkTypeBool);
  vtkGetMacro(Simplify, vtkTypeBool);
  vtkBooleanMacro(Simplify, vtkTypeBool);
  ///@}

  /**
   * How points are pruned when Simplify is on.
   * - GREEDY_ENCLOSURE: the paper's greedy heap on the redundancy factor with the enclosure test.
   * - SET_COVER: a greedy set cover of area-weighted surface samples (see the class comment).
   */
  enum SimplificationModes
  {
    GREEDY_ENCLOSURE = 0,
    SET_COVER = 1
  };

  ///@{
  /**
   * The simplification, one of SimplificationModes. Default SET_COVER.
   */
  vtkSetClampMacro(SimplificationMode, int, GREEDY_ENCLOSURE, SET_COVER);
  vtkGetMacro(SimplificationMode, int);
  void SetSimplificationModeToGreedyEnclosure() { this->SetSimplificationMode(GREEDY_ENCLOSURE); }
  void SetSimplificationModeToSetCover() { this->SetSimplificationMode(SET_COVER); }
  const char* GetSimplificationModeAsString();
  ///@}

  ///@{
  /**
   * Fraction by which the rectangles are scaled down for the simplification's tests (the output
   * keeps their full size), so that neighboring kept rectangles overlap and leave no gap between
   * the tested line segments (GREEDY_ENCLOSURE) or samples (SET_COVER). Default 0.15, the
   * paper's.
   */
  vtkSetClampMacro(SimplificationMargin, double, 0.0, 0.9);
  vtkGetMacro(SimplificationMargin, double);
  ///@}

  /**
   * Number of points in the last output.
   */
  vtkGetMacro(NumberOfKeptPoints, vtkIdType);

  /**
   * Number of input points left out of the last output because a coordinate was NaN or
   * infinite.
   */
  vtkGetMacro(NumberOfSkippedPoints, vtkIdType);

protected:
  vtkDifferentialPointGenerator() = default;
  ~vtkDifferentialPointGenerator() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double MaximumPrincipalError = 0.01;
  double MaximumPrincipalWidth = 0.0;
  int NumberOfNeighbors = 16;
  vtkTypeBool Simplify = true;
  int SimplificationMode = SET_COVER;
  double SimplificationMargin = 0.15;
  vtkIdType NumberOfKeptPoints = 0;
  vtkIdType NumberOfSkippedPoints = 0;

private:
  vtkDifferentialPointGenerator(const vtkDifferentialPointGenerator&) = delete;
  void operator=(const vtkDifferentialPointGenerator&) = delete;
};

#endif
