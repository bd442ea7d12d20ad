// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkVolumeSplatMapper
 * @brief   renders image data and sets of 3D Gaussians by EWA volume splatting
 *
 * vtkVolumeSplatMapper is a volume mapper, drawn by a vtkVolume with a vtkVolumeProperty. Every
 * kernel is a 3D Gaussian; through the local affine approximation of the perspective projection
 * its integral along each view ray is a 2D Gaussian footprint, band-limited by the screen
 * low-pass filter (Zwicker et al., EWA Volume Splatting; SplatVolumeKernel.h), by default as a
 * floor of its spread rather than added to it (SetFootprintFilter). Footprints are
 * composited front to back with emission and absorption, in the visibility order of three lists
 * sorted along the X, Y and Z axes (Hofsetz and Max, see vtkVolumeSplatRasterizer and
 * SetOrderingMode). Kernels with a peak opacity (3D Gaussian Splatting captures) are drawn by
 * default as the rasterizer they were optimized against draws them: the 0.3 px^2 dilation
 * instead of the low-pass (SetFootprintFilter) and the exact per-Gaussian depth order
 * (vtkGaussianSplatRasterizer on the CPU, SplatCaptureKernel.h), the image they were trained to
 * produce. Their kernels are kept in the order of a Z curve through their centers rather than
 * the input's, so that the kernels of a screen tile lie near one another in memory.
 *
 * Inputs:
 * - vtkImageData, scalars on points: one kernel per voxel, centered on the point, with standard
 *   deviation splat::VoxelKernelSigma (0.6) times the spacing along each index axis (the
 *   direction matrix included), which makes the kernels a partition of unity within 0.5%.
 *   The lists are the grid's sheets: image data is never sorted.
 * - any other vtkPointSet of kernels, with a 6-component covariance array (xx, xy, xz, yy, yz,
 *   zz; CovarianceArrayName, default "Covariance"), or a 3-component scale array of standard
 *   deviations (ScaleArrayName, default "Scale") and a 4-component rotation quaternion
 *   (w, x, y, z; RotationArrayName, default "Rotation"), the convention of 3D Gaussian Splatting
 *   (with exponentiated scales) and of VTK 9.4's anisotropic point gaussians. Colors come from
 *   a direct RGB array (ColorArrayName, default "Color"; unsigned char or [0, 1] floats) or the
 *   scalars through the color transfer function. Opacities come from a direct opacity array
 *   (OpacityArrayName, default "Opacity") as each kernel's peak opacity, alpha(x) =
 *   opacity exp(-beta(x)) as in 3D Gaussian Splatting, or else from the scalars through the
 *   scalar opacity transfer function as a density whose peak is the transfer function's
 *   extinction (below). Kernels that sample a field (the voxels of a sparse grid, as
 *   vtkOpenVDBReader writes them) carry instead the world volume their sample stands for in a
 *   1-component array (SampleVolumeArrayName, default "SampleVolume"): such a kernel's density
 *   integrates to the extinction times that volume, as image-data voxels do, so that the kernels
 *   reconstruct the field rather than each peaking at it.
 * - a point set of voxels on a lattice (a sparse grid's active voxels: vtkOpenVDBReader writes
 *   them for fog): a 3-component integer array "VoxelIndex" of each point's index coordinates
 *   and a 16-component field-data array "IndexToWorld" (the row-major 4x4 matrix of the
 *   index-to-world map, column vectors) make the kernels voxels of that grid, drawn as image
 *   data is (positions from the indices, the voxel kernel of the map, the sheets of the grid's
 *   index axes, shading normals from the neighbors present) with memory for the points only;
 *   the covariance and sample-volume arrays are then not read.
 * The scalars are selected as for VTK's volume mappers (SetScalarMode, SelectScalarArray); the
 * first component is used.
 *
 * View-dependent colors (3D Gaussian Splatting): a point set's float array of spherical-harmonic
 * coefficients (SphericalHarmonicsArrayName, default "SphericalHarmonics"), 3 (d + 1)^2
 * components for degree d in 0..3 (3, 12, 27, 48; another count is an error and the array is
 * ignored), coefficient-major with RGB interleaved (k0.r, k0.g, k0.b, k1.r, ...) in the basis
 * order, signs and constants of the 3DGS reference (SplatSphericalHarmonics.h), takes precedence
 * over the color array and the color transfer function. Each frame, each kernel's color is
 * max(0, 0.5 + sum_k Y_k(d) c_k) clamped to 1, with d the direction from the camera position to
 * the kernel's center in the data's coordinates (through the inverse of the vtkVolume's matrix;
 * the view axis in a parallel projection), up to MaximumSphericalHarmonicsDegree; then shaded
 * like any color. The CPU backend evaluates it in parallel when the view point moved; the
 * OpenGL backend in the vertex shader from a half-float buffer of the coefficients. Image data
 * ignores the array.
 *
 * Optical model: the scalar opacity transfer function gives alpha per ScalarOpacityUnitDistance
 * as for VTK's ray casters, i.e. the extinction tau = -ln(1 - alpha) / unitDistance (alpha
 * clamped to 0.999). A voxel's kernel carries tau times the voxel volume, so the kernels
 * reconstruct tau(x); a pixel's optical depth from kernel k is tau_k V_k times its footprint,
 * its opacity 1 - exp(-optical depth) and its emission the color transfer function's color.
 * The same transfer functions thus give images comparable with vtkFixedPointVolumeRayCastMapper
 * (which classifies after interpolation where this mapper classifies voxels). Gradient opacity
 * is not applied.
 *
 * Shading: with the volume property's Shade on, each kernel's color is lit once per frame at its
 * center (pre-shaded splats) with the renderer's lights and the property's Ambient, Diffuse,
 * Specular and SpecularPower, in VTK's lighting model (SplatLighting.h): ambient and diffuse
 * scale the transfer function's color, the specular term is white. The normal is minus the
 * scalar gradient by central differences at the voxel for image data, and the point normals
 * (vtkPointData::GetNormals) for point sets, which are drawn unshaded, with a warning, without
 * them. A zero gradient gets the ambient term only; with the renderer's TwoSidedLighting (VTK's
 * default) normals facing away from the eye are turned towards it, as VTK's volume mappers do.
 *
 * Each render leaves out what the frame does not need: kernels of zero opacity are not in the
 * lists (which are rebuilt when the input, the transfer functions or the array selection change,
 * and only then); a list is built and traversed only where some pixel needs it; kernels whose
 * cutoff ellipsoid reaches the near plane or lies behind the eye, and kernels outside the view
 * frustum, are skipped. All of it is counted (GetListTraversed, GetNumberOfProjectedKernels,
 * GetNumberOf*Kernels). Kernels with a non-finite position, covariance, scale or rotation, a zero
 * quaternion, a covariance that is not positive semi-definite, or spherical-harmonic
 * coefficients that are not finite or exceed the half-float range (+-65504) are skipped and
 * counted.
 *
 * The volume is drawn after the opaque geometry: each pixel's integration stops at the opaque
 * scene's depth (kernels whose center lies behind it are left out of that pixel), and the
 * premultiplied image is blended over the framebuffer.
 *
 * Backends: the multithreaded CPU rasterizer (vtkVolumeSplatRasterizer, threads from
 * vtkSMPTools, the same image for any number of threads) and OpenGL shaders
 * (vtkOpenGLVolumeSplatRasterizer: each list the frame needs splatted into its own float
 * buffer in the render window's context, then merged), with the same image semantics and the
 * same lists, which the CPU rasterizer builds for both. SetBackend picks one; AUTO takes OpenGL
 * on a hardware GPU and the CPU under a software OpenGL renderer (vtkSplatBackend), and
 * GetLastBackend() says what ran. The OpenGL backend does not count the kernels it projects or
 * leaves out (GetNumberOfProjectedKernels, GetNumberOfNearPlaneKernels and
 * GetNumberOfFrustumCulledKernels are -1 after its renders); it reports the lists it traversed.
 *
 * @sa vtkVolumeSplatRasterizer vtkSurfaceSplatMapper vtkFixedPointVolumeRayCastMapper
 */
#ifndef vtkVolumeSplatMapper_h
#define vtkVolumeSplatMapper_h

#include "SplatRenderingModule.h" // For export macro
#include "vtkAbstractVolumeMapper.h"
#include "vtkDataSet.h" // For SetInputData
#include "vtkNew.h" // For vtkNew

#include <memory> // For std::unique_ptr
#include <string> // For KernelSettings

class vtkImageData;
class vtkOpenGLImageDepthCompositor;
class vtkOpenGLVolumeSplatRasterizer;
class vtkPointSet;
class vtkVolumeProperty;
class vtkVolumeSplatRasterizer;

class SPLATRENDERING_EXPORT vtkVolumeSplatMapper : public vtkAbstractVolumeMapper
{
public:
  static vtkVolumeSplatMapper* New();
  vtkTypeMacro(vtkVolumeSplatMapper, vtkAbstractVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Sets the input: a vtkImageData or another vtkPointSet (see the class comment).
   */
  void SetInputData(vtkDataSet* input) { this->SetInputDataInternal(0, input); }

  /**
   * Visibility orderings (paper 003).
   */
  enum OrderingModes
  {
    BLENDED = 0,      ///< lists blended near their region boundaries
    CLIPPED = 1,      ///< each pixel from the list of its ray's dominant axis
    SINGLE_AXIS = 2,  ///< one list per frame, the central ray's (Westover)
    DEPTH_SORTED = 3, ///< a global per-frame sort by eye-space depth
    AUTOMATIC = 4     ///< DEPTH_SORTED for captures, BLENDED for density kernels (default)
  };

  ///@{
  /**
   * Visibility ordering: AUTOMATIC (default), BLENDED, CLIPPED, SINGLE_AXIS or DEPTH_SORTED.
   * AUTOMATIC follows the kind of kernels: captures (an opacity array: 3D Gaussian Splatting)
   * were optimized for their exact per-Gaussian depth order (DEPTH_SORTED, drawn under the
   * rules of their rasterizer on the CPU: vtkGaussianSplatRasterizer), density kernels (image
   * data, sparse grids, kernels through transfer functions) take the three axis lists blended
   * per pixel (BLENDED). GetLastOrderingMode says which ran.
   */
  void SetOrderingMode(int mode);
  vtkGetMacro(OrderingMode, int);
  void SetOrderingModeToAutomatic() { this->SetOrderingMode(AUTOMATIC); }
  void SetOrderingModeToBlended() { this->SetOrderingMode(BLENDED); }
  void SetOrderingModeToClipped() { this->SetOrderingMode(CLIPPED); }
  void SetOrderingModeToSingleAxis() { this->SetOrderingMode(SINGLE_AXIS); }
  void SetOrderingModeToDepthSorted() { this->SetOrderingMode(DEPTH_SORTED); }
  ///@}

  /**
   * The ordering the last render used (AUTOMATIC resolved; AUTOMATIC before the first).
   */
  vtkGetMacro(LastOrderingMode, int);

  /**
   * Screen filters of the footprints (splat::FootprintFilter).
   */
  enum FootprintFilters
  {
    LOW_PASS_FILTER = 0,    ///< EWA's unit screen low-pass (1 px^2), convolved
    DILATION_FILTER = 1,    ///< the 0.3 px^2 dilation captures are trained with
    ANTIALIASED_FILTER = 2, ///< the dilation, peak opacities compensated (Mip-Splatting)
    AUTOMATIC_FILTER = 3,   ///< DILATION for captures, BAND_LIMIT for density kernels (default)
    BAND_LIMIT_FILTER = 4   ///< the low-pass's 1 px^2 as a floor of each footprint's spread
  };

  ///@{
  /**
   * The screen filter convolved with every footprint: LOW_PASS_FILTER, EWA's band limit of
   * 1 px^2 (Zwicker et al.); DILATION_FILTER, the 0.3 px^2 added to the projected covariance
   * with the peak opacity unchanged that 3D Gaussian Splatting captures are trained with (the
   * image their optimization produced: their thin features drawn 1 px^2 wider come out fat);
   * ANTIALIASED_FILTER, the dilation with each peak opacity scaled by
   * sqrt(|V'| / |V' + 0.3 I|) (gsplat's antialiased mode, Mip-Splatting's 2D filter), which keeps
   * sub-pixel Gaussians from aliasing in views far from the capture's training range;
   * BAND_LIMIT_FILTER, the low-pass's 1 px^2 as a floor of the footprint's variance along every
   * direction rather than added to it (Botsch et al. 2005's approximation of EWA;
   * splat::FilteredCovariance), for density kernels (captures take it as LOW_PASS); or
   * AUTOMATIC_FILTER (default): DILATION for captures, BAND_LIMIT for density kernels, whose
   * footprints keep their integral under any filter. Both LOW_PASS and BAND_LIMIT band-limit
   * footprints smaller than a pixel alike, but the sum also widens magnified voxels by a pixel,
   * a blur the ray-marched reference has not. In the report (`splat_report --scenes
   * mri,vdb,gaussians`, 256x256, CPU) BAND_LIMIT takes the MRI head from 40.1 to 49.6 dB
   * (55.1 dB without the sheets) and the OpenVDB cloud from 51.9 to 55.6 dB (59.8), against
   * 54.6 -> 53.9 dB for the random Gaussians, at the same frame time. Image data's sheets merged
   * by pairs lose more of the band-limited image's voxel-to-voxel detail than of the low-passed
   * one's (TestVolumeSplatSheets, the shaded MRI against the exact path: RMSE 0.0023 against
   * 0.0015), still far nearer the reference than the low-pass is.
   */
  void SetFootprintFilter(int filter);
  vtkGetMacro(FootprintFilter, int);
  void SetFootprintFilterToAutomatic() { this->SetFootprintFilter(AUTOMATIC_FILTER); }
  void SetFootprintFilterToLowPass() { this->SetFootprintFilter(LOW_PASS_FILTER); }
  void SetFootprintFilterToDilation() { this->SetFootprintFilter(DILATION_FILTER); }
  void SetFootprintFilterToAntialiased() { this->SetFootprintFilter(ANTIALIASED_FILTER); }
  void SetFootprintFilterToBandLimit() { this->SetFootprintFilter(BAND_LIMIT_FILTER); }
  ///@}

  ///@{
  /**
   * The threshold h of the BLENDED mode: a list contributes where its axis's share of the ray
   * direction |d_a| / max|d| exceeds h. In [0, 0.99]; default 0.85 (paper 003).
   */
  void SetBlendThreshold(double h);
  double GetBlendThreshold();
  ///@}

  ///@{
  /**
   * For image data and voxel lattices on the CPU backend (BLENDED, CLIPPED and SINGLE_AXIS
   * orderings): composite each list sheet by sheet in an intermediate image aligned with the
   * grid's sheets, warped to the screen once per frame (vtkVolumeSplatSheetCompositor), where
   * it applies; off splats every voxel on the screen (the exact per-kernel path). Default on.
   */
  void SetSheetResampling(bool on);
  bool GetSheetResampling();
  vtkBooleanMacro(SheetResampling, bool);
  ///@}

  /**
   * Whether the last frame on the CPU backend went through the sheets (SheetResampling).
   */
  bool GetSheetsUsed();

  ///@{
  /**
   * With SheetResampling: composite each list's sheets merged by pairs along its axis, each
   * pair of voxels one kernel at their strength-weighted center with their summed strength and
   * strength-weighted color, half the footprints of the sheets
   * (vtkVolumeSplatSheetCompositor). Off composites every sheet. Default on.
   */
  void SetSheetMerging(bool on);
  bool GetSheetMerging();
  vtkBooleanMacro(SheetMerging, bool);
  ///@}

  ///@{
  /**
   * Cutoff on the footprint exponent 1/2 x^T M^-1 x, as for vtkSurfaceSplatMapper. Default 4.5,
   * three standard deviations (see splat::DefaultVolumeCutoff).
   */
  void SetCutoff(double cutoff);
  double GetCutoff();
  ///@}

  ///@{
  /**
   * The backend: vtkSplatBackend::AUTO (default), CPU or OPENGL.
   */
  vtkSetClampMacro(Backend, int, 0, 2);
  vtkGetMacro(Backend, int);
  ///@}

  /**
   * The backend that drew the last render (vtkSplatBackend::CPU or OPENGL; AUTO, 0, before the
   * first render).
   */
  vtkGetMacro(LastBackend, int);

  ///@{
  /**
   * Names of the point-data arrays of kernel sets (see the class comment).
   */
  vtkSetStringMacro(CovarianceArrayName);
  vtkGetStringMacro(CovarianceArrayName);
  vtkSetStringMacro(ScaleArrayName);
  vtkGetStringMacro(ScaleArrayName);
  vtkSetStringMacro(RotationArrayName);
  vtkGetStringMacro(RotationArrayName);
  vtkSetStringMacro(ColorArrayName);
  vtkGetStringMacro(ColorArrayName);
  vtkSetStringMacro(OpacityArrayName);
  vtkGetStringMacro(OpacityArrayName);
  vtkSetStringMacro(SampleVolumeArrayName);
  vtkGetStringMacro(SampleVolumeArrayName);
  ///@}

  ///@{
  /**
   * View-dependent colors of kernel sets (see the class comment): the point-data array of
   * spherical-harmonic coefficients (default "SphericalHarmonics"), and the highest degree
   * evaluated, 0 to 3 (default 3; 0 gives the view-independent degree-0 colors). Changing the
   * degree does not rebuild the kernels or their lists.
   */
  vtkSetStringMacro(SphericalHarmonicsArrayName);
  vtkGetStringMacro(SphericalHarmonicsArrayName);
  void SetMaximumSphericalHarmonicsDegree(int degree);
  int GetMaximumSphericalHarmonicsDegree();
  ///@}

  ///@{
  /**
   * What the last render did (paper 003, table 1): whether list `axis` (0, 1, 2 for X, Y, Z;
   * 3 for the per-frame depth sort) was traversed and how many kernels it splatted, and all
   * lists together (-1: not counted by the OpenGL backend).
   */
  bool GetListTraversed(int axis);
  vtkIdType GetNumberOfProjectedKernels(int axis);
  vtkIdType GetNumberOfProjectedKernels();
  ///@}

  ///@{
  /**
   * Kernels in the lists, and those left out: zero opacity under the transfer function or the
   * opacity array, invalid input (see the class comment), reaching the near plane in the last
   * render, or outside the view frustum in the last render (these two are -1 after an OpenGL
   * render: the shaders do not count them).
   */
  vtkGetMacro(NumberOfKernels, vtkIdType);
  vtkGetMacro(NumberOfTransparentKernels, vtkIdType);
  vtkGetMacro(NumberOfInvalidKernels, vtkIdType);
  vtkIdType GetNumberOfNearPlaneKernels();
  vtkIdType GetNumberOfFrustumCulledKernels();
  ///@}

  ///@{
  /**
   * Since the mapper was made: comparison sorts (point-set list builds and per-frame depth
   * sorts; image data needs none), kernel-list builds and kernel builds (classification,
   * gradients: when the input, the volume property or the kernel settings change, never for a
   * moved camera alone).
   */
  vtkIdType GetNumberOfSorts();
  vtkIdType GetNumberOfListBuilds();
  vtkGetMacro(NumberOfKernelBuilds, vtkIdType);
  ///@}

  /**
   * Wall-clock time of the last render, in milliseconds.
   */
  vtkGetMacro(LastRenderTimeInMilliseconds, double);

  /**
   * The input's bounds grown by the kernels' cutoff extent, so camera resets and clipping ranges
   * include whole kernels. Non-finite points are ignored.
   */
  double* GetBounds() override;
  using vtkAbstractVolumeMapper::GetBounds;

  /**
   * Draws the input into the renderer.
   */
  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkVolumeSplatMapper();
  ~vtkVolumeSplatMapper() override;

  /**
   * Rebuilds the kernels when the input, the mapper or the volume property changed. Returns
   * false when the input cannot be drawn.
   */
  bool UpdateKernels(vtkVolumeProperty* property);
  /// The mapper's settings the kernels depend on (array names and scalar selection), as text.
  std::string KernelSettings();
  bool BuildImageKernels(vtkImageData* image, vtkVolumeProperty* property);
  bool BuildPointKernels(vtkPointSet* points, vtkVolumeProperty* property);
  /// Kernels of a point set that carries its voxel lattice, built as for image data.
  bool BuildLatticeKernels(vtkPointSet* points, vtkVolumeProperty* property);

  /**
   * The backend that renders this frame: the requested one, AUTO resolved by
   * vtkSplatBackend::Resolve. The only place that decides.
   */
  int SelectBackend(vtkRenderer* ren);

  int Backend = 0;
  int LastBackend = 0; // no render yet
  int OrderingMode = AUTOMATIC;
  int LastOrderingMode = AUTOMATIC; // no render yet
  int FootprintFilter = AUTOMATIC_FILTER;
  char* CovarianceArrayName = nullptr;
  char* ScaleArrayName = nullptr;
  char* RotationArrayName = nullptr;
  char* ColorArrayName = nullptr;
  char* OpacityArrayName = nullptr;
  char* SampleVolumeArrayName = nullptr;
  char* SphericalHarmonicsArrayName = nullptr;
  vtkIdType NumberOfKernels = 0;
  vtkIdType NumberOfTransparentKernels = 0;
  vtkIdType NumberOfInvalidKernels = 0;
  vtkIdType NumberOfKernelBuilds = 0;
  double LastRenderTimeInMilliseconds = 0.0;

  vtkNew<vtkVolumeSplatRasterizer> Rasterizer; // also the lists and settings of both backends
  vtkNew<vtkOpenGLVolumeSplatRasterizer> OpenGLRasterizer;
  vtkNew<vtkOpenGLImageDepthCompositor> Compositor;

private:
  vtkVolumeSplatMapper(const vtkVolumeSplatMapper&) = delete;
  void operator=(const vtkVolumeSplatMapper&) = delete;

  struct KernelArrays;
  std::unique_ptr<KernelArrays> Kernels;
};

#endif
