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
 * - point normals (required; vtkSurfelGenerator or vtkPolyDataNormals make them);
 * - a per-point radius array (RadiusArrayName, default "Radius"), or the global Radius. The radius
 *   is the extent of the splat's disk at the default cutoff: the Gaussian basis function has
 *   variance Radius^2 / 2 (see SplatSurfelKernel.h). For points sampled with spacing h, a radius
 *   of h gives a partition of unity.
 * Points with a non-finite position, normal or radius, a zero normal or a non-positive radius are
 * skipped and counted (GetNumberOfSkippedPoints), never drawn.
 *
 * Rendering runs on the multithreaded CPU rasterizer (vtkSurfaceSplatRasterizer, threads from
 * vtkSMPTools); the image and its depth are then drawn into the OpenGL framebuffer.
 *
 * @sa vtkSurfaceSplatRasterizer vtkSurfelGenerator vtkPointGaussianMapper
 */
#ifndef vtkSurfaceSplatMapper_h
#define vtkSurfaceSplatMapper_h

#include "SplatRenderingModule.h" // For export macro
#include "vtkNew.h"              // For vtkNew
#include "vtkPolyDataMapper.h"

#include <memory> // For std::unique_ptr

// Not wrapped: the rasterizer's interface is GLM types.
class vtkOpenGLImageDepthCompositor;
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
   * 1/2 x^T M^-1 x < Cutoff. Larger values cost more and blur less at the splats' edges.
   * Default 1, as in the paper.
   */
  void SetCutoff(double cutoff);
  double GetCutoff();
  ///@}

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
   * What the last render did: points given to the rasterizer, splats drawn, splats culled
   * (behind the eye, outside the near/far range or the viewport), input points skipped as
   * invalid, and the wall-clock time of the render in milliseconds.
   */
  vtkGetMacro(NumberOfSplats, vtkIdType);
  vtkIdType GetNumberOfRenderedSplats();
  vtkIdType GetNumberOfCulledSplats();
  vtkGetMacro(NumberOfSkippedPoints, vtkIdType);
  vtkGetMacro(LastRenderTimeInMilliseconds, double);
  ///@}

  /**
   * Draws the input into the renderer.
   */
  void RenderPiece(vtkRenderer* ren, vtkActor* act) override;

  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSurfaceSplatMapper();
  ~vtkSurfaceSplatMapper() override;

  /**
   * The input's bounds grown by the largest radius, so camera resets and clipping ranges
   * include whole splats.
   */
  void ComputeBounds() override;

  /**
   * Rebuilds the surfel arrays when the input, the mapper or the actor's colors changed.
   * Returns false when the input cannot be drawn.
   */
  bool UpdateSurfels(vtkActor* actor);

  double Radius = 1.0;
  char* RadiusArrayName = nullptr;

  vtkIdType NumberOfSplats = 0;
  vtkIdType NumberOfSkippedPoints = 0;
  double LastRenderTimeInMilliseconds = 0.0;

  vtkNew<vtkSurfaceSplatRasterizer> Rasterizer;
  vtkNew<vtkOpenGLImageDepthCompositor> Compositor;

private:
  vtkSurfaceSplatMapper(const vtkSurfaceSplatMapper&) = delete;
  void operator=(const vtkSurfaceSplatMapper&) = delete;

  struct SurfelArrays;
  std::unique_ptr<SurfelArrays> Surfels;
};

#endif
