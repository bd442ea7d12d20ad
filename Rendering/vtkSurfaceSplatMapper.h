// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSurfaceSplatMapper
 * @brief   renders points with normals as screen-space EWA surface splats
 *
 * vtkSurfaceSplatMapper draws the points of a vtkPolyData as surfels: small oriented disks on the
 * tangent plane given by each point's normal, filtered with the screen-space EWA resampling kernel
 * of Zwicker et al. (Surface Splatting, 2001). The result is a hole-free, alias-free surface
 * without meshing the points. It is drawn by a vtkActor: the actor's matrix, the vtkProperty
 * (colors, ambient, diffuse, specular, lighting on/off) and the renderer's lights apply as for
 * vtkPolyDataMapper, and scalar coloring uses the usual mapper settings (lookup table, scalar
 * range, color mode, scalar mode, array selection). Splats are composited with depth into the
 * render window, so they occlude and are occluded by other actors correctly.
 *
 * Input:
 * - point normals (vtkSurfelGenerator or vtkPolyDataNormals make them);
 * - optionally, elliptical surfels: two tangent-axis arrays of 3-vectors (TangentAxis0ArrayName,
 *   TangentAxis1ArrayName, default "TangentAxis0" and "TangentAxis1") whose lengths are the
 *   ellipse's semi-axes; they replace the radius, and give the normal where none is present;
 * - an optional per-point opacity array (OpacityArrayName, default "Opacity"), multiplied with the
 *   actor's opacity and the alpha of the scalar colors;
 * - a per-point radius array (RadiusArrayName, default "Radius"), or the global Radius. The radius
 *   is the extent of the splat's disk at the default cutoff: the Gaussian basis function has
 *   variance Radius^2 / 2 (see SplatSurfelKernel.h). For points sampled with spacing h, a radius
 *   of h gives a partition of unity.
 * Points with a non-finite position, normal, radius or axis, a zero normal, a non-positive radius
 * or parallel axes are skipped and counted (GetNumberOfSkippedPoints), never drawn.
 * Normals may point either way (scans estimate them without a consistent orientation): they
 * are filtered on one side and the filtered normal is turned towards the viewer (two-sided
 * lighting), so that the edge-on splats of a silhouette, whose normals are nearly
 * perpendicular to the view, do not bend it; where a pixel sees its surface edge-on, it is
 * turned towards the view axis instead, so that disks overshooting a silhouette are not drawn
 * dark (splat::FacingNormal).
 *
 * Differential points (SetPrimitiveToDifferentialPoints; Kalaiah and Varshney, *Modeling and
 * Rendering of Points with Local Geometry*, 2003), as vtkDifferentialPointGenerator makes them:
 * each point is the rectangle on its tangent plane spanned by its principal directions
 * (PrincipalDirectionUArrayName, PrincipalDirectionVArrayName) times its half-widths
 * (ExtentsArrayName, 2 components), and every pixel it covers is shaded with the normal its
 * principal curvatures (PrincipalCurvaturesArrayName, 2 components) predict where the pixel's
 * ray meets the tangent plane (eq. 10 of the paper, computed exactly per pixel, where the paper
 * picked one of 256 precomputed normal maps). With the EWA filter (the default) each rectangle's
 * footprint is the Gaussian through its corners, band-limited by the screen low-pass and
 * normalized with its neighbors as surfels are, so that minified points do not alias; with
 * FilterMode UNFILTERED it is the paper's rectangle: weight 1 inside, the nearest surface of
 * the z-buffer, rectangles within the z threshold blended. The actor's rotation, translation
 * and uniform scale apply exactly; a non-uniform scale bends the predicted normals as if the
 * curvatures were unscaled.
 *
 * Each render leaves out what the frame does not need, and counts it: splats outside the view
 * frustum, splats facing away when the actor's property has BackfaceCulling on (for closed,
 * consistently oriented, opaque surfaces), and edge-on splats (foreshortened below a thousandth
 * of their face-on area), whose weight is negligible next to their neighbors.
 *
 * Transparency is order-independent within the mapper: a translucent input is splatted into a
 * frame buffer of NumberOfLayers fragments per pixel (paper 000, section 6) and blended back to
 * front. Edge antialiasing multiplies each pixel's coverage, estimated from its summed kernel
 * weights, into its alpha (section 7); the layers then keep what a partly covered edge shows
 * behind it. An opaque input without edge antialiasing keeps one fragment per pixel.
 *
 * Two backends render the same splats (SetBackend): the multithreaded CPU rasterizer
 * (vtkSurfaceSplatRasterizer, threads from vtkSMPTools, the same image for any number of
 * threads) and OpenGL shaders (vtkOpenGLSurfaceSplatRasterizer: visibility, attribute and
 * normalization passes, layers peeled front to back). AUTO, the default, picks OpenGL on a
 * hardware GPU and the CPU under a software OpenGL renderer such as llvmpipe. Either result is
 * drawn into the OpenGL framebuffer with its depth.
 *
 * Hardware picking (vtkHardwareSelector, e.g. through vtkRenderer::PickProp or
 * vtkRenderedAreaPicker) selects splats by the id of their input point, with either backend.
 *
 * @sa vtkSurfaceSplatRasterizer vtkSurfelGenerator vtkPointGaussianMapper
 */
#ifndef vtkSurfaceSplatMapper_h
#define vtkSurfaceSplatMapper_h

#include "SplatRenderingModule.h" // For export macro
#include "vtkNew.h"              // For vtkNew
#include "vtkPolyDataMapper.h"
#include "vtkSplatBackend.h" // For the backend enumeration

#include <memory> // For std::unique_ptr

class vtkHardwareSelector;
// Not wrapped: the rasterizers' interface is GLM types.
class vtkOpenGLImageDepthCompositor;
class vtkOpenGLSurfaceSplatRasterizer;
class vtkSurfaceSplatRasterizer;

class SPLATRENDERING_EXPORT vtkSurfaceSplatMapper : public vtkPolyDataMapper
{
public:
  static vtkSurfaceSplatMapper* New();
  vtkTypeMacro(vtkSurfaceSplatMapper, vtkPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Radius of every splat when the input has no radius array. Default 1.
   */
  vtkSetClampMacro(Radius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /**
   * Name of the point-data array of per-point radii. Default "Radius".
   */
  vtkSetStringMacro(RadiusArrayName);
  vtkGetStringMacro(RadiusArrayName);
  ///@}

  ///@{
  /**
   * Cutoff on the exponent of the resampling kernel: a kernel is evaluated where
   * 1/2 x^T M^-1 x < Cutoff. A larger cutoff blends more neighbors into each pixel: it costs
   * more and blurs more, but fills wider gaps between scattered points.
   *
   * Default 0, automatic: 0.5 where the surfels still cover their surface at that cutoff,
   * else 0.6, else the paper's 1 (SetCutoffToPaper) where they cover it at 1, else 2, 3 or 4,
   * whichever first covers as 4 does. The test is done once per input, in object space, on samples of the surfels' disks
   * (SplatSurfelCoverage.h), each cutoff against a wider one: surfels on a mesh's vertices with
   * the radius of their longest edge pass at 0.5; a grid whose radius is its spacing passes at
   * 0.6 (its disks at 0.5 only touch, and the pixels between them would be partly
   * transparent); scattered points whose radii only reach their nearest neighbors pass at
   * neither 0.5 nor 1, and at 2 often still leave a percent of small holes. With colors from scalars, splats small enough for the screen low-pass
   * to be a sizable part of their kernel (largest warped variance up to 8 pixels^2, fading
   * out by 32; splat::SplatCutoff) take at least the paper's 1: a tighter cutoff truncates
   * the low-pass and lets colors that change from splat to splat alias.
   * Why: in `splat_report`'s tables (512x384, CPU), the tight cutoff draws magnified splats
   * sharper than 1, faster, and more exactly where the surfels cover at it (RMSE 0.0165
   * against 0.0205 on the bunny, 0.0322 against 0.0414 on the armadillo); on points scattered
   * over the armadillo 0.5 leaves holes (0.0615) and 1 speckles of background (0.0321), which
   * 2 closes but for a few (0.0236; there 2 leaves 1.1 % of what 4 covers open and 3 0.3 %:
   * 3 gives 0.0224, 4 0.0222 in more time). On the checkerboard's colors the
   * paper's 1 everywhere blurs the magnified checks (0.0834) and 0.6 everywhere aliases the
   * small splats (0.0764); the automatic cutoff, 0.6 raised to 1 for the small splats, gives
   * 0.0664.
   * Differential points keep the paper's cutoff; a cutoff set by hand holds for every splat.
   * GetLastCutoff() tells what the last render used (for colors, where splats are large).
   */
  void SetCutoff(double cutoff);
  vtkGetMacro(Cutoff, double);
  void SetCutoffToAutomatic() { this->SetCutoff(0.0); }
  void SetCutoffToPaper() { this->SetCutoff(1.0); }
  vtkGetMacro(LastCutoff, double);
  ///@}

  ///@{
  /**
   * Variance, in pixels^2, of the EWA filter's screen low-pass for magnified splats: the
   * paper's unit low-pass applies to splats below a pixel (warped variance up to 0.75 pixels^2)
   * and fades to this one at 1.5 pixels^2, where a splat's own reconstruction is wider than a
   * pixel (splat::LowPassVariance). 1 (SetMagnifiedLowPassVarianceToPaper) is the paper's
   * filter for every splat; values down to 1/12 (a pixel's box filter) are allowed.
   *
   * Default 0, automatic: for surfels of one color, 1/12 for every splat, minified ones too
   * (each then draws its own kernel, see SetMinifiedVariance); for colors from scalars the
   * paper's 1, since a smaller low-pass lets colors alias wherever they change from splat to
   * splat. Set by hand, the variance holds for magnified splats and minified ones keep the
   * paper's. Minified surfels must overlap, as surfels of a surface do, to cover the pixel
   * centers under the box filter; the paper's filter draws even lone ones (points far
   * smaller than their spacing) a pixel wide.
   * Why: in `splat_report`'s tables (512x384, CPU) the unit low-pass only blurs a magnified
   * surface's shading and silhouettes against the supersampled mesh: RMSE 0.0165 against
   * 0.0184 on the bunny seen whole, 0.0322 against 0.0340 on the armadillo, no slower. On the
   * 1 M-surfel sphere seen whole, about 17 surfels to a pixel, it spreads the silhouette over
   * three pixels: 0.0029 summed per pixel under it against 0.0009 at 1/12 (the level of
   * detail drawing its silhouettes front to back, see vtkSurfelHierarchy), in about a fifth
   * more time. No low-pass at all (FilterMode UNFILTERED) reaches 0.0009 too, with
   * silhouettes that are not antialiased. On the checkerboard's colors 1/12 would alias
   * (0.1213 against 0.0834). GetLastMagnifiedLowPassVariance() and
   * GetLastMinifiedLowPassVariance() tell what the last render used.
   */
  void SetMagnifiedLowPassVariance(double variance);
  vtkGetMacro(MagnifiedLowPassVariance, double);
  void SetMagnifiedLowPassVarianceToAutomatic() { this->SetMagnifiedLowPassVariance(0.0); }
  void SetMagnifiedLowPassVarianceToPaper() { this->SetMagnifiedLowPassVariance(1.0); }
  vtkGetMacro(LastMagnifiedLowPassVariance, double);
  vtkGetMacro(LastMinifiedLowPassVariance, double);
  ///@}

  ///@{
  /**
   * CPU backend: opaque surfels whose warped basis function has no variance above this many
   * pixels^2 (no larger than the screen low-pass filter: the usual case for dense clouds seen
   * whole) are set up in single precision, in batches. Under the paper's low-pass (colors from
   * scalars) they are summed into the pixel holding their center and spread by the low-pass
   * filter once per pixel, instead of each drawing its own kernel over several pixels: several
   * times faster on dense data, within a small error of the exact kernels (see
   * vtkSurfaceSplatRasterizer::SetMinifiedVariance). Surfels of one color, which take a
   * pixel's box filter there (SetMagnifiedLowPassVariance), each draw their kernel, which
   * reaches only the pixel centers next to it. A frame takes this path only where a sample of
   * the surfels
   * in view finds at least a quarter of them minified: on a magnified scan it only costs
   * (the bunny seen whole drew 25 % slower with it, one splat in 34620 minified). Default
   * 0.75; 0 draws every splat with its exact kernel.
   */
  void SetMinifiedVariance(double variance);
  double GetMinifiedVariance();
  ///@}

  /**
   * CPU backend: levels of detail for opaque surfels sampled more densely than the pixels. A
   * hierarchy of merged surfels (vtkSurfelHierarchy) is built once per input, on the first
   * frame that needs it, and each frame draws, region by region, its coarsest level whose
   * splats are still minified (see SetMinifiedVariance): far fewer splats for the same image
   * where many surfels fall in each pixel. Default on; it needs MinifiedVariance above 0, the
   * EWA filter and a frame that takes the minified path, and does nothing for translucent
   * surfels or differential points.
   */
  vtkSetMacro(LevelOfDetail, bool);
  vtkGetMacro(LevelOfDetail, bool);
  vtkBooleanMacro(LevelOfDetail, bool);

  ///@{
  /**
   * Name of the point-data array of per-point opacities in [0, 1]. Default "Opacity".
   */
  vtkSetStringMacro(OpacityArrayName);
  vtkGetStringMacro(OpacityArrayName);
  ///@}

  ///@{
  /**
   * Fragments kept per pixel for translucent inputs and for antialiased edges (which show the
   * surfaces behind them), 1 to 8. Where more opaque surfaces meet in a pixel, a sliver (under
   * 2 % of full coverage: the low-pass fringe of grazing splats at a silhouette) gives way
   * first, else the farthest.
   *
   * Default 0, automatic: on the CPU 5, or the paper's 3 (SetNumberOfLayersToPaper) in frames
   * that draw minified surfels of one color each with its own kernel (dense clouds seen whole,
   * see SetMinifiedVariance) and in opaque EWA frames whose splats are magnified well past a
   * pixel (a median warped variance of 16 pixels^2 or more: scans seen close, where 5 layers
   * gain nothing and cost about 5 % of the time); on OpenGL the paper's 3, since each layer is
   * a pass over every splat. Why: at a partly covered edge, the partial fragments of a grazing
   * surface can fill three layers and push out the fully covered surface behind them, which
   * then lets the background through. In `splat_report`'s tables (512x384, CPU) 5 layers take
   * the RMSE from 0.0140 to 0.0139 on the bunny seen whole, 0.0219 to 0.0216 on the armadillo's
   * points and 0.0665 to 0.0661 on the checkerboard, in about the same time (8 layers gain at
   * most 0.2 % more, slower). Minified splats, thinner in depth than a pixel's stretch of a
   * grazing surface, split it into a fragment per z threshold, and more layers would blend
   * more of those slices of one surface over each other: on the 1 M-surfel sphere seen whole
   * 3 layers give 0.00088, 5 give 0.00104. On the CPU a layer holds 36 bytes per pixel, and 60
   * more in frames that sum minified splats per pixel (colors): at 1920x1080 5 layers take
   * 356 MB, or 949 MB with the sums, against 214 and 569 MB for 3. GetLastNumberOfLayers()
   * tells what the last render kept (1 for an opaque input without edge antialiasing).
   */
  void SetNumberOfLayers(int layers);
  int GetNumberOfLayers();
  void SetNumberOfLayersToAutomatic() { this->SetNumberOfLayers(0); }
  void SetNumberOfLayersToPaper();
  int GetLastNumberOfLayers();
  ///@}

  ///@{
  /**
   * Edge antialiasing by coverage. Default on.
   */
  void SetEdgeAntialiasing(bool antialiasing);
  bool GetEdgeAntialiasing();
  vtkBooleanMacro(EdgeAntialiasing, bool);
  ///@}

  ///@{
  /**
   * Summed kernel weight above which a pixel counts as fully covered, for cutoff 1 (scaled
   * with the cutoff's share of kernel mass for others): tau of paper 000, section 7. Edge
   * antialiasing draws a pixel with less as partly covered.
   *
   * Default 0, automatic: the paper's 0.4 (SetCoverageThresholdToPaper), or 0.8 for surfels
   * of one color under the automatic cutoff and low-pass where the automatic cutoff's coverage
   * test finds that their surface stays covered at 0.8 (the surfels of meshes and of dense
   * clouds; not scattered points whose radii only just reach their neighbors). Why: under a
   * pixel's box filter a silhouette's summed weight falls from the surface's to none within
   * about a pixel, so 0.4 draws pixels half covered as fully covered, with the grazing shading
   * of the rim. In `splat_report`'s tables (512x384, CPU) 0.8 takes the RMSE from 0.0165 to
   * 0.0143 on the bunny seen whole, 0.0321 to 0.0297 on the armadillo, 0.0015 to 0.0012 on
   * the 1 M-surfel sphere; on the armadillo's scattered points it would let the background
   * through (0.0224 to 0.0456: the test keeps 0.4 there), and on the checkerboard's colors,
   * under the paper's low-pass, it costs too (0.0664 to 0.0924). GetLastCoverageThreshold()
   * tells what the last render used.
   */
  vtkSetClampMacro(CoverageThreshold, double, 0.0, 1.0);
  vtkGetMacro(CoverageThreshold, double);
  void SetCoverageThresholdToAutomatic() { this->SetCoverageThreshold(0.0); }
  void SetCoverageThresholdToPaper() { this->SetCoverageThreshold(0.4); }
  vtkGetMacro(LastCoverageThreshold, double);
  ///@}

  ///@{
  /**
   * Names of the point-data arrays of tangent axes for elliptical surfels. Default
   * "TangentAxis0" and "TangentAxis1".
   */
  vtkSetStringMacro(TangentAxis0ArrayName);
  vtkGetStringMacro(TangentAxis0ArrayName);
  vtkSetStringMacro(TangentAxis1ArrayName);
  vtkGetStringMacro(TangentAxis1ArrayName);
  ///@}

  /**
   * The screen-space filter of each splat (paper 000, figure 8).
   */
  enum FilterModes
  {
    EWA = 0,        ///< exact screen-space EWA: warped basis function convolved with the low-pass
    CIRCULAR = 1,   ///< circles with the major axis of the EWA ellipse: blurs magnified areas
    UNFILTERED = 2, ///< warped ellipses without the low-pass: aliases minified areas
    APPROXIMATE = 3 ///< OpenGL only: the larger of the object-space kernel and the low-pass
  };

  ///@{
  /**
   * Screen-space filter: EWA (default), CIRCULAR, UNFILTERED or APPROXIMATE. CIRCULAR and
   * UNFILTERED are the baselines of the error-against-time report. APPROXIMATE is the cheaper
   * filter of GPU splatting (Botsch et al. 2005): per fragment, the larger of the object-space
   * Gaussian where the pixel's ray meets the tangent plane and the screen-space low-pass; the
   * OpenGL backend only, the CPU backend draws EWA instead.
   */
  vtkSetClampMacro(FilterMode, int, EWA, APPROXIMATE);
  vtkGetMacro(FilterMode, int);
  void SetFilterModeToEWA() { this->SetFilterMode(EWA); }
  void SetFilterModeToCircular() { this->SetFilterMode(CIRCULAR); }
  void SetFilterModeToUnfiltered() { this->SetFilterMode(UNFILTERED); }
  void SetFilterModeToApproximate() { this->SetFilterMode(APPROXIMATE); }
  ///@}

  /**
   * What each point is drawn as.
   */
  enum Primitives
  {
    SURFELS = 0,            ///< Gaussian surfels of a normal and a radius or two tangent axes
    DIFFERENTIAL_POINTS = 1 ///< rectangles with principal curvatures, shaded per pixel
  };

  ///@{
  /**
   * SURFELS (default) or DIFFERENTIAL_POINTS (see the class description).
   */
  vtkSetClampMacro(Primitive, int, SURFELS, DIFFERENTIAL_POINTS);
  vtkGetMacro(Primitive, int);
  void SetPrimitiveToSurfels() { this->SetPrimitive(SURFELS); }
  void SetPrimitiveToDifferentialPoints() { this->SetPrimitive(DIFFERENTIAL_POINTS); }
  ///@}

  ///@{
  /**
   * Names of the differential points' point-data arrays: the principal directions (3
   * components each; default "PrincipalDirectionU" and "PrincipalDirectionV"), the principal
   * curvatures along them (2 components, default "PrincipalCurvatures") and the rectangle's
   * half-widths along them (2 components, default "Extents"), as vtkDifferentialPointGenerator
   * names them. The normal is the input's point normals, or U x V without them.
   */
  vtkSetStringMacro(PrincipalDirectionUArrayName);
  vtkGetStringMacro(PrincipalDirectionUArrayName);
  vtkSetStringMacro(PrincipalDirectionVArrayName);
  vtkGetStringMacro(PrincipalDirectionVArrayName);
  vtkSetStringMacro(PrincipalCurvaturesArrayName);
  vtkGetStringMacro(PrincipalCurvaturesArrayName);
  vtkSetStringMacro(ExtentsArrayName);
  vtkGetStringMacro(ExtentsArrayName);
  ///@}

  ///@{
  /**
   * The backend: vtkSplatBackend::AUTO (default: OpenGL on a hardware GPU, the CPU under a
   * software OpenGL renderer), vtkSplatBackend::CPU or vtkSplatBackend::OPENGL.
   */
  vtkSetClampMacro(Backend, int, vtkSplatBackend::AUTO, vtkSplatBackend::OPENGL);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(vtkSplatBackend::AUTO); }
  void SetBackendToCPU() { this->SetBackend(vtkSplatBackend::CPU); }
  void SetBackendToOpenGL() { this->SetBackend(vtkSplatBackend::OPENGL); }
  ///@}

  /**
   * The backend that drew the last render: vtkSplatBackend::CPU or OPENGL (AUTO before the
   * first render).
   */
  vtkGetMacro(LastBackend, int);

  ///@{
  /**
   * Z threshold of the accumulate-or-replace decision, in units of each splat's radius in eye
   * space: contributions whose tangent-plane depths differ by less belong to the same surface.
   * Default 1.
   */
  void SetDepthThreshold(double threshold);
  double GetDepthThreshold();
  ///@}

  ///@{
  /**
   * What the last render did: points given to the rasterizer; splats drawn; surfels drawn
   * through merged splats of the level of detail (see LevelOfDetail; a merged splat counts
   * once among the splats drawn and left out); splats left out (in total, and outside the
   * frustum, back-facing with backface culling, or negligible; the total also counts the
   * back-facing splats of the level of detail found hidden behind nearer surfaces); input
   * points skipped as invalid; and the wall-clock time of the render in milliseconds.
   * The OpenGL backend leaves splats out in its vertex shader without counting them: the
   * splat counts are -1 after an OpenGL render.
   */
  vtkGetMacro(NumberOfSplats, vtkIdType);
  vtkIdType GetNumberOfRenderedSplats();
  vtkIdType GetNumberOfMergedSplats();
  vtkIdType GetNumberOfCulledSplats();
  vtkIdType GetNumberOfFrustumCulledSplats();
  vtkIdType GetNumberOfBackfaceCulledSplats();
  vtkIdType GetNumberOfNegligibleSplats();
  vtkGetMacro(NumberOfSkippedPoints, vtkIdType);
  vtkGetMacro(LastRenderTimeInMilliseconds, double);
  ///@}

  /**
   * Draws the input into the renderer.
   */
  void RenderPiece(vtkRenderer* ren, vtkActor* act) override;

  void ReleaseGraphicsResources(vtkWindow* window) override;

  /**
   * Splats can be picked by point with vtkHardwareSelector.
   */
  bool GetSupportsSelection() override { return true; }

  /**
   * Each splat takes its point's mapped color: never a color texture, whatever
   * InterpolateScalarsBeforeMapping says (ParaView turns it on), since a texture leaves
   * MapScalars without colors.
   */
  int CanUseTextureMapForColoring(vtkDataObject*) override { return 0; }

protected:
  vtkSurfaceSplatMapper();
  ~vtkSurfaceSplatMapper() override;

  /**
   * The input's bounds grown by the largest radius, so camera resets and clipping ranges
   * include whole splats.
   */
  void ComputeBounds() override;

  ///@{
  /**
   * How far splats reach from their points, for the bounds: the largest radius or tangent axis
   * of surfels, and the largest filtered footprint of differential points. Non-finite values
   * are left out.
   */
  double LargestSurfelRadius();
  double LargestDifferentialExtent();
  ///@}

  /**
   * Rebuilds the surfel arrays when the input, the mapper or the actor's colors changed.
   * Returns false when the input cannot be drawn.
   */
  bool UpdateSurfels(vtkActor* actor);

  /**
   * The cutoff and coverage threshold to draw with (LastCutoff, LastCoverageThreshold): Cutoff
   * and CoverageThreshold, or what the input's coverage test picks where they are automatic;
   * `boxFilter`: the splats take a pixel's box filter.
   */
  void ChooseCoverage(bool boxFilter);

  /**
   * Draws the splats into the selector's current pass.
   */
  void RenderSelection(vtkRenderer* ren, vtkActor* actor, vtkHardwareSelector* selector);

  double Radius = 1.0;
  char* RadiusArrayName = nullptr;
  char* OpacityArrayName = nullptr;
  char* TangentAxis0ArrayName = nullptr;
  char* TangentAxis1ArrayName = nullptr;
  int FilterMode = EWA;
  int Primitive = SURFELS;
  char* PrincipalDirectionUArrayName = nullptr;
  char* PrincipalDirectionVArrayName = nullptr;
  char* PrincipalCurvaturesArrayName = nullptr;
  char* ExtentsArrayName = nullptr;
  int Backend = vtkSplatBackend::AUTO;
  int LastBackend = vtkSplatBackend::AUTO;
  bool LevelOfDetail = true;
  double Cutoff = 0.0;
  double LastCutoff = 0.0;
  double CoverageThreshold = 0.0;
  double LastCoverageThreshold = 0.0;
  double MagnifiedLowPassVariance = 0.0;
  double LastMagnifiedLowPassVariance = 0.0;
  double LastMinifiedLowPassVariance = 1.0;

  vtkIdType NumberOfSplats = 0;
  vtkIdType NumberOfSkippedPoints = 0;
  double LastRenderTimeInMilliseconds = 0.0;

  vtkNew<vtkSurfaceSplatRasterizer> Rasterizer;
  vtkNew<vtkOpenGLSurfaceSplatRasterizer> OpenGLRasterizer;
  vtkNew<vtkOpenGLImageDepthCompositor> Compositor;

private:
  vtkSurfaceSplatMapper(const vtkSurfaceSplatMapper&) = delete;
  void operator=(const vtkSurfaceSplatMapper&) = delete;

  struct SurfelArrays;
  std::unique_ptr<SurfelArrays> Surfels;
};

#endif
