// SPDX-License-Identifier: BSD-3-Clause
#include "vtkVolumeSplatRasterizer.h"

#include "SplatVolumeKernel.h"

#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

vtkStandardNewMacro(vtkVolumeSplatRasterizer);

namespace
{
enum SkipReason : std::uint8_t
{
  Kept = 0,
  NearPlane,
  OutsideFrustum
};

// Rows per band: small enough to balance the threads, large enough that few kernels straddle bands.
constexpr int BandHeight = 16;

// Accumulated opacity at which a pixel stops integrating: what is behind changes it by less
// than half an 8-bit step.
constexpr float TerminationAlpha = 1.0f - 1.0f / 512.0f;

// The most a kernel of the 3D Gaussian Splatting convention covers a pixel, as in its viewers.
constexpr float MaximumPeakOpacity = 0.99f;
}

// One kernel after setup, in the single precision the per-pixel loop uses.
struct vtkVolumeSplatRasterizer::ScreenKernel
{
  float CenterX, CenterY;
  float ConicXX, ConicXY, ConicYY; // 1/2 M^-1, so that beta = d^T C d
  float Amplitude; // optical depth (density model) or opacity (peak model) at the center
  float Depth;     // eye-space depth of the center
  float Color[3];
  int X0, X1, Y0, Y1; // inclusive pixel bounds
  SkipReason Skip;
};

// Which lists each pixel uses, with which weight and in which direction.
struct vtkVolumeSplatRasterizer::PixelLists
{
  // Per list, per pixel: the signed weight, positive where the list is traversed in ascending
  // order (the ray's component along the axis is positive), negative where descending, zero
  // where the pixel does not use the list. The depth-sorted list uses every pixel.
  std::array<std::vector<float>, 3> Weights;
  // Per list and band: the pixels' column range using the list (empty when first > last) and
  // whether some use it ascending or descending.
  struct Band
  {
    int First = std::numeric_limits<int>::max();
    int Last = -1;
    bool Ascending = false;
    bool Descending = false;
  };
  std::array<std::vector<Band>, 4> Bands;
};

struct vtkVolumeSplatRasterizer::Internals
{
  std::vector<ScreenKernel> Kernels;
  PixelLists Pixels;
  // Per list, kernels band by band in list order: Offsets per band into Indices.
  std::array<std::vector<vtkIdType>, 4> Offsets;
  std::array<std::vector<vtkIdType>, 4> Indices;
  std::array<std::vector<glm::vec4>, 4> Buffers;
};

namespace
{
using ScreenKernel = vtkVolumeSplatRasterizer::ScreenKernel;
using PixelLists = vtkVolumeSplatRasterizer::PixelLists;

// Composites kernel s under the pixels of rows [rowBegin, rowEnd] whose weight for the list has
// the traversal's sign (all pixels when weights is null), front to back.
void CompositeKernel(const ScreenKernel& s, int rowBegin, int rowEnd, int width, float cutoff,
  bool peakOpacity, const float* weights, bool ascending, const float* sceneDepths,
  glm::vec4* buffer)
{
  const int y0 = std::max(s.Y0, rowBegin);
  const int y1 = std::min(s.Y1, rowEnd);
  for (int y = y0; y <= y1; ++y)
  {
    const float dy = y + 0.5f - s.CenterY;
    // The row's span inside the ellipse: roots of XX dx^2 + XY dy dx + YY dy^2 = cutoff.
    const float bq = s.ConicXY * dy;
    const float discriminant = bq * bq - 4.0f * s.ConicXX * (s.ConicYY * dy * dy - cutoff);
    if (!(discriminant > 0.0f))
    {
      continue;
    }
    const float root = std::sqrt(discriminant);
    const float inverse = 0.5f / s.ConicXX;
    const int xBegin =
      std::max(s.X0, static_cast<int>(std::ceil(s.CenterX + (-bq - root) * inverse - 0.5f)));
    const int xEnd =
      std::min(s.X1, static_cast<int>(std::floor(s.CenterX + (-bq + root) * inverse - 0.5f)));
    const std::size_t row = static_cast<std::size_t>(y) * width;
    for (int x = xBegin; x <= xEnd; ++x)
    {
      const std::size_t p = row + x;
      if (weights && !(ascending ? weights[p] > 0.0f : weights[p] < 0.0f))
      {
        continue;
      }
      glm::vec4& c = buffer[p];
      if (c.a >= TerminationAlpha || (sceneDepths && s.Depth > sceneDepths[p]))
      {
        continue;
      }
      const float dx = x + 0.5f - s.CenterX;
      const float beta = s.ConicXX * dx * dx + s.ConicXY * dx * dy + s.ConicYY * dy * dy;
      if (!(beta < cutoff))
      {
        continue;
      }
      const float g = s.Amplitude * std::exp(-beta);
      const float alpha = peakOpacity ? std::min(g, MaximumPeakOpacity) : -std::expm1(-g);
      const float a = (1.0f - c.a) * alpha;
      c.r += a * s.Color[0];
      c.g += a * s.Color[1];
      c.b += a * s.Color[2];
      c.a += a;
    }
  }
}
}

//------------------------------------------------------------------------------
vtkVolumeSplatRasterizer::vtkVolumeSplatRasterizer()
  : Cutoff(splat::DefaultVolumeCutoff)
  , Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkVolumeSplatRasterizer::~vtkVolumeSplatRasterizer()
{
  delete this->Internal;
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRasterizer::SetKernels(const Kernels& kernels)
{
  this->Input = kernels;
  for (auto& list : this->Lists)
  {
    list.clear();
    list.shrink_to_fit();
  }
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatRasterizer::GetListTraversed(int list) const
{
  return list >= 0 && list <= DepthList && this->Traversed[list];
}

//------------------------------------------------------------------------------
vtkIdType vtkVolumeSplatRasterizer::GetProjectedCount(int list) const
{
  return list >= 0 && list <= DepthList ? this->Projected[list] : 0;
}

//------------------------------------------------------------------------------
vtkIdType vtkVolumeSplatRasterizer::GetProjectedCount() const
{
  return std::accumulate(this->Projected.begin(), this->Projected.end(), vtkIdType(0));
}

//------------------------------------------------------------------------------
const std::vector<vtkIdType>& vtkVolumeSplatRasterizer::GetList(int list)
{
  if (this->Lists[list].size() != this->Input.Count)
  {
    this->BuildList(list);
  }
  return this->Lists[list];
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRasterizer::BuildList(int list)
{
  std::vector<vtkIdType>& order = this->Lists[list];
  const Kernels& k = this->Input;
  const vtkIdType n = static_cast<vtkIdType>(k.Count);
  order.resize(n);
  ++this->ListBuildCount;
  if (k.GridIds)
  {
    // The grid's sheets along the index axis, in the ids' order within each sheet: ids ascend
    // along k, so the Z list is the kernels' own order and the others are gathered by sheet.
    if (list == 2)
    {
      std::iota(order.begin(), order.end(), vtkIdType(0));
      return;
    }
    const vtkIdType nx = k.GridDimensions.x;
    const vtkIdType ny = k.GridDimensions.y;
    const vtkIdType sheets = list == 0 ? nx : ny;
    auto sheetOf = [&](vtkIdType i)
    { return list == 0 ? k.GridIds[i] % nx : (k.GridIds[i] / nx) % ny; };
    std::vector<vtkIdType> offsets(sheets + 1, 0);
    for (vtkIdType i = 0; i < n; ++i)
    {
      ++offsets[sheetOf(i) + 1];
    }
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    for (vtkIdType i = 0; i < n; ++i)
    {
      order[offsets[sheetOf(i)]++] = i;
    }
    return;
  }
  // Point sets: sorted by the coordinate along the list's axis; ties keep the input order.
  const glm::dvec3 axis = k.ListFrame[list];
  std::vector<double> keys(n);
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const double* p = k.Positions + 3 * i;
        keys[i] = glm::dot(axis, glm::dvec3(p[0], p[1], p[2]));
      }
    });
  std::iota(order.begin(), order.end(), vtkIdType(0));
  std::stable_sort(
    order.begin(), order.end(), [&keys](vtkIdType a, vtkIdType b) { return keys[a] < keys[b]; });
  ++this->SortCount;
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRasterizer::BuildDepthList()
{
  const std::vector<ScreenKernel>& kernels = this->Internal->Kernels;
  std::vector<vtkIdType>& order = this->Lists[DepthList];
  order.clear();
  for (std::size_t i = 0; i < kernels.size(); ++i)
  {
    if (kernels[i].Skip == Kept)
    {
      order.push_back(static_cast<vtkIdType>(i));
    }
  }
  // Front to back; equal depths keep the input order.
  std::stable_sort(order.begin(), order.end(),
    [&kernels](vtkIdType a, vtkIdType b) { return kernels[a].Depth < kernels[b].Depth; });
  ++this->SortCount;
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRasterizer::Render(const Camera& camera)
{
  this->Traversed.fill(false);
  this->Projected.fill(0);
  this->NearPlaneCount = 0;
  this->FrustumCulledCount = 0;
  const int width = camera.Viewport.x;
  const int height = camera.Viewport.y;
  const std::size_t pixels = static_cast<std::size_t>(std::max(width, 0)) * std::max(height, 0);
  this->Image.assign(4 * pixels, 0.0f);
  this->Colors.assign(4 * pixels, 0);
  if (pixels == 0)
  {
    return;
  }
  const int bands = (height + BandHeight - 1) / BandHeight;
  const int mode = this->OrderingMode;
  const glm::dvec2 viewport(width, height);

  // 1. The lists each pixel uses. The pixel rays' directions are affine in the pixel position;
  // the lists' axes are those of ListFrame in model coordinates.
  PixelLists& pixelLists = this->Internal->Pixels;
  const splat::PixelRays rays = splat::MakePixelRays(camera.EyeToClip, viewport);
  const glm::dmat3 eyeToList =
    glm::transpose(this->Input.ListFrame) * glm::inverse(glm::dmat3(camera.ModelToEye));
  const glm::dmat3 listRays = eyeToList * rays.Direction;
  auto direction = [&listRays](double x, double y) { return listRays * glm::dvec3(x, y, 1.0); };
  auto dominant = [](const glm::dvec3& d)
  {
    const glm::dvec3 a = glm::abs(d);
    return a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  };
  const int centralList = dominant(direction(0.5 * width, 0.5 * height));
  const double h = this->BlendThreshold;
  for (int list = 0; list < 4; ++list)
  {
    pixelLists.Bands[list].assign(bands, PixelLists::Band());
  }
  if (mode == DEPTH_SORTED)
  {
    for (PixelLists::Band& band : pixelLists.Bands[DepthList])
    {
      band = PixelLists::Band{ 0, width - 1, true, false };
    }
  }
  else
  {
    for (auto& weights : pixelLists.Weights)
    {
      weights.resize(pixels);
    }
    vtkSMPTools::For(0, bands, 1,
      [&](vtkIdType bandBegin, vtkIdType bandEnd)
      {
        for (vtkIdType b = bandBegin; b < bandEnd; ++b)
        {
          const int rowBegin = static_cast<int>(b) * BandHeight;
          const int rowEnd = std::min(rowBegin + BandHeight, height);
          for (int y = rowBegin; y < rowEnd; ++y)
          {
            for (int x = 0; x < width; ++x)
            {
              const glm::dvec3 d = direction(x + 0.5, y + 0.5);
              const double largest = std::max({ std::abs(d.x), std::abs(d.y), std::abs(d.z) });
              const int major = dominant(d);
              const std::size_t p = static_cast<std::size_t>(y) * width + x;
              for (int list = 0; list < 3; ++list)
              {
                double w = 0.0;
                switch (mode)
                {
                  case BLENDED:
                    w = std::max((std::abs(d[list]) / largest - h) / (1.0 - h), 0.0);
                    break;
                  case CLIPPED:
                    w = list == major ? 1.0 : 0.0;
                    break;
                  default: // SINGLE_AXIS
                    w = list == centralList ? 1.0 : 0.0;
                    break;
                }
                w = d[list] > 0.0 ? w : (d[list] < 0.0 ? -w : 0.0);
                pixelLists.Weights[list][p] = static_cast<float>(w);
                if (w != 0.0)
                {
                  PixelLists::Band& band = pixelLists.Bands[list][b];
                  band.First = std::min(band.First, x);
                  band.Last = std::max(band.Last, x);
                  band.Ascending = band.Ascending || w > 0.0;
                  band.Descending = band.Descending || w < 0.0;
                }
              }
            }
          }
        }
      });
  }
  auto listUsed = [&pixelLists](int list)
  {
    const auto& bandsOfList = pixelLists.Bands[list];
    return std::any_of(bandsOfList.begin(), bandsOfList.end(),
      [](const PixelLists::Band& band) { return band.First <= band.Last; });
  };

  // 2. Setup of every kernel, in eye space.
  const Kernels& input = this->Input;
  std::vector<ScreenKernel>& kernels = this->Internal->Kernels;
  kernels.resize(input.Count);
  const glm::dmat4& modelToEye = camera.ModelToEye;
  const glm::dmat3 linear(modelToEye);
  const glm::dmat3 sharedEyeCovariance =
    linear * input.SharedCovariance * glm::transpose(linear);
  const double nearDistance = splat::NearPlaneDistance(camera.EyeToClip);
  const double farDistance = splat::FarPlaneDistance(camera.EyeToClip);
  const double cutoff = this->Cutoff;
  const double compensation = splat::TruncationCompensation(cutoff);
  vtkSMPTools::For(0, static_cast<vtkIdType>(input.Count),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        ScreenKernel& s = kernels[i];
        const double* position = input.Positions + 3 * i;
        const glm::dvec3 e(modelToEye * glm::dvec4(position[0], position[1], position[2], 1.0));
        const glm::dmat3 eyeCovariance = input.Covariances
          ? linear * splat::SymmetricFromComponents(input.Covariances + 6 * i) *
            glm::transpose(linear)
          : sharedEyeCovariance;
        s.Skip = NearPlane;
        splat::VolumeProjection projection;
        if (splat::CrossesNearPlane(e, eyeCovariance, nearDistance, cutoff) ||
          !splat::ProjectVolumeKernel(camera.EyeToClip, viewport, e, projection))
        {
          continue;
        }
        s.Skip = OutsideFrustum;
        const double zExtent = std::sqrt(2.0 * cutoff * eyeCovariance[2][2]);
        if (-e.z - zExtent > farDistance)
        {
          continue;
        }
        const splat::ResamplingKernel footprint =
          splat::MakeVolumeFootprint(projection, eyeCovariance, cutoff);
        glm::ivec4 box;
        if (!splat::CoveredPixels(footprint.Center, footprint.HalfExtent, width, height, box))
        {
          continue;
        }
        s.X0 = box.x;
        s.X1 = box.y;
        s.Y0 = box.z;
        s.Y1 = box.w;
        s.Skip = Kept;
        s.CenterX = static_cast<float>(footprint.Center.x);
        s.CenterY = static_cast<float>(footprint.Center.y);
        s.ConicXX = static_cast<float>(0.5 * footprint.Conic[0][0]);
        s.ConicXY = static_cast<float>(footprint.Conic[1][0]);
        s.ConicYY = static_cast<float>(0.5 * footprint.Conic[1][1]);
        const double strength = input.Strengths[i];
        s.Amplitude = static_cast<float>(
          input.PeakOpacity ? strength : strength * footprint.Amplitude * compensation);
        s.Depth = static_cast<float>(-e.z);
        for (int c = 0; c < 3; ++c)
        {
          s.Color[c] = input.Colors[3 * i + c];
        }
      }
    });
  for (const ScreenKernel& s : kernels)
  {
    this->NearPlaneCount += s.Skip == NearPlane;
    this->FrustumCulledCount += s.Skip == OutsideFrustum;
  }

  // 3. The lists the frame needs, built if missing, and binned into bands in list order; a
  // kernel joins a band's bin when its box overlaps the band's pixels that use the list.
  std::array<bool, 4> used{};
  if (mode == DEPTH_SORTED)
  {
    this->BuildDepthList();
    used[DepthList] = true;
  }
  else
  {
    for (int list = 0; list < 3; ++list)
    {
      used[list] = listUsed(list);
      if (used[list])
      {
        this->GetList(list);
      }
    }
  }
  for (int list = 0; list < 4; ++list)
  {
    this->Traversed[list] = used[list];
    if (!used[list])
    {
      continue;
    }
    const std::vector<PixelLists::Band>& listBands = pixelLists.Bands[list];
    std::vector<vtkIdType>& offsets = this->Internal->Offsets[list];
    std::vector<vtkIdType>& indices = this->Internal->Indices[list];
    offsets.assign(bands + 1, 0);
    auto forEachBand = [&](const ScreenKernel& s, auto&& visit)
    {
      bool any = false;
      for (int b = s.Y0 / BandHeight; b <= s.Y1 / BandHeight; ++b)
      {
        if (s.X0 <= listBands[b].Last && s.X1 >= listBands[b].First)
        {
          visit(b);
          any = true;
        }
      }
      return any;
    };
    const std::vector<vtkIdType>& order = this->Lists[list];
    vtkIdType projected = 0;
    for (vtkIdType k : order)
    {
      const ScreenKernel& s = kernels[k];
      if (s.Skip == Kept)
      {
        projected += forEachBand(s, [&offsets](int b) { ++offsets[b + 1]; });
      }
    }
    this->Projected[list] = projected;
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    indices.resize(offsets[bands]);
    std::vector<vtkIdType> fill(offsets.begin(), offsets.end() - 1);
    for (vtkIdType k : order)
    {
      const ScreenKernel& s = kernels[k];
      if (s.Skip == Kept)
      {
        forEachBand(s, [&](int b) { indices[fill[b]++] = k; });
      }
    }
    this->Internal->Buffers[list].resize(pixels);
  }

  // 4. Compositing, band by band: each list into its own buffer, front to back in each
  // direction the band's pixels need, then the buffers merged with the squared weights.
  const std::vector<float> sceneEyeDepths = this->SceneDepths.size() == pixels
    ? splat::EyeDepthsOfWindowDepths(glm::inverse(camera.EyeToClip), this->SceneDepths)
    : std::vector<float>();
  const float* sceneDepths = sceneEyeDepths.empty() ? nullptr : sceneEyeDepths.data();
  const float cutoffF = static_cast<float>(cutoff);
  vtkSMPTools::For(0, bands, 1,
    [&](vtkIdType bandBegin, vtkIdType bandEnd)
    {
      for (vtkIdType b = bandBegin; b < bandEnd; ++b)
      {
        const int rowBegin = static_cast<int>(b) * BandHeight;
        const int rowEnd = std::min(rowBegin + BandHeight, height) - 1;
        const std::size_t first = static_cast<std::size_t>(rowBegin) * width;
        const std::size_t last = static_cast<std::size_t>(rowEnd + 1) * width;
        for (int list = 0; list < 4; ++list)
        {
          if (!used[list])
          {
            continue;
          }
          glm::vec4* buffer = this->Internal->Buffers[list].data();
          std::fill(buffer + first, buffer + last, glm::vec4(0.0f));
          const PixelLists::Band& band = pixelLists.Bands[list][b];
          const std::vector<vtkIdType>& offsets = this->Internal->Offsets[list];
          const vtkIdType* bin = this->Internal->Indices[list].data();
          const float* weights = list == DepthList ? nullptr : pixelLists.Weights[list].data();
          if (band.Ascending)
          {
            for (vtkIdType k = offsets[b]; k < offsets[b + 1]; ++k)
            {
              CompositeKernel(kernels[bin[k]], rowBegin, rowEnd, width, cutoffF,
                input.PeakOpacity, weights, true, sceneDepths, buffer);
            }
          }
          if (band.Descending)
          {
            for (vtkIdType k = offsets[b + 1]; k-- > offsets[b];)
            {
              CompositeKernel(kernels[bin[k]], rowBegin, rowEnd, width, cutoffF,
                input.PeakOpacity, weights, false, sceneDepths, buffer);
            }
          }
        }
        for (std::size_t p = first; p < last; ++p)
        {
          glm::vec4 color(0.0f);
          if (mode == DEPTH_SORTED)
          {
            color = this->Internal->Buffers[DepthList][p];
          }
          else
          {
            float sum = 0.0f;
            for (int list = 0; list < 3; ++list)
            {
              const float w = pixelLists.Weights[list][p];
              if (used[list] && w != 0.0f)
              {
                color += (w * w) * this->Internal->Buffers[list][p];
                sum += w * w;
              }
            }
            color = sum > 0.0f ? color / sum : glm::vec4(0.0f);
          }
          color = glm::clamp(color, 0.0f, 1.0f);
          for (int c = 0; c < 4; ++c)
          {
            this->Image[4 * p + c] = color[c];
            // Premultiplied: a color channel never exceeds alpha.
            const float v = c < 3 ? std::min(color[c], color.a) : color.a;
            this->Colors[4 * p + c] = static_cast<std::uint8_t>(std::lround(255.0f * v));
          }
        }
      }
    });
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRasterizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OrderingMode: " << this->OrderingMode << "\n";
  os << indent << "BlendThreshold: " << this->BlendThreshold << "\n";
  os << indent << "Cutoff: " << this->Cutoff << "\n";
  os << indent << "Kernels: " << this->Input.Count << "\n";
  for (int list = 0; list <= DepthList; ++list)
  {
    os << indent << "List " << list << ": traversed " << this->Traversed[list] << ", projected "
       << this->Projected[list] << "\n";
  }
  os << indent << "NearPlaneCount: " << this->NearPlaneCount << "\n";
  os << indent << "FrustumCulledCount: " << this->FrustumCulledCount << "\n";
  os << indent << "SortCount: " << this->SortCount << "\n";
  os << indent << "ListBuildCount: " << this->ListBuildCount << "\n";
}
