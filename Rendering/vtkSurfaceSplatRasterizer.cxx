// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSurfaceSplatRasterizer.h"

#include "SplatDifferentialPointNormal.h"
#include "SplatMinifiedSplatCells.h"
#include "SplatMinifiedSurfel.h"
#include "SplatSurfaceFragment.h"
#include "vtkSurfelHierarchy.h"
#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

vtkStandardNewMacro(vtkSurfaceSplatRasterizer);

namespace
{
enum CullReason
{
  Kept = 0,
  OutsideFrustum,
  BackFacing,
  Negligible,
  Minified, // kept, accumulated per pixel
  Hidden    // faces away, in a region hidden by nearer surfaces (vtkSurfelHierarchy)
};

// Rows per band: small enough to balance the threads, large enough that few kernels straddle bands.
constexpr int BandHeight = 16;

// Widest box, in pixels, whose rows are walked whole: for a few pixels, testing each one's
// exponent costs less than the square root and roundings of the row's span.
constexpr int NarrowSplatWidth = 3;

// Surfels per setup chunk: the minified splats are listed chunk by chunk, so that every pixel
// sums them in input order whatever the number of threads.
constexpr vtkIdType ChunkSize = 16384;

// The minified path pays where at least this share of the splats in view is minified: it sets up
// every splat in single precision first, about a quarter of an exact setup, so a frame of
// magnified splats (the bunny seen whole, 1 in 34620 minified) drew 25 % slower with it.
constexpr double MinifiedShareToPay = 0.25;

// Opaque frames whose splats in view have a median warped variance (the mean of J Vr J^T's
// diagonal) of at least this many pixels^2 keep the paper's 3 layers: there the 5 layers that
// smaller splats need at silhouettes gain nothing and cost time (splat_report, 6 rounds: the
// bunny seen magnified, median 49 px^2, 16.0 ms at 3 layers against 17.1 ms at 5, the
// armadillo seen magnified, 38 px^2, 18.8 against 19.5 ms, both at the same RMSE; seen whole,
// 3 to 5 px^2, the bunny draws 0.01358 with 5 and 0.01367 with 3). EWA splats only: circular
// ones, cut off sharply, draw the magnified bunny at 0.0155 with 5 layers and 0.0161 with 3.
constexpr float MagnifiedVariance = 16.0f;

// What a sample of four batches spread over the input shows of the surfels in view: the share
// that `projector` finds minified and their median warped variance (both 0 where none of them
// is in view).
struct ViewSample
{
  double MinifiedShare = 0.0;
  float MedianVariance = 0.0f;
};

ViewSample SampleView(const splat::MinifiedSurfelProjector& projector,
  const vtkSurfaceSplatRasterizer::Surfels& surfels)
{
  constexpr std::size_t BatchSize = splat::MinifiedSurfelProjector::BatchSize;
  const std::size_t samples = std::min(4 * BatchSize, surfels.Count);
  splat::MinifiedSurfelProjector::Batch batch;
  int minified = 0;
  std::vector<float> variances;
  for (std::size_t begin = 0; begin < samples; begin += BatchSize)
  {
    const int count = static_cast<int>(std::min(BatchSize, samples - begin));
    for (int j = 0; j < count; ++j)
    {
      const std::size_t i = (begin + j) * surfels.Count / samples;
      projector.Load(batch, j, surfels.Positions + 3 * i, surfels.Normals + 3 * i,
        surfels.Axes0 + 3 * i, surfels.Axes1 + 3 * i, 1.0f);
    }
    projector.Project(batch, count);
    for (int j = 0; j < count; ++j)
    {
      minified += batch.Outcome[j] == splat::MinifiedSurfelProjector::Minified;
      if (batch.Outcome[j] == splat::MinifiedSurfelProjector::Minified ||
        batch.Outcome[j] == splat::MinifiedSurfelProjector::Magnified)
      {
        variances.push_back(0.5f * (batch.WarpedXX[j] + batch.WarpedYY[j]));
      }
    }
  }
  ViewSample sample;
  if (!variances.empty())
  {
    sample.MinifiedShare = static_cast<double>(minified) / variances.size();
    const auto median = variances.begin() + variances.size() / 2;
    std::nth_element(variances.begin(), median, variances.end());
    sample.MedianVariance = *median;
  }
  return sample;
}

// The pixels a rectangle p +- a0 +- a1 covers, from its corners' exact projections; false when
// it covers none or a corner is not in front of the eye.
bool RectanglePixels(const glm::dmat4& eyeToClip, const glm::dvec2& viewport, const glm::dvec3& p,
  const glm::dvec3& a0, const glm::dvec3& a1, glm::ivec4& box)
{
  glm::dvec2 lo(std::numeric_limits<double>::infinity());
  glm::dvec2 hi(-std::numeric_limits<double>::infinity());
  for (const double s0 : { -1.0, 1.0 })
  {
    for (const double s1 : { -1.0, 1.0 })
    {
      splat::PointProjection corner;
      if (!splat::ProjectPoint(eyeToClip, viewport, p + s0 * a0 + s1 * a1, corner))
      {
        return false;
      }
      lo = glm::min(lo, corner.Center);
      hi = glm::max(hi, corner.Center);
    }
  }
  return splat::CoveredPixels(0.5 * (lo + hi), 0.5 * (hi - lo), static_cast<int>(viewport.x),
    static_cast<int>(viewport.y), box);
}
}

// One surfel after setup, in the single precision the per-pixel loop uses.
struct vtkSurfaceSplatRasterizer::ScreenSplat
{
  float CenterX, CenterY;
  float ConicXX, ConicXY, ConicYY; // 1/2 M^-1, so that beta = d^T C d
  float Amplitude;
  float Cutoff;    // splat::SplatCutoff's
  float Threshold; // eye-space z threshold
  int X0, X1, Y0, Y1; // inclusive pixel bounds
  float DepthNumerator[3];
  float DepthDenominator[3];
  float Normal[3]; // eye space, either side (AddNormal)
  float Color[3];
  float Alpha;
};

// What a differential point adds to its ScreenSplat: where a pixel's view ray meets its tangent
// plane, and the normal it predicts there.
struct vtkSurfaceSplatRasterizer::DifferentialSplat
{
  // The intersection's coordinates in axis units, s = S.(x, y, 1) + t SRay.(x, y, 1) along the
  // first axis and the same with T along the second, at eye depth t of pixel (x, y).
  float S[3], SRay[3];
  float T[3], TRay[3];
  float ExtentU, ExtentV;       // the axes' lengths in model units
  float CurvatureU, CurvatureV; // in inverse model units
  float U[3], V[3]; // unit eye-space principal directions

  // Narrows [xBegin, xEnd] to the pixels of row y (centers at py) that may lie inside the
  // rectangle, where the splat's depth is numerator / denominator (affine in the pixel), so
  // that Shade tests only those. Along a row, s times the denominator, S.(x, y, 1) d + SRay.(x,
  // y, 1) n, is affine in x, and so is r's: the rays' origins (perspective) or directions
  // (parallel) are constant, which zeroes the x terms of S and n, or of SRay and d. The span
  // is solved in double with a relative slack and a pixel of margin, so that every pixel Shade
  // accepts stays in it.
  void NarrowRow(float py, const float* numerator, const float* denominator, int& xBegin,
    int& xEnd) const
  {
    const double y = py;
    const double n0 = numerator[0], ny = numerator[1] * y + numerator[2];
    const double d0 = denominator[0], dy = denominator[1] * y + denominator[2];
    // The denominator keeps one sign across the row, or the row is left whole.
    const double dBegin = d0 * (xBegin + 0.5) + dy;
    const double sign = dBegin > 0.0 ? 1.0 : -1.0;
    if (!(dBegin * (d0 * (xEnd + 0.5) + dy) > 0.0))
    {
      return;
    }
    constexpr double Bound = 1.0 + 1e-4;
    double lo = xBegin + 0.5, hi = xEnd + 0.5;
    // Pixel centers x with -Bound |d(x)| <= c(x) d(x) = a x + b <= Bound |d(x)|, c = s or r.
    auto narrow = [&](const float* c, const float* ray)
    {
      const double cy = c[1] * y + c[2], rayY = ray[1] * y + ray[2];
      const double a = c[0] * dy + cy * d0 + ray[0] * ny + rayY * n0;
      const double b = cy * dy + rayY * ny;
      for (const double side : { -1.0, 1.0 })
      {
        const double slope = side * a - Bound * sign * d0;
        const double offset = Bound * sign * dy - side * b;
        if (slope > 0.0)
        {
          hi = std::min(hi, offset / slope);
        }
        else if (slope < 0.0)
        {
          lo = std::max(lo, offset / slope);
        }
        else if (offset < 0.0)
        {
          lo = std::numeric_limits<double>::infinity();
        }
      }
    };
    narrow(this->S, this->SRay);
    narrow(this->T, this->TRay);
    if (!(lo <= hi))
    {
      xEnd = xBegin - 1;
      return;
    }
    xBegin = static_cast<int>(std::max<double>(xBegin, std::floor(lo - 0.5) - 1.0));
    xEnd = static_cast<int>(std::min<double>(xEnd, std::ceil(hi - 0.5) + 1.0));
  }

  // Whether pixel (x, y) at eye depth t lies inside the rectangle; the unit normal predicted
  // there (eq. 10) into normal, from the splat's normal n.
  bool Shade(float x, float y, float t, const float* n, bool rectangle, float* normal) const
  {
    const float s = this->S[0] * x + this->S[1] * y + this->S[2] +
      t * (this->SRay[0] * x + this->SRay[1] * y + this->SRay[2]);
    const float r = this->T[0] * x + this->T[1] * y + this->T[2] +
      t * (this->TRay[0] * x + this->TRay[1] * y + this->TRay[2]);
    if (rectangle && !(std::abs(s) <= 1.0f && std::abs(r) <= 1.0f))
    {
      return false;
    }
    const float u = s * this->ExtentU;
    const float v = r * this->ExtentV;
    const float g = splat::DifferentialNormalScale(this->CurvatureU, this->CurvatureV, u, v);
    const float du = g * this->CurvatureU * u;
    const float dv = g * this->CurvatureV * v;
    float squared = 0.0f;
    for (int c = 0; c < 3; ++c)
    {
      normal[c] = n[c] - du * this->U[c] - dv * this->V[c];
      squared += normal[c] * normal[c];
    }
    const float scale = 1.0f / std::sqrt(squared);
    for (int c = 0; c < 3; ++c)
    {
      normal[c] *= scale;
    }
    return true;
  }
};

struct vtkSurfaceSplatRasterizer::Internals
{
  // Per splat, written only for those drawn with their exact kernel: left uninitialized, so
  // that the pages of minified and culled splats are never touched (100 bytes each).
  std::unique_ptr<ScreenSplat[]> Splats;
  std::size_t SplatCapacity = 0;
  std::vector<std::uint32_t> Items; // the splats a hierarchy selected (vtkSurfelHierarchy)
  std::vector<vtkSurfelHierarchy::BackRegion> BackRegions; // and its regions facing away
  std::vector<std::uint8_t> CullReasons; // per splat: why it is left out, or Kept, or Minified
  std::vector<DifferentialSplat> DifferentialSplats; // parallel to Splats; empty for surfels
  std::vector<std::uint32_t> SplatBands; // per kept splat: first band, last in the high half
  std::vector<vtkIdType> BandOffsets; // per band, into BandSplats
  std::vector<vtkIdType> BandSplats;  // splat indices, band by band, in input order
  std::vector<vtkIdType> ChunkBandStarts; // per setup chunk and band, where its splats go
  splat::MinifiedSplatCells MinifiedCells;
};

namespace
{
using Fragment = vtkSurfaceSplatRasterizer::Fragment;
using ScreenSplat = vtkSurfaceSplatRasterizer::ScreenSplat;
using DifferentialSplat = vtkSurfaceSplatRasterizer::DifferentialSplat;

// A differential point's per-pixel terms, in eye space: p its center, a0 and a1 its axes (the
// principal directions scaled by the half-widths extentU, extentV in model units), curvatures
// lambda_u, lambda_v.
void SetUpDifferentialSplat(const splat::PixelRays& rays, const glm::dvec3& p,
  const glm::dvec3& a0, const glm::dvec3& a1, double extentU, double extentV,
  const float* curvatures, DifferentialSplat& d)
{
  // The dual basis of the axes: (X - p).b0 and (X - p).b1 are X's coordinates in axis units.
  const glm::dmat2 inverseGram = glm::inverse(
    glm::dmat2(glm::dot(a0, a0), glm::dot(a0, a1), glm::dot(a0, a1), glm::dot(a1, a1)));
  const glm::dvec3 b0 = inverseGram[0][0] * a0 + inverseGram[0][1] * a1;
  const glm::dvec3 b1 = inverseGram[1][0] * a0 + inverseGram[1][1] * a1;
  // X = Origin(x, y) + t Direction(x, y), both affine in the pixel (columns A, B, C).
  const glm::dvec3 s0 = b0 * rays.Origin - glm::dvec3(0.0, 0.0, glm::dot(b0, p));
  const glm::dvec3 s1 = b0 * rays.Direction;
  const glm::dvec3 t0 = b1 * rays.Origin - glm::dvec3(0.0, 0.0, glm::dot(b1, p));
  const glm::dvec3 t1 = b1 * rays.Direction;
  const glm::dvec3 u = glm::normalize(a0);
  const glm::dvec3 v = glm::normalize(a1);
  for (int c = 0; c < 3; ++c)
  {
    d.S[c] = static_cast<float>(s0[c]);
    d.SRay[c] = static_cast<float>(s1[c]);
    d.T[c] = static_cast<float>(t0[c]);
    d.TRay[c] = static_cast<float>(t1[c]);
    d.U[c] = static_cast<float>(u[c]);
    d.V[c] = static_cast<float>(v[c]);
  }
  d.ExtentU = static_cast<float>(extentU);
  d.ExtentV = static_cast<float>(extentV);
  d.CurvatureU = curvatures[0];
  d.CurvatureV = curvatures[1];
}

// An opaque contribution to a pixel's fragments: it joins the surface within its z threshold,
// or becomes a new surface, in place of a sliver or the farthest once `layers` are held
// (OpaqueSlot).
inline void AddOpaque(Fragment* fragments, std::uint8_t& count, int layers, float z, float w,
  float negligible, const float* normal, const ScreenSplat& s)
{
  bool inserted;
  const int i =
    splat::OpaqueSlot(fragments, count, layers, z, s.Threshold, inserted, w, negligible);
  if (i < 0)
  {
    return;
  }
  if (inserted)
  {
    fragments[i] = splat::NewFragment(z, w, normal, s.Color, s.Alpha);
  }
  else
  {
    splat::Accumulate(fragments[i], z, w, normal, s.Color, s.Alpha);
  }
}

}

//------------------------------------------------------------------------------
vtkSurfaceSplatRasterizer::vtkSurfaceSplatRasterizer()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkSurfaceSplatRasterizer::~vtkSurfaceSplatRasterizer()
{
  delete this->Internal;
}

//------------------------------------------------------------------------------
float vtkSurfaceSplatRasterizer::FullCoverageWeight() const
{
  return static_cast<float>(splat::FullCoverageWeight(this->CoverageThreshold, this->Cutoff));
}

//------------------------------------------------------------------------------
glm::vec4 vtkSurfaceSplatRasterizer::ShadeFragment(const Fragment& f, int x, int y) const
{
  if (f.Shaded())
  {
    return glm::vec4(f.Color[0], f.Color[1], f.Color[2], f.Alpha);
  }
  const Frame& frame = this->CurrentFrame;
  // Eye position of the fragment: on its pixel's ray at its depth.
  const glm::vec3 pixel(x + 0.5f, y + 0.5f, 1.0f);
  const glm::vec3 position = frame.RayOrigin * pixel + f.Depth * (frame.RayDirection * pixel);

  glm::vec3 normal(f.Normal[0], f.Normal[1], f.Normal[2]);
  const float length = glm::length(normal);
  normal = length > 0.0f ? normal / length : glm::vec3(0.0f, 0.0f, 1.0f);
  // Two-sided lighting: the filtered normal (AddNormal) turned towards the viewer.
  normal = splat::FacingNormal(normal, frame.RayDirection * pixel);
  const glm::vec3 color = glm::vec3(f.Color[0], f.Color[1], f.Color[2]) / f.Weight;
  const glm::vec3 shaded = glm::clamp(
    splat::Shade(*frame.Lights, *frame.Surface, color, position, normal, !frame.Perspective),
    0.0f, 1.0f);
  float alpha = f.Alpha / f.Weight;
  if (this->EdgeAntialiasing)
  {
    // Coverage (paper 000, section 7): summed weights below the full-coverage threshold.
    alpha *= std::min(1.0f, f.Weight / frame.FullCoverage);
  }
  return glm::vec4(shaded * alpha, alpha);
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRasterizer::Render(const Surfels& surfels, const Camera& camera,
  const std::vector<splat::Light>& lights, const splat::Material& material)
{
  this->Splat(surfels, camera, lights, material);
  this->Resolve();
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRasterizer::Splat(const Surfels& surfels, const Camera& camera)
{
  splat::Material unlit;
  unlit.Ambient = 0.0f;
  unlit.Diffuse = 1.0f;
  this->Splat(surfels, camera, {}, unlit);
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRasterizer::Splat(const Surfels& surfels, const Camera& camera,
  const std::vector<splat::Light>& lights, const splat::Material& material)
{
  const int width = camera.Viewport.x;
  const int height = camera.Viewport.y;
  const std::size_t pixels = static_cast<std::size_t>(std::max(width, 0)) * std::max(height, 0);
  bool translucent = false;
  for (std::size_t i = 0; surfels.Opacities && i < surfels.Count && !translucent; ++i)
  {
    translucent = surfels.Opacities[i] < 1.0f;
  }
  this->Layers = 1;
  this->FragmentCounts.assign(pixels, 0);
  this->SplattedCount = this->MinifiedCount = this->MergedCount = 0;
  this->FrustumCulledCount = this->BackfaceCulledCount = this->HiddenCount = 0;
  this->NegligibleCount = this->FragmentCount = 0;

  Frame& frame = this->CurrentFrame;
  frame.View = camera;
  frame.ClipToEye = glm::inverse(camera.EyeToClip);
  frame.Lights = &lights;
  frame.Surface = &material;
  frame.FullCoverage = this->FullCoverageWeight();
  if (pixels == 0)
  {
    this->FrustumCulledCount = static_cast<vtkIdType>(surfels.Count);
    return;
  }

  const glm::dmat4& modelToEye = camera.ModelToEye;
  const glm::dmat4& eyeToClip = camera.EyeToClip;
  const glm::dmat3 normalToEye = glm::transpose(glm::inverse(glm::dmat3(modelToEye)));
  const glm::dvec2 viewport(width, height);
  const splat::PixelRays rays = splat::MakePixelRays(eyeToClip, viewport);
  frame.RayOrigin = glm::mat3(rays.Origin);
  frame.RayDirection = glm::mat3(rays.Direction);
  frame.Perspective = rays.Perspective;
  // Depths of the near and far planes: the eye depths of NDC z = -1 and 1.
  auto eyeDepth = [&frame](double zNdc)
  {
    const glm::dvec4 eye = frame.ClipToEye * glm::dvec4(0.0, 0.0, zNdc, 1.0);
    return -eye.z / eye.w;
  };
  const double nearDepth = eyeDepth(-1.0);
  const double farDepth = eyeDepth(1.0);
  const double cutoff = this->Cutoff;
  const double depthThreshold = this->DepthThreshold;
  const splat::KernelFilter filter = this->Filter;
  const double antialiasingCutoff =
    filter == splat::KernelFilter::EWA ? this->AntialiasingCutoff : 0.0;
  // The widest cutoff any splat gets: that of splats below CutoffFadeStart, minified ones too.
  const double widestCutoff = splat::SplatCutoff(0.0, cutoff, antialiasingCutoff);
  const double magnifiedLowPass = this->MagnifiedLowPassVariance;
  // Hidden back faces may only be left out of an opaque surface.
  const bool cullBackFaces = this->BackfaceCulling && !translucent;
  const bool differential = surfels.Curvatures != nullptr;
  const bool rectangles = differential && filter == splat::KernelFilter::Unfiltered;
  // A filtered differential point's Gaussian passes through its rectangle's corners: axes
  // sqrt(2) times the half-widths, whose mass in the input's units, R0 R1 = 2 e_u e_v, doubled
  // is the rectangle's area, so that rectangles that tile the surface sum to one as surfels on
  // their grid do.
  const double footprintScale = differential && !rectangles ? std::sqrt(2.0) : 1.0;
  const float amplitudeScale = differential && !rectangles ? 2.0f : 1.0f;
  // How far a splat reaches along an axis, in units of the axis: its cutoff ellipse (beta =
  // |u|^2 < cutoff in axis units) or its rectangle.
  const double depthReach = footprintScale * std::max(std::sqrt(widestCutoff), 1.0);

  // Minified splats are summed per pixel where the exact kernel is the EWA one of an opaque
  // surfel (SplatMinifiedSplatCells.h), in frames where enough of them are minified to pay.
  splat::MinifiedSplatCells& minifiedCells = this->Internal->MinifiedCells;
  const int reach = splat::MinifiedSplatCells::ReachOf(widestCutoff, this->MinifiedVariance);
  splat::MinifiedSurfelProjector::Frame minifiedFrame;
  minifiedFrame.ModelToEye = modelToEye;
  minifiedFrame.EyeToClip = eyeToClip;
  minifiedFrame.Viewport = viewport;
  minifiedFrame.NearDepth = nearDepth;
  minifiedFrame.FarDepth = farDepth;
  minifiedFrame.DepthReach = depthReach;
  minifiedFrame.MaximumVariance = this->MinifiedVariance;
  minifiedFrame.DepthThreshold = depthThreshold;
  minifiedFrame.Reach = reach;
  minifiedFrame.Perspective = rays.Perspective;
  minifiedFrame.CullBackFaces = cullBackFaces;
  const splat::MinifiedSurfelProjector minifiedProjector(minifiedFrame);
  const ViewSample sample = SampleView(minifiedProjector, surfels);
  const bool minify = this->MinifiedVariance > 0.0 && filter == splat::KernelFilter::EWA &&
    !differential && !translucent && sample.MinifiedShare >= MinifiedShareToPay;
  // Minified splats are summed per pixel under the paper's unit low-pass; under a smaller one
  // (splats of one color) each is drawn with its own kernel, which then reaches only the pixel
  // centers next to it, set up from its single-precision projection.
  const bool sumMinified = this->MinifiedLowPassVariance >= 1.0;
  // Layers only where something can be seen through: translucent splats, or the partly covered
  // edges of edge antialiasing, which show the surfaces behind them (an edge of a thin part
  // shows its own back side first). Otherwise one fragment per pixel. Automatic: minified
  // splats drawn with their own kernels are thinner in depth than a pixel's stretch of a
  // grazing surface, which they split into a fragment per z threshold; further layers would
  // keep more of those slices of one surface and blend them over each other. Opaque EWA
  // splats magnified well past a pixel need no more than the paper's layers
  // (MagnifiedVariance).
  if (translucent || this->EdgeAntialiasing)
  {
    const bool paperLayers = (minify && !sumMinified) ||
      (!translucent && filter == splat::KernelFilter::EWA &&
        sample.MedianVariance >= MagnifiedVariance);
    this->Layers = this->NumberOfLayers > 0 ? this->NumberOfLayers
      : paperLayers                         ? PaperLayers
                                            : AutomaticLayers;
  }
  this->Fragments.resize(pixels * this->Layers);
  minifiedCells.SetUp(width, height, this->Layers, widestCutoff, this->MinifiedVariance);
  // With a hierarchy of the surfels, the splats are the nodes it selects (whose coarser levels
  // are all minified), read block by block from its copy, and regions facing away come last.
  const vtkSurfelHierarchy* hierarchy = minify && surfels.Hierarchy &&
      surfels.Hierarchy->GetNumberOfSurfels() == static_cast<vtkIdType>(surfels.Count)
    ? surfels.Hierarchy
    : nullptr;
  std::vector<std::uint32_t>& items = this->Internal->Items;
  std::vector<vtkSurfelHierarchy::BackRegion>& backRegions = this->Internal->BackRegions;
  backRegions.clear();
  this->MergedCount =
    hierarchy ? hierarchy->Select(camera, this->MinifiedVariance, items, backRegions) : 0;
  // Where it merges nothing and leaves no region to be found hidden (or the input is
  // degenerate), its selection is the surfels themselves: they are drawn in their own order.
  if (hierarchy && (items.empty() || (this->MergedCount == 0 && backRegions.empty())))
  {
    hierarchy = nullptr;
  }
  const Surfels nodes = hierarchy ? hierarchy->GetNodes() : Surfels();
  const float* massScales = hierarchy ? hierarchy->GetMassScales() : nullptr;
  const vtkIdType count = static_cast<vtkIdType>(hierarchy ? items.size() : surfels.Count);
  std::vector<DifferentialSplat>& differentials = this->Internal->DifferentialSplats;
  differentials.resize(differential ? count : 0);

  const float widestCutoffF = static_cast<float>(widestCutoff);
  const float nearClip = static_cast<float>(nearDepth);
  const float farClip = static_cast<float>(farDepth);
  // The opaque scene's window depths as linear eye depths, for the per-fragment test.
  const std::vector<float> sceneEyeDepths = this->SceneDepths.size() == pixels
    ? splat::EyeDepthsOfWindowDepths(frame.ClipToEye, this->SceneDepths)
    : std::vector<float>();
  const float* sceneDepths = sceneEyeDepths.empty() ? nullptr : sceneEyeDepths.data();
  const int layers = this->Layers;
  const splat::ExponentialTable exponential(widestCutoffF);
  const float full = frame.FullCoverage;
  const float negligible = splat::NegligibleCoverage * full;

  if (this->Internal->SplatCapacity < static_cast<std::size_t>(count))
  {
    this->Internal->Splats.reset(new ScreenSplat[count]);
    this->Internal->SplatCapacity = count;
  }
  ScreenSplat* const splats = this->Internal->Splats.get();
  std::vector<std::uint8_t>& reasons = this->Internal->CullReasons;
  reasons.resize(count);
  // The bands of the kept splats, apart from them: binning reads only these and the reasons.
  std::vector<std::uint32_t>& splatBands = this->Internal->SplatBands;
  splatBands.resize(count);
  auto bandsOf = [](const ScreenSplat& s)
  { return static_cast<std::uint32_t>((s.Y0 / BandHeight) | (s.Y1 / BandHeight) << 16); };
  const glm::dmat3 axisToEye(modelToEye);
  const glm::dvec3 eyeTranslation(modelToEye[3]);
  const double minifiedLowPass =
    std::max(this->MinifiedLowPassVariance, splat::UnfilteredMinimumVariance);
  const double minifiedMassScale =
    widestCutoff > cutoff ? splat::TruncatedMassScale(cutoff, widestCutoff) : 1.0;
  const float minifiedLowPassF = static_cast<float>(minifiedLowPass);
  const glm::mat3 rayOrigin(rays.Origin), rayDirection(rays.Direction);
  // Returns Kept, or why not: a kernel between pixel centers draws nothing.
  auto setUpMinified = [&](const splat::MinifiedSurfelProjector::Batch& batch,
                         const splat::MinifiedSurfelProjector::Kernels& kernels, int j,
                         const float* color, ScreenSplat& s) -> std::uint8_t
  {
    const float cx = batch.CenterX[j], cy = batch.CenterY[j];
    const float rx = kernels.ReachX[j], ry = kernels.ReachY[j];
    if (!(cx + rx > 0.0f && cx - rx < width && cy + ry > 0.0f && cy - ry < height))
    {
      return OutsideFrustum; // also keeps the conversions below in range
    }
    // The pixels whose centers x + 0.5 lie within the box, as CoveredPixels.
    s.X0 = std::max(-splat::FloorToInt(rx + 0.5f - cx), 0);
    s.X1 = std::min(splat::FloorToInt(cx + rx - 0.5f), width - 1);
    s.Y0 = std::max(-splat::FloorToInt(ry + 0.5f - cy), 0);
    s.Y1 = std::min(splat::FloorToInt(cy + ry - 0.5f), height - 1);
    if (!(kernels.Amplitude[j] > 0.0f) || s.X0 > s.X1 || s.Y0 > s.Y1)
    {
      return Negligible;
    }
    s.CenterX = cx;
    s.CenterY = cy;
    s.ConicXX = kernels.ConicXX[j];
    s.ConicXY = kernels.ConicXY[j];
    s.ConicYY = kernels.ConicYY[j];
    s.Amplitude = kernels.Amplitude[j];
    s.Cutoff = widestCutoffF;
    s.Threshold = batch.Threshold[j];
    for (int c = 0; c < 3; ++c)
    {
      s.DepthNumerator[c] = kernels.Numerator[c][j];
      s.DepthDenominator[c] = kernels.Denominator[c][j];
      s.Color[c] = color[c];
    }
    s.Normal[0] = batch.NX[j];
    s.Normal[1] = batch.NY[j];
    s.Normal[2] = batch.NZ[j];
    s.Alpha = 1.0f;
    return Kept;
  };
  // Steps 1 and 2 for splats [first, last).
  auto drawRange = [&](vtkIdType first, vtkIdType last)
  {
    // 1. Setup, in eye space, chunk by chunk.
    const vtkIdType chunks = (last - first + ChunkSize - 1) / ChunkSize;
    if (minify)
    {
      minifiedCells.ReserveChunks(chunks);
    }
    vtkSMPTools::For(0, chunks, 1,
      [&](vtkIdType chunkBegin, vtkIdType chunkEnd)
      {
        const vtkIdType begin = first + chunkBegin * ChunkSize;
        const vtkIdType end = std::min(first + chunkEnd * ChunkSize, last);
        for (vtkIdType c = chunkBegin; minify && c < chunkEnd; ++c)
        {
          minifiedCells.ClearChunk(c);
        }
        // Splat k: surfel k of the input or the node of the hierarchy that item k selects, and
        // the ratio of its mass to the area its axes span (1 but for merged nodes).
        struct Source
        {
          const Surfels* Data;
          std::size_t Index;
          double MassScale;
        };
        auto sourceOf = [&](vtkIdType k)
        {
          return hierarchy ? Source{ &nodes, items[k], massScales[items[k]] }
                           : Source{ &surfels, static_cast<std::size_t>(k), 1.0 };
        };
        splat::MinifiedSurfelProjector::Batch batch;
        splat::MinifiedSurfelProjector::Kernels kernels;
        for (vtkIdType batchBegin = begin; batchBegin < end;
             batchBegin += splat::MinifiedSurfelProjector::BatchSize)
        {
          const int batchCount = static_cast<int>(std::min<vtkIdType>(
            splat::MinifiedSurfelProjector::BatchSize, end - batchBegin));
          Source sources[splat::MinifiedSurfelProjector::BatchSize];
          for (int j = 0; j < batchCount; ++j)
          {
            const Source& at = sources[j] = sourceOf(batchBegin + j);
            const std::size_t i = at.Index;
            if (minify)
            {
              minifiedProjector.Load(batch, j, at.Data->Positions + 3 * i,
                at.Data->Normals + 3 * i, at.Data->Axes0 + 3 * i, at.Data->Axes1 + 3 * i,
                static_cast<float>(at.MassScale));
            }
          }
          if (minify)
          {
            minifiedProjector.Project(batch, batchCount);
            if (!sumMinified)
            {
              minifiedProjector.ProjectKernels(batch, batchCount, minifiedLowPassF,
                widestCutoffF, static_cast<float>(minifiedMassScale), rayOrigin, rayDirection,
                kernels);
            }
          }
          for (int j = 0; j < batchCount; ++j)
          {
            const vtkIdType k = batchBegin + j;
            std::uint8_t& reason = reasons[k];
            reason = OutsideFrustum;
            const Source& at = sources[j];
            const Surfels& source = *at.Data;
            const std::size_t i = at.Index;
            const double massScale = at.MassScale;
            const double* position = source.Positions + 3 * i;
            const float* n = source.Normals + 3 * i;
            const float* axis0 = source.Axes0 + 3 * i;
            const float* axis1 = source.Axes1 + 3 * i;
            if (minify)
            {
              splat::MinifiedSurfel m;
              switch (batch.Outcome[j])
              {
                case splat::MinifiedSurfelProjector::Minified:
                  if (!sumMinified)
                  {
                    reason = setUpMinified(batch, kernels, j, source.Colors + 3 * i, splats[k]);
                    if (reason == Kept)
                    {
                      splatBands[k] = bandsOf(splats[k]);
                    }
                  }
                  else if (minifiedProjector.Fill(batch, j, m))
                  {
                    std::copy(source.Colors + 3 * i, source.Colors + 3 * i + 3, m.Color);
                    m.Alpha = 1.0f;
                    minifiedCells.List((k - first) / ChunkSize, m);
                    reason = Minified;
                  }
                  continue;
                case splat::MinifiedSurfelProjector::FacingAway:
                  reason = BackFacing;
                  continue;
                case splat::MinifiedSurfelProjector::EdgeOn:
                  reason = Negligible;
                  continue;
                case splat::MinifiedSurfelProjector::Magnified:
                  break;
                default:
                  continue;
              }
            }
            const glm::dvec3 p =
              axisToEye * glm::dvec3(position[0], position[1], position[2]) + eyeTranslation;
            const glm::dvec3 a0 = axisToEye * glm::dvec3(axis0[0], axis0[1], axis0[2]);
            const glm::dvec3 a1 = axisToEye * glm::dvec3(axis1[0], axis1[1], axis1[2]);
            // Culled when the whole splat lies outside the depth range: a large one reaches past
            // the near or far plane from a center outside it (its fragments are clipped there).
            const double depthExtent = depthReach * (std::abs(a0.z) + std::abs(a1.z));
            if (!(-p.z + depthExtent >= nearDepth && -p.z - depthExtent <= farDepth))
            {
              continue;
            }
            splat::SurfelProjection projection;
            if (!splat::ProjectSurfel(
                  eyeToClip, viewport, p, footprintScale * a0, footprintScale * a1, projection))
            {
              continue;
            }
            const glm::dvec3 normal = glm::normalize(normalToEye * glm::dvec3(n[0], n[1], n[2]));
            const glm::dvec3 view = rays.Perspective ? p : glm::dvec3(0.0, 0.0, -1.0);
            if (cullBackFaces && glm::dot(normal, view) > 0.0)
            {
              reason = BackFacing;
              continue;
            }
            if (!(splat::Foreshortening(projection) >= splat::EdgeOnForeshortening))
            {
              reason = Negligible;
              continue;
            }
            const splat::ResamplingKernel kernel =
              splat::MakeResamplingKernel(projection, cutoff, filter, magnifiedLowPass,
                antialiasingCutoff, minifiedLowPass);
            glm::ivec4 box;
            if (rectangles
                ? !RectanglePixels(eyeToClip, viewport, p, a0, a1, box)
                : !splat::CoveredPixels(kernel.Center, kernel.HalfExtent, width, height, box))
            {
              continue;
            }
            ScreenSplat& s = splats[k];
            s.X0 = box.x;
            s.X1 = box.y;
            s.Y0 = box.z;
            s.Y1 = box.w;
            splatBands[k] = bandsOf(s);
            reason = Kept;

            s.CenterX = static_cast<float>(kernel.Center.x);
            s.CenterY = static_cast<float>(kernel.Center.y);
            s.ConicXX = static_cast<float>(0.5 * kernel.Conic[0][0]);
            s.ConicXY = static_cast<float>(kernel.Conic[1][0]);
            s.ConicYY = static_cast<float>(0.5 * kernel.Conic[1][1]);
            s.Amplitude = amplitudeScale * static_cast<float>(massScale * kernel.Amplitude);
            s.Cutoff = static_cast<float>(kernel.Cutoff);

            splat::PlaneDepth depth;
            if (!splat::MakePlaneDepth(rays, p, normal, depth))
            {
              depth.Numerator = glm::dvec3(0.0, 0.0, -p.z);
              depth.Denominator = glm::dvec3(0.0, 0.0, 1.0);
            }
            for (int c = 0; c < 3; ++c)
            {
              s.DepthNumerator[c] = static_cast<float>(depth.Numerator[c]);
              s.DepthDenominator[c] = static_cast<float>(depth.Denominator[c]);
            }
            s.Threshold =
              static_cast<float>(depthThreshold * std::max(glm::length(a0), glm::length(a1)));

            for (int c = 0; c < 3; ++c)
            {
              s.Normal[c] = static_cast<float>(normal[c]);
              s.Color[c] = source.Colors[3 * i + c];
            }
            s.Alpha = source.Opacities ? source.Opacities[i] : 1.0f;
            if (differential)
            {
              SetUpDifferentialSplat(rays, p, a0, a1, glm::length(glm::dvec3(axis0[0], axis0[1],
                axis0[2])), glm::length(glm::dvec3(axis1[0], axis1[1], axis1[2])),
                source.Curvatures + 2 * i, differentials[k]);
            }
          }
        }
      });

    // Binning into bands in input order, which is the accumulation order of every pixel
    // whatever the number of threads: each chunk of splats counts its own per band, and then
    // lists them from where the chunks before it end in each band.
    const int bands = (height + BandHeight - 1) / BandHeight;
    std::vector<vtkIdType>& offsets = this->Internal->BandOffsets;
    std::vector<vtkIdType>& bandSplats = this->Internal->BandSplats;
    std::vector<vtkIdType>& starts = this->Internal->ChunkBandStarts;
    starts.assign(chunks * bands, 0);
    // Calls f(b, i) for each band b of each kept splat i of chunk c, in input order.
    auto forBandsOfChunk = [&](vtkIdType c, auto&& f)
    {
      const vtkIdType end = std::min(first + (c + 1) * ChunkSize, last);
      for (vtkIdType i = first + c * ChunkSize; i < end; ++i)
      {
        if (reasons[i] == Kept)
        {
          for (std::uint32_t b = splatBands[i] & 0xffff; b <= splatBands[i] >> 16; ++b)
          {
            f(b, i);
          }
        }
      }
    };
    vtkSMPTools::For(0, chunks,
      [&](vtkIdType chunkBegin, vtkIdType chunkEnd)
      {
        for (vtkIdType c = chunkBegin; c < chunkEnd; ++c)
        {
          vtkIdType* counts = &starts[c * bands];
          forBandsOfChunk(c, [counts](std::uint32_t b, vtkIdType) { ++counts[b]; });
        }
      });
    offsets.assign(bands + 1, 0);
    for (int b = 0; b < bands; ++b)
    {
      vtkIdType end = offsets[b];
      for (vtkIdType c = 0; c < chunks; ++c)
      {
        const vtkIdType count = starts[c * bands + b];
        starts[c * bands + b] = end;
        end += count;
      }
      offsets[b + 1] = end;
    }
    bandSplats.resize(offsets[bands]);
    vtkSMPTools::For(0, chunks,
      [&](vtkIdType chunkBegin, vtkIdType chunkEnd)
      {
        for (vtkIdType c = chunkBegin; c < chunkEnd; ++c)
        {
          vtkIdType* fill = &starts[c * bands];
          forBandsOfChunk(
            c, [&, fill](std::uint32_t b, vtkIdType i) { bandSplats[fill[b]++] = i; });
        }
      });
    const vtkIdType minifiedInRange =
      std::count(reasons.begin() + first, reasons.begin() + last, Minified);

    // 2. Splatting, band by band.
    std::vector<vtkIdType> fragments(bands, 0);
    vtkSMPTools::For(0, bands, 1,
      [&](vtkIdType bandBegin, vtkIdType bandEnd)
      {
        for (vtkIdType b = bandBegin; b < bandEnd; ++b)
        {
          const int rowBegin = static_cast<int>(b) * BandHeight;
          const int rowEnd = std::min(rowBegin + BandHeight, height) - 1;
          vtkIdType written = 0;
          for (vtkIdType k = offsets[b]; k < offsets[b + 1]; ++k)
          {
            const ScreenSplat& s = splats[bandSplats[k]];
            const DifferentialSplat* d = differential ? &differentials[bandSplats[k]] : nullptr;
            const float splatCutoff = s.Cutoff; // a local: the fragment writes may alias s
            const int y0 = std::max(s.Y0, rowBegin);
            const int y1 = std::min(s.Y1, rowEnd);
            const bool wholeRows = rectangles || s.X1 - s.X0 < NarrowSplatWidth;
            for (int y = y0; y <= y1; ++y)
            {
              const float py = y + 0.5f;
              const float dy = py - s.CenterY;
              int xBegin = s.X0;
              int xEnd = s.X1;
              if (!wholeRows)
              {
                // The row's span inside the ellipse: roots of XX dx^2 + XY dy dx + YY dy^2 =
                // cutoff.
                const float bq = s.ConicXY * dy;
                const float discriminant =
                  bq * bq - 4.0f * s.ConicXX * (s.ConicYY * dy * dy - splatCutoff);
                if (!(discriminant > 0.0f))
                {
                  continue;
                }
                const float root = std::sqrt(discriminant);
                const float inverse = 0.5f / s.ConicXX;
                xBegin = std::max(
                  xBegin, static_cast<int>(std::ceil(s.CenterX + (-bq - root) * inverse - 0.5f)));
                xEnd = std::min(
                  xEnd, static_cast<int>(std::floor(s.CenterX + (-bq + root) * inverse - 0.5f)));
              }
              if (rectangles)
              {
                d->NarrowRow(py, s.DepthNumerator, s.DepthDenominator, xBegin, xEnd);
              }
              // Forward differences along the row (paper 000, section 4): the exponent is
              // quadratic and the depth's numerator and denominator affine in x.
              const float dx0 = xBegin + 0.5f - s.CenterX;
              float beta = s.ConicXX * dx0 * dx0 + s.ConicXY * dx0 * dy + s.ConicYY * dy * dy;
              float betaStep = s.ConicXX * (2.0f * dx0 + 1.0f) + s.ConicXY * dy;
              const float betaStep2 = 2.0f * s.ConicXX;
              const float px0 = xBegin + 0.5f;
              float numerator = s.DepthNumerator[0] * px0 + s.DepthNumerator[1] * py +
                s.DepthNumerator[2];
              float denominator = s.DepthDenominator[0] * px0 + s.DepthDenominator[1] * py +
                s.DepthDenominator[2];
              std::size_t pixel = static_cast<std::size_t>(y) * width + xBegin;
              for (int x = xBegin; x <= xEnd; ++x, ++pixel, beta += betaStep,
                       betaStep += betaStep2, numerator += s.DepthNumerator[0],
                       denominator += s.DepthDenominator[0])
              {
                if (!rectangles && (!(beta < splatCutoff) || beta < 0.0f))
                {
                  continue; // outside the ellipse, or rounding at the span's ends
                }
                const float z = numerator / denominator;
                if (!(z >= nearClip && z <= farClip) || (sceneDepths && z > sceneDepths[pixel]))
                {
                  continue; // clipped, or hidden by opaque geometry already in the scene
                }
                Fragment* pixelFragments = &this->Fragments[pixel * layers];
                std::uint8_t& count = this->FragmentCounts[pixel];
                // Behind such a front by more than its z threshold, it would not join it and
                // cannot show: left out before its weight and predicted normal are computed.
                if (!translucent && count > 0 &&
                  splat::FullyCoveredOpaque(pixelFragments[0], full) &&
                  z > pixelFragments[0].Depth + s.Threshold)
                {
                  continue;
                }
                const float* normal = s.Normal;
                float predicted[3];
                if (d)
                {
                  if (!d->Shade(x + 0.5f, py, z, s.Normal, rectangles, predicted))
                  {
                    continue; // outside the rectangle
                  }
                  normal = predicted;
                }
                const float w = rectangles ? 1.0f : s.Amplitude * exponential(beta);
                if (!translucent)
                {
                  AddOpaque(pixelFragments, count, layers, z, w, negligible, normal, s);
                }
                else
                {
                  this->AddLayered(pixelFragments, count, x, y, z, w, normal, s);
                }
                ++written;
              }
            }
          }
          fragments[b] = written;
        }
      });
    for (vtkIdType f : fragments)
    {
      this->FragmentCount += f;
    }
    if (minifiedInRange > 0)
    {
      minifiedCells.Sum(chunks);
      this->FragmentCount += minifiedCells.Gather(this->Fragments.data(),
        this->FragmentCounts.data(), widestCutoffF, frame.FullCoverage, sceneDepths,
        static_cast<float>(splat::TruncatedMassScale(cutoff, widestCutoff)));
    }
  };

  // Regions whose splats all face away go last: those that the splats before them hide, behind
  // fully covered nearer surfaces, are left out, and the rest are drawn in a second pass.
  const vtkIdType front = backRegions.empty() ? count : backRegions.front().Begin;
  drawRange(0, front);
  if (!backRegions.empty())
  {
    this->CloseCoverageDips();
  }
  std::vector<char> hidden(backRegions.size());
  vtkSMPTools::For(0, static_cast<vtkIdType>(backRegions.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType r = begin; r < end; ++r)
      {
        const vtkSurfelHierarchy::BackRegion& region = backRegions[r];
        hidden[r] = this->RegionHidden(region.Low, region.High, region.Reach, nearDepth);
      }
    });
  vtkIdType drawn = front;
  for (std::size_t r = 0; r < backRegions.size(); ++r)
  {
    const vtkSurfelHierarchy::BackRegion& region = backRegions[r];
    if (!hidden[r])
    {
      if (static_cast<std::size_t>(drawn) != region.Begin)
      {
        std::copy(items.begin() + region.Begin, items.begin() + region.End, items.begin() + drawn);
      }
      drawn += region.End - region.Begin;
    }
  }
  std::fill(reasons.begin() + drawn, reasons.begin() + count, Hidden);
  drawRange(front, drawn);
  // The dips closed before the hidden test stay closed unless regions facing away were drawn.
  if (!translucent && this->EdgeAntialiasing && (backRegions.empty() || drawn != front))
  {
    this->CloseCoverageDips();
  }

  vtkIdType culled[6] = { 0, 0, 0, 0, 0, 0 };
  for (vtkIdType i = 0; i < count; ++i)
  {
    ++culled[reasons[i]];
  }
  this->FrustumCulledCount = culled[OutsideFrustum];
  this->BackfaceCulledCount = culled[BackFacing];
  this->NegligibleCount = culled[Negligible];
  this->HiddenCount = culled[Hidden];
  this->MinifiedCount = culled[Minified];
  this->SplattedCount = culled[Kept] + culled[Minified];
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRasterizer::CloseCoverageDips()
{
  // Inside a surface, the summed weight dips below full coverage where few splats overlap:
  // merged nodes (few per pixel and narrow for their mass; about 2.5 % of a 1 M-surfel sphere's
  // interior pixels, down to a quarter of full coverage, in dips of one or two pixels), surfels
  // at a tight cutoff, scattered points. Drawn so, edge antialiasing lets the surface behind or
  // the background show through them, and one such pixel keeps a whole region facing away from
  // being found hidden. A dip (splat::DipCoverage) is a local minimum of coverage inside a
  // surface (its depth on the line between each pair of opposite neighbors, within four pixel
  // widths: steep surfaces too), which a silhouette's edge never is: the pixel beyond it is
  // covered less, or holds a surface behind. Raised in passes, each closing the dips the last
  // one left, so that a crack between splats two pixels wide and several long (a surfel cutoff
  // that covers at the paper's threshold but not quite at the box filter's) closes from its
  // lowest pixel on; eight passes close all of those on the report's scenes.
  using splat::DipCoverage;
  constexpr int DipPasses = 8;
  const Frame& frame = this->CurrentFrame;
  const int width = frame.View.Viewport.x;
  const int height = frame.View.Viewport.y;
  const int layers = this->Layers;
  const float full = frame.FullCoverage;
  const float depthTolerance = splat::DipDepthTolerance(frame.View.EyeToClip[1][1], height);
  auto front = [&](std::size_t pixel) -> const Fragment* {
    const Fragment& f = this->Fragments[pixel * layers];
    return this->FragmentCounts[pixel] > 0 && !f.Shaded() &&
        f.Alpha >= splat::OpaqueAlpha * f.Weight
      ? &f
      : nullptr;
  };
  // The candidates, partly covered opaque front surfaces away from the image's border, in one
  // sweep; the passes then test only those.
  std::vector<std::vector<std::uint32_t>> rows(height);
  vtkSMPTools::For(1, height - 1,
    [&](vtkIdType rowBegin, vtkIdType rowEnd)
    {
      for (vtkIdType y = rowBegin; y < rowEnd; ++y)
      {
        for (int x = 1; x < width - 1; ++x)
        {
          const std::size_t pixel = static_cast<std::size_t>(y) * width + x;
          const Fragment* f = front(pixel);
          if (f && f->Weight < full && f->Weight >= DipCoverage * full)
          {
            rows[y].push_back(static_cast<std::uint32_t>(pixel));
          }
        }
      }
    });
  std::vector<std::uint32_t> candidates;
  for (const std::vector<std::uint32_t>& row : rows)
  {
    candidates.insert(candidates.end(), row.begin(), row.end());
  }
  std::vector<std::uint32_t> dips;
  for (int pass = 0; pass < DipPasses && !candidates.empty(); ++pass)
  {
    dips.clear();
    auto open = std::partition(candidates.begin(), candidates.end(),
      [&](std::uint32_t pixel)
      {
        const Fragment& f = *front(pixel);
        const float tolerance = depthTolerance * (frame.Perspective ? f.Depth : 1.0f);
        // The four pairs of opposite neighbors: right and left, the two diagonals, down and up.
        for (const std::ptrdiff_t step : { std::ptrdiff_t{ 1 }, width - std::ptrdiff_t{ 1 },
               static_cast<std::ptrdiff_t>(width), width + std::ptrdiff_t{ 1 } })
        {
          const Fragment* g = front(pixel + step);
          const Fragment* h = front(pixel - step);
          if (!g || !h || g->Weight < f.Weight || h->Weight < f.Weight ||
            std::abs(g->Depth + h->Depth - 2.0f * f.Depth) > tolerance)
          {
            return true; // stays open
          }
        }
        return false;
      });
    dips.assign(open, candidates.end());
    candidates.erase(open, candidates.end());
    for (std::uint32_t pixel : dips)
    {
      Fragment& f = this->Fragments[static_cast<std::size_t>(pixel) * layers];
      f = splat::Scaled(f, full / f.Weight, f.Depth);
      f.Weight = std::max(f.Weight, full); // not a rounding below it
    }
    if (dips.empty())
    {
      break;
    }
  }
}

//------------------------------------------------------------------------------
bool vtkSurfaceSplatRasterizer::RegionHidden(
  const glm::dvec3& low, const glm::dvec3& high, double reach, double nearDepth) const
{
  // The region's box, widened by its splats' reach along their axes, in eye space: its corners'
  // nearest depth and projected box, widened by the low-pass filter's reach.
  const Camera& view = this->CurrentFrame.View;
  const glm::dmat4& modelToEye = view.ModelToEye;
  const double scale = std::max({ glm::length(glm::dvec3(modelToEye[0])),
    glm::length(glm::dvec3(modelToEye[1])), glm::length(glm::dvec3(modelToEye[2])) });
  const double cutoff = splat::SplatCutoff(0.0, this->Cutoff, this->AntialiasingCutoff);
  const glm::dvec3 widening(std::max(std::sqrt(cutoff), 1.0) * reach);
  const glm::dvec3 corners[2] = { low - widening, high + widening };
  double nearest = std::numeric_limits<double>::infinity();
  glm::dvec2 lo(std::numeric_limits<double>::infinity());
  glm::dvec2 hi(-std::numeric_limits<double>::infinity());
  const glm::dvec2 viewport(view.Viewport);
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::dvec3 p(modelToEye *
      glm::dvec4(corners[corner & 1].x, corners[(corner >> 1) & 1].y, corners[corner >> 2].z, 1.0));
    nearest = std::min(nearest, -p.z);
    splat::PointProjection projection;
    if (!splat::ProjectPoint(view.EyeToClip, viewport, p, projection))
    {
      return false;
    }
    lo = glm::min(lo, projection.Center);
    hi = glm::max(hi, projection.Center);
  }
  if (!(nearest > nearDepth))
  {
    return false;
  }
  const double margin = this->Internal->MinifiedCells.GetReach() + 1.0;
  const int x0 = static_cast<int>(std::max(std::floor(lo.x - margin), 0.0));
  const int y0 = static_cast<int>(std::max(std::floor(lo.y - margin), 0.0));
  const int x1 = static_cast<int>(std::min(std::ceil(hi.x + margin), viewport.x - 1.0));
  const int y1 = static_cast<int>(std::min(std::ceil(hi.y + margin), viewport.y - 1.0));
  // Hidden where every pixel it may reach has a fully covered opaque front surface nearer than
  // the region by more than the z threshold of its splats: they would be dropped behind it,
  // and nothing behind a fully covered opaque surface shows.
  const float farthest = static_cast<float>(nearest - this->DepthThreshold * scale * reach);
  const float full = this->CurrentFrame.FullCoverage;
  for (int y = y0; y <= y1; ++y)
  {
    for (int x = x0; x <= x1; ++x)
    {
      const std::size_t pixel = static_cast<std::size_t>(y) * view.Viewport.x + x;
      const Fragment& f = this->Fragments[pixel * this->Layers];
      if (this->FragmentCounts[pixel] == 0 || !splat::FullyCoveredOpaque(f, full) ||
        !(f.Depth < farthest))
      {
        return false;
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRasterizer::AddLayered(Fragment* fragments, std::uint8_t& count, int x, int y,
  float z, float w, const float* normal, const ScreenSplat& s) const
{
  // 1. Accumulate-or-separate: the nearest unshaded fragment within the z threshold takes it.
  int nearest = -1;
  float nearestDistance = s.Threshold;
  for (int i = 0; i < count; ++i)
  {
    const float distance = std::abs(fragments[i].Depth - z);
    if (!fragments[i].Shaded() && distance <= nearestDistance)
    {
      nearest = i;
      nearestDistance = distance;
    }
  }
  if (nearest >= 0)
  {
    splat::Accumulate(fragments[nearest], z, w, normal, s.Color, s.Alpha);
    return;
  }
  // Fragments stay sorted front to back: insert the new one in place.
  Fragment candidates[MaximumLayers + 1];
  int n = 0;
  const Fragment added = splat::NewFragment(z, w, normal, s.Color, s.Alpha);
  bool inserted = false;
  for (int i = 0; i < count; ++i)
  {
    if (!inserted && z < fragments[i].Depth)
    {
      candidates[n++] = added;
      inserted = true;
    }
    candidates[n++] = fragments[i];
  }
  if (!inserted)
  {
    candidates[n++] = added;
  }
  // 2. Insertion into a free layer.
  if (n <= this->Layers)
  {
    std::copy(candidates, candidates + n, fragments);
    count = static_cast<std::uint8_t>(n);
    return;
  }
  // 3. Merging: the two fragments nearest in depth are shaded and blended front over back
  //    (eq. 12), which least risks a later surface falling between them.
  int front = 0;
  for (int i = 1; i + 1 < n; ++i)
  {
    if (candidates[i + 1].Depth - candidates[i].Depth <
      candidates[front + 1].Depth - candidates[front].Depth)
    {
      front = i;
    }
  }
  const glm::vec4 f = this->ShadeFragment(candidates[front], x, y);
  const glm::vec4 b = this->ShadeFragment(candidates[front + 1], x, y);
  const glm::vec4 merged = f + b * (1.0f - f.a);
  Fragment& m = candidates[front];
  m.Weight = -1.0f;
  m.Alpha = merged.a;
  for (int c = 0; c < 3; ++c)
  {
    m.Color[c] = merged[c];
  }
  std::copy(candidates + front + 2, candidates + n, candidates + front + 1);
  std::copy(candidates, candidates + n - 1, fragments);
  count = static_cast<std::uint8_t>(n - 1);
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRasterizer::Resolve()
{
  const int width = this->CurrentFrame.View.Viewport.x;
  const int height = this->CurrentFrame.View.Viewport.y;
  const std::size_t pixels = this->FragmentCounts.size();
  this->Colors.assign(4 * pixels, 0);
  this->Depths.assign(pixels, 1.0f);
  const glm::dmat4& P = this->CurrentFrame.View.EyeToClip;
  const int layers = this->Layers;
  // Per row, its first and last covered pixel.
  std::vector<glm::ivec2> rowSpans(height, glm::ivec2(width, -1));

  vtkSMPTools::For(0, height,
    [&](vtkIdType rowBegin, vtkIdType rowEnd)
    {
      for (vtkIdType y = rowBegin; y < rowEnd; ++y)
      {
        for (int x = 0; x < width; ++x)
        {
          const std::size_t pixel = static_cast<std::size_t>(y) * width + x;
          const int count = this->FragmentCounts[pixel];
          if (count == 0)
          {
            continue;
          }
          rowSpans[y] = glm::ivec2(std::min(rowSpans[y].x, x), x);
          // Blend of the pixel's fragments (premultiplied colors, eq. 12), front to back until
          // what lies behind can no longer show.
          const Fragment* fragments = &this->Fragments[pixel * layers];
          glm::vec4 result(0.0f);
          for (int i = 0; i < count && result.a < splat::OpaqueAlpha; ++i)
          {
            const glm::vec4 shaded = this->ShadeFragment(fragments[i], x, static_cast<int>(y));
            result += shaded * (1.0f - result.a);
          }
          std::uint8_t* rgba = &this->Colors[4 * pixel];
          for (int c = 0; c < 4; ++c)
          {
            // Rounded to nearest: the value is not negative.
            rgba[c] = static_cast<std::uint8_t>(
              255.0f * std::min(std::max(result[c], 0.0f), 1.0f) + 0.5f);
          }
          const double zEye = -static_cast<double>(fragments[0].Depth);
          const double zNdc = (P[2][2] * zEye + P[3][2]) / (P[2][3] * zEye + P[3][3]);
          this->Depths[pixel] =
            static_cast<float>(std::min(std::max(0.5 * zNdc + 0.5, 0.0), 1.0));
        }
      }
    });
  int* region = this->CoveredRegion;
  region[0] = width;
  region[1] = height;
  region[2] = region[3] = -1;
  for (int y = 0; y < height; ++y)
  {
    if (rowSpans[y].x <= rowSpans[y].y)
    {
      region[0] = std::min(region[0], rowSpans[y].x);
      region[2] = std::max(region[2], rowSpans[y].y);
      region[1] = std::min(region[1], y);
      region[3] = y;
    }
  }
}

//------------------------------------------------------------------------------
std::vector<float> vtkSurfaceSplatRasterizer::GetWeights() const
{
  std::vector<float> weights(this->FragmentCounts.size(), 0.0f);
  for (std::size_t pixel = 0; pixel < weights.size(); ++pixel)
  {
    if (this->FragmentCounts[pixel] > 0)
    {
      weights[pixel] = this->Fragments[pixel * this->Layers].Weight;
    }
  }
  return weights;
}

//------------------------------------------------------------------------------
void vtkSurfaceSplatRasterizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Cutoff: " << this->Cutoff << "\n";
  os << indent << "DepthThreshold: " << this->DepthThreshold << "\n";
  os << indent << "NumberOfLayers: " << this->NumberOfLayers << "\n";
  os << indent << "EdgeAntialiasing: " << this->EdgeAntialiasing << "\n";
  os << indent << "CoverageThreshold: " << this->CoverageThreshold << "\n";
  os << indent << "Filter: " << static_cast<int>(this->Filter) << "\n";
  os << indent << "BackfaceCulling: " << this->BackfaceCulling << "\n";
  os << indent << "AntialiasingCutoff: " << this->AntialiasingCutoff << "\n";
  os << indent << "MagnifiedLowPassVariance: " << this->MagnifiedLowPassVariance << "\n";
  os << indent << "MinifiedLowPassVariance: " << this->MinifiedLowPassVariance << "\n";
  os << indent << "MinifiedVariance: " << this->MinifiedVariance << "\n";
  os << indent << "SplattedCount: " << this->SplattedCount << "\n";
  os << indent << "MinifiedCount: " << this->MinifiedCount << "\n";
  os << indent << "MergedCount: " << this->MergedCount << "\n";
  os << indent << "HiddenCount: " << this->HiddenCount << "\n";
  os << indent << "FrustumCulledCount: " << this->FrustumCulledCount << "\n";
  os << indent << "BackfaceCulledCount: " << this->BackfaceCulledCount << "\n";
  os << indent << "NegligibleCount: " << this->NegligibleCount << "\n";
  os << indent << "FragmentCount: " << this->FragmentCount << "\n";
}
