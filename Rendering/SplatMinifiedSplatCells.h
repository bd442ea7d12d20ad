// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatMinifiedSplatCells.h
 * @brief The minified splats of a frame of the CPU surface rasterizer, summed per pixel and
 * spread once per pixel by the screen low-pass filter.
 *
 * A minified splat (SplatMinifiedSurfel.h) is summed into the cell of the pixel holding its
 * center, with the splats of the same surface there (the z threshold separates surfaces, as
 * fragments do). Each pixel then gathers the cells within the filter's reach into its
 * fragments: one contribution per cell, the low-pass Gaussian widened by the cell's mean
 * warped variance, at the cell's mean center and on its mean depth plane. Private to
 * vtkSurfaceSplatRasterizer.
 */
#ifndef SplatMinifiedSplatCells_h
#define SplatMinifiedSplatCells_h

#include "SplatMinifiedSurfel.h"
#include "SplatSurfaceFragment.h"
#include "vtkType.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace splat
{

class MinifiedSplatCells
{
public:
  /// Rows of cells per band: the splats are listed by band, and bands are summed in parallel.
  static constexpr int BandHeight = 16;

  /**
   * One surface's minified splats whose centers lie in one pixel: their weighted sums and,
   * once summed, the weighted means of their centers relative to the pixel's center and of
   * their depth slopes, and the inverse of the gather's variance, 1 + their mean spread.
   */
  struct Cell
  {
    SurfaceFragment Sum;
    float Threshold;
    float Offset[2];
    float DepthSlope[2];
    float InverseVariance;
  };

  /**
   * Sets up a frame over a viewport of width x height pixels with `layers` fragments per pixel:
   * a pixel gathers the cells within the cutoff's reach of its center for the widest spread,
   * sqrt(2 cutoff (1 + maximumVariance)) pixels, so the grid pads the viewport by as many
   * cells on each side. (A cell one further would contribute only with its mean center well
   * off its own center, a sparsely filled cell; it is left out, a truncation the tests bound.)
   */
  void SetUp(int width, int height, int layers, double cutoff, double maximumVariance);

  /// Cells kept outside the viewport on each side.
  int GetReach() const { return this->Reach; }

  /// The reach SetUp gives the grid, before it is set up.
  static int ReachOf(double cutoff, double maximumVariance)
  {
    return static_cast<int>(std::floor(std::sqrt(2.0 * cutoff * (1.0 + maximumVariance))));
  }

  /**
   * Makes room for the lists of `chunks` chunks of splats; the lists keep their capacity from
   * frame to frame. ClearChunk empties one chunk's lists (each chunk may be listed by its own
   * thread), and List appends a splat to its chunk's list of the band holding its center.
   */
  void ReserveChunks(vtkIdType chunks);
  void ClearChunk(vtkIdType chunk);
  void List(vtkIdType chunk, const MinifiedSurfel& m)
  {
    const int band = (FloorToInt(m.CenterY) + this->Reach) / BandHeight;
    this->Lists[chunk * this->Bands + band].push_back(m);
  }

  /**
   * Sums the listed splats of the first `chunks` chunks into their cells, band by band in
   * parallel, in each cell in chunk order and then list order: the order of the input,
   * whatever the number of threads.
   */
  void Sum(vtkIdType chunks);

  /**
   * Gathers the cells into the pixels' fragments (`layers` per pixel, counted by `counts`, as
   * the rasterizer keeps them); pixels whose scene depth (eye depth, or null for none) is
   * nearer than a contribution do not take it. Each contribution's weight is scaled by
   * `weightScale` (TruncatedMassScale, where `cutoff` is not the one `fullCoverage` is for).
   * Returns the contributions written.
   */
  vtkIdType Gather(SurfaceFragment* fragments, std::uint8_t* counts, float cutoff,
    float fullCoverage, const float* sceneDepths, float weightScale) const;

private:
  int ViewportWidth = 0;
  int ViewportHeight = 0;
  int Layers = 1;
  int Reach = 0;
  int Width = 0;  // cells per row: the viewport's width padded by Reach on each side
  int Height = 0; // rows of cells
  int Bands = 0;
  // Minified splats of chunk c whose center lies in band b: Lists[c * Bands + b].
  std::vector<std::vector<MinifiedSurfel>> Lists;
  // Per cell, its surfaces front to back (Layers at most), and how many.
  std::vector<Cell> Cells;
  std::vector<std::uint8_t> Counts;
  // Per cell, a bound below which none of its farther surfaces reaches a pixel it is gathered
  // into: the smallest depth minus z threshold over its reach (infinite with one surface).
  std::vector<float> DeeperDepths;
  // Per row of cells, a bit per cell that holds any (Words words a row): the gather visits only
  // the pixels a filled cell reaches.
  int Words = 0;
  std::vector<std::uint64_t> Filled;
};

inline float DepthOf(const MinifiedSplatCells::Cell& c)
{
  return c.Sum.Depth;
}

inline float WeightOf(const MinifiedSplatCells::Cell& c)
{
  return c.Sum.Weight;
}

} // namespace splat

#endif
