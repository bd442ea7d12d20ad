// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatVolumeLayerCompositor.h
 * @brief Front-to-back compositing of layers of volume footprints into a band of image rows:
 * the per-pixel loop of vtkVolumeSplatRasterizer, on the screen for the exact per-kernel path
 * and on a sheet-aligned intermediate image for vtkVolumeSplatSheetCompositor.
 *
 * A layer is a sheet of the grid for image data (kernels side by side at one index along the
 * list's axis, whose order within the sheet is arbitrary) and a single kernel otherwise. A
 * layer's footprints are first summed per pixel as optical depth and optical-depth-weighted
 * color; the layer then goes under the pixel once, with opacity 1 - exp(-sum). That is the
 * transmittance of compositing its kernels one by one, with colors weighted by each kernel's
 * share of the optical depth, independent of their order, and one exponential per pixel and
 * layer instead of one per kernel and pixel.
 */
#ifndef SplatVolumeLayerCompositor_h
#define SplatVolumeLayerCompositor_h

#include "SplatFloat8.h"
#include "vtkVolumeSplatRasterizer.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace splat
{
/// Why the setup left a kernel out of a frame.
enum VolumeSkipReason : std::uint8_t
{
  Kept = 0,
  NearPlane,
  OutsideFrustum
};

/// Accumulated opacity at which a pixel stops integrating: what is behind changes it by less
/// than half an 8-bit step.
constexpr float TerminationAlpha = 1.0f - 1.0f / 512.0f;
}

/// One kernel after setup, in the single precision the per-pixel loop uses.
struct vtkVolumeSplatRasterizer::ScreenKernel
{
  float CenterX, CenterY;
  float ConicXX, ConicXY, ConicYY; // 1/2 M^-1, so that beta = d^T C d
  float Amplitude; // optical depth (density model) or opacity (peak model) at the center
  float Depth;     // eye-space depth of the center
  float Color[3];
  int X0, X1, Y0, Y1; // inclusive pixel bounds
  splat::VolumeSkipReason Skip;
};

namespace splat
{
/// Composites the kernels of one list into one band of its buffer, front to back, layer by
/// layer (see the file comment).
class VolumeLayerCompositor
{
public:
  using ScreenKernel = vtkVolumeSplatRasterizer::ScreenKernel;

  /// The pixels of a row that the per-pixel loops take at once (Float8).
  static constexpr int Lanes = 8;

  /// A band of rows [rowBegin, rowEnd] of an image `width` pixels wide; sceneDepths, when not
  /// null, holds the opaque scene's eye depth per image pixel.
  VolumeLayerCompositor(int width, int rowBegin, int rowEnd, float cutoff, bool peakOpacity,
    const float* sceneDepths);

  /// Starts a traversal of a list into `buffer`: a band pixel is open while it integrates, that
  /// is below the termination opacity and, when weights is not null, with the traversal's sign.
  void Begin(const float* weights, bool ascending, const glm::vec4* buffer);

  /// Adds kernel s to the current layer, unless every pixel of its box has stopped integrating
  /// or does not take this traversal (early termination per tile of Lanes columns of a row):
  /// Flush would leave its sums unused.
  void Add(const ScreenKernel& s);

  /// Puts kernel s alone under the pixels, as Add and Flush would for a layer of that one
  /// kernel, without the layer's sums. The current layer must be empty (flushed).
  void Composite(const ScreenKernel& s, const float* weights, bool ascending, glm::vec4* buffer);

  /// The most columns and rows AddFactored takes.
  static constexpr int MaximumFactoredColumns = 64;

  /// What the footprints of AddFactored share in a run of kernels: a conic, a cross table and
  /// the row of their centers (a tile's voxels in one row of a sheet). Set up by BeginFactoredRun.
  struct FactoredRun
  {
    int Rows;        // the band rows the footprints cover, from FirstRow (none when zero)
    int FirstRow;    // as a band offset
    float ConicXX, ConicXY, ConicYY;
    float ColumnSlope; // ConicXY times the centers' offset along y from their pixel's center
    const float* Cross; // the cross table at the first row and the centers' column
    int CrossStride;
    // Per row from the first, dy its offset from the centers: ConicYY dy^2, ConicXY dy and
    // -2 ConicYY dy (for a kernel's own shift along y).
    Float8 RowSquares[MaximumFactoredColumns / Lanes];
    Float8 RowSlopes[MaximumFactoredColumns / Lanes];
    Float8 RowShifts[MaximumFactoredColumns / Lanes];
  };

  /**
   * Sets up `run` for kernels centered on row centerY of the image, with conic (xx, xy, yy)
   * and rows [y0, y1] (clipped to the band here): each footprint is taken over its whole box
   * (no cutoff ellipse), factored so that for the pixel at offset (m, n) from the one holding
   * the kernel's center, exp(-beta) is a factor of column m times a factor of row n times
   * cross[(n + reach) crossStride + m + reach] = exp(-xy m n), a table of the run's conic. That
   * is one exponential per group of columns and of rows instead of one per pixel. The table
   * must cover the boxes (|m|, |n| <= reach, a further group of lanes of zeros per row), and
   * |xy| reach^2 stay below 60: that bounds the cross parts of the factors' exponents within
   * the boxes by 30, so that they need no clamp from below (Float8::NegativeExponentialAbove).
   */
  SPLAT_ALWAYS_INLINE void BeginFactoredRun(FactoredRun& run, float centerY, int y0, int y1,
    float xx, float xy, float yy, const float* cross, int reach, int crossStride) const;

  /**
   * Adds the kernel of run `run` centered on column centerX and shifted by shiftY from the
   * run's row of centers (the run's rows must hold its box), over columns [x0, x1] (within the
   * image), as Add does. Inlined into the caller's loop over kernels (built for AVX2 too),
   * with a path of its own for footprints of at most a group of lanes by a group of rows (the
   * most at the sheets' intermediate scale): the footprints are a few pixels, and the setup a
   * good part of them. Unlike Add it neither tests whether the kernel's box still integrates
   * nor grows the layer's rows and spans: its caller tests the first (IntegratesInRows) before
   * it sets the kernel up and does the second with Touch, once for a row of kernels.
   */
  SPLAT_ALWAYS_INLINE void AddFactored(const FactoredRun& run, float centerX, float shiftY,
    int x0, int x1, float amplitude, const glm::vec3& color)
  {
    if (x1 - x0 < Lanes && run.Rows <= Lanes)
    {
      this->AddFactoredGroups<1>(run, centerX, shiftY, x0, x1, amplitude, color);
    }
    else
    {
      this->AddFactoredGroups<MaximumFactoredColumns / Lanes>(
        run, centerX, shiftY, x0, x1, amplitude, color);
    }
  }

  /// Puts the current layer under the band's pixels of `buffer` whose weight for the list has
  /// the traversal's sign (all pixels when weights is null), and starts a new layer.
  void Flush(const float* weights, bool ascending, glm::vec4* buffer);

  /// Grows the current layer to columns [x0, x1] (within the image) of rows [y0, y1]: a box that
  /// holds the kernels AddFactored adds.
  SPLAT_ALWAYS_INLINE void Touch(int x0, int x1, int y0, int y1)
  {
    y0 = std::max(y0, this->RowBegin);
    y1 = std::min(y1, this->RowEnd);
    this->LayerRows = glm::ivec2(std::min(this->LayerRows.x, y0), std::max(this->LayerRows.y, y1));
    for (int y = y0; y <= y1; ++y)
    {
      glm::ivec2& span = this->Spans[y - this->RowBegin];
      span = glm::ivec2(std::min(span.x, x0), std::max(span.y, x1));
    }
  }

  /// Whether some pixel of the band still integrates.
  SPLAT_ALWAYS_INLINE bool Integrates() const { return this->OpenTotal > 0; }

  /// Sets the rows that IntegratesInRows tests: [y0, y1], clipped to the band.
  SPLAT_ALWAYS_INLINE void SelectRows(int y0, int y1)
  {
    std::fill(this->SelectedRows.begin(), this->SelectedRows.end(), 0);
    const int tiles = this->Tiles;
    for (int y = std::max(y0, this->RowBegin); y <= std::min(y1, this->RowEnd); ++y)
    {
      const int* row =
        this->OpenPixels.data() + static_cast<std::ptrdiff_t>(y - this->RowBegin) * tiles;
      for (int tile = 0; tile < tiles; ++tile)
      {
        this->SelectedRows[tile] += row[tile];
      }
    }
  }

  /// Integrates for columns [x0, x1] of the rows SelectRows set, until the current layer is
  /// flushed (when pixels close): for kernels whose rows lie within those, one test per kernel
  /// as cheap as for a single row.
  SPLAT_ALWAYS_INLINE bool IntegratesInRows(int x0, int x1) const
  {
    return IntegratesIn(this->SelectedRows.data(), x0, x1);
  }

private:
  /// Whether some pixel of columns [x0, x1] (within the image) of rows [y0, y1] (clipped to the
  /// band here) still integrates, at the granularity of the early termination (see Add).
  SPLAT_ALWAYS_INLINE bool IntegratesInBox(int x0, int x1, int y0, int y1) const
  {
    const int tiles = this->Tiles;
    const int* row = this->OpenPixels.data() +
      static_cast<std::ptrdiff_t>(std::max(y0, this->RowBegin) - this->RowBegin) * tiles;
    for (int y = std::max(y0, this->RowBegin); y <= std::min(y1, this->RowEnd); ++y, row += tiles)
    {
      if (IntegratesIn(row, x0, x1))
      {
        return true;
      }
    }
    return false;
  }

  /// Whether some pixel of kernel s's box still integrates (see Add).
  SPLAT_ALWAYS_INLINE bool Reaches(const ScreenKernel& s) const
  {
    return this->IntegratesInBox(s.X0, s.X1, s.Y0, s.Y1);
  }

  /// The sums (red, green, blue, optical depth) from band offset q on.
  SPLAT_ALWAYS_INLINE std::array<float*, 4> SumsAt(std::size_t q)
  {
    return { this->Sums[0].data() + q, this->Sums[1].data() + q, this->Sums[2].data() + q,
      this->Sums[3].data() + q };
  }

  /// Whether openTiles (open pixels per tile of a row, or of rows) has some for columns
  /// [x0, x1].
  SPLAT_ALWAYS_INLINE static bool IntegratesIn(const int* openTiles, int x0, int x1)
  {
    // The first and the last tile first, without a loop: a footprint of the sheets spans two
    // tiles at most.
    const int first = x0 / Lanes, last = x1 / Lanes;
    if (openTiles[first] > 0 || openTiles[last] > 0)
    {
      return true;
    }
    for (int tile = first + 1; tile < last; ++tile)
    {
      if (openTiles[tile] > 0)
      {
        return true;
      }
    }
    return false;
  }

  /// Adds optical depths t times the color to the eight pixels of `sums` from offset q.
  SPLAT_ALWAYS_INLINE static void Accumulate(const std::array<float*, 4>& sums, std::size_t q,
    const Float8& t, const Float8& red, const Float8& green, const Float8& blue)
  {
    (Float8::Load(sums[3] + q) + t).Store(sums[3] + q);
    (Float8::Load(sums[0] + q) + t * red).Store(sums[0] + q);
    (Float8::Load(sums[1] + q) + t * green).Store(sums[1] + q);
    (Float8::Load(sums[2] + q) + t * blue).Store(sums[2] + q);
  }

  /// AddFactored for footprints of at most MaximumGroups groups of Lanes columns and rows.
  template <int MaximumGroups>
  SPLAT_ALWAYS_INLINE void AddFactoredGroups(const FactoredRun& run, float centerX,
    float shiftY, int x0, int x1, float amplitude, const glm::vec3& color);

  static bool IsOpen(const float* weights, bool ascending, const glm::vec4* buffer, std::size_t p)
  {
    return buffer[p].a < TerminationAlpha &&
      (!weights || (ascending ? weights[p] > 0.0f : weights[p] < 0.0f));
  }

  /// Calls visit(y, x, q, t) for each group of Lanes pixels of kernel s's box within the band:
  /// (x, y) is the group's first pixel, q indexes the band's sums there, t holds the kernel's
  /// optical depths there (zero beyond the box, outside the cutoff ellipse and behind the
  /// opaque scene).
  template <typename Visit>
  SPLAT_ALWAYS_INLINE void ForEachGroup(const ScreenKernel& s, Visit&& visit);

  /// Puts a layer of opacity alpha and color `color` (times alpha) under pixel p (column x,
  /// whose row's open pixels per tile are openTiles) of `buffer`, where it is open. Without
  /// branches: which pixels of a footprint's rim or of the list's blend region are open is hard
  /// to predict.
  SPLAT_ALWAYS_INLINE void Under(const float* weights, bool ascending, glm::vec4* buffer,
    std::size_t p, int x, int* openTiles, float alpha, const glm::vec3& color)
  {
    glm::vec4& c = buffer[p];
    const bool open = alpha > 0.0f && IsOpen(weights, ascending, buffer, p);
    const float transmittance = open ? 1.0f - c.a : 0.0f;
    c += glm::vec4(transmittance * color, transmittance * alpha);
    const bool closed = open && c.a >= TerminationAlpha;
    openTiles[x / Lanes] -= closed;
    this->OpenTotal -= closed;
  }

  /**
   * Under for the pixels of `buffer` from p (column x of row y) with opacities alpha and colors
   * (times alpha) red, green and blue, lane by lane: eight pixels as vectors where they lie
   * within the image's row (a lane of zero opacity leaves its pixel as it is), the first
   * `lanes` one by one otherwise.
   */
  SPLAT_ALWAYS_INLINE void UnderGroup(const float* weights, bool ascending, glm::vec4* buffer,
    std::size_t p, int x, int y, int lanes, const Float8& alpha, const Float8& red,
    const Float8& green, const Float8& blue);

  /// The opacity of optical depths t, which are at most `largest` (peak opacities in the peak
  /// model).
  SPLAT_ALWAYS_INLINE Float8 Opacity(
    const Float8& t, float largest = std::numeric_limits<float>::infinity()) const;

  int Width;
  int RowBegin;
  int RowEnd;
  float Cutoff;
  bool PeakOpacity;
  // Band rows are padded by a group of Lanes, which the last group of a kernel at the right
  // edge may reach (adding zeros).
  int Stride;
  // Per band pixel: the opaque scene's eye depth (infinite where there is none).
  std::vector<float> SceneDepths;
  // Per band pixel: optical depth times red, green, blue, and optical depth (opacity in the
  // peak model), in separate arrays so that the row loop vectorizes.
  std::array<std::vector<float>, 4> Sums;
  std::vector<glm::ivec2> Spans; // per band row: the columns the layer touched
  glm::ivec2 LayerRows;           // the band rows the layer touched (first, last)
  int Tiles;                      // tiles of Lanes columns in a row
  std::vector<int> OpenPixels;    // per band row and tile: its open pixels (see Begin)
  int OpenTotal;                  // the band's open pixels
  std::vector<int> SelectedRows;  // per tile: the open pixels of the rows SelectRows set
};

//------------------------------------------------------------------------------
SPLAT_ALWAYS_INLINE void VolumeLayerCompositor::BeginFactoredRun(FactoredRun& run, float centerY,
  int y0, int y1, float xx, float xy, float yy, const float* cross, int reach,
  int crossStride) const
{
  y0 = std::max(y0, this->RowBegin);
  y1 = std::min(y1, this->RowEnd);
  run.Rows = std::max(y1 - y0 + 1, 0);
  run.FirstRow = y0 - this->RowBegin;
  // Offsets from the pixel holding the centers, where the cross table is centered.
  const int yc = static_cast<int>(std::floor(centerY));
  const float dyc = yc + 0.5f - centerY;
  const int n0 = y0 - yc;
  run.ConicXX = xx;
  run.ConicXY = xy;
  run.ConicYY = yy;
  run.ColumnSlope = xy * dyc;
  run.Cross = cross + static_cast<std::ptrdiff_t>(n0 + reach) * crossStride + reach;
  run.CrossStride = crossStride;
  for (int j = 0; j < run.Rows; j += Lanes)
  {
    const Float8 dy = Float8::Iota() + static_cast<float>(n0 + j) + dyc;
    run.RowSquares[j / Lanes] = yy * dy * dy;
    run.RowSlopes[j / Lanes] = xy * dy;
    run.RowShifts[j / Lanes] = (-2.0f * yy) * dy;
  }
}

//------------------------------------------------------------------------------
template <int MaximumGroups>
SPLAT_ALWAYS_INLINE void VolumeLayerCompositor::AddFactoredGroups(const FactoredRun& run,
  float centerX, float shiftY, int x0, int x1, float amplitude, const glm::vec3& color)
{
  const int columns = x1 - x0 + 1;
  const int groups = MaximumGroups == 1 ? 1 : (columns + Lanes - 1) / Lanes;
  const int xc = static_cast<int>(std::floor(centerX));
  const float dxc = xc + 0.5f - centerX;
  const int m0 = x0 - xc;
  // With the kernel's rows at dy - shiftY, the exponent gains -ConicXY shiftY m in its columns
  // and shiftY (-2 ConicYY dy + ConicYY shiftY - ConicXY dxc) in its rows.
  const float columnSlope = run.ColumnSlope - run.ConicXY * shiftY;
  const float rowShift = shiftY * (run.ConicYY * shiftY - run.ConicXY * dxc);
  const Float8 lane = Float8::Iota();
  Float8 columnFactors[MaximumGroups];
  for (int group = 0; group < groups; ++group)
  {
    const Float8 i = lane + static_cast<float>(group * Lanes);
    const Float8 m = i + static_cast<float>(m0);
    const Float8 dx = m + dxc;
    const Float8 factor =
      Float8::NegativeExponentialAbove(run.ConicXX * dx * dx + columnSlope * m);
    columnFactors[group] =
      Float8::SelectLess(i, Float8(static_cast<float>(columns)), factor, Float8(0.0f));
  }
  alignas(32) float rowFactors[MaximumGroups * Lanes];
  const int rows = run.Rows;
  for (int j = 0; j < rows; j += Lanes)
  {
    (amplitude *
      Float8::NegativeExponentialAbove(run.RowSquares[j / Lanes] +
        dxc * run.RowSlopes[j / Lanes] + shiftY * run.RowShifts[j / Lanes] + rowShift))
      .Store(rowFactors + j);
  }
  const Float8 red(color.r), green(color.g), blue(color.b);
  // Local copies: the stores through the sums could alias the members as far as the compiler
  // knows, which would reload them for every row.
  const std::size_t stride = this->Stride;
  const std::size_t crossStride = run.CrossStride;
  const std::array<float*, 4> sums = this->SumsAt(run.FirstRow * stride + x0);
  const float* crossRow = run.Cross + m0;
  for (int j = 0; j < rows; ++j)
  {
    const float rowFactor = rowFactors[j];
    for (int group = 0; group < groups; ++group)
    {
      const int i = group * Lanes;
      Accumulate(sums, j * stride + i,
        rowFactor * columnFactors[group] * Float8::Load(crossRow + i), red, green, blue);
    }
    crossRow += crossStride;
  }
}
}

#endif
