// SPDX-License-Identifier: BSD-3-Clause
#include "vtkVolumeSplatSheetCompositor.h"

#include "SplatVolumeKernel.h"
#include "SplatVolumeLayerCompositor.h"

#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

vtkStandardNewMacro(vtkVolumeSplatSheetCompositor);

namespace
{
// Intermediate rows per band of the compositing: twice the rasterizer's screen bands, as a
// footprint crossing a band's edge is set up once per band (a few rows tall, it crosses one
// of 16-row bands about a quarter of the time) and an intermediate image has fewer rows.
constexpr int BandHeight = 32;

// Intermediate pixels per standard deviation of the narrowest footprint on the front sheet.
constexpr double SamplesPerSigma = 0.7;

// The largest intermediate image, in pixels, beyond which the exact path is cheaper.
constexpr double MaximumIntermediatePixels = 1 << 26;

// The index axes spanning list `list`'s sheets, in the order the list visits them within a
// sheet (voxel ids ascend): u varies fastest.
glm::ivec2 SheetAxes(int list)
{
  return list == 0 ? glm::ivec2(1, 2) : (list == 1 ? glm::ivec2(0, 2) : glm::ivec2(0, 1));
}

// Where a screen pixel reads no intermediate image.
const glm::vec2 Unused(-1.0e30f);

// The row length of a cross table of the given reach: a further group of lanes of zeros.
int CrossStride(int reach)
{
  return 2 * reach + 1 + 8;
}

// Each sheet is cut into Tiles x Tiles tiles, each with the footprint of the rays through its
// center: in a perspective view the rays' direction, and so the footprints' shape, changes
// across a sheet.
constexpr int Tiles = 4;

// A footprint on the intermediate image, shared by the voxels of one tile of a sheet.
struct Footprint
{
  float ConicXX, ConicXY, ConicYY; // as in ScreenKernel
  float Amplitude;                 // optical depth per unit of strength and path length
  glm::vec2 HalfExtent;
  // The cross table of splat::VolumeLayerCompositor::AddFactored in Internals::List::Cross,
  // or Reach 0 where its factors would leave the float range (Add instead).
  std::size_t Cross;
  int Reach;
};

// Where one sheet lands on the intermediate image: voxel (u, v) at Scale (u, v) + Offset; the
// largest half extent of its footprints.
struct Sheet
{
  float Scale;
  glm::vec2 Offset;
  glm::vec2 HalfExtent;
};
}

struct vtkVolumeSplatSheetCompositor::Internals
{
  Kernels Input;
  Camera View;
  bool Perspective = false;
  double Cutoff = splat::DefaultVolumeCutoff;
  // Index coordinates y of the grid, model point GridOrigin + GridAxes y.
  glm::dmat4 IndexToEye{ 1.0 };
  glm::dmat4 EyeToIndex{ 1.0 };
  glm::dvec3 Eye{ 0.0 };       // perspective: the eye in index coordinates
  glm::dvec3 Direction{ 0.0 }; // parallel: the view direction in index coordinates
  glm::dmat3 IndexCovariance{ 1.0 };

  // Per list, built from the kernels once: each list entry's (u, v) in its sheet packed as
  // u + 65536 v, and per sheet and row v the first list entry at or after it.
  std::array<std::vector<std::uint32_t>, 3> Lattice;
  // Per list, each entry's color and strength, in list order so that the compositing reads
  // them in sequence (the X and Y lists would gather them from all over memory), and the
  // colors they came from.
  std::array<std::vector<glm::vec4>, 3> Values;
  std::array<const float*, 3> ValueColors{};
  std::array<std::vector<vtkIdType>, 3> RowStarts;
  // Per list, sheet and row: the smallest and largest u of its entries, packed as the lattice.
  std::array<std::vector<std::uint32_t>, 3> RowSpans;

  // Per list, per frame.
  struct List
  {
    bool Ascending = true;
    int Reference = 0; // the front sheet, whose plane holds the intermediate image
    double Resolution = 1.0; // intermediate pixels per lattice unit of the front sheet
    glm::dvec2 Origin{ 0.0 }; // intermediate pixel (X, Y) has its center at Origin + (X, Y) + 0.5
    glm::ivec2 Size{ 0 };
    std::vector<Sheet> Sheets;
    std::vector<Footprint> Footprints; // per sheet, Tiles x Tiles, row by row
    glm::vec2 TileScale{ 0.0f };       // tiles per lattice unit along u and v
    std::vector<float> Cross;
  };
  std::array<List, 3> Lists;
  std::vector<glm::vec4> Image;
  std::vector<glm::vec2> Samples; // per screen pixel: where it reads the intermediate image

  // The frame's geometry of list `list`; false where the sheets do not apply.
  bool MakeList(int list);
  void BuildTables(int list, const std::vector<vtkIdType>& order);
  // Per screen pixel taking list `list` in its traversal's direction, where its ray meets the
  // intermediate image, in pixels; Unused elsewhere.
  void FindSamples(int list, const float* weights);
  // Composites the sheets of list `list` into Image, by bands of its rows.
  void Composite(int list);
  void CompositeBand(int list, int band);
};

//------------------------------------------------------------------------------
bool vtkVolumeSplatSheetCompositor::Internals::MakeList(int list)
{
  const glm::ivec2 axes = SheetAxes(list);
  const glm::ivec3 dimensions = this->Input.GridDimensions;
  const int sheets = dimensions[list];
  const glm::dmat3& S = this->IndexCovariance;
  const double reach = std::sqrt(2.0 * this->Cutoff * S[list][list]) + 0.5;
  List& l = this->Lists[list];
  // The eye outside the slab of sheets: every ray meeting the kernels crosses them in one order.
  if (this->Perspective)
  {
    const double e = this->Eye[list];
    if (!(e < -reach || e > sheets - 1 + reach))
    {
      return false;
    }
    l.Ascending = e < 0.0;
  }
  else
  {
    if (this->Direction[list] == 0.0)
    {
      return false;
    }
    l.Ascending = this->Direction[list] > 0.0;
  }
  l.Reference = l.Ascending ? 0 : sheets - 1;
  const double eyeOffset = this->Perspective ? l.Reference - this->Eye[list] : 0.0;
  const glm::dvec2 eyeUV(this->Eye[axes.x], this->Eye[axes.y]);
  const glm::dvec2 shear = this->Perspective
    ? glm::dvec2(0.0)
    : glm::dvec2(this->Direction[axes.x], this->Direction[axes.y]) / this->Direction[list];
  const glm::dmat3 indexToEye(this->IndexToEye);
  const glm::dvec2 viewport(this->View.Viewport);
  const double compensation = splat::TruncationCompensation(this->Cutoff);
  const double boxMass = std::erf(std::sqrt(this->Cutoff));
  const double boxCompensation = 1.0 / (boxMass * boxMass);
  const double volume = std::abs(glm::determinant(this->Input.GridAxes));
  const glm::dvec2 extent(dimensions[axes.x] - 1, dimensions[axes.y] - 1);
  glm::dvec2 lo(std::numeric_limits<double>::infinity());
  glm::dvec2 hi(-std::numeric_limits<double>::infinity());
  // Per sheet and tile, the voxel's Gaussian integrated along the rays (their direction per
  // unit of index along the list's axis at the tile's center, t) as a density on the sheet's
  // lattice, plus the screen's low-pass filter, a unit pixel, mapped onto the sheet there.
  const int u = axes.x, v = axes.y, a = list;
  const glm::dvec2 tileSize = (extent + 1.0) / static_cast<double>(Tiles);
  l.TileScale = glm::vec2(1.0 / tileSize);
  std::vector<glm::dmat2> lattices(static_cast<std::size_t>(sheets) * Tiles * Tiles);
  for (std::size_t f = 0; f < lattices.size(); ++f)
  {
    const int k = static_cast<int>(f / (Tiles * Tiles));
    const int tile = static_cast<int>(f % (Tiles * Tiles));
    const glm::dvec2 center =
      (glm::dvec2(tile % Tiles, tile / Tiles) + 0.5) * tileSize - 0.5;
    const glm::dvec2 t =
      this->Perspective ? (center - eyeUV) / (k - this->Eye[list]) : shear;
    glm::dmat2& lattice = lattices[f];
    lattice[0][0] = S[u][u] - 2.0 * t.x * S[u][a] + t.x * t.x * S[a][a];
    lattice[0][1] = lattice[1][0] =
      S[u][v] - t.x * S[v][a] - t.y * S[u][a] + t.x * t.y * S[a][a];
    lattice[1][1] = S[v][v] - 2.0 * t.y * S[v][a] + t.y * t.y * S[a][a];
    glm::dvec3 point(0.0);
    point[u] = center.x;
    point[v] = center.y;
    point[a] = k;
    splat::VolumeProjection projection;
    if (!splat::ProjectVolumeKernel(this->View.EyeToClip, viewport,
          glm::dvec3(this->IndexToEye * glm::dvec4(point, 1.0)), projection))
    {
      return false;
    }
    const glm::dmat3 toPixels = projection.Jacobian * indexToEye;
    const glm::dmat2 sheetToPixels(
      toPixels[u][0], toPixels[u][1], toPixels[v][0], toPixels[v][1]);
    const double determinant = glm::determinant(sheetToPixels);
    if (!(std::abs(determinant) > 1e-12) || !std::isfinite(determinant))
    {
      return false;
    }
    const glm::dmat2 pixelsToSheet = glm::inverse(sheetToPixels);
    lattice += pixelsToSheet * glm::transpose(pixelsToSheet);
  }
  // The intermediate image's pixels per lattice unit of the front sheet: SamplesPerSigma along
  // the narrowest footprint there, so that the warp follows the footprints' shape.
  double narrowest = std::numeric_limits<double>::infinity();
  for (int tile = 0; tile < Tiles * Tiles; ++tile)
  {
    const glm::dmat2& front = lattices[l.Reference * Tiles * Tiles + tile];
    narrowest =
      std::min(narrowest, front[0][0] + front[1][1] - splat::LargestEigenvalue(front));
  }
  l.Resolution = SamplesPerSigma / std::sqrt(narrowest);
  if (!std::isfinite(l.Resolution))
  {
    return false;
  }
  l.Sheets.resize(sheets);
  l.Footprints.resize(lattices.size());
  l.Cross.clear();
  for (int k = 0; k < sheets; ++k)
  {
    Sheet& s = l.Sheets[k];
    // Voxel p of sheet k lands on the front sheet's plane at p' = scale p + offset (lattice
    // units of the front sheet), and on the intermediate image at Resolution p'.
    const double scale = this->Perspective ? eyeOffset / (k - this->Eye[list]) : 1.0;
    const glm::dvec2 offset = this->Perspective ? (1.0 - scale) * eyeUV
                                                : -static_cast<double>(k - l.Reference) * shear;
    s.Scale = static_cast<float>(l.Resolution * scale);
    s.Offset = glm::vec2(l.Resolution * offset);
    s.HalfExtent = glm::vec2(0.0f);
    for (int tile = 0; tile < Tiles * Tiles; ++tile)
    {
      const std::size_t index = static_cast<std::size_t>(k) * Tiles * Tiles + tile;
      const glm::dmat2& lattice = lattices[index];
      Footprint& footprint = l.Footprints[index];
      const glm::dmat2 intermediate = (l.Resolution * l.Resolution * scale * scale) * lattice;
      const glm::dmat2 conic = glm::inverse(intermediate);
      footprint.ConicXX = static_cast<float>(0.5 * conic[0][0]);
      footprint.ConicXY = static_cast<float>(conic[1][0]);
      footprint.ConicYY = static_cast<float>(0.5 * conic[1][1]);
      footprint.HalfExtent = glm::vec2(std::sqrt(2.0 * this->Cutoff * intermediate[0][0]),
        std::sqrt(2.0 * this->Cutoff * intermediate[1][1]));
      s.HalfExtent = glm::max(s.HalfExtent, footprint.HalfExtent);
      // exp(-ConicXY m n) over the box's offsets from the pixel holding a voxel's center.
      const int reach = static_cast<int>(
                          std::ceil(std::max(footprint.HalfExtent.x, footprint.HalfExtent.y))) +
        1;
      const bool factored = std::abs(footprint.ConicXY) * reach * reach < 60.0f &&
        2 * reach + 1 + 8 <= splat::VolumeLayerCompositor::MaximumFactoredColumns;
      footprint.Reach = factored ? reach : 0;
      // AddFactored takes the Gaussian over its box, which holds erf(sqrt(cutoff))^2 of its
      // mass (exactly so for uncorrelated axes); Add cuts it at the cutoff ellipse.
      footprint.Amplitude = static_cast<float>((factored ? boxCompensation : compensation) /
        (2.0 * 3.14159265358979323846 * std::sqrt(glm::determinant(lattice)) * volume));
      footprint.Cross = l.Cross.size();
      const int stride = CrossStride(footprint.Reach);
      l.Cross.resize(
        l.Cross.size() + static_cast<std::size_t>(2 * footprint.Reach + 1) * stride, 0.0f);
      for (int n = -footprint.Reach; n <= footprint.Reach && factored; ++n)
      {
        for (int m = -footprint.Reach; m <= footprint.Reach; ++m)
        {
          l.Cross[footprint.Cross + (n + footprint.Reach) * stride + m + footprint.Reach] =
            std::exp(-footprint.ConicXY * static_cast<float>(m * n));
        }
      }
    }
    for (const glm::dvec2 corner : { glm::dvec2(0.0), extent })
    {
      const glm::dvec2 q = glm::dvec2(s.Scale) * corner + glm::dvec2(s.Offset);
      lo = glm::min(lo, q - glm::dvec2(s.HalfExtent));
      hi = glm::max(hi, q + glm::dvec2(s.HalfExtent));
    }
  }
  l.Origin = glm::floor(lo) - 1.0;
  const glm::dvec2 size = glm::ceil(hi) + 1.0 - l.Origin;
  if (!(size.x * size.y <= MaximumIntermediatePixels))
  {
    return false;
  }
  l.Size = glm::ivec2(size);
  return true;
}

//------------------------------------------------------------------------------
void vtkVolumeSplatSheetCompositor::Internals::BuildTables(
  int list, const std::vector<vtkIdType>& order)
{
  const glm::ivec3 dimensions = this->Input.GridDimensions;
  const glm::ivec2 axes = SheetAxes(list);
  const vtkIdType rows = dimensions[axes.y];
  const vtkIdType nx = dimensions.x, ny = dimensions.y;
  std::vector<std::uint32_t>& lattice = this->Lattice[list];
  std::vector<vtkIdType>& starts = this->RowStarts[list];
  lattice.resize(order.size());
  starts.assign(static_cast<std::size_t>(dimensions[list] * rows + 1), 0);
  std::vector<std::uint32_t>& spans = this->RowSpans[list];
  spans.assign(static_cast<std::size_t>(dimensions[list] * rows), 0xffffu);
  const vtkIdType* ids = this->Input.GridIds;
  for (std::size_t n = 0; n < order.size(); ++n)
  {
    const vtkIdType id = ids[order[n]];
    const glm::ivec3 index(static_cast<int>(id % nx), static_cast<int>((id / nx) % ny),
      static_cast<int>(id / (nx * ny)));
    lattice[n] = static_cast<std::uint32_t>(index[axes.x]) |
      (static_cast<std::uint32_t>(index[axes.y]) << 16);
    const vtkIdType row = index[list] * rows + index[axes.y];
    ++starts[row + 1];
    const std::uint32_t u = static_cast<std::uint32_t>(index[axes.x]);
    spans[row] = std::min(spans[row] & 0xffffu, u) | (std::max(spans[row] >> 16, u) << 16);
  }
  std::partial_sum(starts.begin(), starts.end(), starts.begin());
}

//------------------------------------------------------------------------------
void vtkVolumeSplatSheetCompositor::Internals::FindSamples(int list, const float* weights)
{
  const List& l = this->Lists[list];
  const glm::ivec2 axes = SheetAxes(list);
  const int width = this->View.Viewport.x;
  const splat::PixelRays rays =
    splat::MakePixelRays(this->View.EyeToClip, glm::dvec2(this->View.Viewport));
  this->Samples.resize(static_cast<std::size_t>(width) * this->View.Viewport.y);
  vtkSMPTools::For(0, this->View.Viewport.y,
    [&](vtkIdType rowBegin, vtkIdType rowEnd)
    {
      for (vtkIdType y = rowBegin; y < rowEnd; ++y)
      {
        for (int x = 0; x < width; ++x)
        {
          const std::size_t p = static_cast<std::size_t>(y) * width + x;
          glm::vec2& sample = this->Samples[p];
          sample = Unused;
          if (l.Ascending ? !(weights[p] > 0.0f) : !(weights[p] < 0.0f))
          {
            continue;
          }
          const glm::dvec3 pixel(x + 0.5, y + 0.5, 1.0);
          const glm::dvec3 origin =
            this->Perspective ? glm::dvec3(0.0) : rays.Origin * pixel;
          const glm::dvec3 o(this->EyeToIndex * glm::dvec4(origin, 1.0));
          const glm::dvec3 d(this->EyeToIndex * glm::dvec4(rays.Direction * pixel, 0.0));
          const double s = (l.Reference - o[list]) / d[list];
          const glm::dvec2 q = l.Resolution *
              glm::dvec2(o[axes.x] + s * d[axes.x], o[axes.y] + s * d[axes.y]) -
            l.Origin - 0.5;
          // Far outside the image (or no meeting at all) reads nothing.
          if (q.x > -1.0 && q.y > -1.0 && q.x < l.Size.x && q.y < l.Size.y)
          {
            sample = glm::vec2(q);
          }
        }
      }
    });
}

//------------------------------------------------------------------------------
SPLAT_VECTOR_CLONES void vtkVolumeSplatSheetCompositor::Internals::CompositeBand(int list, int band)
{
  const List& l = this->Lists[list];
  const glm::ivec2 axes = SheetAxes(list);
  const vtkIdType rows = this->Input.GridDimensions[axes.y];
  const int sheets = this->Input.GridDimensions[list];
  const glm::dmat3& A = this->Input.GridAxes;
  const glm::vec3 axisU(A[axes.x]), axisV(A[axes.y]), axisA(A[list]);
  const glm::vec3 eye(this->Eye[axes.x], this->Eye[axes.y], this->Eye[list]);
  const glm::vec2 shear = this->Perspective
    ? glm::vec2(0.0f)
    : glm::vec2(this->Direction[axes.x], this->Direction[axes.y]) /
      static_cast<float>(this->Direction[list]);
  const std::vector<std::uint32_t>& lattice = this->Lattice[list];
  const std::vector<glm::vec4>& values = this->Values[list];
  const std::vector<vtkIdType>& starts = this->RowStarts[list];
  const std::vector<std::uint32_t>& rowSpans = this->RowSpans[list];
  const float cutoff = static_cast<float>(this->Cutoff);
  const int rowBegin = band * BandHeight;
  const int rowEnd = std::min(rowBegin + BandHeight, l.Size.y) - 1;
  splat::VolumeLayerCompositor compositor(l.Size.x, rowBegin, rowEnd, cutoff, false, nullptr);
  compositor.Begin(nullptr, true, this->Image.data());
  for (int n = 0; n < sheets; ++n)
  {
    // Where the whole band has stopped integrating the sheets behind add nothing.
    if (!compositor.Integrates())
    {
      break;
    }
    const int k = l.Ascending ? n : sheets - 1 - n;
    const Sheet& s = l.Sheets[k];
    const glm::vec2 offset = s.Offset - glm::vec2(l.Origin);
    // The sheet's rows whose footprints reach the band.
    const vtkIdType first = std::max<vtkIdType>(0,
      static_cast<vtkIdType>(std::ceil((rowBegin + 0.5f - s.HalfExtent.y - offset.y) / s.Scale)));
    const vtkIdType last = std::min<vtkIdType>(rows - 1,
      static_cast<vtkIdType>(std::floor((rowEnd + 0.5f + s.HalfExtent.y - offset.y) / s.Scale)));
    const float toSheet = this->Perspective ? 1.0f / (k - eye.z) : 0.0f;
    const Footprint* footprints = l.Footprints.data() + static_cast<std::size_t>(k) * Tiles * Tiles;
    // The first and last intermediate columns that footprints of lattice columns [u0, u1] reach.
    const auto columns = [&](float u0, float u1, const glm::vec2& halfExtent)
    {
      return glm::ivec2(
        std::max(0, static_cast<int>(std::ceil(s.Scale * u0 + offset.x - halfExtent.x - 0.5f))),
        std::min(l.Size.x - 1,
          static_cast<int>(std::floor(s.Scale * u1 + offset.x + halfExtent.x - 0.5f))));
    };
    vtkVolumeSplatRasterizer::ScreenKernel kernel;
    kernel.Depth = 0.0f;
    for (vtkIdType row = first; row <= last; ++row)
    {
      const std::size_t r = static_cast<std::size_t>(k * rows + row);
      // The row's footprints together, left out where the band's pixels they reach have all
      // stopped integrating (behind the opaque parts, or where no pixel takes the list).
      const glm::ivec2 span = columns(static_cast<float>(rowSpans[r] & 0xffffu),
        static_cast<float>(rowSpans[r] >> 16), s.HalfExtent);
      const float v = static_cast<float>(row);
      kernel.CenterY = s.Scale * v + offset.y;
      const glm::ivec2 spanRows(
        static_cast<int>(std::ceil(kernel.CenterY - s.HalfExtent.y - 0.5f)),
        static_cast<int>(std::floor(kernel.CenterY + s.HalfExtent.y - 0.5f)));
      if (starts[r] == starts[r + 1] || span.x > span.y)
      {
        continue;
      }
      // The voxels' footprints lie within the row's rows.
      compositor.SelectRows(spanRows.x, spanRows.y);
      if (!compositor.IntegratesInRows(span.x, span.y))
      {
        continue;
      }
      const Footprint* rowFootprints = footprints + static_cast<int>(v * l.TileScale.y) * Tiles;
      compositor.Touch(span.x, span.y, spanRows.x, spanRows.y);
      // The path length along a voxel's ray per unit of index along the list's axis is
      // |path + u pathPerColumn|.
      const glm::vec3 path = this->Perspective
        ? axisA + ((v - eye.y) * toSheet) * axisV - (eye.x * toSheet) * axisU
        : axisA + shear.x * axisU + shear.y * axisV;
      const glm::vec3 pathPerColumn = this->Perspective ? toSheet * axisU : glm::vec3(0.0f);
      // The voxels' tile along the row, whose footprint they share.
      int tile = -1;
      const Footprint* f = nullptr;
      splat::VolumeLayerCompositor::FactoredRun run;
      for (vtkIdType e = starts[r]; e < starts[r + 1]; ++e)
      {
        const float u = static_cast<float>(lattice[e] & 0xffffu);
        const int column = static_cast<int>(u * l.TileScale.x);
        if (column != tile)
        {
          tile = column;
          f = rowFootprints + tile;
          kernel.ConicXX = f->ConicXX;
          kernel.ConicXY = f->ConicXY;
          kernel.ConicYY = f->ConicYY;
          kernel.Y0 = static_cast<int>(std::ceil(kernel.CenterY - f->HalfExtent.y - 0.5f));
          kernel.Y1 = static_cast<int>(std::floor(kernel.CenterY + f->HalfExtent.y - 0.5f));
          if (f->Reach > 0)
          {
            compositor.BeginFactoredRun(run, kernel.CenterY, kernel.Y0, kernel.Y1, f->ConicXX,
              f->ConicXY, f->ConicYY, l.Cross.data() + f->Cross, f->Reach,
              CrossStride(f->Reach));
          }
        }
        const glm::ivec2 x = columns(u, u, f->HalfExtent);
        if (x.x > x.y || !compositor.IntegratesInRows(x.x, x.y))
        {
          continue;
        }
        const float centerX = s.Scale * u + offset.x;
        const float length = glm::length(path + u * pathPerColumn);
        const glm::vec4& value = values[e];
        const float amplitude = f->Amplitude * length * value.w;
        if (f->Reach > 0)
        {
          compositor.AddFactored(run, centerX, x.x, x.y, amplitude, glm::vec3(value));
        }
        else
        {
          kernel.X0 = x.x;
          kernel.X1 = x.y;
          kernel.CenterX = centerX;
          kernel.Amplitude = amplitude;
          // Assigned one by one: std::copy_n of three floats became a memmove call per voxel.
          kernel.Color[0] = value.x;
          kernel.Color[1] = value.y;
          kernel.Color[2] = value.z;
          compositor.Add(kernel);
        }
      }
    }
    compositor.Flush(nullptr, true, this->Image.data());
  }
}

//------------------------------------------------------------------------------
void vtkVolumeSplatSheetCompositor::Internals::Composite(int list)
{
  const int bands = (this->Lists[list].Size.y + BandHeight - 1) / BandHeight;
  vtkSMPTools::For(0, bands, 1,
    [this, list](vtkIdType bandBegin, vtkIdType bandEnd)
    {
      for (vtkIdType b = bandBegin; b < bandEnd; ++b)
      {
        this->CompositeBand(list, static_cast<int>(b));
      }
    });
}

//------------------------------------------------------------------------------
vtkVolumeSplatSheetCompositor::vtkVolumeSplatSheetCompositor()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkVolumeSplatSheetCompositor::~vtkVolumeSplatSheetCompositor() = default;

//------------------------------------------------------------------------------
void vtkVolumeSplatSheetCompositor::Reset()
{
  for (int list = 0; list < 3; ++list)
  {
    this->Internal->Lattice[list].clear();
    this->Internal->ValueColors[list] = nullptr;
    this->Internal->RowStarts[list].clear();
    this->Internal->RowSpans[list].clear();
  }
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatSheetCompositor::BeginFrame(const Kernels& kernels, const Camera& camera,
  double cutoff, double nearestSceneDepth, const std::array<bool, 3>& used)
{
  Internals& in = *this->Internal;
  for (Internals::List& l : in.Lists)
  {
    l.Size = glm::ivec2(0);
  }
  const glm::ivec3 dimensions = kernels.GridDimensions;
  const double volume = glm::determinant(kernels.GridAxes);
  // Lattice coordinates are packed in 16 bits each.
  const bool fits = glm::all(glm::lessThanEqual(dimensions, glm::ivec3(1 << 16)));
  if (!kernels.GridIds || kernels.Covariances || !fits || !(std::abs(volume) > 0.0) ||
    !std::isfinite(volume))
  {
    return false;
  }
  in.Input = kernels;
  in.View = camera;
  in.Cutoff = cutoff;
  in.Perspective = !splat::IsParallelProjection(camera.EyeToClip);
  const glm::dmat3& A = kernels.GridAxes;
  const glm::dmat4 indexToModel(glm::dvec4(A[0], 0.0), glm::dvec4(A[1], 0.0),
    glm::dvec4(A[2], 0.0), glm::dvec4(kernels.GridOrigin, 1.0));
  in.IndexToEye = camera.ModelToEye * indexToModel;
  in.EyeToIndex = glm::inverse(in.IndexToEye);
  in.Eye = glm::dvec3(in.EyeToIndex * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  in.Direction = glm::dvec3(in.EyeToIndex * glm::dvec4(0.0, 0.0, -1.0, 0.0));
  const glm::dmat3 toIndex = glm::inverse(A);
  in.IndexCovariance = toIndex * kernels.SharedCovariance * glm::transpose(toIndex);
  // The grid's box grown by the kernels' reach: in front of the near plane and the opaque
  // scene.
  glm::dvec3 reach;
  for (int axis = 0; axis < 3; ++axis)
  {
    reach[axis] = std::sqrt(2.0 * cutoff * in.IndexCovariance[axis][axis]);
  }
  const double nearDistance = splat::NearPlaneDistance(camera.EyeToClip);
  for (int corner = 0; corner < 8; ++corner)
  {
    glm::dvec3 y;
    for (int axis = 0; axis < 3; ++axis)
    {
      y[axis] = (corner >> axis) & 1 ? dimensions[axis] - 1 + reach[axis] : -reach[axis];
    }
    const double depth = -(in.IndexToEye * glm::dvec4(y, 1.0)).z;
    if (!(depth > nearDistance) || !(depth < nearestSceneDepth))
    {
      return false;
    }
  }
  for (int list = 0; list < 3; ++list)
  {
    if (used[list] && !in.MakeList(list))
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
vtkIdType vtkVolumeSplatSheetCompositor::Render(int list, const std::vector<vtkIdType>& order,
  const float* colors, bool perFrameColors, const float* weights, std::vector<glm::vec4>& buffer)
{
  Internals& in = *this->Internal;
  const Internals::List& l = in.Lists[list];
  if (in.Lattice[list].size() != order.size())
  {
    in.BuildTables(list, order);
  }
  in.FindSamples(list, weights);
  // Intermediate pixels that no screen pixel reads start closed (opaque): nothing is splatted
  // there.
  in.Image.assign(static_cast<std::size_t>(l.Size.x) * l.Size.y, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  // Catmull-Rom weights: the image is sampled about once per footprint deviation, where
  // bilinear interpolation would flatten the footprints' peaks.
  auto forEachTap = [&l](const glm::vec2& sample, auto&& visit)
  {
    const glm::ivec2 base(glm::floor(sample));
    const glm::vec2 f = sample - glm::vec2(base);
    const auto weights = [](float t)
    {
      const float t2 = t * t, t3 = t2 * t;
      return glm::vec4(-0.5f * t3 + t2 - 0.5f * t, 1.5f * t3 - 2.5f * t2 + 1.0f,
        -1.5f * t3 + 2.0f * t2 + 0.5f * t, 0.5f * t3 - 0.5f * t2);
    };
    const glm::vec4 wx = weights(f.x), wy = weights(f.y);
    for (int j = 0; j < 4; ++j)
    {
      for (int i = 0; i < 4; ++i)
      {
        const glm::ivec2 tap = base + glm::ivec2(i - 1, j - 1);
        if (tap.x >= 0 && tap.y >= 0 && tap.x < l.Size.x && tap.y < l.Size.y)
        {
          visit(static_cast<std::size_t>(tap.y) * l.Size.x + tap.x, wx[i] * wy[j]);
        }
      }
    }
  };
  for (const glm::vec2& sample : in.Samples)
  {
    if (sample != Unused)
    {
      forEachTap(sample, [&in](std::size_t q, float) { in.Image[q] = glm::vec4(0.0f); });
    }
  }
  if (in.ValueColors[list] != colors || perFrameColors)
  {
    std::vector<glm::vec4>& values = in.Values[list];
    values.resize(order.size());
    const float* strengths = in.Input.Strengths;
    vtkSMPTools::For(0, static_cast<vtkIdType>(order.size()),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType e = begin; e < end; ++e)
        {
          const vtkIdType id = order[e];
          values[e] =
            glm::vec4(colors[3 * id], colors[3 * id + 1], colors[3 * id + 2], strengths[id]);
        }
      });
    in.ValueColors[list] = colors;
  }
  in.Composite(list);
  // The warp to the screen pixels.
  buffer.resize(in.Samples.size());
  vtkSMPTools::For(0, static_cast<vtkIdType>(in.Samples.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType p = begin; p < end; ++p)
      {
        glm::vec4 color(0.0f);
        if (in.Samples[p] != Unused)
        {
          forEachTap(in.Samples[p], [&](std::size_t q, float w) { color += w * in.Image[q]; });
        }
        buffer[p] = color;
      }
    });
  return static_cast<vtkIdType>(order.size());
}

//------------------------------------------------------------------------------
glm::ivec2 vtkVolumeSplatSheetCompositor::GetIntermediateSize(int list) const
{
  return list >= 0 && list < 3 ? this->Internal->Lists[list].Size : glm::ivec2(0);
}

//------------------------------------------------------------------------------
void vtkVolumeSplatSheetCompositor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  for (int list = 0; list < 3; ++list)
  {
    const glm::ivec2 size = this->GetIntermediateSize(list);
    os << indent << "IntermediateSize " << list << ": " << size.x << " x " << size.y << "\n";
  }
}
