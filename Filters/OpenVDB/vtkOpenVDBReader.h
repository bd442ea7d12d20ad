// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkOpenVDBReader
 * @brief   reads a grid of an OpenVDB (.vdb) file as splat kernels, surfels or points
 *
 * vtkOpenVDBReader lists the grids of a .vdb file and turns the selected one (GridName; by
 * default the first grid of a supported type) into the input of a splat mapper. The grid
 * listing (RequestInformation) reads metadata only: name, class, value type, active voxel count
 * and index-to-world transform (GetNumberOfGrids, GetGridName, ...). RequestData reads the file
 * (all its grids: OpenVDB's stream reader, which stops with an error at the first truncated or
 * unreadable byte, so that a damaged file never yields a half-built output) and builds, on
 * output port 0, a vtkPolyData:
 *
 * - scalar grids (float, double, int32, int64; half-float files are read as float) that are not
 *   level sets, e.g. fog volumes: one Gaussian kernel per active voxel for vtkVolumeSplatMapper,
 *   at the voxel center in world coordinates, with a 6-component "Covariance" array
 *   A diag(sigma^2) A^T (A the grid's index-to-world linear map, sigma splat::VoxelKernelSigma,
 *   0.6 voxel: splat::VoxelCovariance, the kernel of an image-data voxel), a "SampleVolume" array
 *   |det A| (the mapper then reconstructs the field as it does for image data) and the voxel
 *   value as point scalars named after the grid. An active tile becomes TileSubdivision^3
 *   kernels, the cells of a coarse grid of spacing b = tile width / TileSubdivision voxels,
 *   each with sigma 0.6 b and sample volume b^3 |det A|, which keeps adjacent tiles a partition
 *   of unity and the cost bounded per tile. The default, 8, makes the tiles of a leaf node's
 *   size (8^3 voxels, the usual tiles of fog) their voxels. Non-linear (frustum) transforms use
 *   the local linear map at each voxel.
 *   When every kernel is one voxel (no tile wider than TileSubdivision) under a linear
 *   transform, the kernels sit on the grid's lattice and say so: a 3-component int array
 *   "VoxelIndex" (each voxel's index coordinates) and a 16-component field-data array
 *   "IndexToWorld" (the matrix of GetGridIndexToWorld). vtkVolumeSplatMapper then draws them
 *   as it draws image data, sheet by sheet, without the grid's dense memory.
 *   When no value is negative (a fog's densities), a 3-component field-data array
 *   "DensityStatistics" holds the mean and the largest of the positive values and the volume
 *   of their kernels: what a first view's opacity needs (SplatFogOpacity.h; splat_render and
 *   ParaView's Volume Splats use it).
 * - level sets (class GRID_LEVEL_SET): surfels for vtkSurfaceSplatMapper. Every active voxel
 *   whose sign differs from one of its six neighbors (math::GradStencil::zeroCrossing) gives a
 *   point projected onto the zero crossing by a Newton step x - phi grad(phi) / |grad(phi)|^2,
 *   "Normals" from the gradient (second-order central differences, mapped to world by the
 *   transform) and a "Radius" array of SurfelRadiusScale times the longest voxel edge: each
 *   column of voxels across the surface holds at least two such points, so the default scale 1
 *   covers the surface without holes.
 * - vector grids (Vec3f, Vec3d): kernels as for scalar grids, the magnitude as point scalars
 *   ("<grid>_magnitude") and the vectors as a 3-component array named after the grid (the
 *   point data's vectors).
 * - point data grids (OpenVDB points): the world positions of every point and its float, double,
 *   int32, int64, Vec3f and Vec3d attributes as point-data arrays of the same names, with one
 *   vertex cell per point; other attribute types are left out with a warning.
 *
 * Voxels with a non-finite value and surfels with a non-finite or zero gradient are skipped and
 * counted (GetNumberOfSkippedValues). Surfels and volume kernels also get one vertex cell per
 * point (32-bit ids): vtkVolumeSplatMapper draws kernels from the points, but ParaView's default
 * representation shows cells, and its volume opacity unit distance follows their number.
 *
 * With ProduceDenseOutput on, output port 1 is a vtkImageData of the grid's values (vector grids:
 * the vectors and their magnitude as scalars) over DenseIndexBounds (index space, inclusive; by
 * default the active voxel bounding box), with the spacing, origin and direction matrix of the
 * grid's linear transform, for VTK's ray-cast volume mappers; inactive voxels hold the
 * background value. Images beyond MaximumDenseVoxels voxels are refused.
 *
 * Errors (a missing or unreadable file, a file that is not a VDB, truncated or corrupt data, a
 * missing grid name, an empty or unsupported grid, a dense request with a non-linear transform
 * or too large) are reported with vtkErrorMacro naming the file and the grid, and leave both
 * outputs empty. Progress events are sent over the leaf nodes.
 */
#ifndef vtkOpenVDBReader_h
#define vtkOpenVDBReader_h

#include "SplatOpenVDBModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // For std::unique_ptr

class vtkImageData;
class vtkStringArray;

class SPLATOPENVDB_EXPORT vtkOpenVDBReader : public vtkPolyDataAlgorithm
{
public:
  static vtkOpenVDBReader* New();
  vtkTypeMacro(vtkOpenVDBReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The .vdb file to read.
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Name of the grid to read. Empty or null (the default): the first grid of a supported type.
   */
  vtkSetStringMacro(GridName);
  vtkGetStringMacro(GridName);
  ///@}

  ///@{
  /**
   * Kernels per edge of an active tile (the tile becomes TileSubdivision^3 kernels). Default 8,
   * a leaf node's width: leaf-sized tiles become their voxels and the kernels stay a lattice.
   */
  vtkSetClampMacro(TileSubdivision, int, 1, 16);
  vtkGetMacro(TileSubdivision, int);
  ///@}

  ///@{
  /**
   * Surfel radius of level sets in units of the longest voxel edge. Default 1.
   */
  vtkSetClampMacro(SurfelRadiusScale, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SurfelRadiusScale, double);
  ///@}

  ///@{
  /**
   * Whether output port 1 gets the dense vtkImageData of the grid. Default off.
   */
  vtkSetMacro(ProduceDenseOutput, bool);
  vtkGetMacro(ProduceDenseOutput, bool);
  vtkBooleanMacro(ProduceDenseOutput, bool);
  ///@}

  ///@{
  /**
   * Index-space box (imin, imax, jmin, jmax, kmin, kmax, inclusive) of the dense output. An empty
   * box (the default, min > max) selects the grid's active voxel bounding box.
   */
  vtkSetVector6Macro(DenseIndexBounds, int);
  vtkGetVector6Macro(DenseIndexBounds, int);
  ///@}

  ///@{
  /**
   * Largest dense output, in voxels. Default 2^27 (512^3 voxels, 512 MiB of floats).
   */
  vtkSetClampMacro(MaximumDenseVoxels, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumDenseVoxels, vtkIdType);
  ///@}

  /**
   * The dense image (output port 1).
   */
  vtkImageData* GetDenseOutput();

  ///@{
  /**
   * The grids of the file, from its metadata (valid after UpdateInformation). GetGridClass is
   * OpenVDB's class name ("level set", "fog volume", "staggered", "unknown"), GetGridValueType
   * its value type ("float", "vec3s", "ptdataidx32", ...), GetGridTransformType its map type
   * ("UniformScaleTranslateMap", "AffineMap", "NonlinearFrustumMap", ...).
   * GetGridActiveVoxelCount is the count the file records (-1 when it records none).
   * GetGridIndexToWorld gives the 4x4 matrix (row-major, column vectors: world = M (i, j, k, 1))
   * of a linear transform and returns false for a non-linear one. Out-of-range indices give
   * null, -1 or false.
   */
  int GetNumberOfGrids();
  const char* GetGridName(int index);
  const char* GetGridClass(int index);
  const char* GetGridValueType(int index);
  const char* GetGridTransformType(int index);
  vtkIdType GetGridActiveVoxelCount(int index);
  bool GetGridIndexToWorld(int index, double matrix[16]);
  ///@}

  /**
   * The names of the grids of a supported type, in the order of GetGridName (valid after
   * UpdateInformation): the values GridName can take, the first being the default. ParaView's
   * grid drop-down lists them.
   */
  vtkStringArray* GetSupportedGridNames();

  ///@{
  /**
   * What the last RequestData built: kernels of leaf voxels, kernels of active tiles (and the
   * tiles), and the values skipped (non-finite values, degenerate level-set gradients).
   */
  vtkGetMacro(NumberOfVoxelKernels, vtkIdType);
  vtkGetMacro(NumberOfTileKernels, vtkIdType);
  vtkGetMacro(NumberOfTiles, vtkIdType);
  vtkGetMacro(NumberOfSkippedValues, vtkIdType);
  ///@}

protected:
  vtkOpenVDBReader();
  ~vtkOpenVDBReader() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  char* GridName = nullptr;
  int TileSubdivision = 8;
  double SurfelRadiusScale = 1.0;
  bool ProduceDenseOutput = false;
  int DenseIndexBounds[6] = { 0, -1, 0, -1, 0, -1 };
  vtkIdType MaximumDenseVoxels = vtkIdType(1) << 27;
  vtkIdType NumberOfVoxelKernels = 0;
  vtkIdType NumberOfTileKernels = 0;
  vtkIdType NumberOfTiles = 0;
  vtkIdType NumberOfSkippedValues = 0;

private:
  vtkOpenVDBReader(const vtkOpenVDBReader&) = delete;
  void operator=(const vtkOpenVDBReader&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
  friend struct vtkOpenVDBReaderBuilder; // builds the outputs of one grid
};

#endif
