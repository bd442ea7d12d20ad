// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSurfelTextureAcquisition
 * @brief   samples an image or procedural texture onto surfels (Zwicker et al. 2001, section 5)
 *
 * vtkSurfelTextureAcquisition gives each surfel of its input the color coefficient w_k of the
 * continuous texture sum_k w_k r_k that vtkSurfaceSplatMapper reconstructs. Input port 0 takes
 * surfels as vtkSurfelGenerator makes them: points with normals and a radius array
 * (RadiusArrayName, default "Radius", else the global Radius), or two tangent-axis arrays
 * (TangentAxis0ArrayName, TangentAxis1ArrayName) for elliptical surfels, and texture coordinates
 * (the active TCoords, or the array named by TextureCoordinatesArrayName). The basis function
 * r_k is the mapper's: the Gaussian of variance R^2/2 in object space (SplatSurfelKernel.h),
 * truncated where |u|^2 >= Cutoff in axis units (the mapper's cutoff, default 1).
 *
 * The texture is a vtkImageData on input port 1 (SetTextureData or SetTextureConnection; 1 to 4
 * components, grey, grey + alpha, RGB, RGBA; unsigned char scaled by 1/255, other types taken as
 * they are in [0, 1]; texture coordinate (0, 0) is the lower-left corner of the first texel, as
 * in OpenGL), or a procedural texture: a vtkImplicitFunction evaluated at (s, t, 0), its value
 * mapped through ImplicitTextureColors (a vtkScalarsToColors; without one the value clamped to
 * [0, 1] is grey), or, from C++, a callback (SetTextureFunction). Image coordinates outside [0, 1]
 * repeat (RepeatOn, the default) or clamp to the edge; procedural textures are evaluated at the
 * coordinates as they are.
 *
 * Per surfel, the local affine map from its tangent plane (axis units) to texture coordinates is
 * the least-squares fit of the texture-coordinate differences to its NumberOfNeighbors nearest
 * surfels (vtkStaticPointLocator). Modes (SetMode):
 * - POINT_SAMPLING: the texture at the surfel's texture coordinates (bilinear for images), the
 *   baseline that aliases textures finer than the surfel spacing.
 * - VIEW_INDEPENDENT_EWA (the default): the texture filtered with the surfel's own basis Gaussian
 *   mapped into texture space, w_k = <r_k, f> / <r_k, 1>. For images the filter is EWA over the
 *   texels with the texel reconstruction Gaussian (variance 1/2 texel^2) added; procedural
 *   textures are sampled on ProceduralSamples x ProceduralSamples points over +-2.5 sigma of the
 *   Gaussian.
 * - OPTIMAL: the coefficients minimizing || sum_k w_k rhat_k - f ||_L2 (eq. 10 and 11: R w = b,
 *   R_kj = <rhat_k, rhat_j>, b_k = <rhat_k, f>), where rhat_k = r_k / sum_j r_j are the basis
 *   functions normalized to a partition of unity, as the mapper normalizes its kernels by their
 *   summed weights. (With the paper's unnormalized r_k a constant texture does not come back
 *   constant on irregular samples; with rhat_k it does, exactly.) The inner products are
 *   integrated with the partition of unity itself: integral g = sum_k integral (r_k / S) g, each
 *   term on a QuadratureResolution^2 grid of nodes over surfel k's support in its tangent plane,
 *   the texture at each node filtered with the node's cell. R is sparse, symmetric and positive
 *   semi-definite (the Gram matrix of the node quadrature); the system is solved with Eigen's
 *   conjugate gradients (Jacobi preconditioner) from the view-independent result.
 *
 * Ill-conditioned systems: coincident surfels would have identical rows; they share one unknown
 * instead (centers within 1e-6 of the radius; the basis of the shared unknown is the
 * representative's times their number), so they get equal colors. A surfel covered by its
 * neighbors' supports has a nearly dependent row, and the solution then oscillates without
 * bound. The filter solves instead the Tikhonov-regularized system
 * (R + lambda D) w = b + lambda D w_VI, D = diag(R), lambda = Regularization (default 1e-3): it
 * pulls each coefficient towards its view-independent value. After Jacobi scaling the matrix's
 * eigenvalues lie in [lambda, m + lambda] with m the most surfels overlapping one node, so its
 * condition number is at most (m + lambda) / lambda (about 1e4 for m = 10); an isolated surfel
 * gets its view-independent color. Coefficients are clamped to [0, 1]
 * (GetNumberOfClampedValues): the optimal fit overshoots at sharp edges, as any L2 fit does.
 * Cost: per surfel, QuadratureResolution^2 nodes times the surfels within about 2.4 radii, and the
 * squares of those counts for R; heavily oversampled regions (the poles of a UV sphere, where
 * hundreds of vertices lie within one radius) cost far more than uniform sampling (about 50 us
 * per surfel on a jittered plane, 2 threads) and condition the system worse (more CG
 * iterations).
 *
 * Output: the input surfels with an RGB or RGBA point-data array (OutputArrayName, default
 * "TextureColors", unsigned char or float by OutputScalarType), made the active scalars: draw
 * it with vtkSurfaceSplatMapper, ScalarVisibilityOn() and SetColorModeToDirectScalars().
 * Surfels with non-finite positions, zero or non-finite axes or texture coordinates get black and
 * are counted (GetNumberOfSkippedPoints); surfels whose affine map cannot be fitted (coincident or
 * collinear neighbors) are point sampled and counted (GetNumberOfDegenerateMaps).
 *
 * @sa vtkSurfelGenerator vtkSurfaceSplatMapper
 */
#ifndef vtkSurfelTextureAcquisition_h
#define vtkSurfelTextureAcquisition_h

#include "SplatFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // For members

#ifndef __VTK_WRAP__
#include <functional> // For the texture callback
#endif

class vtkImageData;
class vtkImplicitFunction;
class vtkScalarsToColors;

class SPLATFILTERS_EXPORT vtkSurfelTextureAcquisition : public vtkPolyDataAlgorithm
{
public:
  static vtkSurfelTextureAcquisition* New();
  vtkTypeMacro(vtkSurfelTextureAcquisition, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Modes
  {
    POINT_SAMPLING = 0,
    VIEW_INDEPENDENT_EWA = 1,
    OPTIMAL = 2
  };

  ///@{
  /**
   * How the coefficients are computed (see the class comment). Default VIEW_INDEPENDENT_EWA.
   */
  vtkSetClampMacro(Mode, int, POINT_SAMPLING, OPTIMAL);
  vtkGetMacro(Mode, int);
  void SetModeToPointSampling() { this->SetMode(POINT_SAMPLING); }
  void SetModeToViewIndependentEWA() { this->SetMode(VIEW_INDEPENDENT_EWA); }
  void SetModeToOptimal() { this->SetMode(OPTIMAL); }
  static const char* GetModeAsString(int mode);
  ///@}

  ///@{
  /**
   * The texture image, on input port 1.
   */
  void SetTextureData(vtkImageData* image);
  void SetTextureConnection(vtkAlgorithmOutput* output);
  ///@}

  ///@{
  /**
   * A procedural texture: the implicit function's value at (s, t, 0), mapped through
   * ImplicitTextureColors (grey clamped to [0, 1] without one). Used when port 1 has no image.
   */
  virtual void SetImplicitTexture(vtkImplicitFunction*);
  vtkImplicitFunction* GetImplicitTexture();
  virtual void SetImplicitTextureColors(vtkScalarsToColors*);
  vtkScalarsToColors* GetImplicitTextureColors();
  ///@}

#ifndef __VTK_WRAP__
  /**
   * A procedural texture as a callback: fills rgba in [0, 1] for texture coordinates (s, t). It is
   * called from several threads at once. Used when port 1 has no image and no implicit texture
   * is set; an empty function clears it.
   */
  using TextureFunction = std::function<void(double s, double t, double rgba[4])>;
  void SetTextureFunction(TextureFunction function, bool hasAlpha = false);
#endif

  ///@{
  /**
   * Image texture coordinates outside [0, 1] repeat (on, the default) or clamp to the edge
   * (off). Procedural textures are evaluated at the coordinates as they are.
   */
  vtkSetMacro(Repeat, bool);
  vtkGetMacro(Repeat, bool);
  vtkBooleanMacro(Repeat, bool);
  ///@}

  ///@{
  /**
   * Surfel geometry, named as vtkSurfaceSplatMapper names it: the radius array (default
   * "Radius"), the global Radius when there is none (default 1), the tangent-axis arrays of
   * elliptical surfels (default "TangentAxis0" and "TangentAxis1", used when both exist).
   */
  vtkSetStringMacro(RadiusArrayName);
  vtkGetStringMacro(RadiusArrayName);
  vtkSetClampMacro(Radius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Radius, double);
  vtkSetStringMacro(TangentAxis0ArrayName);
  vtkGetStringMacro(TangentAxis0ArrayName);
  vtkSetStringMacro(TangentAxis1ArrayName);
  vtkGetStringMacro(TangentAxis1ArrayName);
  ///@}

  ///@{
  /**
   * Name of the texture-coordinate array; null or empty (the default) takes the active TCoords.
   */
  vtkSetStringMacro(TextureCoordinatesArrayName);
  vtkGetStringMacro(TextureCoordinatesArrayName);
  ///@}

  ///@{
  /**
   * Number of nearest surfels over which each surfel's affine map to texture space is fitted.
   * Default 8.
   */
  vtkSetClampMacro(NumberOfNeighbors, int, 2, 256);
  vtkGetMacro(NumberOfNeighbors, int);
  ///@}

  ///@{
  /**
   * Support of the basis functions: |u|^2 < Cutoff in axis units, as vtkSurfaceSplatMapper's
   * cutoff. Default 1.
   */
  vtkSetClampMacro(Cutoff, double, 0.01, 16.0);
  vtkGetMacro(Cutoff, double);
  ///@}

  ///@{
  /**
   * OPTIMAL: quadrature nodes per axis over each surfel's support. Default 5 (21 nodes inside
   * the disk).
   */
  vtkSetClampMacro(QuadratureResolution, int, 2, 32);
  vtkGetMacro(QuadratureResolution, int);
  ///@}

  ///@{
  /**
   * Procedural textures: samples per axis of the Gaussian prefilter. Default 16.
   */
  vtkSetClampMacro(ProceduralSamples, int, 1, 256);
  vtkGetMacro(ProceduralSamples, int);
  ///@}

  ///@{
  /**
   * OPTIMAL: the Tikhonov weight lambda towards the view-independent solution (see the class
   * comment), the conjugate-gradient iteration limit and relative residual tolerance.
   * Defaults 1e-3, 500, 1e-6.
   */
  vtkSetClampMacro(Regularization, double, 1e-12, 1e6);
  vtkGetMacro(Regularization, double);
  vtkSetClampMacro(MaximumNumberOfIterations, int, 1, 100000);
  vtkGetMacro(MaximumNumberOfIterations, int);
  vtkSetClampMacro(Tolerance, double, 1e-14, 1.0);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /**
   * The output color array: name (default "TextureColors") and type (VTK_UNSIGNED_CHAR, the
   * default, or VTK_FLOAT).
   */
  vtkSetStringMacro(OutputArrayName);
  vtkGetStringMacro(OutputArrayName);
  vtkSetMacro(OutputScalarType, int);
  vtkGetMacro(OutputScalarType, int);
  void SetOutputScalarTypeToUnsignedChar() { this->SetOutputScalarType(VTK_UNSIGNED_CHAR); }
  void SetOutputScalarTypeToFloat() { this->SetOutputScalarType(VTK_FLOAT); }
  ///@}

  ///@{
  /**
   * What the last update did: surfels left black (invalid input), surfels point sampled because
   * their affine map could not be fitted, coefficient components clamped to [0, 1], and for
   * OPTIMAL the unknowns (valid surfels, coincident ones counted once), the nonzeros of R's upper triangle, the conjugate-gradient iterations
   * (the most over the channels) and the final relative residual (the largest).
   */
  vtkGetMacro(NumberOfSkippedPoints, vtkIdType);
  vtkGetMacro(NumberOfDegenerateMaps, vtkIdType);
  vtkGetMacro(NumberOfClampedValues, vtkIdType);
  vtkGetMacro(NumberOfUnknowns, vtkIdType);
  vtkGetMacro(NumberOfNonZeros, vtkIdType);
  vtkGetMacro(NumberOfIterations, int);
  vtkGetMacro(SolverError, double);
  ///@}

  vtkMTimeType GetMTime() override;

protected:
  vtkSurfelTextureAcquisition();
  ~vtkSurfelTextureAcquisition() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Mode = VIEW_INDEPENDENT_EWA;
  bool Repeat = true;
  char* RadiusArrayName = nullptr;
  double Radius = 1.0;
  char* TangentAxis0ArrayName = nullptr;
  char* TangentAxis1ArrayName = nullptr;
  char* TextureCoordinatesArrayName = nullptr;
  int NumberOfNeighbors = 8;
  double Cutoff = 1.0;
  int QuadratureResolution = 5;
  int ProceduralSamples = 16;
  double Regularization = 1e-3;
  int MaximumNumberOfIterations = 500;
  double Tolerance = 1e-6;
  char* OutputArrayName = nullptr;
  int OutputScalarType = VTK_UNSIGNED_CHAR;

  vtkSmartPointer<vtkImplicitFunction> ImplicitTexture;
  vtkSmartPointer<vtkScalarsToColors> ImplicitTextureColors;

  vtkIdType NumberOfSkippedPoints = 0;
  vtkIdType NumberOfDegenerateMaps = 0;
  vtkIdType NumberOfClampedValues = 0;
  vtkIdType NumberOfUnknowns = 0;
  vtkIdType NumberOfNonZeros = 0;
  int NumberOfIterations = 0;
  double SolverError = 0.0;

private:
  vtkSurfelTextureAcquisition(const vtkSurfelTextureAcquisition&) = delete;
  void operator=(const vtkSurfelTextureAcquisition&) = delete;

  struct Callback;
  Callback* Function;
};

#endif
