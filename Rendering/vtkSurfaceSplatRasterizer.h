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
 *    overlap it in input order, so the image does not depend on the number of threads. Each
 *    contribution is accumulated into, replaces, or is discarded by the pixel's surface by the
 *    z threshold (a multiple of the surfel's eye-space radius).
 * 3. Resolve: normalization by the summed weights (eq. 9) and deferred shading of the filtered
 *    normal with VTK's lighting model (SplatLighting.h).
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
   * Z threshold of the accumulate-or-replace decision, in units of each surfel's eye-space
   * radius: contributions whose depths differ by less are the same surface. Default 1.
   */
  vtkSetClampMacro(DepthThreshold, double, 0.0, 1e3);
  vtkGetMacro(DepthThreshold, double);

  /**
   * The screen-space filter: exact EWA (default), circular or unfiltered (paper 000, figure 8).
   */
  void SetFilter(splat::KernelFilter filter) { this->Filter = filter; }
  splat::KernelFilter GetFilter() const { return this->Filter; }

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
   * coordinates (the axes' lengths are the semi-axes), normals unit 3-vectors, colors RGB in [0,1].
   */
  struct Surfels
  {
    const double* Positions = nullptr;
    const float* Normals = nullptr;
    const float* Axes0 = nullptr;
    const float* Axes1 = nullptr;
    const float* Colors = nullptr;
    std::size_t Count = 0;
  };

  /**
   * Splats the surfels and resolves the frame. After it, GetColors() and GetDepths() hold the
   * image and Get*Count() what was done.
   */
  void Render(const Surfels& surfels, const Camera& camera, const std::vector<splat::Light>& lights,
    const splat::Material& material);

  /**
   * Steps 1 and 2 only: the unnormalized accumulation buffers, for tests of the filter itself.
   */
  void Splat(const Surfels& surfels, const Camera& camera);

  /**
   * Per pixel, row by row from the bottom: RGBA (alpha 0 where no splat covers the pixel) and
   * the window-space depth in [0, 1] of the nearest surface.
   */
  const std::vector<std::uint8_t>& GetColors() const { return this->Colors; }
  const std::vector<float>& GetDepths() const { return this->Depths; }

  /**
   * The accumulation buffers after Splat(): summed kernel weights, weighted colors (3 per pixel),
   * weighted eye normals (3 per pixel) and the linear eye depth of each pixel's surface.
   */
  const std::vector<float>& GetWeights() const { return this->Weights; }
  const std::vector<float>& GetWeightedColors() const { return this->WeightedColors; }
  const std::vector<float>& GetWeightedNormals() const { return this->WeightedNormals; }
  const std::vector<float>& GetEyeDepths() const { return this->EyeDepths; }

  ///@{
  /**
   * What the last frame did: surfels splatted; surfels left out because they lie outside the
   * view frustum (behind the eye, outside the near/far range, footprint outside the viewport),
   * face away with BackfaceCulling on, or have a negligible peak weight (edge-on); and pixel
   * contributions written.
   */
  vtkGetMacro(SplattedCount, vtkIdType);
  vtkGetMacro(FrustumCulledCount, vtkIdType);
  vtkGetMacro(BackfaceCulledCount, vtkIdType);
  vtkGetMacro(NegligibleCount, vtkIdType);
  vtkGetMacro(FragmentCount, vtkIdType);
  ///@}

protected:
  vtkSurfaceSplatRasterizer();
  ~vtkSurfaceSplatRasterizer() override;

  void Resolve(const Camera& camera, const std::vector<splat::Light>& lights,
    const splat::Material& material);

  double Cutoff = 1.0;
  double DepthThreshold = 1.0;
  splat::KernelFilter Filter = splat::KernelFilter::EWA;
  bool BackfaceCulling = false;

  vtkIdType SplattedCount = 0;
  vtkIdType FrustumCulledCount = 0;
  vtkIdType BackfaceCulledCount = 0;
  vtkIdType NegligibleCount = 0;
  vtkIdType FragmentCount = 0;

  std::vector<float> Weights;
  std::vector<float> WeightedColors;
  std::vector<float> WeightedNormals;
  std::vector<float> EyeDepths;
  std::vector<std::uint8_t> Colors;
  std::vector<float> Depths;

private:
  vtkSurfaceSplatRasterizer(const vtkSurfaceSplatRasterizer&) = delete;
  void operator=(const vtkSurfaceSplatRasterizer&) = delete;

  struct Internals;
  Internals* Internal;
};

#endif
