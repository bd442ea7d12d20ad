// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkVolumeSplatRasterizer
 * @brief   multithreaded CPU rasterizer for EWA volume splatting ordered by three axis lists
 *
 * vtkVolumeSplatRasterizer is the CPU backend of vtkVolumeSplatMapper. It takes 3D Gaussian
 * kernels (positions, covariances, emitted colors, strengths) and a camera, and produces a
 * premultiplied RGBA image by emission-absorption compositing of the kernels' footprints
 * (SplatVolumeKernel.h) front to back.
 *
 * Visibility ordering follows Hofsetz and Max (paper 003): the kernels are kept in three lists
 * sorted along the X, Y and Z axes of the data's frame (for image data the index axes, whose
 * lists are the grid's sheets and need no sort). Each pixel's view ray picks its lists from its
 * direction d in that frame; a list a is traversed in ascending order for pixels with d_a > 0
 * and descending for d_a < 0, which is front to back along those rays. Modes:
 * - Blended: every list whose weight w_a = (|d_a| / max|d| - h) / (1 - h) is positive at a pixel
 *   is composited into its own buffer, and the buffers are merged per pixel by
 *   C = sum C_a w_a^2 / sum w_a^2 (paper 003, eq. 1);
 * - Clipped: each pixel from the list of its dominant axis only (paper 003, section 5);
 * - SingleAxis: one list for the whole frame, the central ray's (Westover);
 * - DepthSorted: one global front-to-back sort of the kernels by eye-space depth per frame;
 *   for kernels with a peak opacity (3D Gaussian Splatting captures) the frame is drawn by
 *   vtkGaussianSplatRasterizer under the rules of the rasterizer captures are trained with.
 *
 * A frame has four steps: per-pixel list weights; setup of every kernel, parallel over kernels
 * (footprint, bounding box, skip reasons; spherical-harmonic colors, evaluated again only when
 * the view point or the degree changed); binning into 16-row bands in list order, for each list
 * some pixel needs, keeping only the kernels that overlap the band's pixels of that list (a
 * counting sort by band and layer in parallel over fixed chunks, into copies of the kernels that
 * the compositing reads in sequence; for image data over the kernels in memory order, sheet by
 * sheet, rather than gathered along the X and Y lists); and compositing, parallel over bands. A
 * band's pixels see their kernels in list order whatever the number of threads, so the image
 * does not depend on it.
 *
 * Compositing goes layer by layer: for image data a layer is one sheet of the grid along the
 * list's axis (kernels side by side, whose order within the sheet is arbitrary), otherwise one
 * kernel. A layer's footprints are summed per pixel as optical depth and optical-depth-weighted
 * color, and the layer goes under the pixel once with opacity 1 - exp(-sum): the transmittance
 * of compositing its kernels one by one, the colors weighted by each kernel's share of the
 * optical depth whatever their order, and one exponential per pixel and layer. Footprints are
 * evaluated over whole groups of 8 columns of their box with the cutoff ellipse as a mask, so
 * that the loop vectorizes (splat::NegativeExponential; an AVX2/FMA clone where GCC dispatches on
 * the CPU). Pixels stop integrating once their accumulated opacity reaches 1 - 1/512 (early ray
 * termination); a kernel whose columns of the band (in tiles of 8) hold no pixel that still
 * integrates along that list and direction is not evaluated at all. A kernel adds nothing to
 * pixels where its center lies behind the opaque scene's depth.
 *
 * For image data in the axis-list orderings, SheetResampling (the default) replaces steps two
 * to four by vtkVolumeSplatSheetCompositor where it applies: each list's sheets are composited
 * in an intermediate image aligned with them and warped to the list's buffer, which is merged as
 * above; SheetResampling off keeps the exact per-kernel path described here.
 *
 * Kernels are not validated here: the caller passes finite data only.
 *
 * @sa vtkVolumeSplatMapper
 */
#ifndef vtkVolumeSplatRasterizer_h
#define vtkVolumeSplatRasterizer_h

#include "SplatLighting.h"        // For splat::Light, splat::Material
#include "SplatRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <glm/glm.hpp> // For the camera matrices

#include <array>   // For the lists
#include <cstdint> // For std::uint8_t
#include <vector>  // For the frame buffer

class SPLATRENDERING_EXPORT vtkVolumeSplatRasterizer : public vtkObject
{
public:
  static vtkVolumeSplatRasterizer* New();
  vtkTypeMacro(vtkVolumeSplatRasterizer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Visibility orderings (see the class comment); the values of vtkVolumeSplatMapper's modes.
  enum OrderingModes
  {
    BLENDED = 0,
    CLIPPED = 1,
    SINGLE_AXIS = 2,
    DEPTH_SORTED = 3,
  };

  /// The index of the per-frame depth-sorted list in the per-list statistics.
  static constexpr int DepthList = 3;

  ///@{
  /**
   * Visibility ordering. Default BLENDED.
   */
  vtkSetClampMacro(OrderingMode, int, BLENDED, DEPTH_SORTED);
  vtkGetMacro(OrderingMode, int);
  ///@}

  ///@{
  /**
   * The blending threshold h of the BLENDED mode, in [0, 0.99]. Default 0.85 (paper 003).
   */
  vtkSetClampMacro(BlendThreshold, double, 0.0, 0.99);
  vtkGetMacro(BlendThreshold, double);
  ///@}

  ///@{
  /**
   * Cutoff on the footprint exponent. Default splat::DefaultVolumeCutoff (4.5).
   */
  vtkSetClampMacro(Cutoff, double, 1e-3, 50.0);
  vtkGetMacro(Cutoff, double);
  ///@}

  ///@{
  /**
   * The screen filter of the footprints, a splat::FootprintFilter: LowPass (0, the default: the
   * unit EWA low-pass), Dilation (1, the 0.3 px^2 that captures are trained with),
   * Antialiased (2, the dilation with the peak opacity compensated; as Dilation for density
   * kernels, whose footprints keep their integral under any filter) or BandLimit (3, the
   * low-pass as a floor of the footprint's variance; for density kernels).
   */
  vtkSetClampMacro(FootprintFilter, int, 0, 3);
  vtkGetMacro(FootprintFilter, int);
  ///@}

  ///@{
  /**
   * For image data in the BLENDED, CLIPPED and SINGLE_AXIS orderings: composite each list
   * sheet by sheet in an intermediate image aligned with the sheets and warp it to the screen
   * (vtkVolumeSplatSheetCompositor), where it applies; off, or where it does not apply (the eye
   * between a list's first and last sheets, kernels reaching the near plane, opaque geometry in
   * front of the volume's far side), every kernel is splatted on the screen (the exact
   * per-kernel path). Default on.
   */
  vtkSetMacro(SheetResampling, bool);
  vtkGetMacro(SheetResampling, bool);
  vtkBooleanMacro(SheetResampling, bool);
  ///@}

  ///@{
  /**
   * With SheetResampling: the sheets merged by pairs along each list's axis
   * (vtkVolumeSplatSheetCompositor::SetMergePairs). Default on.
   */
  vtkSetMacro(SheetMerging, bool);
  vtkGetMacro(SheetMerging, bool);
  vtkBooleanMacro(SheetMerging, bool);
  ///@}

  /**
   * Whether the last frame went through the sheets (SheetResampling).
   */
  vtkGetMacro(SheetsUsed, bool);

  ///@{
  /**
   * The highest spherical-harmonic degree evaluated for kernels with SphericalHarmonics, in
   * [0, 3]; 0 gives their view-independent Colors. Default 3.
   */
  vtkSetClampMacro(MaximumSphericalHarmonicsDegree, int, 0, 3);
  vtkGetMacro(MaximumSphericalHarmonicsDegree, int);
  ///@}

  /**
   * The camera: model-to-eye and eye-to-clip (projection) matrices and the viewport in pixels.
   */
  struct Camera
  {
    glm::dmat4 ModelToEye{ 1.0 };
    glm::dmat4 EyeToClip{ 1.0 };
    glm::ivec2 Viewport{ 0 };
  };

  /**
   * Kernels as arrays of Count entries, all in model coordinates, all with a positive strength.
   * - Strengths: with PeakOpacity off (the density model), the optical depth of the kernel
   *   integrated over space (extinction per unit length times the kernel's volume), so that a
   *   ray's optical depth is Strength times the footprint; with PeakOpacity on (the convention
   *   of 3D Gaussian Splatting), the opacity at the footprint's center,
   *   alpha(x) = Strength exp(-beta(x)), without amplitude normalization.
   * - Covariances: six components (xx, xy, xz, yy, yz, zz) per kernel, or null when every
   *   kernel has SharedCovariance (image data).
   * - ListFrame: the columns are the unit axes of the lists' frame in model coordinates.
   * - GridIds and GridDimensions: for image data, each kernel's voxel id i + nx (j + ny k),
   *   ascending; the lists are then the grid's sheets and are not sorted. Null for point sets,
   *   whose lists are sorted by position. GridAxes and GridOrigin: for image data, the index
   *   axes (spacing included, as columns) and voxel (0, 0, 0)'s position in model coordinates.
   * - Normals: for shading, a unit normal per kernel in model coordinates (zero where there is
   *   none, which gets the ambient term only); null for unshaded kernels, which emit Colors.
   * - SphericalHarmonics: for view-dependent colors, 3 (SphericalHarmonicsDegree + 1)^2 floats
   *   per kernel (SplatSphericalHarmonics.h), evaluated up to MaximumSphericalHarmonicsDegree
   *   for the direction from the eye to the kernel (the view axis in a parallel projection) in
   *   model coordinates, in place of Colors, which then hold the degree-0 colors; null for
   *   none.
   */
  struct Kernels
  {
    std::size_t Count = 0;
    const double* Positions = nullptr;
    const float* Covariances = nullptr;
    glm::dmat3 SharedCovariance{ 1.0 };
    const float* Colors = nullptr;
    const float* Strengths = nullptr;
    bool PeakOpacity = false;
    glm::dmat3 ListFrame{ 1.0 };
    const vtkIdType* GridIds = nullptr;
    glm::ivec3 GridDimensions{ 0 };
    glm::dmat3 GridAxes{ 1.0 };
    glm::dvec3 GridOrigin{ 0.0 };
    const float* Normals = nullptr;
    const float* SphericalHarmonics = nullptr;
    int SphericalHarmonicsDegree = 0;
  };

  /**
   * Sets the kernels: the arrays must stay valid until the next call. Clears the lists, which
   * are rebuilt when a frame needs them.
   */
  void SetKernels(const Kernels& kernels);

  /**
   * The lighting of kernels with normals (SplatLighting.h): lights in eye coordinates, the
   * material, and whether a normal facing away from the eye is turned towards it (two-sided
   * lighting, as VTK's volume mappers do for gradients). Each kernel is shaded once per frame
   * at its center (pre-shaded splats, as in Westover's splatting), in both backends.
   */
  void SetLighting(
    const std::vector<splat::Light>& lights, const splat::Material& material, bool twoSided);
  const std::vector<splat::Light>& GetLights() const { return this->Lights; }
  const splat::Material& GetMaterial() const { return this->Material; }
  bool GetTwoSidedLighting() const { return this->TwoSidedLighting; }

  /**
   * Window-space depth in [0, 1] of the opaque scene per pixel (row by row from the bottom);
   * kernels whose center lies behind it do not reach the pixel. Empty (the default) for none.
   */
  void SetSceneDepths(std::vector<float> depths) { this->SceneDepths = std::move(depths); }

  /**
   * Renders the kernels. After it, GetColors() holds the image and the statistics what was done.
   */
  void Render(const Camera& camera);

  /**
   * Per pixel, row by row from the bottom: premultiplied RGBA, alpha 0 where no kernel reaches
   * the pixel.
   */
  const std::vector<std::uint8_t>& GetColors() const { return this->Colors; }

  /**
   * The same before quantization, RGBA floats.
   */
  const std::vector<float>& GetImage() const { return this->Image; }

  ///@{
  /**
   * What the last frame did (paper 003, table 1): whether each list (0, 1, 2 for the X, Y and Z
   * axes, DepthList for the depth-sorted one) was traversed and how many kernels it splatted;
   * kernels left out because their cutoff ellipsoid reaches the near plane or lies behind the
   * eye, or because they lie outside the view frustum; and the comparison sorts done (list
   * builds of point sets and per-frame depth sorts; never for image data), the list builds and
   * the evaluations of the kernels' spherical-harmonic colors since this object was made.
   */
  bool GetListTraversed(int list) const;
  vtkIdType GetProjectedCount(int list) const;
  vtkIdType GetProjectedCount() const;
  vtkGetMacro(NearPlaneCount, vtkIdType);
  vtkGetMacro(FrustumCulledCount, vtkIdType);
  vtkGetMacro(SortCount, vtkIdType);
  vtkGetMacro(ListBuildCount, vtkIdType);
  vtkGetMacro(ViewColorCount, vtkIdType);
  ///@}

  /**
   * List `list` (0, 1, 2 for the X, Y and Z axes of ListFrame): the kernels' indices in
   * ascending order along the axis, built if missing (the grid's sheets for image data, a sort by
   * position for point sets). The OpenGL backend draws in this order too.
   */
  const std::vector<vtkIdType>& GetList(int list);

  // Per-frame data of the implementation; declared here so that its helper functions can name
  // them.
  struct ScreenKernel;
  struct PixelLists;

protected:
  vtkVolumeSplatRasterizer();
  ~vtkVolumeSplatRasterizer() override;

  /// Builds list `list` if it is missing: sheets of the grid, or a sort by position.
  void BuildList(int list);
  /// The per-frame depth order of the kept kernels.
  void BuildDepthList();
  /// The frame through vtkVolumeSplatSheetCompositor; false where it does not apply.
  bool RenderSheets(const Camera& camera, const std::array<bool, 4>& used);
  /// The frame of a capture in its depth order, through vtkGaussianSplatRasterizer.
  void RenderCaptures(const Camera& camera);
  /// The kernels' colors for this frame: seen from the camera (spherical harmonics), then
  /// shaded (SetLighting) where the kernels have normals.
  const float* FrameColors(const Camera& camera);
  /// The opaque scene's eye depths per pixel (SetSceneDepths), empty for none.
  std::vector<float> SceneEyeDepths(const Camera& camera) const;
  /// Merges the lists' buffers into the image's pixels [first, last).
  void MergeBuffers(std::size_t first, std::size_t last, const std::array<bool, 4>& used);
  /// The same for every pixel, in parallel.
  void MergeAllBuffers(const std::array<bool, 4>& used);
  /// The color of a kernel at eye position `eye` lit with its model normal (SetLighting).
  glm::vec3 ShadeKernel(const glm::vec3& color, const glm::vec3& eye,
    const glm::mat3& normalToEye, const float* modelNormal, bool parallelProjection) const;
  /// The kernels' spherical-harmonic colors seen from `camera`: evaluated again only when the
  /// view point (or axis), the degree or the kernels changed. Null without harmonics.
  const float* UpdateViewColors(const Camera& camera, bool perspective);

  int OrderingMode = BLENDED;
  double BlendThreshold = 0.85;
  double Cutoff;
  int FootprintFilter = 0;
  int MaximumSphericalHarmonicsDegree = 3;
  bool SheetResampling = true;
  bool SheetMerging = true;
  bool SheetsUsed = false;

  Kernels Input;
  std::array<std::vector<vtkIdType>, 4> Lists;
  std::array<bool, 4> Traversed{};
  std::array<vtkIdType, 4> Projected{};
  vtkIdType NearPlaneCount = 0;
  vtkIdType FrustumCulledCount = 0;
  vtkIdType SortCount = 0;
  vtkIdType ListBuildCount = 0;
  vtkIdType ViewColorCount = 0;

  std::vector<splat::Light> Lights;
  splat::Material Material;
  bool TwoSidedLighting = true;

  std::vector<float> SceneDepths;
  std::vector<float> Image;
  std::vector<std::uint8_t> Colors;

private:
  vtkVolumeSplatRasterizer(const vtkVolumeSplatRasterizer&) = delete;
  void operator=(const vtkVolumeSplatRasterizer&) = delete;

  struct Internals;
  Internals* Internal;
};

#endif
