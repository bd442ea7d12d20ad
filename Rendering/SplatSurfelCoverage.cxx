// SPDX-License-Identifier: BSD-3-Clause
#include "SplatSurfelCoverage.h"

#include "SplatSurfelKernel.h"

#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>

namespace
{
// Surfels whose disks are sampled (evenly spread over the input order), and points per disk:
// about 16 k neighborhood queries, a few milliseconds, whatever the size of the set.
constexpr std::size_t SampledSurfels = 2048;
constexpr int PointsPerDisk = 8;
// Neighbors the queries may return in all: tens of times what a surface's 16 k queries return.
// Piled-up points return the whole pile to every query (1e6 coincident points took minutes);
// there the samples stop once the next batch would pass this, and the share is that of the
// samples taken, which a permuted order spreads over the whole set.
constexpr double NeighborBudget = 2e7;

// A stride that visits 0..n-1 in a spread-out order: coprime with n, near n / golden ratio.
std::size_t SpreadStride(std::size_t n)
{
  std::size_t stride = std::max<std::size_t>(1, static_cast<std::size_t>(0.6180339887 * n));
  while (std::gcd(stride, n) != 1)
  {
    ++stride;
  }
  return stride;
}

glm::dvec3 Vec(const float* v)
{
  return glm::dvec3(v[0], v[1], v[2]);
}
}

namespace splat
{

SurfelCoverage::SurfelCoverage(const vtkSurfaceSplatRasterizer::Surfels& surfels)
  : Surfels(surfels)
{
  for (std::size_t i = 0; i < 3 * surfels.Count; i += 3)
  {
    this->LargestAxis = std::max({ this->LargestAxis, glm::length(Vec(surfels.Axes0 + i)),
      glm::length(Vec(surfels.Axes1 + i)) });
  }
  if (surfels.Count == 0 || !(this->LargestAxis > 0.0 && std::isfinite(this->LargestAxis)))
  {
    this->LargestAxis = 0.0;
    return;
  }
  // The positions in place, as the points of a data set for the locator.
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetArray(const_cast<double*>(surfels.Positions),
    static_cast<vtkIdType>(3 * surfels.Count), /*save=*/1);
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  this->Locator->SetDataSet(cloud);
  this->Locator->BuildLocator();
}

//------------------------------------------------------------------------------
double SurfelCoverage::UncoveredShare(double cutoff, double referenceCutoff,
  double coverageThreshold, double referenceThreshold) const
{
  if (this->LargestAxis == 0.0)
  {
    return 0.0;
  }
  const vtkSurfaceSplatRasterizer::Surfels& surfels = this->Surfels;
  const std::size_t count = surfels.Count;
  vtkStaticPointLocator* locator = this->Locator;
  const double largestAxis = this->LargestAxis;
  const double reach = std::sqrt(std::max(cutoff, referenceCutoff)) * largestAxis;
  const double referenceFull = FullCoverageWeight(referenceThreshold, referenceCutoff);
  const double full = FullCoverageWeight(coverageThreshold, cutoff);
  const std::size_t sampled = std::min(count, SampledSurfels);
  const std::size_t stride = SpreadStride(sampled);
  std::atomic<vtkIdType> coveredByReference(0), uncovered(0), returned(0);
  vtkSMPThreadLocalObject<vtkIdList> neighborLists;
  auto sample = [&](vtkIdType begin, vtkIdType end)
  {
    vtkIdList* neighbors = neighborLists.Local();
    vtkIdType covered = 0, holes = 0, found = 0;
    for (vtkIdType s = begin; s < end; ++s)
    {
      const std::size_t t = static_cast<std::size_t>(s) * stride % sampled;
      const std::size_t i = t * count / sampled;
      const glm::dvec3 p(surfels.Positions[3 * i], surfels.Positions[3 * i + 1],
        surfels.Positions[3 * i + 2]);
      const glm::dvec3 a0 = Vec(surfels.Axes0 + 3 * i), a1 = Vec(surfels.Axes1 + 3 * i);
      const glm::dvec3 n = Vec(surfels.Normals + 3 * i);
      for (int k = 0; k < PointsPerDisk; ++k)
      {
        // Points spread evenly over the disk |u| < 1 (a sunflower pattern).
        const double radius = std::sqrt((k + 0.5) / PointsPerDisk);
        const double angle = 2.39996322972865332 * k + 0.7 * t;
        const glm::dvec3 x = p + radius * (std::cos(angle) * a0 + std::sin(angle) * a1);
        locator->FindPointsWithinRadius(reach, &x[0], neighbors);
        found += neighbors->GetNumberOfIds();
        double referenceWeight = 0.0, weight = 0.0;
        for (vtkIdType m = 0; m < neighbors->GetNumberOfIds(); ++m)
        {
          const std::size_t j = static_cast<std::size_t>(neighbors->GetId(m));
          const glm::dvec3 b0 = Vec(surfels.Axes0 + 3 * j), b1 = Vec(surfels.Axes1 + 3 * j);
          const glm::dvec3 nj = Vec(surfels.Normals + 3 * j);
          const glm::dvec3 d = x -
            glm::dvec3(surfels.Positions[3 * j], surfels.Positions[3 * j + 1],
              surfels.Positions[3 * j + 2]);
          const double size = std::max(glm::length(b0), glm::length(b1));
          if (!(glm::dot(n, nj) > 0.0) ||
            !(std::abs(glm::dot(d, nj)) <= size * glm::length(nj)))
          {
            continue;
          }
          const double u0 = glm::dot(d, b0) / glm::dot(b0, b0);
          const double u1 = glm::dot(d, b1) / glm::dot(b1, b1);
          const double beta = u0 * u0 + u1 * u1;
          const double w = 2.0 * InverseTwoPi * std::exp(-beta);
          referenceWeight += beta < referenceCutoff ? w : 0.0;
          weight += beta < cutoff ? w : 0.0;
          if (referenceWeight >= referenceFull && weight >= full)
          {
            break; // covered at both cutoffs: on coincident points, after a few neighbors
          }
        }
        if (referenceWeight >= referenceFull)
        {
          ++covered;
          holes += weight < full;
        }
      }
    }
    coveredByReference += covered;
    uncovered += holes;
    returned += found;
  };
  // Batches of samples that double in size, each run in parallel, while the neighbors the next
  // would return (at the mean so far) fit the budget: the same samples on every run.
  vtkIdType done = 0;
  for (vtkIdType batch = 1; done < static_cast<vtkIdType>(sampled); batch *= 2)
  {
    if (done > 0 && static_cast<double>(returned) * (done + batch) / done > NeighborBudget)
    {
      break;
    }
    const vtkIdType end = std::min(static_cast<vtkIdType>(sampled), done + batch);
    vtkSMPTools::For(done, end, sample);
    done = end;
  }
  return coveredByReference > 0 ? static_cast<double>(uncovered) / coveredByReference : 0.0;
}

}
