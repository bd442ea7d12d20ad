// SPDX-License-Identifier: BSD-3-Clause
#include "vtkVolumeSplatRasterizer.h"

#include "SplatCaptureKernel.h"
#include "SplatFloat8.h"
#include "SplatSphericalHarmonics.h"
#include "SplatVolumeLayerCompositor.h"
#include "SplatVolumeKernel.h"
#include "vtkGaussianSplatRasterizer.h"
#include "vtkVolumeSplatSheetCompositor.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

vtkStandardNewMacro(vtkVolumeSplatRasterizer);

namespace
{
using splat::Kept;
using splat::NearPlane;
using splat::OutsideFrustum;

// Rows per band: small enough to balance the threads, large enough that few kernels straddle bands.
constexpr int BandHeight = 16;
}

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

// A kernel in a band's bin of a list, with its compositing layer (see
// splat::VolumeLayerCompositor).
struct BinnedKernel
{
  vtkVolumeSplatRasterizer::ScreenKernel Kernel;
  vtkIdType Layer;
};

struct vtkVolumeSplatRasterizer::Internals
{
  std::vector<ScreenKernel> Kernels;
  PixelLists Pixels;
  // Per list, copies of the kernels band by band in list order (read in sequence by the
  // compositing, where the lists' order scatters the kernels in memory): Offsets per band into
  // Bins.
  std::array<std::vector<vtkIdType>, 4> Offsets;
  std::array<std::vector<BinnedKernel>, 4> Bins;
  std::array<std::vector<glm::vec4>, 4> Buffers;
  // Image data's sheets; captures in their depth order; the frame's colors of shaded kernels
  // for them.
  vtkNew<vtkVolumeSplatSheetCompositor> Sheets;
  vtkNew<vtkGaussianSplatRasterizer> Captures;
  std::vector<float> ShadedColors;
  // The kernels' spherical-harmonic colors for ViewKey, the view point (w = 1) or the view
  // axis (w = 0) in model coordinates, up to ViewDegree (0: not evaluated).
  std::vector<float> ViewColors;
  glm::dvec4 ViewKey{ 0.0 };
  int ViewDegree = 0;
};

namespace
{
using ScreenKernel = vtkVolumeSplatRasterizer::ScreenKernel;
using PixelLists = vtkVolumeSplatRasterizer::PixelLists;

// The spherical-harmonic colors of kernels begin (a multiple of eight) to end (of `count`) seen
// from `key` (the view point, w = 1, or the view axis, w = 0), into colors (RGB per kernel).
// Eight kernels at a time, one per lane: their rows of coefficients transposed eight floats at
// a time, so that each float is one fused step for eight kernels. SphericalHarmonicsColor's
// result but for rounding, at 3.6 times its speed (1 M kernels of degree 3 on one thread, AVX2:
// 12.6 ms against 45.5). A function of its own for SPLAT_VECTOR_CLONES_INLINED.
SPLAT_VECTOR_CLONES_INLINED void EvaluateViewColors(const double* positions,
  const float* coefficients, vtkIdType count, int stride, int degree, const glm::dvec4& key,
  vtkIdType begin, vtkIdType end, float* colors)
{
  using splat::Float8;
  const auto direction = [&](vtkIdType i)
  {
    const double* p = positions + 3 * i;
    return key.w != 0.0 ? glm::vec3(glm::dvec3(p[0], p[1], p[2]) - glm::dvec3(key))
                        : glm::vec3(key);
  };
  const int floats = 3 * splat::SphericalHarmonicsCoefficients(degree);
  const int blocks = (floats + 7) / 8;
  vtkIdType i = begin;
  // A row is read in whole blocks of eight floats, past its end into the next kernel's row:
  // the kernels with no row after theirs take the per-kernel sums.
  for (; i + 8 <= end && (8 * blocks <= stride || i + 8 < count); i += 8)
  {
    alignas(32) float d[3][8];
    for (int lane = 0; lane < 8; ++lane)
    {
      const glm::vec3 v = direction(i + lane);
      for (int c = 0; c < 3; ++c)
      {
        d[c][lane] = v[c];
      }
    }
    const Float8 x = Float8::Load(d[0]), y = Float8::Load(d[1]), z = Float8::Load(d[2]);
    const Float8 length = Float8::Sqrt(x * x + y * y + z * z);
    const Float8 zero(0.0f);
    const auto unit = [&](const Float8& v)
    { return Float8::SelectLess(zero, length, v / length, zero); };
    Float8 basis[splat::MaximumSphericalHarmonicsCoefficients];
    splat::SphericalHarmonicsBasis(unit(x), unit(y), unit(z), degree, basis);
    // The rows of the group two ahead, asked for now: read eight rows at a time, they come
    // from memory at half the speed otherwise (22 ms instead of 12.6 in the figure above).
    splat::PrefetchBytes(coefficients + stride * (i + 16), 8 * sizeof(float) * stride);
    Float8 columns[3 * splat::MaximumSphericalHarmonicsCoefficients];
    for (int block = 0; block < blocks; ++block)
    {
      Float8::LoadColumns(coefficients + stride * i + 8 * block, stride, columns + 8 * block);
    }
    // Three sums in registers (an array indexed by the float would keep them in memory).
    Float8 red(0.5f), green(0.5f), blue(0.5f);
    for (int k = 0; k < floats / 3; ++k)
    {
      red = red + basis[k] * columns[3 * k];
      green = green + basis[k] * columns[3 * k + 1];
      blue = blue + basis[k] * columns[3 * k + 2];
    }
    alignas(32) float rgb[3][8];
    const Float8 sums[3] = { red, green, blue };
    for (int c = 0; c < 3; ++c)
    {
      const Float8 clamped = Float8::SelectLess(sums[c], zero, zero, sums[c]);
      Float8::SelectLess(1.0f, clamped, 1.0f, clamped).Store(rgb[c]);
    }
    for (int lane = 0; lane < 8; ++lane)
    {
      for (int c = 0; c < 3; ++c)
      {
        colors[3 * (i + lane) + c] = rgb[c][lane];
      }
    }
  }
  for (; i < end; ++i)
  {
    const glm::vec3 color =
      splat::SphericalHarmonicsColor(coefficients + stride * i, degree, direction(i));
    std::copy_n(&color.x, 3, colors + 3 * i);
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
  this->Internal->ViewDegree = 0;
  this->Internal->Sheets->Reset();
  for (auto& list : this->Lists)
  {
    list.clear();
    list.shrink_to_fit();
  }
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRasterizer::SetLighting(
  const std::vector<splat::Light>& lights, const splat::Material& material, bool twoSided)
{
  this->Lights = lights;
  this->Material = material;
  this->TwoSidedLighting = twoSided;
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
  if (this->OrderingMode == DEPTH_SORTED && this->Input.PeakOpacity)
  {
    this->RenderCaptures(camera);
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

  std::array<bool, 4> used{};
  used[DepthList] = mode == DEPTH_SORTED;
  for (int list = 0; list < 3 && mode != DEPTH_SORTED; ++list)
  {
    used[list] = listUsed(list);
  }
  this->SheetsUsed = this->RenderSheets(camera, used);
  if (this->SheetsUsed)
  {
    return;
  }

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
  const auto filter = static_cast<splat::FootprintFilter>(this->FootprintFilter);
  const double filterVariance = splat::FilterVariance(filter);
  const bool bandLimit = filter == splat::FootprintFilter::BandLimit;
  // Normals go to eye coordinates by the inverse transpose.
  const glm::mat3 normalToEye(glm::transpose(glm::inverse(linear)));
  const float* viewColors = this->UpdateViewColors(camera, rays.Perspective);
  const float* colors = viewColors ? viewColors : input.Colors;
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
          splat::MakeVolumeFootprint(
            projection, eyeCovariance, cutoff, filterVariance, bandLimit);
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
        s.Amplitude = static_cast<float>(input.PeakOpacity
            ? strength *
              splat::PeakOpacityCompensation(
                filter, footprint.Covariance - glm::dmat2(filterVariance))
            : strength * footprint.Amplitude * compensation);
        s.Depth = static_cast<float>(-e.z);
        glm::vec3 color(colors[3 * i], colors[3 * i + 1], colors[3 * i + 2]);
        if (input.Normals)
        {
          color = this->ShadeKernel(
            color, glm::vec3(e), normalToEye, input.Normals + 3 * i, !rays.Perspective);
        }
        for (int c = 0; c < 3; ++c)
        {
          s.Color[c] = color[c];
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
  // For image data, the sheet of kernel k along list `list`'s axis: its compositing layer.
  const glm::ivec3 dimensions = input.GridDimensions;
  auto layerOf = [&input, dimensions](int list, vtkIdType k) -> vtkIdType
  {
    const vtkIdType id = input.GridIds[k];
    const vtkIdType nx = dimensions.x, ny = dimensions.y;
    return list == 0 ? id % nx : (list == 1 ? (id / nx) % ny : id / (nx * ny));
  };
  if (mode == DEPTH_SORTED)
  {
    this->BuildDepthList();
  }
  else
  {
    for (int list = 0; list < 3; ++list)
    {
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
    // A counting sort of the kept kernels by band and slot, in parallel over chunks: each chunk
    // counts its kernels per band and slot, the counts become each chunk's start in each band's
    // bin, and each chunk fills its places, so the bins do not depend on the number of threads.
    // Point sets go through the list in chunks, one slot per band. Grids go through the kernels
    // in memory order (the X and Y lists would gather them from all over memory), a slot per
    // sheet: the bins come out sheet by sheet, in id order within a sheet.
    const bool grid = input.GridIds && list != DepthList;
    const std::vector<vtkIdType>& order = this->Lists[list];
    const vtkIdType slots = grid ? (list == 0 ? dimensions.x
                                              : (list == 1 ? dimensions.y : dimensions.z))
                                 : 1;
    const vtkIdType keys = bands * slots;
    const vtkIdType total = grid ? static_cast<vtkIdType>(kernels.size())
                                 : static_cast<vtkIdType>(order.size());
    const vtkIdType chunkSize = 1 << 16;
    const vtkIdType chunks = (total + chunkSize - 1) / chunkSize;
    auto forEachKept = [&](vtkIdType chunk, auto&& visit)
    {
      const vtkIdType end = std::min(total, (chunk + 1) * chunkSize);
      for (vtkIdType j = chunk * chunkSize; j < end; ++j)
      {
        const vtkIdType k = grid ? j : order[j];
        if (kernels[k].Skip == Kept)
        {
          visit(k, grid ? layerOf(list, k) : 0);
        }
      }
    };
    std::vector<vtkIdType> starts(static_cast<std::size_t>(chunks * keys), 0);
    std::vector<vtkIdType> projected(chunks, 0);
    vtkSMPTools::For(0, chunks,
      [&](vtkIdType chunkBegin, vtkIdType chunkEnd)
      {
        for (vtkIdType c = chunkBegin; c < chunkEnd; ++c)
        {
          vtkIdType* count = starts.data() + c * keys;
          forEachKept(c,
            [&](vtkIdType k, vtkIdType slot)
            {
              projected[c] +=
                forEachBand(kernels[k], [count, slot, slots](int b) { ++count[b * slots + slot]; });
            });
        }
      });
    this->Projected[list] = std::accumulate(projected.begin(), projected.end(), vtkIdType(0));
    std::vector<vtkIdType>& offsets = this->Internal->Offsets[list];
    offsets.assign(bands + 1, 0);
    vtkIdType next = 0;
    for (vtkIdType key = 0; key < keys; ++key)
    {
      for (vtkIdType c = 0; c < chunks; ++c)
      {
        const vtkIdType count = starts[c * keys + key];
        starts[c * keys + key] = next;
        next += count;
      }
      offsets[key / slots + 1] = next;
    }
    std::vector<BinnedKernel>& bin = this->Internal->Bins[list];
    bin.resize(offsets[bands]);
    vtkSMPTools::For(0, chunks,
      [&](vtkIdType chunkBegin, vtkIdType chunkEnd)
      {
        for (vtkIdType c = chunkBegin; c < chunkEnd; ++c)
        {
          vtkIdType* place = starts.data() + c * keys;
          forEachKept(c,
            [&](vtkIdType k, vtkIdType slot)
            {
              const BinnedKernel binned{ kernels[k], grid ? slot : k };
              forEachBand(
                kernels[k], [&](int b) { bin[place[b * slots + slot]++] = binned; });
            });
        }
      });
    this->Internal->Buffers[list].resize(pixels);
  }

  // 4. Compositing, band by band: each list into its own buffer, front to back in each
  // direction the band's pixels need, then the buffers merged with the squared weights.
  const std::vector<float> sceneEyeDepths = this->SceneEyeDepths(camera);
  const float* sceneDepths = sceneEyeDepths.empty() ? nullptr : sceneEyeDepths.data();
  const float cutoffF = static_cast<float>(cutoff);
  vtkSMPTools::For(0, bands, 1,
    [&](vtkIdType bandBegin, vtkIdType bandEnd)
    {
      for (vtkIdType b = bandBegin; b < bandEnd; ++b)
      {
        const int rowBegin = static_cast<int>(b) * BandHeight;
        const int rowEnd = std::min(rowBegin + BandHeight, height) - 1;
        splat::VolumeLayerCompositor compositor(
          width, rowBegin, rowEnd, cutoffF, input.PeakOpacity, sceneDepths);
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
          const BinnedKernel* bin = this->Internal->Bins[list].data();
          const float* weights = list == DepthList ? nullptr : pixelLists.Weights[list].data();
          for (const bool ascending : { true, false })
          {
            if (ascending ? !band.Ascending : !band.Descending)
            {
              continue;
            }
            compositor.Begin(weights, ascending, buffer);
            const vtkIdType count = offsets[b + 1] - offsets[b];
            const auto binned = [&](vtkIdType n) -> const BinnedKernel&
            { return bin[ascending ? offsets[b] + n : offsets[b + 1] - 1 - n]; };
            vtkIdType layer = -1;
            for (vtkIdType n = 0; n < count; ++n)
            {
              const BinnedKernel& k = binned(n);
              if (k.Layer != layer)
              {
                compositor.Flush(weights, ascending, buffer);
                layer = k.Layer;
                // A kernel alone in its layer (every point kernel) goes under the pixels
                // directly.
                if (n + 1 == count || binned(n + 1).Layer != layer)
                {
                  compositor.Composite(k.Kernel, weights, ascending, buffer);
                  continue;
                }
              }
              compositor.Add(k.Kernel);
            }
            compositor.Flush(weights, ascending, buffer);
          }
        }
        this->MergeBuffers(first, last, used);
      }
    });
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRasterizer::MergeBuffers(
  std::size_t first, std::size_t last, const std::array<bool, 4>& used)
{
  for (std::size_t p = first; p < last; ++p)
  {
    glm::vec4 color(0.0f);
    if (this->OrderingMode == DEPTH_SORTED)
    {
      color = this->Internal->Buffers[DepthList][p];
    }
    else
    {
      float sum = 0.0f;
      for (int list = 0; list < 3; ++list)
      {
        const float w = this->Internal->Pixels.Weights[list][p];
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
      // Rounded by truncation (v is in [0, 1]): std::lround was a library call per channel.
      this->Colors[4 * p + c] = static_cast<std::uint8_t>(255.0f * v + 0.5f);
    }
  }
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatRasterizer::RenderSheets(const Camera& camera, const std::array<bool, 4>& used)
{
  const Kernels& input = this->Input;
  if (!this->SheetResampling || !input.GridIds || this->OrderingMode == DEPTH_SORTED)
  {
    return false;
  }
  // The nearest opaque surface: the sheets need it behind every kernel.
  const float nearestWindowDepth = this->SceneDepths.empty()
    ? 1.0f
    : *std::min_element(this->SceneDepths.begin(), this->SceneDepths.end());
  const double nearestSceneDepth =
    splat::EyeDepthsOfWindowDepths(glm::inverse(camera.EyeToClip), { nearestWindowDepth })[0];
  vtkVolumeSplatSheetCompositor* sheets = this->Internal->Sheets;
  sheets->SetMergePairs(this->SheetMerging);
  sheets->SetFootprintFilter(this->FootprintFilter);
  if (!sheets->BeginFrame(input, camera, this->Cutoff, nearestSceneDepth,
        { used[0], used[1], used[2] }))
  {
    return false;
  }
  const float* colors = this->FrameColors(camera);
  const std::size_t pixels = this->Colors.size() / 4;
  for (int list = 0; list < 3; ++list)
  {
    this->Traversed[list] = used[list];
    if (used[list])
    {
      this->Projected[list] = sheets->Render(list, this->GetList(list), colors,
        input.Normals != nullptr, this->Internal->Pixels.Weights[list].data(),
        this->Internal->Buffers[list]);
    }
  }
  this->MergeAllBuffers(used);
  return true;
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRasterizer::MergeAllBuffers(const std::array<bool, 4>& used)
{
  const std::size_t pixels = this->Colors.size() / 4;
  const vtkIdType chunk = 1 << 14;
  vtkSMPTools::For(0, static_cast<vtkIdType>((pixels + chunk - 1) / chunk),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType c = begin; c < end; ++c)
      {
        this->MergeBuffers(c * chunk, std::min<std::size_t>(pixels, (c + 1) * chunk), used);
      }
    });
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRasterizer::RenderCaptures(const Camera& camera)
{
  vtkGaussianSplatRasterizer* captures = this->Internal->Captures;
  captures->SetFootprintFilter(static_cast<splat::FootprintFilter>(this->FootprintFilter));
  const std::vector<float> sceneEyeDepths = this->SceneEyeDepths(camera);
  captures->Render(this->Input, this->FrameColors(camera), camera,
    sceneEyeDepths.empty() ? nullptr : sceneEyeDepths.data(), this->Internal->Buffers[DepthList]);
  this->Traversed[DepthList] = true;
  this->Projected[DepthList] = captures->GetProjectedCount();
  this->NearPlaneCount = captures->GetNearPlaneCount();
  this->FrustumCulledCount = captures->GetOutsideViewCount();
  ++this->SortCount;
  this->MergeAllBuffers({ false, false, false, true });
}

//------------------------------------------------------------------------------
const float* vtkVolumeSplatRasterizer::FrameColors(const Camera& camera)
{
  const Kernels& input = this->Input;
  const bool parallel = splat::IsParallelProjection(camera.EyeToClip);
  const float* viewColors = this->UpdateViewColors(camera, !parallel);
  const float* colors = viewColors ? viewColors : input.Colors;
  if (!input.Normals)
  {
    return colors;
  }
  std::vector<float>& shaded = this->Internal->ShadedColors;
  shaded.resize(3 * input.Count);
  const glm::dmat3 linear(camera.ModelToEye);
  const glm::mat3 normalToEye(glm::transpose(glm::inverse(linear)));
  vtkSMPTools::For(0, static_cast<vtkIdType>(input.Count),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const double* p = input.Positions + 3 * i;
        const glm::vec3 eye(camera.ModelToEye * glm::dvec4(p[0], p[1], p[2], 1.0));
        const float* c = colors + 3 * i;
        const glm::vec3 color = this->ShadeKernel(
          glm::vec3(c[0], c[1], c[2]), eye, normalToEye, input.Normals + 3 * i, parallel);
        std::copy_n(&color.x, 3, shaded.begin() + 3 * i);
      }
    });
  return shaded.data();
}

//------------------------------------------------------------------------------
std::vector<float> vtkVolumeSplatRasterizer::SceneEyeDepths(const Camera& camera) const
{
  const std::size_t pixels = this->Colors.size() / 4;
  return this->SceneDepths.size() == pixels && pixels > 0
    ? splat::EyeDepthsOfWindowDepths(glm::inverse(camera.EyeToClip), this->SceneDepths)
    : std::vector<float>();
}

//------------------------------------------------------------------------------
glm::vec3 vtkVolumeSplatRasterizer::ShadeKernel(const glm::vec3& color, const glm::vec3& eye,
  const glm::mat3& normalToEye, const float* modelNormal, bool parallelProjection) const
{
  glm::vec3 normal = normalToEye * glm::vec3(modelNormal[0], modelNormal[1], modelNormal[2]);
  const float length = glm::length(normal);
  normal = length > 0.0f ? normal / length : glm::vec3(0.0f);
  if (this->TwoSidedLighting && glm::dot(normal, eye) > 0.0f)
  {
    normal = -normal;
  }
  return glm::clamp(
    splat::Shade(this->Lights, this->Material, color, eye, normal, parallelProjection), 0.0f,
    1.0f);
}

//------------------------------------------------------------------------------
const float* vtkVolumeSplatRasterizer::UpdateViewColors(const Camera& camera, bool perspective)
{
  const Kernels& input = this->Input;
  const int degree = input.SphericalHarmonics
    ? std::min(input.SphericalHarmonicsDegree, this->MaximumSphericalHarmonicsDegree)
    : 0;
  if (degree == 0)
  {
    return nullptr; // the Colors are the degree-0 colors
  }
  const glm::dmat4 eyeToModel = glm::inverse(camera.ModelToEye);
  const glm::dvec4 key = perspective
    ? eyeToModel * glm::dvec4(0.0, 0.0, 0.0, 1.0)
    : glm::dvec4(glm::normalize(glm::dvec3(eyeToModel * glm::dvec4(0.0, 0.0, -1.0, 0.0))), 0.0);
  Internals& internal = *this->Internal;
  if (degree == internal.ViewDegree && key == internal.ViewKey)
  {
    return internal.ViewColors.data();
  }
  internal.ViewColors.resize(3 * input.Count);
  const int stride = 3 * splat::SphericalHarmonicsCoefficients(input.SphericalHarmonicsDegree);
  // In whole groups of eight, so that which kernels EvaluateViewColors takes eight at a time
  // (and so their rounding) does not depend on the threads' ranges.
  const vtkIdType count = static_cast<vtkIdType>(input.Count);
  vtkSMPTools::For(0, (count + 7) / 8,
    [&](vtkIdType begin, vtkIdType end)
    {
      EvaluateViewColors(input.Positions, input.SphericalHarmonics, count, stride, degree, key,
        8 * begin, std::min(8 * end, count), internal.ViewColors.data());
    });
  internal.ViewDegree = degree;
  internal.ViewKey = key;
  ++this->ViewColorCount;
  return internal.ViewColors.data();
}

//------------------------------------------------------------------------------
void vtkVolumeSplatRasterizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OrderingMode: " << this->OrderingMode << "\n";
  os << indent << "BlendThreshold: " << this->BlendThreshold << "\n";
  os << indent << "Cutoff: " << this->Cutoff << "\n";
  os << indent << "FootprintFilter: " << this->FootprintFilter << "\n";
  os << indent << "SheetResampling: " << this->SheetResampling << "\n";
  os << indent << "SheetMerging: " << this->SheetMerging << "\n";
  os << indent << "SheetsUsed: " << this->SheetsUsed << "\n";
  os << indent << "Kernels: " << this->Input.Count << "\n";
  os << indent << "Shaded: " << (this->Input.Normals != nullptr) << "\n";
  os << indent << "SphericalHarmonicsDegree: "
     << (this->Input.SphericalHarmonics ? this->Input.SphericalHarmonicsDegree : -1) << "\n";
  os << indent << "MaximumSphericalHarmonicsDegree: " << this->MaximumSphericalHarmonicsDegree
     << "\n";
  os << indent << "Lights: " << this->Lights.size() << "\n";
  os << indent << "TwoSidedLighting: " << this->TwoSidedLighting << "\n";
  for (int list = 0; list <= DepthList; ++list)
  {
    os << indent << "List " << list << ": traversed " << this->Traversed[list] << ", projected "
       << this->Projected[list] << "\n";
  }
  os << indent << "NearPlaneCount: " << this->NearPlaneCount << "\n";
  os << indent << "FrustumCulledCount: " << this->FrustumCulledCount << "\n";
  os << indent << "SortCount: " << this->SortCount << "\n";
  os << indent << "ListBuildCount: " << this->ListBuildCount << "\n";
  os << indent << "ViewColorCount: " << this->ViewColorCount << "\n";
}
