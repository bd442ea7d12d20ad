// SPDX-License-Identifier: BSD-3-Clause
#include "SplatMinifiedSplatCells.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace splat
{
namespace
{
// The largest reach for which a pixel's gather first tries to join all its cells into one
// fragment (the default cutoff and variance have a reach of 1).
constexpr int MaximumJoinedReach = 2;

// The index of the lowest set bit of a nonzero word.
inline int CountTrailingZeros(std::uint64_t word)
{
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_ctzll(word);
#else
  int n = 0;
  for (; !(word & 1); word >>= 1)
  {
    ++n;
  }
  return n;
#endif
}

// A minified splat into the cells of the pixel holding its center, as an opaque contribution
// joins a pixel's fragments, with its offset from the pixel's center weighted by its mass.
inline void Deposit(MinifiedSplatCells::Cell* cells, std::uint8_t& count, int layers,
  const MinifiedSurfel& m, float offsetX, float offsetY)
{
  bool inserted;
  const int i = OpaqueSlot(cells, count, layers, m.Depth, m.Threshold, inserted);
  if (i < 0)
  {
    return;
  }
  MinifiedSplatCells::Cell& cell = cells[i];
  if (inserted)
  {
    cell.Sum = NewFragment(m.Depth, m.Mass, m.Normal, m.Color, m.Alpha);
    cell.Threshold = m.Threshold;
    cell.Offset[0] = cell.Offset[1] = cell.DepthSlope[0] = cell.DepthSlope[1] = 0.0f;
    cell.InverseVariance = 0.0f;
  }
  else
  {
    Accumulate(cell.Sum, m.Depth, m.Mass, m.Normal, m.Color, m.Alpha);
  }
  cell.Offset[0] += m.Mass * offsetX;
  cell.Offset[1] += m.Mass * offsetY;
  cell.DepthSlope[0] += m.Mass * m.DepthSlope[0];
  cell.DepthSlope[1] += m.Mass * m.DepthSlope[1];
  cell.InverseVariance += m.Mass * m.Spread;
}
}

//------------------------------------------------------------------------------
void MinifiedSplatCells::SetUp(
  int width, int height, int layers, double cutoff, double maximumVariance)
{
  this->ViewportWidth = width;
  this->ViewportHeight = height;
  this->Layers = layers;
  this->Reach = ReachOf(cutoff, maximumVariance);
  this->Width = width + 2 * this->Reach;
  this->Height = height + 2 * this->Reach;
  this->Bands = (this->Height + BandHeight - 1) / BandHeight;
  this->Words = (this->Width + 63) / 64;
}

//------------------------------------------------------------------------------
void MinifiedSplatCells::ReserveChunks(vtkIdType chunks)
{
  if (this->Lists.size() < static_cast<std::size_t>(chunks * this->Bands))
  {
    this->Lists.resize(chunks * this->Bands);
  }
}

//------------------------------------------------------------------------------
void MinifiedSplatCells::ClearChunk(vtkIdType chunk)
{
  for (vtkIdType b = 0; b < this->Bands; ++b)
  {
    this->Lists[chunk * this->Bands + b].clear();
  }
}

//------------------------------------------------------------------------------
void MinifiedSplatCells::Sum(vtkIdType chunks)
{
  // Each band sums its splats chunk by chunk, in input order, into the cells of the pixels
  // holding their centers, then turns the sums of offsets, slopes and spreads into what the
  // gather reads.
  const std::vector<std::vector<MinifiedSurfel>>& lists = this->Lists;
  std::vector<Cell>& cells = this->Cells;
  std::vector<std::uint8_t>& counts = this->Counts;
  const int layers = this->Layers;
  cells.resize(static_cast<std::size_t>(this->Width) * this->Height * layers);
  counts.resize(static_cast<std::size_t>(this->Width) * this->Height);
  std::vector<float>& deeperDepths = this->DeeperDepths;
  deeperDepths.resize(counts.size());
  std::vector<std::uint64_t>& filled = this->Filled;
  filled.resize(static_cast<std::size_t>(this->Words) * this->Height);
  vtkSMPTools::For(0, this->Bands, 1,
    [&](vtkIdType bandBegin, vtkIdType bandEnd)
    {
      const std::size_t first = static_cast<std::size_t>(bandBegin) * BandHeight * this->Width;
      const std::size_t last = std::min(
        static_cast<std::size_t>(bandEnd) * BandHeight * this->Width, counts.size());
      std::fill(counts.begin() + first, counts.begin() + last, 0);
      const int rowBegin = static_cast<int>(bandBegin) * BandHeight;
      const int rowEnd = std::min(static_cast<int>(bandEnd) * BandHeight, this->Height);
      std::fill(filled.begin() + static_cast<std::size_t>(rowBegin) * this->Words,
        filled.begin() + static_cast<std::size_t>(rowEnd) * this->Words, 0);
      for (vtkIdType b = bandBegin; b < bandEnd; ++b)
      {
        for (vtkIdType chunk = 0; chunk < chunks; ++chunk)
        {
          for (const MinifiedSurfel& m : lists[chunk * this->Bands + b])
          {
            const int x = FloorToInt(m.CenterX);
            const int y = FloorToInt(m.CenterY);
            const int column = x + this->Reach;
            filled[static_cast<std::size_t>(y + this->Reach) * this->Words + column / 64] |=
              std::uint64_t(1) << (column % 64);
            const std::size_t cell =
              static_cast<std::size_t>(y + this->Reach) * this->Width + (x + this->Reach);
            Deposit(&cells[cell * layers], counts[cell], layers, m, m.CenterX - (x + 0.5f),
              m.CenterY - (y + 0.5f));
          }
        }
      }
      for (std::size_t cell = first; cell < last; ++cell)
      {
        float deeper = std::numeric_limits<float>::infinity();
        for (int j = 0; j < counts[cell]; ++j)
        {
          Cell& c = cells[cell * layers + j];
          for (int k = 0; k < 2; ++k)
          {
            c.Offset[k] /= c.Sum.Weight;
            c.DepthSlope[k] /= c.Sum.Weight;
          }
          c.InverseVariance = 1.0f / (1.0f + c.InverseVariance / c.Sum.Weight);
          if (j > 0)
          {
            deeper = std::min(deeper, c.Sum.Depth -
                this->Reach * (std::abs(c.DepthSlope[0]) + std::abs(c.DepthSlope[1])) -
                c.Threshold);
          }
        }
        deeperDepths[cell] = deeper;
      }
    });
}

//------------------------------------------------------------------------------
vtkIdType MinifiedSplatCells::Gather(SurfaceFragment* fragments, std::uint8_t* counts,
  float cutoff, float fullCoverage, const float* sceneDepths, float weightScale) const
{
  // Each pixel gathers its neighbors' cells into its own fragments, one contribution per cell:
  // the low-pass filter widened by the cell's spread, the Gaussian of variance v = 1 + spread,
  // e^-beta / (2 pi v), at the offset to its mean center within the cutoff. The nearest surface
  // of every cell comes first; the cells' farther surfaces are then left out where they fall
  // behind a fully covered opaque front fragment, through which nothing shows, which on a
  // closed surface is most of its back.
  const std::vector<Cell>& cells = this->Cells;
  const std::vector<std::uint8_t>& cellCounts = this->Counts;
  const std::vector<float>& deeperDepths = this->DeeperDepths;
  const std::vector<std::uint64_t>& filled = this->Filled;
  const int words = this->Words;
  const int width = this->ViewportWidth;
  const int height = this->ViewportHeight;
  const int layers = this->Layers;
  const int reach = this->Reach;
  const float full = fullCoverage;
  const float negligible = NegligibleCoverage * full;
  const ExponentialTable exponential(cutoff);
  const int bands = (height + BandHeight - 1) / BandHeight;
  std::vector<vtkIdType> gathered(bands, 0);
  vtkSMPTools::For(0, bands, 1,
    [&](vtkIdType bandBegin, vtkIdType bandEnd)
    {
      const int rowBegin = static_cast<int>(bandBegin) * BandHeight;
      const int rowEnd = std::min(static_cast<int>(bandEnd) * BandHeight, height);
      vtkIdType written = 0;
      // Pixel (x, y) gathers the cells within the reach into its fragments.
      auto gatherPixel = [&](int x, int y)
      {
        const std::size_t pixel = static_cast<std::size_t>(y) * width + x;
        SurfaceFragment* pixelFragments = &fragments[pixel * layers];
        std::uint8_t& count = counts[pixel];
        // One cell's surface, dx, dy pixels away, at depth z; left out behind a fully covered
        // opaque front fragment by more than its z threshold, where it could not show.
        // The weight of a cell's surface dx, dy pixels away, at depth z: false where it lies
        // beyond the cutoff or behind the scene.
        auto weightOf = [&](const Cell& c, int dx, int dy, float z, float& w)
        {
          const float ox = dx + c.Offset[0];
          const float oy = dy + c.Offset[1];
          const float beta = 0.5f * (ox * ox + oy * oy) * c.InverseVariance;
          if (!(beta < cutoff) || (sceneDepths && z > sceneDepths[pixel]))
          {
            return false;
          }
          w = weightScale * static_cast<float>(InverseTwoPi) * exponential(beta) * c.InverseVariance;
          return true;
        };
        auto add = [&](const Cell& c, int dx, int dy, float z)
        {
          float w;
          if ((count > 0 && z > pixelFragments[0].Depth + c.Threshold &&
                FullyCoveredOpaque(pixelFragments[0], full)) ||
            !weightOf(c, dx, dy, z, w))
          {
            return;
          }
          bool inserted;
          const int i = OpaqueSlot(
            pixelFragments, count, layers, z, c.Threshold, inserted, w * c.Sum.Weight, negligible);
          if (i < 0)
          {
            return;
          }
          if (inserted)
          {
            pixelFragments[i] = Scaled(c.Sum, w, z);
          }
          else
          {
            AccumulateScaled(pixelFragments[i], c.Sum, w, z);
          }
          ++written;
        };
        // The cell's plane at this pixel's center, dx, dy pixels from its own.
        auto depthAt = [](const Cell& c, int dx, int dy)
        { return c.Sum.Depth - dx * c.DepthSlope[0] - dy * c.DepthSlope[1]; };
        // Most pixels hold nothing yet and have one surface in each cell within the reach,
        // all within each other's z thresholds: every contribution then joins one fragment,
        // added here in the same order as below, without the search for its slot.
        if (count == 0 && reach <= MaximumJoinedReach)
        {
          const Cell* joined[(2 * MaximumJoinedReach + 1) * (2 * MaximumJoinedReach + 1)];
          float weights[(2 * MaximumJoinedReach + 1) * (2 * MaximumJoinedReach + 1)];
          float depths[(2 * MaximumJoinedReach + 1) * (2 * MaximumJoinedReach + 1)];
          int n = 0;
          bool oneSurface = true;
          float nearest = std::numeric_limits<float>::infinity();
          float farthest = -nearest;
          float threshold = nearest;
          for (int dy = -reach; dy <= reach && oneSurface; ++dy)
          {
            const std::size_t row = static_cast<std::size_t>(y + dy + reach) * this->Width;
            for (int dx = -reach; dx <= reach; ++dx)
            {
              const std::size_t cell = row + (x + dx + reach);
              oneSurface = oneSurface && cellCounts[cell] <= 1;
              if (cellCounts[cell] == 0)
              {
                continue;
              }
              const Cell& c = cells[cell * layers];
              const float z = depthAt(c, dx, dy);
              if (!weightOf(c, dx, dy, z, weights[n]))
              {
                continue;
              }
              joined[n] = &c;
              depths[n++] = z;
              nearest = std::min(nearest, z);
              farthest = std::max(farthest, z);
              threshold = std::min(threshold, c.Threshold);
            }
          }
          if (oneSurface && farthest - nearest <= threshold)
          {
            if (n > 0)
            {
              pixelFragments[0] = Scaled(joined[0]->Sum, weights[0], depths[0]);
              for (int i = 1; i < n; ++i)
              {
                AccumulateScaled(pixelFragments[0], joined[i]->Sum, weights[i], depths[i]);
              }
              count = 1;
              written += n;
            }
            return;
          }
        }
        // The cells' nearest surfaces first.
        float deeper = std::numeric_limits<float>::infinity();
        for (int dy = -reach; dy <= reach; ++dy)
        {
          const std::size_t row = static_cast<std::size_t>(y + dy + reach) * this->Width;
          for (int dx = -reach; dx <= reach; ++dx)
          {
            const std::size_t cell = row + (x + dx + reach);
            if (cellCounts[cell] > 0)
            {
              deeper = std::min(deeper, deeperDepths[cell]);
              const Cell& c = cells[cell * layers];
              add(c, dx, dy, depthAt(c, dx, dy));
            }
          }
        }
        // Then their farther ones, but those behind a fully covered opaque front (whose
        // depth can only decrease as the pixel gathers more).
        const SurfaceFragment& front = pixelFragments[0];
        const float hiding = count > 0 && FullyCoveredOpaque(front, full)
          ? front.Depth
          : std::numeric_limits<float>::infinity();
        if (!(deeper <= hiding))
        {
          return;
        }
        for (int dy = -reach; dy <= reach; ++dy)
        {
          const std::size_t row = static_cast<std::size_t>(y + dy + reach) * this->Width;
          for (int dx = -reach; dx <= reach; ++dx)
          {
            const std::size_t cell = row + (x + dx + reach);
            for (int j = 1; j < cellCounts[cell] && deeperDepths[cell] <= hiding; ++j)
            {
              const Cell& c = cells[cell * layers + j];
              const float z = depthAt(c, dx, dy);
              if (!(z > hiding + c.Threshold))
              {
                add(c, dx, dy, z);
              }
            }
          }
        }
      };
      std::vector<std::uint64_t> reached(words + 1); // one word past the row: none filled
      for (int y = rowBegin; y < rowEnd; ++y)
      {
        // The pixels of the row that a filled cell reaches: pixel x gathers cells x to
        // x + 2 reach of rows y to y + 2 reach (the grid is padded by reach), so bit x of
        // `pixels` is set where any of those is filled (2 reach < 64: the rasterizer clamps
        // the cutoff to 50 and the variance to 1).
        for (int word = 0; word < words; ++word)
        {
          std::uint64_t any = 0;
          for (int dy = 0; dy <= 2 * reach; ++dy)
          {
            any |= filled[static_cast<std::size_t>(y + dy) * words + word];
          }
          reached[word] = any;
        }
        for (int word = 0; word < words; ++word)
        {
          std::uint64_t pixels = reached[word];
          for (int shift = 1; shift <= 2 * reach; ++shift)
          {
            pixels |= (reached[word] >> shift) | (reached[word + 1] << (64 - shift));
          }
          for (; pixels != 0; pixels &= pixels - 1)
          {
            const int x = 64 * word + CountTrailingZeros(pixels);
            if (x >= width)
            {
              break;
            }
            gatherPixel(x, y);
          }
        }
      }
      gathered[bandBegin] = written;
    });
  return std::accumulate(gathered.begin(), gathered.end(), vtkIdType(0));
}

} // namespace splat
