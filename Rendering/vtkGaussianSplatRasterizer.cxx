// SPDX-License-Identifier: BSD-3-Clause
#include "vtkGaussianSplatRasterizer.h"

#include "SplatFloat8.h"

#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>

vtkStandardNewMacro(vtkGaussianSplatRasterizer);

namespace
{
// Pixels per tile side: two groups of eight columns per row.
constexpr int TileSize = 16;
constexpr int Lanes = 8;
// A tile's groups of eight pixels as the bits of a word, bit TileSize g + y for group g of row
// y: a kernel tests its rows of a group eight at a time, and its loops visit only the groups
// it draws.
constexpr int Groups = TileSize / Lanes;
static_assert(Groups == 2 && TileSize * Groups <= 32, "two groups a row, one bit each");
using GroupBits = std::uint32_t;

// The bits of group g of rows ya to yb.
SPLAT_ALWAYS_INLINE GroupBits GroupsOfRows(int ya, int yb, int g)
{
  return ((GroupBits{ 2 } << yb) - (GroupBits{ 1 } << ya)) << TileSize * g;
}

// Where pixel (x, y) of a tile lies in its buffers: group by group (the bits' order), so that
// group bit b holds floats 8 b to 8 b + 7.
SPLAT_ALWAYS_INLINE int PixelOf(int x, int y)
{
  return (x / Lanes * TileSize + y) * Lanes + x % Lanes;
}

// The index of the lowest set bit of a nonzero word.
SPLAT_ALWAYS_INLINE int LowestBit(GroupBits bits)
{
#if defined(__GNUC__)
  return __builtin_ctz(bits);
#else
  int index = 0;
  for (; !(bits & 1u); bits >>= 1)
  {
    ++index;
  }
  return index;
#endif
}

// The number of a kernel's groups in a tile beyond which CompositeTile tests each group against
// the kernel's ellipse before drawing it. Groups outside the ellipse draw nothing (their alphas
// are below 1/255), so the test only saves time, and only for large kernels: drawing every group
// took the donut capture at 800^2 from 48-50 ms to 59-68 per frame, while testing the few groups
// of small kernels cost more than drawing them (the bench's 3dgs scene at 512^2, 2.6 groups per
// tile entry: this limit took about 4 % off a frame, farm-bench 4 pairs on a loaded machine).
constexpr int TestedGroups = 8;

// The number of set bits of a word.
SPLAT_ALWAYS_INLINE int BitCount(GroupBits bits)
{
#if defined(__GNUC__)
  return __builtin_popcount(bits);
#else
  int count = 0;
  for (; bits != 0; bits &= bits - 1)
  {
    ++count;
  }
  return count;
#endif
}

// A kept kernel on the screen, in the single precision of the per-pixel loop. Its exponent in
// base 2, as splat::NegativeExponential2 takes it.
struct ScreenSplat
{
  float CenterX, CenterY;
  float ConicXX, ConicXY, ConicYY; // alpha = Opacity 2^-(XX dx^2 + XY dx dy + YY dy^2)
  float HalfInverseXX;             // 0.5 / ConicXX
  float Opacity;
  float Level; // the exponent beyond which alpha is below 1/255
  float Depth;
  float Color[3];
  int X0, X1, Y0, Y1; // inclusive pixel bounds
};

// A kernel's tiles (inclusive columns and rows of tiles; none where X0 > X1) and its depth:
// all the binning reads of a kernel, a fifth of its footprint's bytes.
struct TileRange
{
  float Depth;
  std::uint16_t X0, X1, Y0, Y1;
};

// How many kernels ahead the loops over a scattered order fetch their kernel.
constexpr std::size_t PrefetchDistance = 8;

// Sorts a tile's entries by their depth keys (the high halves), keeping the order of equal keys:
// an LSD radix sort of 11-bit digits, a pass left out where all entries share its digit. The
// lists are already in id order, so this gives std::sort's order, at a sixth of its cost for a
// list of 1500 and a quarter for 256 (a micro-benchmark of depth keys); below 128 entries,
// where clearing the digits' counts costs more than the sort, std::sort itself. `scratch`
// holds at least `count` entries.
void SortByDepth(std::uint64_t* entries, std::size_t count, std::uint64_t* scratch)
{
  if (count < 128)
  {
    std::sort(entries, entries + count);
    return;
  }
  constexpr int DigitBits = 11;
  constexpr std::uint64_t DigitMask = (1u << DigitBits) - 1;
  std::uint64_t* from = entries;
  std::uint64_t* to = scratch;
  for (int shift = 32; shift < 64; shift += DigitBits)
  {
    std::uint32_t places[DigitMask + 1] = {};
    for (std::size_t i = 0; i < count; ++i)
    {
      ++places[from[i] >> shift & DigitMask];
    }
    if (places[from[0] >> shift & DigitMask] == count)
    {
      continue;
    }
    std::uint32_t next = 0;
    for (std::uint32_t& place : places)
    {
      next += std::exchange(place, next);
    }
    for (std::size_t i = 0; i < count; ++i)
    {
      to[places[from[i] >> shift & DigitMask]++] = from[i];
    }
    std::swap(from, to);
  }
  if (from != entries)
  {
    std::copy_n(from, count, entries);
  }
}

const ScreenSplat* KernelOf(const ScreenSplat* splats, std::uint64_t entry)
{
  return splats + (entry & 0xffffffffu);
}

// Composites one tile's kernels (sorted entries) front to back into the tile of the image
// whose lower left pixel is (x0, y0). A pixel's transmittance is kept negated once it stops (and
// from the start outside the image), so that one comparison per lane tells both; a group of
// eight pixels of a row is skipped once all its pixels stop, a kernel once all its groups do,
// and the tile ends when all do.
SPLAT_VECTOR_CLONES void CompositeTile(const ScreenSplat* splats, const std::uint64_t* entries,
  std::size_t count, int x0, int y0, int width, int height, const float* sceneDepths,
  glm::vec4* image)
{
  using splat::Float8;
  constexpr int Pixels = TileSize * TileSize;
  const int columns = std::min(TileSize, width - x0);
  const int rows = std::min(TileSize, height - y0);
  alignas(32) float transmittance[Pixels];
  alignas(32) float red[Pixels] = {};
  alignas(32) float green[Pixels] = {};
  alignas(32) float blue[Pixels] = {};
  alignas(32) float scene[Pixels];
  for (int y = 0; y < TileSize; ++y)
  {
    for (int x = 0; x < TileSize; ++x)
    {
      transmittance[PixelOf(x, y)] = x < columns && y < rows ? 1.0f : -1.0f;
    }
  }
  GroupBits open = 0;
  for (int g = 0; g < Groups && rows > 0; ++g)
  {
    open |= g * Lanes < columns ? GroupsOfRows(0, rows - 1, g) : 0;
  }
  std::fill_n(scene, Pixels, std::numeric_limits<float>::infinity());
  for (int y = 0; sceneDepths && y < rows; ++y)
  {
    const float* row = sceneDepths + static_cast<std::size_t>(y0 + y) * width + x0;
    for (int x = 0; x < columns; ++x)
    {
      scene[PixelOf(x, y)] = row[x];
    }
  }
  // The kernels behind none of the tile's scene depths skip the per-pixel depth test.
  const float sceneNearest = *std::min_element(scene, scene + Pixels);
  const Float8 minimumAlpha(splat::CaptureMinimumAlpha);
  const Float8 maximumAlpha(splat::CaptureMaximumAlpha);
  const Float8 minimumTransmittance(splat::CaptureMinimumTransmittance);
  const Float8 zero(0.0f);
  for (std::size_t n = 0; n < count && open != 0; ++n)
  {
    // The tile's kernels come in depth order, not in memory order (near one another when the
    // mapper keeps captures along a Z curve, all over memory otherwise): fetched ahead, they
    // come while the kernels before them are composited.
    if (n + PrefetchDistance < count)
    {
      splat::PrefetchBytes(KernelOf(splats, entries[n + PrefetchDistance]), sizeof(ScreenSplat));
    }
    const ScreenSplat& s = *KernelOf(splats, entries[n]);
    const int xa = std::max(s.X0 - x0, 0);
    const int xb = std::min(s.X1 - x0, columns - 1);
    const int ya = std::max(s.Y0 - y0, 0);
    const int yb = std::min(s.Y1 - y0, rows - 1);
    const GroupBits candidates = open &
      (GroupsOfRows(ya, yb, xa / Lanes) | GroupsOfRows(ya, yb, xb / Lanes));
    if (candidates == 0)
    {
      continue;
    }
    const float offsetX = static_cast<float>(x0) + 0.5f - s.CenterX;
    const bool occludable = sceneNearest < s.Depth;
    const Float8 depth(s.Depth);
    // Per group: its columns' dx and the peak opacity on the kernel's columns (zero on the
    // others).
    Float8 dx[Groups];
    Float8 opacity[Groups];
    for (int g = 0; g < Groups; ++g)
    {
      const Float8 column = Float8::Iota() + static_cast<float>(g * Lanes);
      dx[g] = column + offsetX;
      opacity[g] = Float8::SelectLess(column, static_cast<float>(xa), 0.0f,
        Float8::SelectLess(static_cast<float>(xb), column, 0.0f, s.Opacity));
    }
    // A group is drawn where the row's exponent comes below Level over its columns, at the
    // parabola's least value there: in a real capture half the groups of its large kernels'
    // boxes lie outside their ellipses (the donut at 800^2: 55 %). Eight rows at a time, for
    // kernels with more than TestedGroups groups in the tile.
    alignas(32) float crossOf[TileSize]; // per row: the exponent's dx dy and dy^2 terms
    alignas(32) float rowTermOf[TileSize];
    const bool tested = BitCount(candidates) > TestedGroups;
    GroupBits drawn = tested ? 0 : candidates;
    for (int y = 0; y < TileSize; y += Lanes)
    {
      const GroupBits eightRows = GroupsOfRows(y, y + Lanes - 1, 0);
      if (!(candidates & (eightRows | eightRows << TileSize)))
      {
        continue;
      }
      const Float8 dy = Float8::Iota() + static_cast<float>(y0 + y) + 0.5f - s.CenterY;
      const Float8 cross = dy * s.ConicXY;
      const Float8 rowTerm = dy * s.ConicYY * dy;
      cross.Store(crossOf + y);
      rowTerm.Store(rowTermOf + y);
      if (!tested)
      {
        continue;
      }
      const Float8 lowest = (0.0f - cross) * s.HalfInverseXX;
      for (int g = 0; g < Groups; ++g)
      {
        if (!(candidates & eightRows << TileSize * g))
        {
          continue;
        }
        // The group's first and last columns within the kernel's.
        const Float8 nearestFrom = static_cast<float>(std::max(g * Lanes, xa)) + offsetX;
        const Float8 nearestTo =
          static_cast<float>(std::min(g * Lanes + Lanes - 1, xb)) + offsetX;
        Float8 nearest = Float8::SelectLess(lowest, nearestFrom, nearestFrom, lowest);
        nearest = Float8::SelectLess(nearestTo, nearest, nearestTo, nearest);
        const Float8 least = nearest * (nearest * s.ConicXX + cross) + rowTerm;
        const int outside = Float8::LessMask(s.Level, least);
        drawn |= static_cast<GroupBits>(~outside & 0xff) << (TileSize * g + y);
      }
    }
    drawn &= candidates;
    // The kernel's alphas over its drawn groups, blended under the pixels as they come (a pass
    // of alphas before a pass of blending measured no faster).
    for (; drawn != 0; drawn &= drawn - 1)
    {
      const int bit = LowestBit(drawn);
      const int y = bit % TileSize;
      const int g = bit / TileSize;
      const int p = bit * Lanes;
      const Float8 q = dx[g] * (dx[g] * s.ConicXX + crossOf[y]) + rowTermOf[y];
      Float8 alpha = Float8::NegativeExponential2(q) * opacity[g];
      alpha = Float8::SelectLess(alpha, maximumAlpha, alpha, maximumAlpha);
      alpha = Float8::SelectLess(alpha, minimumAlpha, 0.0f, alpha);
      if (occludable)
      {
        alpha = Float8::SelectLess(Float8::Load(scene + p), depth, 0.0f, alpha);
      }
      const Float8 t = Float8::Load(transmittance + p);
      const Float8 next = t * (1.0f - alpha);
      // A pixel whose transmittance would fall below the minimum stops before this kernel
      // (stopped pixels hold their transmittance negated, so `next` is negative there).
      const Float8 weight = Float8::SelectLess(next, minimumTransmittance, 0.0f, alpha * t);
      const Float8 kept =
        Float8::SelectLess(next, minimumTransmittance, t.NegatedMagnitude(), next);
      kept.Store(transmittance + p);
      (Float8::Load(red + p) + weight * s.Color[0]).Store(red + p);
      (Float8::Load(green + p) + weight * s.Color[1]).Store(green + p);
      (Float8::Load(blue + p) + weight * s.Color[2]).Store(blue + p);
      if (!Float8::AnyLess(zero, kept))
      {
        open &= ~(GroupBits{ 1 } << bit);
      }
    }
  }
  for (int y = 0; y < rows; ++y)
  {
    glm::vec4* out = image + static_cast<std::size_t>(y0 + y) * width + x0;
    for (int x = 0; x < columns; ++x)
    {
      const int p = PixelOf(x, y);
      out[x] = glm::vec4(red[p], green[p], blue[p], 1.0f - std::abs(transmittance[p]));
    }
  }
}

// The footprints of kernels begin to end, eight at a time (a function of its own for
// SPLAT_VECTOR_CLONES_INLINED: the AVX2 clone holds the math of eight kernels in one register).
SPLAT_VECTOR_CLONES_INLINED void ProjectKernels(
  const vtkVolumeSplatRasterizer::Kernels& input, const float* colors,
  const vtkVolumeSplatRasterizer::Camera& camera, splat::FootprintFilter filter, vtkIdType begin,
  vtkIdType end, ScreenSplat* splats, TileRange* ranges, splat::CaptureSkip* skips)
{
  using splat::Float8;
  const glm::dvec2 viewport(std::max(camera.Viewport.x, 0), std::max(camera.Viewport.y, 0));
  const splat::CaptureFrame frame(
    camera.EyeToClip, viewport, glm::dmat3(camera.ModelToEye), filter);
  const glm::dmat3& S = input.SharedCovariance;
  const float shared[6] = { static_cast<float>(S[0][0]), static_cast<float>(S[0][1]),
    static_cast<float>(S[0][2]), static_cast<float>(S[1][1]), static_cast<float>(S[1][2]),
    static_cast<float>(S[2][2]) };
  // Per lane: the center in eye coordinates, the covariance and the peak opacity; then the
  // footprint's values, in the order of `results` below.
  alignas(32) float in[10][8];
  alignas(32) float out[11][8];
  for (vtkIdType first = begin; first < end; first += 8)
  {
    const int count = static_cast<int>(std::min<vtkIdType>(8, end - first));
    for (int lane = 0; lane < 8; ++lane)
    {
      // The lanes past the end repeat the last kernel, and are not stored.
      const vtkIdType i = first + std::min(lane, count - 1);
      const double* p = input.Positions + 3 * i;
      const glm::dvec3 e(camera.ModelToEye * glm::dvec4(p[0], p[1], p[2], 1.0));
      const float* v = input.Covariances ? input.Covariances + 6 * i : shared;
      for (int c = 0; c < 3; ++c)
      {
        in[c][lane] = static_cast<float>(e[c]);
      }
      for (int c = 0; c < 6; ++c)
      {
        in[3 + c][lane] = v[c];
      }
      in[9][lane] = input.Strengths[i];
    }
    splat::CaptureLanes k;
    for (int c = 0; c < 3; ++c)
    {
      k.Eye[c] = Float8::Load(in[c]);
    }
    for (int c = 0; c < 6; ++c)
    {
      k.Covariance[c] = Float8::Load(in[3 + c]);
    }
    k.Opacity = Float8::Load(in[9]);
    splat::MakeCaptureFootprints(frame, k);
    // The exponent in base 2, as CompositeTile takes it.
    constexpr float Log2E = 1.44269504088896341f;
    k.ConicXX = k.ConicXX * Log2E;
    k.ConicXY = k.ConicXY * Log2E;
    k.ConicYY = k.ConicYY * Log2E;
    k.Level = k.Level * Log2E;
    const Float8 halfInverseXX = Float8(0.5f) / k.ConicXX;
    const Float8* results[11] = { &k.CenterX, &k.CenterY, &k.ConicXX, &k.ConicXY, &k.ConicYY,
      &k.Opacity, &k.Level, &k.Depth, &k.HalfExtentX, &k.HalfExtentY, &halfInverseXX };
    for (int r = 0; r < 11; ++r)
    {
      results[r]->Store(out[r]);
    }
    for (int lane = 0; lane < count; ++lane)
    {
      const vtkIdType i = first + lane;
      glm::ivec4 box;
      skips[i] = !(k.InFront >> lane & 1) ? splat::CaptureSkip::NearPlane
        : (k.Visible >> lane & 1) &&
          splat::CoveredPixels(glm::dvec2(out[0][lane], out[1][lane]),
            glm::dvec2(out[8][lane], out[9][lane]), static_cast<int>(viewport.x),
            static_cast<int>(viewport.y), box)
        ? splat::CaptureSkip::Kept
        : splat::CaptureSkip::OutsideView;
      if (skips[i] == splat::CaptureSkip::Kept)
      {
        splats[i] = ScreenSplat{ out[0][lane], out[1][lane], out[2][lane], out[3][lane],
          out[4][lane], out[10][lane], out[5][lane], out[6][lane], out[7][lane],
          { colors[3 * i], colors[3 * i + 1], colors[3 * i + 2] }, box.x, box.y, box.z, box.w };
        ranges[i] = TileRange{ out[7][lane], static_cast<std::uint16_t>(box.x / TileSize),
          static_cast<std::uint16_t>(box.y / TileSize),
          static_cast<std::uint16_t>(box.z / TileSize),
          static_cast<std::uint16_t>(box.w / TileSize) };
      }
      else
      {
        ranges[i] = TileRange{ 0.0f, 1, 0, 1, 0 };
      }
    }
  }
}
}

struct vtkGaussianSplatRasterizer::Internals
{
  // Per input kernel: its footprint, its tiles, and why it is left out.
  std::vector<ScreenSplat> Splats;
  std::vector<TileRange> Ranges;
  std::vector<splat::CaptureSkip> Skips;
  // Per tile, its entries (splat::DepthOrderKey of depth and id): TileOffsets[t] to
  // TileOffsets[t + 1].
  std::vector<std::size_t> TileOffsets;
  std::vector<std::uint64_t> TileEntries;
};

//------------------------------------------------------------------------------
vtkGaussianSplatRasterizer::vtkGaussianSplatRasterizer()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkGaussianSplatRasterizer::~vtkGaussianSplatRasterizer()
{
  delete this->Internal;
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterizer::Render(const vtkVolumeSplatRasterizer::Kernels& input,
  const float* colors, const vtkVolumeSplatRasterizer::Camera& camera, const float* sceneDepths,
  std::vector<glm::vec4>& image)
{
  this->ProjectedCount = 0;
  this->NearPlaneCount = 0;
  this->OutsideViewCount = 0;
  this->TileEntryCount = 0;
  const int width = std::max(camera.Viewport.x, 0);
  const int height = std::max(camera.Viewport.y, 0);
  image.assign(static_cast<std::size_t>(width) * height, glm::vec4(0.0f));
  if (image.empty())
  {
    return;
  }
  Internals& internal = *this->Internal;

  // 1. The footprints.
  const vtkIdType n = static_cast<vtkIdType>(input.Count);
  // Tile entries hold a kernel's id in 32 bits.
  if (input.Count > std::numeric_limits<std::uint32_t>::max())
  {
    vtkErrorMacro(<< input.Count << " kernels: at most " << std::numeric_limits<std::uint32_t>::max()
                  << " are drawn in one frame.");
    return;
  }
  internal.Splats.resize(n);
  internal.Ranges.resize(n);
  internal.Skips.resize(n);
  vtkSMPTools::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      ProjectKernels(input, colors, camera, this->FootprintFilter, begin, end,
        internal.Splats.data(), internal.Ranges.data(), internal.Skips.data());
    });

  for (const splat::CaptureSkip skip : internal.Skips)
  {
    this->ProjectedCount += skip == splat::CaptureSkip::Kept;
    this->NearPlaneCount += skip == splat::CaptureSkip::NearPlane;
    this->OutsideViewCount += skip == splat::CaptureSkip::OutsideView;
  }

  // 2. The tiles' lists: a counting sort of the kept kernels by tile in parallel over fixed
  // chunks of the kernels (each chunk counts its entries per tile, the counts become each
  // chunk's first place in each tile's list, each chunk fills its places), which reads the
  // kernels' tile ranges in memory order; each tile's list is then sorted by depth where the
  // tile is composited. Every entry holds its depth and id, so the lists do not depend on the
  // number of threads.
  const int tilesX = (width + TileSize - 1) / TileSize;
  const int tilesY = (height + TileSize - 1) / TileSize;
  const vtkIdType tiles = static_cast<vtkIdType>(tilesX) * tilesY;
  const vtkIdType chunkSize = std::max<vtkIdType>(1 << 16, (n + 63) / 64);
  const vtkIdType chunks = (n + chunkSize - 1) / chunkSize;
  std::vector<std::size_t> places(static_cast<std::size_t>(chunks * tiles), 0);
  auto forEachEntry = [&](vtkIdType chunk, auto&& visit)
  {
    const vtkIdType end = std::min(n, (chunk + 1) * chunkSize);
    for (vtkIdType i = chunk * chunkSize; i < end; ++i)
    {
      const TileRange& r = internal.Ranges[i];
      for (int ty = r.Y0; ty <= r.Y1; ++ty)
      {
        for (int tx = r.X0; tx <= r.X1; ++tx)
        {
          visit(i, static_cast<vtkIdType>(ty) * tilesX + tx);
        }
      }
    }
  };
  vtkSMPTools::For(0, chunks,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType c = begin; c < end; ++c)
      {
        std::size_t* count = places.data() + c * tiles;
        forEachEntry(c, [count](vtkIdType, vtkIdType tile) { ++count[tile]; });
      }
    });
  internal.TileOffsets.assign(tiles + 1, 0);
  std::size_t next = 0;
  for (vtkIdType tile = 0; tile < tiles; ++tile)
  {
    for (vtkIdType c = 0; c < chunks; ++c)
    {
      const std::size_t count = places[c * tiles + tile];
      places[c * tiles + tile] = next;
      next += count;
    }
    internal.TileOffsets[tile + 1] = next;
  }
  this->TileEntryCount = static_cast<vtkIdType>(next);
  internal.TileEntries.resize(next);
  vtkSMPTools::For(0, chunks,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType c = begin; c < end; ++c)
      {
        std::size_t* place = places.data() + c * tiles;
        forEachEntry(c,
          [&](vtkIdType i, vtkIdType tile)
          {
            internal.TileEntries[place[tile]++] =
              splat::DepthOrderKey(internal.Ranges[i].Depth, static_cast<std::uint32_t>(i));
          });
      }
    });

  // 3. The tiles, each sorted by depth, then front to back.
  vtkSMPTools::For(0, tiles,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<std::uint64_t> scratch;
      for (vtkIdType tile = begin; tile < end; ++tile)
      {
        std::uint64_t* first = internal.TileEntries.data() + internal.TileOffsets[tile];
        std::uint64_t* last = internal.TileEntries.data() + internal.TileOffsets[tile + 1];
        scratch.resize(std::max<std::size_t>(scratch.size(), last - first));
        SortByDepth(first, last - first, scratch.data());
        CompositeTile(internal.Splats.data(), first, last - first,
          static_cast<int>(tile % tilesX) * TileSize,
          static_cast<int>(tile / tilesX) * TileSize, width, height, sceneDepths, image.data());
      }
    });
}

//------------------------------------------------------------------------------
void vtkGaussianSplatRasterizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FootprintFilter: " << static_cast<int>(this->FootprintFilter) << "\n";
  os << indent << "ProjectedCount: " << this->ProjectedCount << "\n";
  os << indent << "NearPlaneCount: " << this->NearPlaneCount << "\n";
  os << indent << "OutsideViewCount: " << this->OutsideViewCount << "\n";
  os << indent << "TileEntryCount: " << this->TileEntryCount << "\n";
}
