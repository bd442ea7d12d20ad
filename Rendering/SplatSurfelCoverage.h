// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatSurfelCoverage.h
 * @brief Whether a set of surfels still covers its surface at a cutoff as it does at a wider one.
 *
 * A smaller cutoff blends fewer neighbors per pixel: sharper and faster on surfaces whose
 * surfels overlap well (mesh vertices with the radius of their longest edge, regular grids),
 * but it opens holes between scattered points whose radii only just reach their neighbors,
 * which a wider cutoff than the paper's closes.
 * The test is done once per surfel set, in object space (magnified, where holes show): at
 * sample points spread over the disks of some of the surfels, the summed kernel weights of
 * their neighbors, as a magnified splat draws them (e^-beta / pi for beta = |u|^2 in axis
 * units, see SplatSurfelKernel.h), are compared with the full-coverage weight of each cutoff.
 * A sample counts where the tighter cutoff gives it less than full coverage, so that edge
 * antialiasing would let the background through: between the tight disks of a regular grid
 * (R = h, cutoff 0.5, where one or two of them reach) as between scattered points.
 */
#ifndef SplatSurfelCoverage_h
#define SplatSurfelCoverage_h

#include "vtkNew.h"                    // For vtkNew
#include "vtkStaticPointLocator.h"     // For the locator
#include "vtkSurfaceSplatRasterizer.h" // For Surfels

namespace splat
{

/**
 * The coverage tests of a set of surfels, sharing one point locator over their positions (the
 * arrays are referenced, not copied: they must outlive it).
 */
class SurfelCoverage
{
public:
  explicit SurfelCoverage(const vtkSurfaceSplatRasterizer::Surfels& surfels);

  /**
   * The share of the sample points covered at `referenceCutoff` (wider) that `cutoff` leaves
   * uncovered, with `coverageThreshold` the full-coverage weight tau at the paper's cutoff
   * (scaled for others as vtkSurfaceSplatRasterizer does). Sample points that the reference
   * does not cover either are the surface's boundary, not holes. Neighbors facing the other
   * way or off the sample's tangent plane by more than their size (the other side of a thin
   * part) do not count. 0 for sets without finite positive axes.
   */
  double UncoveredShare(double cutoff, double referenceCutoff, double coverageThreshold) const
  {
    return this->UncoveredShare(cutoff, referenceCutoff, coverageThreshold, coverageThreshold);
  }

  /**
   * As above, the reference covering at its own threshold tau: whether `cutoff` still covers
   * the surface that the reference finds at `referenceThreshold` when full coverage takes
   * `coverageThreshold`.
   */
  double UncoveredShare(double cutoff, double referenceCutoff, double coverageThreshold,
    double referenceThreshold) const;

private:
  const vtkSurfaceSplatRasterizer::Surfels Surfels;
  double LargestAxis = 0.0;
  vtkNew<vtkStaticPointLocator> Locator;
};
}

#endif
