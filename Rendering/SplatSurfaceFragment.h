// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatSurfaceFragment.h
 * @brief One surface's contributions to a pixel of the CPU surface rasterizer (paper 000, table
 * 1), and how contributions join a pixel's fragments, which are kept sorted front to back.
 *
 * VTK-free; private to vtkSurfaceSplatRasterizer and its cells of minified splats
 * (SplatMinifiedSplatCells.h).
 */
#ifndef SplatSurfaceFragment_h
#define SplatSurfaceFragment_h

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace splat
{

/// Accumulated alpha beyond which the fragments behind change no 8-bit color.
constexpr float OpaqueAlpha = 1.0f - 1e-4f;

/**
 * One surface's contributions to a pixel. A merged fragment has been shaded: its Weight is
 * negative and Color holds the premultiplied shaded color.
 */
struct SurfaceFragment
{
  float Depth; ///< linear eye depth of the nearest contribution
  float Weight;
  float Alpha; ///< weighted opacity, or the merged opacity once shaded
  float Color[3];
  float Normal[3];

  bool Shaded() const { return this->Weight < 0.0f; }
};

/// Whether f is a fully covered (summed weight `full`) opaque surface: a pixel's blend stops at
/// it, and nothing behind it shows.
inline bool FullyCoveredOpaque(const SurfaceFragment& f, float full)
{
  return f.Weight >= full && f.Alpha >= OpaqueAlpha * f.Weight;
}

/**
 * Adds w times a normal to a running sum, turned to the sum's side. Normals are added as they
 * come, unturned towards the viewer: a scan's normals, estimated without a consistent
 * orientation, point either way, and turning each towards the viewer on its own bends the ones
 * seen edge-on (the silhouettes) by up to a right angle; added on one side, they average to the
 * surface's normal, which is turned towards the viewer once, when the fragment is shaded.
 */
inline void AddNormal(float* sum, float w, const float* normal)
{
  const float side = sum[0] * normal[0] + sum[1] * normal[1] + sum[2] * normal[2];
  const float signedW = side < 0.0f ? -w : w;
  sum[0] += signedW * normal[0];
  sum[1] += signedW * normal[1];
  sum[2] += signedW * normal[2];
}

/// A contribution with its own normal (a differential point's varies from pixel to pixel).
inline void Accumulate(
  SurfaceFragment& f, float z, float w, const float* normal, const float* color, float alpha)
{
  f.Depth = std::min(f.Depth, z);
  f.Weight += w;
  f.Alpha += w * alpha;
  f.Color[0] += w * color[0];
  f.Color[1] += w * color[1];
  f.Color[2] += w * color[2];
  AddNormal(f.Normal, w, normal);
}

inline SurfaceFragment NewFragment(
  float z, float w, const float* normal, const float* color, float alpha)
{
  SurfaceFragment f;
  f.Depth = z;
  f.Weight = w;
  f.Alpha = w * alpha;
  for (int c = 0; c < 3; ++c)
  {
    f.Color[c] = w * color[c];
    f.Normal[c] = w * normal[c];
  }
  return f;
}

/// Sums of contributions at depth z, each weighted w times as much.
inline void AccumulateScaled(SurfaceFragment& f, const SurfaceFragment& sums, float w, float z)
{
  f.Depth = std::min(f.Depth, z);
  f.Weight += w * sums.Weight;
  f.Alpha += w * sums.Alpha;
  for (int c = 0; c < 3; ++c)
  {
    f.Color[c] += w * sums.Color[c];
  }
  AddNormal(f.Normal, w, sums.Normal);
}

inline SurfaceFragment Scaled(const SurfaceFragment& sums, float w, float z)
{
  SurfaceFragment f = sums;
  f.Depth = z;
  f.Weight *= w;
  f.Alpha *= w;
  for (int c = 0; c < 3; ++c)
  {
    f.Color[c] *= w;
    f.Normal[c] *= w;
  }
  return f;
}

inline float DepthOf(const SurfaceFragment& f)
{
  return f.Depth;
}

/// The share of full coverage below which a fragment is a sliver that gives way (OpaqueSlot):
/// alone, edge antialiasing draws it with at most that alpha.
constexpr float NegligibleCoverage = 0.02f;

/// A coverage dip, raised to full coverage before the resolve (the CPU rasterizer's
/// CloseCoverageDips, the OpenGL resolve's first layer): an opaque front surface covered at
/// least DipCoverage of full coverage but not fully, whose eight neighbors hold the same opaque
/// surface covered at least as much: each pair of opposite ones at depths on a line through
/// its own within DipDepthPixels pixel widths, which a steep surface's are too and a surface
/// seen behind an edge (at this tolerance) is not.
constexpr float DipCoverage = 0.25f;
constexpr float DipDepthPixels = 4.0f;

/// The dip's depth tolerance, DipDepthPixels pixel widths, for a viewport `height` pixels high
/// whose projection scales eye y by `eyeToClipYY`: per unit eye depth in perspective, in eye
/// units in parallel projection.
inline float DipDepthTolerance(double eyeToClipYY, int height)
{
  return static_cast<float>(DipDepthPixels * 2.0 / (std::abs(eyeToClipYY) * height));
}

inline float WeightOf(const SurfaceFragment& f)
{
  return f.Weight;
}

/**
 * Where an opaque contribution of weight w at eye depth z goes among a pixel's `count` items
 * (fragments, or anything with a DepthOf and a WeightOf), sorted front to back: the index of
 * the surface within the z threshold, or, with `inserted` set, of a new surface moved into
 * place for the caller to fill; -1 when it is left out.
 *
 * Once `layers` surfaces are held, an item of weight below `negligible` gives way first (the
 * lightest), else the farthest to a new surface in front of it; a new surface below
 * `negligible` takes no held layer. This is for the splats' fragments: at silhouettes, the depth
 * planes of grazing splats, extrapolated over their low-pass fringe, land far in front of and
 * behind the surface, and those slivers of a thousandth of a pixel's weight took the layers and
 * pushed the surface's own fragment out (the silhouette of a dense sphere came out 1.5 pixels
 * inside the true one, its edge pixels empty).
 */
template <typename Item>
inline int OpaqueSlot(Item* items, std::uint8_t& count, int layers, float z, float threshold,
  bool& inserted, float w = 0.0f, float negligible = 0.0f)
{
  int i = 0;
  while (i < count && z > DepthOf(items[i]) + threshold)
  {
    ++i;
  }
  inserted = !(i < count && z >= DepthOf(items[i]) - threshold);
  if (!inserted)
  {
    return i;
  }
  int out = count; // the item that gives way; none while a layer is free
  if (count == layers)
  {
    if (w < negligible)
    {
      return -1;
    }
    out = -1;
    for (int j = 0; j < count; ++j)
    {
      const float weight = WeightOf(items[j]);
      out = weight < negligible && (out < 0 || weight < WeightOf(items[out])) ? j : out;
    }
    if (out < 0)
    {
      if (i == layers)
      {
        return -1;
      }
      out = count - 1;
    }
  }
  else
  {
    ++count;
  }
  // The items between the one given way (or the free layer) and the new one's place close up.
  for (int j = out; j + 1 < i; ++j)
  {
    items[j] = items[j + 1];
  }
  for (int j = out; j > i; --j)
  {
    items[j] = items[j - 1];
  }
  return out < i ? i - 1 : i;
}

/**
 * exp(-beta) for beta in [0, cutoff], tabulated once per frame and linearly interpolated: the
 * paper's lookup table, within 2e-6 of std::exp for the default cutoff.
 */
class ExponentialTable
{
public:
  explicit ExponentialTable(float cutoff)
    : Scale(Size / cutoff)
  {
    for (int i = 0; i <= Size + 1; ++i)
    {
      this->Table[i] = std::exp(-static_cast<float>(i) / this->Scale);
    }
  }

  float operator()(float beta) const
  {
    const float t = beta * this->Scale;
    const int i = static_cast<int>(t);
    return this->Table[i] + (t - i) * (this->Table[i + 1] - this->Table[i]);
  }

private:
  static constexpr int Size = 1024;
  float Scale;
  float Table[Size + 2];
};

} // namespace splat

#endif
