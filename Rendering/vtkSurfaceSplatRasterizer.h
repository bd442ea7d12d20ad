// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSurfaceSplatRasterizer
 * @brief   multithreaded CPU rasterizer for screen-space EWA surface splatting
 *
 * vtkSurfaceSplatRasterizer is the CPU backend of vtkSurfaceSplatMapper and the reference
 * implementation of the project's exactness tests. It takes surfels (positions, normals, tangent
 * axes, colors) and a camera, and produces a shaded RGBA image with a window-space depth per pixel.
 *
 * A frame has three steps (paper 000, section 4):
 * 1. Setup, parallel over surfels: the Jacobian, the resampling kernel of eq. (6), its bounding
 *    box, and the depth of its tangent plane as a function of the pixel (SplatSurfelKernel.h).
 * 2. Splatting, parallel over horizontal bands of the image: each band visits the kernels that
 *    overlap it in input order, so the image does not depend on the number of threads. Opaque
 *    scenes keep the nearest surface of each pixel (and, with edge antialiasing, the ones
 *    behind it that a partly covered edge shows, up to NumberOfLayers): a contribution is
 *    accumulated into a surface within the z threshold (a multiple of the surfel's eye-space
 *    radius), inserted in front, or dropped behind. Translucent scenes keep up to NumberOfLayers fragments per pixel (section 6):
 *    accumulate-or-separate, insertion into a free layer, or merging of the two fragments
 *    nearest in depth, shaded first (eq. 12). Opaque minified splats (see MinifiedVariance) are
 *    summed into the pixel holding their center instead (2b), and each pixel then gathers its
 *    neighbors' sums through the low-pass filter into its fragments (2c).
 * 3. Resolve: normalization by the summed weights (eq. 9), deferred shading of the filtered
 *    normal with VTK's lighting model (SplatLighting.h), coverage from the summed weights
 *    multiplied into alpha (edge antialiasing, section 7), and a back-to-front blend.
 *
 * Differential points (Kalaiah and Varshney 2003) are surfels with principal curvatures: their
 * axes are the principal directions scaled by the rectangle's half-widths, and each pixel they
 * cover takes the normal they predict where its view ray meets their tangent plane
 * (SplatDifferentialPointNormal.h, eq. 10 of the paper), computed exactly. With the EWA filter
 * a point's footprint is the elliptical Gaussian through its rectangle's corners (axes sqrt(2)
 * times the half-widths) with the mass of the rectangle's area, band-limited by the screen
 * low-pass and normalized like a surfel's; unfiltered, it is the paper's rectangle itself: weight
 * 1 inside, nothing outside, blended with the rectangles within the z threshold.
 *
 * Surfels are not validated here: the caller passes finite data only.
 *
 * @sa vtkSurfaceSplatMapper
 */
#ifndef vtkSurfaceSplatRasterizer_h
#define vtkSurfaceSplatRasterizer_h

#include "SplatRenderingModule.h" // For export macro
#include "vtkObject.h"

#include "SplatLighting.h"     // For splat::Light, splat::Material
#include "SplatSurfelKernel.h" // For splat::KernelFilter

#include <glm/glm.hpp> // For the camera matrices

#include <cstdint> // For std::uint8_t
#include <vector>  // For the frame buffer

class vtkSurfelHierarchy;
namespace splat
{
struct SurfaceFragment;
}


class SPLATRENDERING_EXPORT vtkSurfaceSplatRasterizer : public vtkObject
{
public:
  static vtkSurfaceSplatRasterizer* New();
  vtkTypeMacro(vtkSurfaceSplatRasterizer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Cutoff on the kernel exponent beta (paper 000, section 4). Default 1, the paper's choice.
   */
  vtkSetClampMacro(Cutoff, double, 1e-3, 50.0);
  vtkGetMacro(Cutoff, double);

  /**
   * EWA filter: the least cutoff of splats whose screen low-pass is a sizable part of their
   * kernel (largest warped variance up to splat::CutoffFadeStart pixels^2, fading to Cutoff by
   * splat::CutoffFadeEnd; see splat::SplatCutoff), for colors that change from splat to splat,
   * which a low-pass cut short lets alias. Each such splat's weight is scaled to the mass it
   * would keep at Cutoff, so the coverage threshold holds for all. Default 0: Cutoff for every
   * splat.
   */
  vtkSetClampMacro(AntialiasingCutoff, double, 0.0, 50.0);
  vtkGetMacro(AntialiasingCutoff, double);

  /**
   * Z threshold of the accumulate-or-replace decision, in units of each surfel's eye-space
   * radius: contributions whose depths differ by less are the same surface. Default 1.
   */
  vtkSetClampMacro(DepthThreshold, double, 0.0, 1e3);
  vtkGetMacro(DepthThreshold, double);

  /// Most fragments a pixel can hold.
  static constexpr int MaximumLayers = 8;

  /// The paper's fragments per pixel.
  static constexpr int PaperLayers = 3;
  /// What NumberOfLayers 0 gives a frame whose splats are neither minified surfels drawn each
  /// with its own kernel nor opaque splats magnified well past a pixel.
  static constexpr int AutomaticLayers = 5;

  /**
   * Fragments per pixel (paper 000, section 6) for translucent scenes, and for the partly
   * covered edges of opaque ones with edge antialiasing. Opaque scenes without edge
   * antialiasing keep one fragment per pixel and allocate no more. Default 0, automatic: the
   * paper's 3 in frames that draw minified surfels each with its own kernel (surfels of one
   * color under a low-pass below 1, see MinifiedLowPassVariance), else 5 (see
   * vtkSurfaceSplatMapper::SetNumberOfLayers for why). GetLastNumberOfLayers() tells what the
   * last frame kept.
   */
  vtkSetClampMacro(NumberOfLayers, int, 0, MaximumLayers);
  vtkGetMacro(NumberOfLayers, int);
  int GetLastNumberOfLayers() const { return this->Layers; }

  /**
   * Edge antialiasing: a pixel's summed kernel weight q below the full-coverage threshold
   * tau scales its alpha by q / tau (paper 000, section 7). Default on.
   */
  vtkSetMacro(EdgeAntialiasing, bool);
  vtkGetMacro(EdgeAntialiasing, bool);
  vtkBooleanMacro(EdgeAntialiasing, bool);

  /**
   * The full-coverage threshold tau for the default cutoff 1. Default 0.4, the paper's value.
   * For another cutoff c it is scaled by the share of kernel mass inside the cutoff,
   * (1 - e^-c) / (1 - e^-1).
   */
  vtkSetClampMacro(CoverageThreshold, double, 1e-3, 1.0);
  vtkGetMacro(CoverageThreshold, double);

  /**
   * Window-space depth in [0, 1] of the opaque scene per pixel (row by row from the bottom);
   * contributions behind it are dropped. Empty (the default) for none.
   */
  void SetSceneDepths(std::vector<float> depths) { this->SceneDepths = std::move(depths); }

  /**
   * The summed kernel weight at which a pixel counts as fully covered: the coverage threshold
   * scaled to the cutoff's share of kernel mass.
   */
  float FullCoverageWeight() const;

  /**
   * The screen-space filter: exact EWA (default), circular or unfiltered (paper 000, figure 8).
   */
  void SetFilter(splat::KernelFilter filter) { this->Filter = filter; }
  splat::KernelFilter GetFilter() const { return this->Filter; }

  /**
   * Variance of the EWA filter's screen low-pass for magnified splats, in pixels^2
   * (splat::LowPassVariance): 1, the default, is the paper's filter for every splat; down to
   * splat::BoxFilterVariance for splats of one color.
   */
  vtkSetClampMacro(MagnifiedLowPassVariance, double, splat::BoxFilterVariance, 1.0);
  vtkGetMacro(MagnifiedLowPassVariance, double);

  /**
   * Variance of the EWA filter's screen low-pass for minified splats, in pixels^2
   * (splat::LowPassVariance): 1, the default, is the paper's filter, under which the minified
   * splats are summed per pixel (MinifiedVariance); below it each minified splat is drawn with
   * its own kernel, which then reaches only the pixel centers next to it. Splats of one color
   * have no colors to alias: splat::BoxFilterVariance, a pixel's own footprint, keeps their
   * silhouettes antialiased without spreading them over the neighbors (splat_report's 1
   * M-surfel sphere: RMSE 0.0009 against 0.0029 summed). 0 samples the surface they
   * reconstruct at the pixel centers (0.0009 there too, and silhouettes without partial
   * coverage).
   */
  vtkSetClampMacro(MinifiedLowPassVariance, double, 0.0, 1.0);
  vtkGetMacro(MinifiedLowPassVariance, double);

  /**
   * Minified splats, accumulated per pixel: an opaque EWA splat whose warped basis function
   * (J Vr J^T of eq. 6) has no variance above this many pixels^2 is about as small as the screen
   * low-pass filter or smaller, so its resampling kernel is nearly a Gaussian of variance
   * 1 + its mean warped variance, centered on it. Such splats are summed into the pixel that
   * holds their center (weights, attributes, and the weighted means of their centers, depth
   * slopes and warped variances, with the z threshold of the exact path), and each pixel then
   * gathers its neighbors' sums through that Gaussian at their mean centers: one write per
   * splat instead of a kernel over several pixels. Under a MinifiedLowPassVariance below 1
   * they are not summed: each draws its kernel, set up from the same single-precision
   * projection. Default 0.75 (splats up to about 1.2 pixels apart); 0 draws every splat with
   * its exact kernel. Translucent scenes, differential points and the other filters always
   * take the exact kernel, and so does a frame where fewer than a quarter of a sample of the
   * surfels in view are minified (the path's single-precision setup of every splat would cost
   * more than it saves).
   */
  vtkSetClampMacro(MinifiedVariance, double, 0.0, 1.0);
  vtkGetMacro(MinifiedVariance, double);

  /**
   * Leave out splats whose normal faces away from the viewer: right for closed, opaque,
   * consistently oriented surfaces only. Default off (two-sided splats).
   */
  vtkSetMacro(BackfaceCulling, bool);
  vtkGetMacro(BackfaceCulling, bool);
  vtkBooleanMacro(BackfaceCulling, bool);

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
   * Surfels as arrays of n entries: positions and tangent axes are 3-vectors in model
   * coordinates (the axes' lengths are the semi-axes), normals unit 3-vectors, colors RGB in [0,1],
   * opacities in [0, 1] (null when all are 1). Differential points add their principal
   * curvatures (lambda_u, lambda_v along Axes0 and Axes1, signed as dN(u) = -lambda_u u, in
   * inverse model units); their axes are orthogonal, the principal directions scaled by the
   * rectangle's half-widths. Null for plain surfels.
   */
  struct Surfels
  {
    const double* Positions = nullptr;
    const float* Normals = nullptr;
    const float* Axes0 = nullptr;
    const float* Axes1 = nullptr;
    const float* Colors = nullptr;
    const float* Opacities = nullptr;
    const float* Curvatures = nullptr;
    std::size_t Count = 0;
    /// Coarser levels of these surfels, for minified splats (see vtkSurfelHierarchy): drawn
    /// where the EWA filter minifies opaque surfels. Null for none.
    const vtkSurfelHierarchy* Hierarchy = nullptr;

    /// Surfels over arrays held in vectors: 3 values per surfel, 1 opacity, 2 curvatures;
    /// empty opacities or curvatures for none.
    static Surfels Of(const std::vector<double>& positions, const std::vector<float>& normals,
      const std::vector<float>& axes0, const std::vector<float>& axes1,
      const std::vector<float>& colors, const std::vector<float>& opacities = {},
      const std::vector<float>& curvatures = {})
    {
      Surfels s;
      s.Positions = positions.data();
      s.Normals = normals.data();
      s.Axes0 = axes0.data();
      s.Axes1 = axes1.data();
      s.Colors = colors.data();
      s.Opacities = opacities.empty() ? nullptr : opacities.data();
      s.Curvatures = curvatures.empty() ? nullptr : curvatures.data();
      s.Count = normals.size() / 3;
      return s;
    }
  };

  /**
   * Splats the surfels and resolves the frame. After it, GetColors() and GetDepths() hold the
   * image and Get*Count() what was done.
   */
  void Render(const Surfels& surfels, const Camera& camera, const std::vector<splat::Light>& lights,
    const splat::Material& material);

  /**
   * Steps 1 and 2 only, unlit, for tests of the filter itself: see GetWeights().
   */
  void Splat(const Surfels& surfels, const Camera& camera);

  /**
   * Per pixel, row by row from the bottom: premultiplied RGBA (alpha 0 where no splat covers the
   * pixel) and the window-space depth in [0, 1] of the nearest surface.
   */
  const std::vector<std::uint8_t>& GetColors() const { return this->Colors; }
  const std::vector<float>& GetDepths() const { return this->Depths; }

  /**
   * The smallest box of pixels that holds every pixel the last frame covers, as x0, y0, x1, y1
   * (inclusive; x0 > x1 when it covers none): outside it the image is transparent.
   */
  const int* GetCoveredRegion() const { return this->CoveredRegion; }

  /**
   * After Splat(): the summed kernel weights of each pixel's nearest surface, before
   * normalization.
   */
  std::vector<float> GetWeights() const;

  // A pixel's surface and a splat after setup; declared here so that the implementation's
  // helper functions can name them.
  using Fragment = splat::SurfaceFragment;
  struct ScreenSplat;
  struct DifferentialSplat;

  ///@{
  /**
   * What the last frame did: splats drawn, of which minified (accumulated per pixel, see
   * MinifiedVariance); splats left out because they lie outside the view frustum (behind the
   * eye, wholly outside the near/far range, footprint outside the viewport), face away with
   * BackfaceCulling on, or are edge-on (negligible weight); and pixel contributions written.
   * A splat is a surfel or, with a hierarchy, a merged node of it: MergedCount is the number
   * of surfels the merged nodes among the splats stand for, and HiddenCount the splats left
   * out because they face away in a region of the hierarchy found hidden behind nearer, fully
   * covered surfaces.
   */
  vtkGetMacro(SplattedCount, vtkIdType);
  vtkGetMacro(MergedCount, vtkIdType);
  vtkGetMacro(HiddenCount, vtkIdType);
  vtkGetMacro(MinifiedCount, vtkIdType);
  vtkGetMacro(FrustumCulledCount, vtkIdType);
  vtkGetMacro(BackfaceCulledCount, vtkIdType);
  vtkGetMacro(NegligibleCount, vtkIdType);
  vtkGetMacro(FragmentCount, vtkIdType);
  ///@}

protected:
  vtkSurfaceSplatRasterizer();
  ~vtkSurfaceSplatRasterizer() override;

  void Splat(const Surfels& surfels, const Camera& camera, const std::vector<splat::Light>& lights,
    const splat::Material& material);
  /// Raises to full coverage the dips in the summed weight of opaque surfaces' interiors: before
  /// regions facing away are tested (RegionHidden), and before the fragments are resolved.
  void CloseCoverageDips();
  /// Whether the fragments drawn so far hide a region of back-facing splats: splat centers in
  /// a box in model coordinates, axes up to `reach` long.
  bool RegionHidden(
    const glm::dvec3& low, const glm::dvec3& high, double reach, double nearDepth) const;
  void AddLayered(Fragment* fragments, std::uint8_t& count, int x, int y, float z, float w,
    const float* normal, const ScreenSplat& s) const;
  /// Shaded premultiplied color and alpha (coverage included) of a fragment at pixel (x, y).
  glm::vec4 ShadeFragment(const Fragment& f, int x, int y) const;
  void Resolve();

  double Cutoff = 1.0;
  double DepthThreshold = 1.0;
  int NumberOfLayers = 0;
  bool EdgeAntialiasing = true;
  double CoverageThreshold = splat::PaperCoverageThreshold;
  splat::KernelFilter Filter = splat::KernelFilter::EWA;
  bool BackfaceCulling = false;

  double AntialiasingCutoff = 0.0;
  double MagnifiedLowPassVariance = 1.0;
  double MinifiedLowPassVariance = 1.0;
  double MinifiedVariance = 0.75;

  vtkIdType SplattedCount = 0;
  vtkIdType MinifiedCount = 0;
  vtkIdType MergedCount = 0;
  vtkIdType HiddenCount = 0;
  vtkIdType FrustumCulledCount = 0;
  vtkIdType BackfaceCulledCount = 0;
  vtkIdType NegligibleCount = 0;
  vtkIdType FragmentCount = 0;

  // What shading a fragment needs, for the frame being drawn.
  struct Frame
  {
    Camera View;
    glm::dmat4 ClipToEye{ 1.0 };
    const std::vector<splat::Light>* Lights = nullptr;
    const splat::Material* Surface = nullptr;
    float FullCoverage = 1.0f;
    // A fragment's eye position at pixel p = (x, y, 1) and eye depth d: RayOrigin p + d
    // RayDirection p (splat::PixelRays).
    glm::mat3 RayOrigin{ 0.0f };
    glm::mat3 RayDirection{ 0.0f };
    bool Perspective = true;
  };
  Frame CurrentFrame;
  int Layers = 1; // fragments per pixel in this frame
  std::vector<Fragment> Fragments;
  std::vector<std::uint8_t> FragmentCounts;
  std::vector<float> SceneDepths;
  std::vector<std::uint8_t> Colors;
  std::vector<float> Depths;
  int CoveredRegion[4] = { 0, 0, -1, -1 };

private:
  vtkSurfaceSplatRasterizer(const vtkSurfaceSplatRasterizer&) = delete;
  void operator=(const vtkSurfaceSplatRasterizer&) = delete;

  struct Internals;
  Internals* Internal;
};

#endif
