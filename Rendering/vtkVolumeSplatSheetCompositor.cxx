// SPDX-License-Identifier: BSD-3-Clause
#include "vtkVolumeSplatSheetCompositor.h"

#include "SplatCaptureKernel.h"
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

// Intermediate pixels per standard deviation of the narrowest footprint on the front sheet, and
// at least per screen pixel along the sheet's least foreshortened direction there. The first
// rules where the screen's low-pass dominates the footprints (0.7 per sigma is then about 0.6
// per pixel: the MRI at 512^2); the second where voxels are magnified, whose footprints 0.7
// samples per sigma leave blurred and aliased (the report's vdb cloud: 0.33 per pixel).
constexpr double SamplesPerSigma = 0.7;
constexpr double SamplesPerPixel = 0.6;

// The largest optical depth per sheet spacing (along the axis) of two voxels that
// vtkVolumeSplatSheetCompositor merges into one kernel: the order within a pair, which the merge
// loses, changes their color by up to about tau1 tau2 / 2 times their color difference.
constexpr float MergedOpticalDepth = 0.5f;

// Intermediate pixels around the footprints' box, left empty: the warp's Catmull-Rom taps of a
// sample that reads any footprint all lie within the image.
constexpr int Margin = 3;

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

// A layer of the traversal, a sheet or a merged pair of sheets, at Position along the list's
// axis (index units), and where it lands on the intermediate image: voxel (u, v) at
// Scale (u, v) + Offset. A pair's kernels lie up to half a sheet off that position along the
// axis; Shift bounds where that puts their centers on the image. HalfExtent is its footprints'
// largest reach from the lattice point, Shift included.
struct Layer
{
  float Position;
  float Scale;
  glm::vec2 Offset;
  glm::vec2 Shift;
  glm::vec2 HalfExtent;
};

// Per list, built from the kernels: each entry's (u, v) in its layer packed as u + 65536 v,
// per layer and row v the first entry at or after it, and per layer and row the smallest and
// largest u of its entries, packed as the lattice. Where the colors change: each entry's color
// and strength in this order, so that the compositing reads them in sequence (the X and Y
// lists would gather them from all over memory), and the colors they came from; for pairs,
// each entry's offset along the axis from the pair's middle (its strength-weighted center) and
// the kernels it holds (the second -1 for one).
struct Tables
{
  std::vector<std::uint32_t> Lattice;
  std::vector<vtkIdType> RowStarts;
  std::vector<std::uint32_t> RowSpans;
  std::vector<glm::vec4> Values;
  std::vector<float> Shifts;
  std::vector<std::array<vtkIdType, 2>> Kernels;
  const float* Colors = nullptr;
};

// Kernel id's color and strength, a value of Tables.
glm::vec4 KernelValue(const float* colors, const float* strengths, vtkIdType id)
{
  return glm::vec4(colors[3 * id], colors[3 * id + 1], colors[3 * id + 2], strengths[id]);
}
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

  // Per list: its sheets (entries in list order) and the sheets merged by pairs.
  std::array<Tables, 3> Sheets, Pairs;
  bool MergePairs = true;
  splat::FootprintFilter Filter = splat::FootprintFilter::LowPass;

  // Per list, per frame.
  struct List
  {
    bool Ascending = true;
    bool Pairs = false; // the layers are the sheets merged by pairs
    int Reference = 0; // the front sheet, whose plane holds the intermediate image
    double Resolution = 1.0; // intermediate pixels per lattice unit of the front sheet
    glm::dvec2 Origin{ 0.0 }; // intermediate pixel (X, Y) has its center at Origin + (X, Y) + 0.5
    glm::ivec2 Size{ 0 };
    std::vector<Layer> Layers;
    std::vector<Footprint> Footprints; // per layer, Tiles x Tiles, row by row
    glm::vec2 TileScale{ 0.0f };       // tiles per lattice unit along u and v
    std::vector<float> Cross;
  };
  std::array<List, 3> Lists;
  std::vector<glm::vec4> Image;
  std::vector<glm::vec2> Samples; // per screen pixel: where it reads the intermediate image

  // The frame's geometry of list `list`; false where the sheets do not apply.
  bool MakeList(int list);
  void BuildTables(int list, const std::vector<vtkIdType>& order);
  // The sheets' values of list `list` (entries `order`) for `colors`.
  void CopyValues(int list, const std::vector<vtkIdType>& order, const float* colors);
  // The pairs' tables of list `list` (entries `order`) from the sheets', but their values.
  void BuildPairs(int list, const std::vector<vtkIdType>& order);
  // The pairs' values of list `list` for `colors`.
  void MergeValues(int list, const float* colors);
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
  List& l = this->Lists[list];
  l.Pairs = this->MergePairs && sheets > 1;
  // A lone last sheet is a layer as it is.
  const int layers = l.Pairs ? (sheets + 1) / 2 : sheets;
  const auto merged = [&](int layer) { return l.Pairs && 2 * layer + 1 < sheets; };
  const auto position = [&](int layer)
  { return l.Pairs ? 2.0 * layer + (merged(layer) ? 0.5 : 0.0) : static_cast<double>(layer); };
  const double reach = std::sqrt(2.0 * this->Cutoff * S[list][list]) + 0.5;
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
  const double filterVariance = splat::FilterVariance(this->Filter);
  const bool bandLimit = this->Filter == splat::FootprintFilter::BandLimit;
  const double boxMass = std::erf(std::sqrt(this->Cutoff));
  const double boxCompensation = 1.0 / (boxMass * boxMass);
  const double volume = std::abs(glm::determinant(this->Input.GridAxes));
  const glm::dvec2 extent(dimensions[axes.x] - 1, dimensions[axes.y] - 1);
  glm::dvec2 lo(std::numeric_limits<double>::infinity());
  glm::dvec2 hi(-std::numeric_limits<double>::infinity());
  // Per layer and tile, the voxel's Gaussian integrated along the rays (their direction per
  // unit of index along the list's axis at the tile's center, t) as a density on the sheet's
  // lattice, under the screen's filter (splat::FilteredCovariance) mapped onto the sheet there.
  const int u = axes.x, v = axes.y, a = list;
  const glm::dvec2 tileSize = (extent + 1.0) / static_cast<double>(Tiles);
  l.TileScale = glm::vec2(1.0 / tileSize);
  std::vector<glm::dmat2> lattices(static_cast<std::size_t>(layers) * Tiles * Tiles);
  // The front sheet's largest stretch from sheet to screen, in pixels per lattice unit.
  const int front = l.Ascending ? 0 : layers - 1;
  double finest = 0.0;
  for (std::size_t f = 0; f < lattices.size(); ++f)
  {
    const int layer = static_cast<int>(f / (Tiles * Tiles));
    const int tile = static_cast<int>(f % (Tiles * Tiles));
    const double k = position(layer);
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
    if (layer == front)
    {
      finest = std::max(finest,
        std::sqrt(splat::LargestEigenvalue(glm::transpose(sheetToPixels) * sheetToPixels)));
    }
    lattice = pixelsToSheet *
      splat::FilteredCovariance(sheetToPixels * lattice * glm::transpose(sheetToPixels),
        filterVariance, bandLimit) *
      glm::transpose(pixelsToSheet);
  }
  // The intermediate image's pixels per lattice unit of the front sheet: SamplesPerSigma along
  // the narrowest footprint there, so that the warp follows the footprints' shape, and
  // SamplesPerPixel along the screen's finest stretch of the sheet.
  double narrowest = std::numeric_limits<double>::infinity();
  for (int tile = 0; tile < Tiles * Tiles; ++tile)
  {
    const glm::dmat2& f = lattices[front * Tiles * Tiles + tile];
    narrowest = std::min(narrowest, f[0][0] + f[1][1] - splat::LargestEigenvalue(f));
  }
  l.Resolution = std::max(SamplesPerSigma / std::sqrt(narrowest), SamplesPerPixel * finest);
  if (!std::isfinite(l.Resolution))
  {
    return false;
  }
  l.Layers.resize(layers);
  l.Footprints.resize(lattices.size());
  l.Cross.clear();
  for (int layer = 0; layer < layers; ++layer)
  {
    Layer& s = l.Layers[layer];
    const double k = position(layer);
    // Voxel p of the layer lands on the front sheet's plane at p' = scale p + offset (lattice
    // units of the front sheet), and on the intermediate image at Resolution p'.
    const double scale = this->Perspective ? eyeOffset / (k - this->Eye[list]) : 1.0;
    const glm::dvec2 offset =
      this->Perspective ? (1.0 - scale) * eyeUV : -(k - l.Reference) * shear;
    s.Position = static_cast<float>(k);
    s.Scale = static_cast<float>(l.Resolution * scale);
    s.Offset = glm::vec2(l.Resolution * offset);
    // A kernel d off the layer along the axis lands -d t Scale off its lattice point.
    const glm::dvec2 largestT = this->Perspective
      ? glm::max(glm::abs(eyeUV), glm::abs(extent - eyeUV)) / std::abs(k - this->Eye[list])
      : glm::abs(shear);
    s.Shift = glm::vec2(merged(layer) ? 0.5 * s.Scale * largestT : glm::dvec2(0.0));
    s.HalfExtent = glm::vec2(0.0f);
    for (int tile = 0; tile < Tiles * Tiles; ++tile)
    {
      const std::size_t index = static_cast<std::size_t>(layer) * Tiles * Tiles + tile;
      const glm::dmat2& lattice = lattices[index];
      Footprint& footprint = l.Footprints[index];
      const glm::dmat2 intermediate = (l.Resolution * l.Resolution * scale * scale) * lattice;
      const glm::dmat2 conic = glm::inverse(intermediate);
      footprint.ConicXX = static_cast<float>(0.5 * conic[0][0]);
      footprint.ConicXY = static_cast<float>(conic[1][0]);
      footprint.ConicYY = static_cast<float>(0.5 * conic[1][1]);
      footprint.HalfExtent = glm::vec2(std::sqrt(2.0 * this->Cutoff * intermediate[0][0]),
        std::sqrt(2.0 * this->Cutoff * intermediate[1][1]));
      s.HalfExtent = glm::max(s.HalfExtent, footprint.HalfExtent + s.Shift);
      // exp(-ConicXY m n) over the box's offsets from the pixel holding a voxel's center (for
      // the rows, the run's center: a pair's kernel may lie Shift off it).
      const int reach = static_cast<int>(std::ceil(std::max(
                          footprint.HalfExtent.x, footprint.HalfExtent.y + s.Shift.y))) +
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
  l.Origin = glm::floor(lo) - static_cast<double>(Margin);
  const glm::dvec2 size = glm::ceil(hi) + static_cast<double>(Margin) - l.Origin;
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
  Tables& tables = this->Sheets[list];
  std::vector<std::uint32_t>& lattice = tables.Lattice;
  std::vector<vtkIdType>& starts = tables.RowStarts;
  lattice.resize(order.size());
  starts.assign(static_cast<std::size_t>(dimensions[list] * rows + 1), 0);
  std::vector<std::uint32_t>& spans = tables.RowSpans;
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
  tables.Colors = nullptr;
  this->Pairs[list] = Tables();
}

//------------------------------------------------------------------------------
void vtkVolumeSplatSheetCompositor::Internals::CopyValues(
  int list, const std::vector<vtkIdType>& order, const float* colors)
{
  std::vector<glm::vec4>& values = this->Sheets[list].Values;
  values.resize(order.size());
  const float* strengths = this->Input.Strengths;
  vtkSMPTools::For(0, static_cast<vtkIdType>(order.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType e = begin; e < end; ++e)
      {
        values[e] = KernelValue(colors, strengths, order[e]);
      }
    });
}

//------------------------------------------------------------------------------
void vtkVolumeSplatSheetCompositor::Internals::BuildPairs(
  int list, const std::vector<vtkIdType>& order)
{
  const Tables& sheets = this->Sheets[list];
  Tables& pairs = this->Pairs[list];
  const int count = this->Input.GridDimensions[list];
  const vtkIdType rows = this->Input.GridDimensions[SheetAxes(list).y];
  const vtkIdType pairRows = (count + 1) / 2 * rows;
  // Whether pair row `pairRow` is of the lone last sheet of an odd count.
  const auto lone = [rows, count](vtkIdType pairRow) { return 2 * (pairRow / rows) + 1 == count; };
  // Visits the entries of row `pairRow` of the pairs: those of the row in the pair's sheets
  // merged by u, as visit(first, second, e) with the kernels of the lower and the upper sheet
  // (-1 where that sheet has none at u) and an entry of the sheets at that u.
  const auto forEachEntry = [&](vtkIdType pairRow, auto&& visit)
  {
    const vtkIdType r = (pairRow / rows) * 2 * rows + pairRow % rows;
    vtkIdType first = sheets.RowStarts[r];
    const vtkIdType firstEnd = sheets.RowStarts[r + 1];
    const bool single = lone(pairRow);
    vtkIdType second = single ? 0 : sheets.RowStarts[r + rows];
    const vtkIdType secondEnd = single ? 0 : sheets.RowStarts[r + rows + 1];
    while (first < firstEnd || second < secondEnd)
    {
      const std::uint32_t u0 = first < firstEnd ? sheets.Lattice[first] & 0xffffu : 0x10000u;
      const std::uint32_t u1 = second < secondEnd ? sheets.Lattice[second] & 0xffffu : 0x10000u;
      const vtkIdType entry = u0 <= u1 ? first : second;
      visit(u0 <= u1 ? order[first++] : -1, u1 <= u0 ? order[second++] : -1, entry);
    }
  };
  // Two voxels are merged where their optical depths per sheet along the axis add up to at
  // most MergedOpticalDepth; otherwise the lower one stays in the pair's first layer, the upper
  // one goes into its second (where the first is merged or alone, at its own center). Which
  // voxels merge depends on the strengths alone.
  const float* strengths = this->Input.Strengths;
  const glm::dmat3& A = this->Input.GridAxes;
  const float depthPerStrength =
    static_cast<float>(glm::length(A[list]) / std::abs(glm::determinant(A)));
  const auto merges = [&](vtkIdType first, vtkIdType second)
  {
    return first < 0 || second < 0 ||
      (strengths[first] + strengths[second]) * depthPerStrength <= MergedOpticalDepth;
  };
  // The row of the tables of the first and the second layer of pair row (j, v).
  const auto lower = [rows](vtkIdType pairRow) { return pairRow + (pairRow / rows) * rows; };
  const auto upper = [rows](vtkIdType pairRow) { return pairRow + (pairRow / rows + 1) * rows; };
  pairs.RowStarts.assign(2 * pairRows + 1, 0);
  vtkSMPTools::For(0, pairRows,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType row = begin; row < end; ++row)
      {
        forEachEntry(row,
          [&](vtkIdType first, vtkIdType second, vtkIdType)
          {
            ++pairs.RowStarts[lower(row) + 1];
            pairs.RowStarts[upper(row) + 1] += !merges(first, second);
          });
      }
    });
  std::partial_sum(pairs.RowStarts.begin(), pairs.RowStarts.end(), pairs.RowStarts.begin());
  const std::size_t entries = static_cast<std::size_t>(pairs.RowStarts.back());
  pairs.Lattice.resize(entries);
  pairs.Shifts.resize(entries);
  pairs.Kernels.resize(entries);
  pairs.RowSpans.assign(2 * pairRows, 0xffffu);
  pairs.Colors = nullptr;
  vtkSMPTools::For(0, pairRows,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType row = begin; row < end; ++row)
      {
        const bool single = lone(row);
        const vtkIdType tableRows[2] = { lower(row), upper(row) };
        vtkIdType next[2] = { pairs.RowStarts[tableRows[0]], pairs.RowStarts[tableRows[1]] };
        // Kernels `kernels` at entry `e` of the sheets into layer `layer` of the pair, d off the
        // pair's middle along the axis.
        const auto put = [&](int layer, vtkIdType e, const std::array<vtkIdType, 2>& kernels,
                           float d)
        {
          const std::uint32_t lattice = sheets.Lattice[e];
          std::uint32_t& span = pairs.RowSpans[tableRows[layer]];
          const std::uint32_t u = lattice & 0xffffu;
          span = std::min(span & 0xffffu, u) | (std::max(span >> 16, u) << 16);
          pairs.Lattice[next[layer]] = lattice;
          pairs.Shifts[next[layer]] = d;
          pairs.Kernels[next[layer]] = kernels;
          ++next[layer];
        };
        forEachEntry(row,
          [&](vtkIdType first, vtkIdType second, vtkIdType e)
          {
            if (!merges(first, second))
            {
              put(0, e, { first, -1 }, -0.5f);
              put(1, e, { second, -1 }, 0.5f);
              return;
            }
            // The pair's kernel at their strength-weighted center (one voxel: its own).
            const float s0 = first >= 0 ? strengths[first] : 0.0f;
            const float s1 = second >= 0 ? strengths[second] : 0.0f;
            const float w1 = s0 + s1 > 0.0f ? s1 / (s0 + s1) : 0.0f;
            put(0, e, { first >= 0 ? first : second, first >= 0 ? second : -1 },
              single ? 0.0f : w1 - 0.5f);
          });
      }
    });
}

//------------------------------------------------------------------------------
void vtkVolumeSplatSheetCompositor::Internals::MergeValues(int list, const float* colors)
{
  Tables& pairs = this->Pairs[list];
  pairs.Values.resize(pairs.Kernels.size());
  const float* strengths = this->Input.Strengths;
  vtkSMPTools::For(0, static_cast<vtkIdType>(pairs.Kernels.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType e = begin; e < end; ++e)
      {
        // A merged pair: the sum of the strengths and their weighted color.
        const std::array<vtkIdType, 2>& kernels = pairs.Kernels[e];
        const glm::vec4 v0 = KernelValue(colors, strengths, kernels[0]);
        if (kernels[1] < 0)
        {
          pairs.Values[e] = v0;
          continue;
        }
        const glm::vec4 v1 = KernelValue(colors, strengths, kernels[1]);
        const float strength = v0.w + v1.w;
        const float w1 = strength > 0.0f ? v1.w / strength : 0.0f;
        pairs.Values[e] = glm::vec4(glm::mix(glm::vec3(v0), glm::vec3(v1), w1), strength);
      }
    });
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
        // A pixel's ray in index coordinates, origin o and direction d, at column x of the
        // row: both are affine in x.
        const auto ray = [&](double x)
        {
          const glm::dvec3 pixel(x + 0.5, y + 0.5, 1.0);
          const glm::dvec3 origin = this->Perspective ? glm::dvec3(0.0) : rays.Origin * pixel;
          return std::make_pair(glm::dvec3(this->EyeToIndex * glm::dvec4(origin, 1.0)),
            glm::dvec3(this->EyeToIndex * glm::dvec4(rays.Direction * pixel, 0.0)));
        };
        const auto first = ray(0.0), next = ray(1.0);
        const glm::dvec3 originStep = next.first - first.first;
        const glm::dvec3 directionStep = next.second - first.second;
        for (int x = 0; x < width; ++x)
        {
          const std::size_t p = static_cast<std::size_t>(y) * width + x;
          glm::vec2& sample = this->Samples[p];
          sample = Unused;
          if (l.Ascending ? !(weights[p] > 0.0f) : !(weights[p] < 0.0f))
          {
            continue;
          }
          const glm::dvec3 o = first.first + static_cast<double>(x) * originStep;
          const glm::dvec3 d = first.second + static_cast<double>(x) * directionStep;
          const double s = (l.Reference - o[list]) / d[list];
          const glm::dvec2 q = l.Resolution *
              glm::dvec2(o[axes.x] + s * d[axes.x], o[axes.y] + s * d[axes.y]) -
            l.Origin - 0.5;
          // Where a tap would leave the image the sample reads only the empty margin (or the
          // ray does not meet the plane at all).
          if (q.x >= 1.0 && q.y >= 1.0 && q.x < l.Size.x - 2 && q.y < l.Size.y - 2)
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
  const int layers = static_cast<int>(l.Layers.size());
  const glm::dmat3& A = this->Input.GridAxes;
  const glm::vec3 axisU(A[axes.x]), axisV(A[axes.y]), axisA(A[list]);
  const glm::vec3 eye(this->Eye[axes.x], this->Eye[axes.y], this->Eye[list]);
  const glm::vec2 shear = this->Perspective
    ? glm::vec2(0.0f)
    : glm::vec2(this->Direction[axes.x], this->Direction[axes.y]) /
      static_cast<float>(this->Direction[list]);
  const Tables& tables = l.Pairs ? this->Pairs[list] : this->Sheets[list];
  const std::vector<std::uint32_t>& lattice = tables.Lattice;
  const std::vector<glm::vec4>& values = tables.Values;
  const std::vector<vtkIdType>& starts = tables.RowStarts;
  const std::vector<std::uint32_t>& rowSpans = tables.RowSpans;
  const float* shifts = l.Pairs ? tables.Shifts.data() : nullptr;
  const float cutoff = static_cast<float>(this->Cutoff);
  const int rowBegin = band * BandHeight;
  const int rowEnd = std::min(rowBegin + BandHeight, l.Size.y) - 1;
  splat::VolumeLayerCompositor compositor(l.Size.x, rowBegin, rowEnd, cutoff, false, nullptr);
  compositor.Begin(nullptr, true, this->Image.data());
  // The tables hold two layers per pair (see BuildPairs), with the pair's geometry.
  const int tableLayers = l.Pairs ? 2 : 1;
  for (int n = 0; n < layers * tableLayers; ++n)
  {
    // Where the whole band has stopped integrating the layers behind add nothing.
    if (!compositor.Integrates())
    {
      break;
    }
    const int k = l.Ascending ? n : layers * tableLayers - 1 - n;
    const int layer = k / tableLayers;
    const Layer& s = l.Layers[layer];
    const glm::vec2 offset = s.Offset - glm::vec2(l.Origin);
    // The layer's rows whose footprints reach the band.
    const vtkIdType first = std::max<vtkIdType>(0,
      static_cast<vtkIdType>(std::ceil((rowBegin + 0.5f - s.HalfExtent.y - offset.y) / s.Scale)));
    const vtkIdType last = std::min<vtkIdType>(rows - 1,
      static_cast<vtkIdType>(std::floor((rowEnd + 0.5f + s.HalfExtent.y - offset.y) / s.Scale)));
    const float toSheet = this->Perspective ? 1.0f / (s.Position - eye.z) : 0.0f;
    const Footprint* footprints =
      l.Footprints.data() + static_cast<std::size_t>(layer) * Tiles * Tiles;
    // The first and last intermediate columns that footprints centered on [x0, x1] reach.
    const auto columns = [&](float x0, float x1, float halfExtent)
    {
      return glm::ivec2(std::max(0, static_cast<int>(std::ceil(x0 - halfExtent - 0.5f))),
        std::min(l.Size.x - 1, static_cast<int>(std::floor(x1 + halfExtent - 0.5f))));
    };
    vtkVolumeSplatRasterizer::ScreenKernel kernel;
    kernel.Depth = 0.0f;
    for (vtkIdType row = first; row <= last; ++row)
    {
      const std::size_t r = static_cast<std::size_t>(k * rows + row);
      // The row's footprints together, left out where the band's pixels they reach have all
      // stopped integrating (behind the opaque parts, or where no pixel takes the list).
      const glm::ivec2 span =
        columns(s.Scale * static_cast<float>(rowSpans[r] & 0xffffu) + offset.x,
          s.Scale * static_cast<float>(rowSpans[r] >> 16) + offset.x, s.HalfExtent.x);
      const float v = static_cast<float>(row);
      const float centerY = s.Scale * v + offset.y;
      const glm::ivec2 spanRows(static_cast<int>(std::ceil(centerY - s.HalfExtent.y - 0.5f)),
        static_cast<int>(std::floor(centerY + s.HalfExtent.y - 0.5f)));
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
      // The rays' direction per unit of index along the list's axis is t = (tU + u tPerColumn,
      // tV): the path length along a voxel's ray per unit of that index is |axisA + t.x axisU +
      // t.y axisV|, and a kernel d off the layer lands -d Scale t off its lattice point.
      const float tU = this->Perspective ? -eye.x * toSheet : shear.x;
      const float tPerColumn = this->Perspective ? toSheet : 0.0f;
      const float tV = this->Perspective ? (v - eye.y) * toSheet : shear.y;
      const glm::vec3 path = axisA + tU * axisU + tV * axisV;
      const glm::vec3 pathPerColumn = tPerColumn * axisU;
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
          kernel.Y0 = static_cast<int>(std::ceil(centerY - f->HalfExtent.y - s.Shift.y - 0.5f));
          kernel.Y1 = static_cast<int>(std::floor(centerY + f->HalfExtent.y + s.Shift.y - 0.5f));
          if (f->Reach > 0)
          {
            compositor.BeginFactoredRun(run, centerY, kernel.Y0, kernel.Y1, f->ConicXX,
              f->ConicXY, f->ConicYY, l.Cross.data() + f->Cross, f->Reach,
              CrossStride(f->Reach));
          }
        }
        const float shift = shifts ? -s.Scale * shifts[e] : 0.0f;
        const float centerX = s.Scale * u + offset.x + shift * (tU + u * tPerColumn);
        const glm::ivec2 x = columns(centerX, centerX, f->HalfExtent.x);
        if (x.x > x.y || !compositor.IntegratesInRows(x.x, x.y))
        {
          continue;
        }
        const float shiftY = shift * tV;
        const float length = glm::length(path + u * pathPerColumn);
        const glm::vec4& value = values[e];
        const float amplitude = f->Amplitude * length * value.w;
        if (f->Reach > 0)
        {
          compositor.AddFactored(run, centerX, shiftY, x.x, x.y, amplitude, glm::vec3(value));
        }
        else
        {
          kernel.X0 = x.x;
          kernel.X1 = x.y;
          kernel.CenterX = centerX;
          kernel.CenterY = centerY + shiftY;
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
    this->Internal->Sheets[list] = Tables();
    this->Internal->Pairs[list] = Tables();
  }
}

//------------------------------------------------------------------------------
void vtkVolumeSplatSheetCompositor::SetMergePairs(bool merge)
{
  this->Internal->MergePairs = merge;
}

//------------------------------------------------------------------------------
bool vtkVolumeSplatSheetCompositor::GetMergePairs() const
{
  return this->Internal->MergePairs;
}

//------------------------------------------------------------------------------
void vtkVolumeSplatSheetCompositor::SetFootprintFilter(int filter)
{
  this->Internal->Filter = static_cast<splat::FootprintFilter>(filter);
}

//------------------------------------------------------------------------------
int vtkVolumeSplatSheetCompositor::GetFootprintFilter() const
{
  return static_cast<int>(this->Internal->Filter);
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
  if (in.Sheets[list].Lattice.size() != order.size())
  {
    in.BuildTables(list, order);
  }
  if (l.Pairs && in.Pairs[list].RowStarts.empty())
  {
    in.BuildPairs(list, order);
  }
  in.FindSamples(list, weights);
  // Intermediate pixels that no screen pixel reads start closed (opaque): nothing is splatted
  // there.
  in.Image.assign(static_cast<std::size_t>(l.Size.x) * l.Size.y, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  // The first of the 4 x 4 pixels (within the image, see FindSamples) whose Catmull-Rom
  // weights give a sample's color: the image is sampled about once per footprint deviation,
  // where bilinear interpolation would flatten the footprints' peaks.
  const auto firstTap = [&l](const glm::vec2& sample)
  {
    const glm::ivec2 base = glm::ivec2(glm::floor(sample)) - 1;
    return static_cast<std::size_t>(base.y) * l.Size.x + base.x;
  };
  for (const glm::vec2& sample : in.Samples)
  {
    if (sample != Unused)
    {
      const auto tap = in.Image.begin() + firstTap(sample);
      for (int j = 0; j < 4; ++j)
      {
        std::fill_n(tap + static_cast<std::ptrdiff_t>(j) * l.Size.x, 4, glm::vec4(0.0f));
      }
    }
  }
  Tables& tables = l.Pairs ? in.Pairs[list] : in.Sheets[list];
  if (tables.Colors != colors || perFrameColors)
  {
    if (l.Pairs)
    {
      in.MergeValues(list, colors);
    }
    else
    {
      in.CopyValues(list, order, colors);
    }
    tables.Colors = colors;
  }
  in.Composite(list);
  // The warp to the screen pixels.
  buffer.resize(in.Samples.size());
  vtkSMPTools::For(0, static_cast<vtkIdType>(in.Samples.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType p = begin; p < end; ++p)
      {
        const glm::vec2 sample = in.Samples[p];
        glm::vec4 color(0.0f);
        if (sample != Unused)
        {
          const auto weights = [](float t)
          {
            const float t2 = t * t, t3 = t2 * t;
            return glm::vec4(-0.5f * t3 + t2 - 0.5f * t, 1.5f * t3 - 2.5f * t2 + 1.0f,
              -1.5f * t3 + 2.0f * t2 + 0.5f * t, 0.5f * t3 - 0.5f * t2);
          };
          const glm::vec2 f = sample - glm::floor(sample);
          const glm::vec4 wx = weights(f.x), wy = weights(f.y);
          const glm::vec4* tap = in.Image.data() + firstTap(sample);
          for (int j = 0; j < 4; ++j, tap += l.Size.x)
          {
            color += wy[j] * (wx[0] * tap[0] + wx[1] * tap[1] + wx[2] * tap[2] + wx[3] * tap[3]);
          }
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
int vtkVolumeSplatSheetCompositor::GetNumberOfLayers(int list) const
{
  return list >= 0 && list < 3 && this->Internal->Lists[list].Size.x > 0
    ? static_cast<int>(this->Internal->Lists[list].Layers.size())
    : 0;
}

//------------------------------------------------------------------------------
void vtkVolumeSplatSheetCompositor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MergePairs: " << this->GetMergePairs() << "\n";
  os << indent << "FootprintFilter: " << this->GetFootprintFilter() << "\n";
  for (int list = 0; list < 3; ++list)
  {
    const glm::ivec2 size = this->GetIntermediateSize(list);
    os << indent << "IntermediateSize " << list << ": " << size.x << " x " << size.y
       << ", Layers: " << this->GetNumberOfLayers(list) << "\n";
  }
}
