// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatFogOpacity.h
 * @brief The opacity of a fog volume's first view (splat_render, ParaView's Volume Splats).
 *
 * A fog's values are densities, so
 * - extinction is linear in the density from zero (a density of 0 is clear air, not the low end
 *   of a value range to threshold away: the thin fringe of smoke stays visible);
 * - the emission is white, the color of lit water droplets and smoke alike, and needs no range;
 * - the scale makes a ray through a compact cloud of the grid's active volume V at the grid's
 *   mean positive density m have an optical depth of 2 (a transmittance of e^-2, 14%): the
 *   extinction per unit density is 2 / (m cbrt(V)). Dense cores come out nearly opaque, the
 *   bulk translucent, the shape readable from any side, whatever units the densities have.
 * The opacity function is given per unit distance cbrt(V) / 100 (a volume property's
 * ScalarOpacityUnitDistance), sampled at 33 densities from 0 to the largest (alpha =
 * 1 - exp(-tau u) at each, so that the mapper's extinction is linear between them).
 *
 * VTK-free: vtkOpenVDBReader writes the statistics, the examples and the ParaView plugin read
 * them.
 */
#ifndef SplatFogOpacity_h
#define SplatFogOpacity_h

#include <cmath>

namespace splat
{

/// What a fog's first view depends on: over the kernels of positive density, their mean and
/// largest density and their total volume.
struct FogStatistics
{
  double Mean = 0.0;
  double Largest = 0.0;
  double Volume = 0.0;
};

/// The opacity function's samples: Alpha[i] at Density[i], per UnitDistance.
struct FogOpacity
{
  static constexpr int Samples = 33;
  double Density[Samples] = {};
  double Alpha[Samples] = {};
  double UnitDistance = 1.0;
};

/**
 * The opacity of a fog of the given statistics (see the file comment); false, and only the
 * clear first sample, when the statistics hold no positive density or volume.
 */
inline bool MakeFogOpacity(const FogStatistics& statistics, FogOpacity& out)
{
  out = FogOpacity{};
  if (!(statistics.Mean > 0.0 && statistics.Largest > 0.0 && statistics.Volume > 0.0) ||
    !std::isfinite(statistics.Mean * statistics.Largest * statistics.Volume))
  {
    return false;
  }
  const double size = std::cbrt(statistics.Volume);
  const double perDensity = 2.0 / (statistics.Mean * size);
  out.UnitDistance = size / 100.0;
  for (int i = 1; i < FogOpacity::Samples; ++i)
  {
    out.Density[i] = statistics.Largest * i / (FogOpacity::Samples - 1);
    out.Alpha[i] = 1.0 - std::exp(-perDensity * out.Density[i] * out.UnitDistance);
  }
  return true;
}

} // namespace splat

#endif
