// SPDX-License-Identifier: BSD-3-Clause
// The set-cover simplification of differential points for vtkDifferentialPointGenerator, an
// alternative to the paper's greedy enclosure test (SplatDifferentialPointSimplifier.h) that keeps
// far fewer points. The surface is sampled densely (a mesh's vertices and polygon centroids, a
// cloud's points and the midpoints to their ring neighbors), each sample weighted by the area it
// stands for. A candidate, every input point's differential point, covers the samples that its
// rectangle (scaled down by the margin) holds on its tangent plane, that lie within a tolerance of
// its quadric along its normal and whose normal its predicted normal (eq. 10) matches within the
// error bound. The greedy cover takes the candidate with the most uncovered area first (a lazy
// max-heap: gains only shrink, so a popped entry whose recomputed gain still leads is taken; ties
// go to the lower index), until every sample some candidate covers is covered; then it drops, last
// chosen first, the points whose samples all stay covered by others. Every candidate covers its own
// sample, so every input point's position stays covered: that is the invariant the paper's
// enclosure test keeps with line segments.
#ifndef SplatDifferentialPointSetCover_h
#define SplatDifferentialPointSetCover_h

#include "SplatDifferentialPointGeometry.h"

#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <queue>
#include <utility>
#include <vector>

namespace splat
{
struct CoverSample
{
  Eigen::Vector3d Position;
  Eigen::Vector3d Normal; // unit
  double Weight;          // the area it stands for
};

class DifferentialPointSetCover
{
public:
  // epsilon: the maximum principal error. A sample's normal must be within the angle whose
  // 1 - cosine is NormalErrorFactor * epsilon of the normal the candidate predicts there (the
  // error bound lets the normal turn by 1 - cosine = epsilon across a rectangle: twice that leaves
  // room for the fit's noise).
  static constexpr double NormalErrorFactor = 2.0;

  DifferentialPointSetCover(const std::vector<DifferentialPoint>& points, double margin,
    double epsilon)
    : Points(points)
    , Scale(1.0 - margin)
    , MinimumCosine(1.0 - NormalErrorFactor * std::max(epsilon, 1e-6))
    , Slope(std::sqrt(std::max(2.0 * epsilon - epsilon * epsilon, 1e-12)))
  {
  }

  // Returns which points are kept; only points with candidate[p] set may be kept (the others
  // neither cover nor are kept). progress(fraction) returns false to stop, keeping every candidate
  // not yet decided against.
  std::vector<bool> Run(const std::vector<CoverSample>& samples, const std::vector<bool>& candidate,
    const std::function<bool(double)>& progress)
  {
    const std::int64_t n = static_cast<std::int64_t>(this->Points.size());
    this->BuildCoverage(samples, candidate);
    if (!progress(0.2))
    {
      return candidate;
    }

    // The lazy greedy cover by area. Samples of no area (coincident points) still count a little,
    // so that they are covered too.
    double mean = 0.0;
    for (const CoverSample& sample : samples)
    {
      mean += sample.Weight / static_cast<double>(samples.size());
    }
    std::vector<double> weights(samples.size());
    for (std::size_t s = 0; s < samples.size(); ++s)
    {
      weights[s] = std::max(samples[s].Weight, mean > 0.0 ? 1e-6 * mean : 1.0);
    }
    std::vector<char> covered(samples.size(), 0);
    auto gain = [&](std::int64_t p)
    {
      double sum = 0.0;
      for (std::int64_t s = this->Offsets[p]; s < this->Offsets[p + 1]; ++s)
      {
        sum += covered[this->Covered[s]] ? 0.0 : weights[this->Covered[s]];
      }
      return sum;
    };
    // Larger gain first, then the lower index.
    using Entry = std::pair<double, std::int64_t>;
    auto after = [](const Entry& a, const Entry& b)
    { return a.first < b.first || (a.first == b.first && a.second > b.second); };
    std::priority_queue<Entry, std::vector<Entry>, decltype(after)> heap(after);
    for (std::int64_t p = 0; p < n; ++p)
    {
      if (candidate[p])
      {
        heap.emplace(gain(p), p);
      }
    }
    // The area to cover, for progress: the samples' that some candidate covers.
    std::vector<char> coverable(samples.size(), 0);
    for (std::int64_t s : this->Covered)
    {
      coverable[s] = 1;
    }
    double total = 0.0;
    for (std::size_t s = 0; s < samples.size(); ++s)
    {
      total += coverable[s] ? weights[s] : 0.0;
    }
    std::vector<std::int64_t> chosen;
    double done = 0.0;
    std::int64_t pops = 0;
    while (!heap.empty())
    {
      const Entry top = heap.top();
      heap.pop();
      const double g = gain(top.second);
      if (g <= 0.0)
      {
        continue;
      }
      if (!heap.empty() && after(Entry(g, top.second), heap.top()))
      {
        heap.emplace(g, top.second);
        continue;
      }
      chosen.push_back(top.second);
      for (std::int64_t s = this->Offsets[top.second]; s < this->Offsets[top.second + 1]; ++s)
      {
        covered[this->Covered[s]] = 1;
      }
      done += g;
      if (++pops % 256 == 0 && total > 0.0 && !progress(0.2 + 0.7 * std::min(1.0, done / total)))
      {
        return candidate;
      }
    }

    // Redundant points: every sample they cover is covered by another chosen point.
    std::vector<int> count(samples.size(), 0);
    for (std::int64_t p : chosen)
    {
      for (std::int64_t s = this->Offsets[p]; s < this->Offsets[p + 1]; ++s)
      {
        ++count[this->Covered[s]];
      }
    }
    std::vector<bool> kept(n, false);
    for (auto it = chosen.rbegin(); it != chosen.rend(); ++it)
    {
      bool redundant = true;
      for (std::int64_t s = this->Offsets[*it]; s < this->Offsets[*it + 1] && redundant; ++s)
      {
        redundant = count[this->Covered[s]] > 1;
      }
      if (redundant)
      {
        for (std::int64_t s = this->Offsets[*it]; s < this->Offsets[*it + 1]; ++s)
        {
          --count[this->Covered[s]];
        }
      }
      else
      {
        kept[*it] = true;
      }
    }
    progress(1.0);
    return kept;
  }

  // Whether candidate p covers the sample (see the file comment).
  bool Covers(std::int64_t p, const CoverSample& sample) const
  {
    const DifferentialPoint& point = this->Points[p];
    const Eigen::Vector3d d = sample.Position - point.Position;
    const double u = d.dot(point.U), v = d.dot(point.V);
    const double hu = this->Scale * point.ExtentU, hv = this->Scale * point.ExtentV;
    if (std::abs(u) > hu || std::abs(v) > hv)
    {
      return false;
    }
    // The quadric's height, and as tolerance the height a flat point's error bound allows at the
    // rectangle's border: sqrt(2 eps - eps^2) / 2 times the half-width.
    const double height = 0.5 * (point.CurvatureU * u * u + point.CurvatureV * v * v);
    if (std::abs(d.dot(point.Normal) - height) > 0.5 * this->Slope * std::max(hu, hv))
    {
      return false;
    }
    return sample.Normal.dot(PredictedNormal(point, sample.Position)) >= this->MinimumCosine;
  }

private:
  // Offsets and Covered: the samples each candidate covers, found among those within its
  // rectangle's circumradius with a vtkStaticPointLocator.
  void BuildCoverage(const std::vector<CoverSample>& samples, const std::vector<bool>& candidate)
  {
    const std::int64_t n = static_cast<std::int64_t>(this->Points.size());
    vtkNew<vtkPoints> positions;
    positions->SetDataTypeToDouble();
    positions->SetNumberOfPoints(static_cast<vtkIdType>(samples.size()));
    for (std::size_t s = 0; s < samples.size(); ++s)
    {
      positions->SetPoint(static_cast<vtkIdType>(s), samples[s].Position.data());
    }
    vtkNew<vtkPolyData> cloud;
    cloud->SetPoints(positions);
    vtkNew<vtkStaticPointLocator> locator;
    locator->SetDataSet(cloud);
    locator->BuildLocator();
    std::vector<std::vector<std::int64_t>> lists(n);
    vtkSMPThreadLocalObject<vtkIdList> found;
    vtkSMPTools::For(0, n,
      [&](std::int64_t begin, std::int64_t end)
      {
        vtkIdList* near = found.Local();
        for (std::int64_t p = begin; p < end; ++p)
        {
          if (!candidate[p])
          {
            continue;
          }
          const DifferentialPoint& point = this->Points[p];
          const double radius = this->Scale * std::hypot(point.ExtentU, point.ExtentV);
          locator->FindPointsWithinRadius(radius, point.Position.data(), near);
          for (vtkIdType i = 0; i < near->GetNumberOfIds(); ++i)
          {
            if (this->Covers(p, samples[near->GetId(i)]))
            {
              lists[p].push_back(near->GetId(i));
            }
          }
          std::sort(lists[p].begin(), lists[p].end());
        }
      });
    this->Offsets.assign(n + 1, 0);
    for (std::int64_t p = 0; p < n; ++p)
    {
      this->Offsets[p + 1] = this->Offsets[p] + static_cast<std::int64_t>(lists[p].size());
    }
    this->Covered.resize(this->Offsets[n]);
    for (std::int64_t p = 0; p < n; ++p)
    {
      std::copy(lists[p].begin(), lists[p].end(), this->Covered.begin() + this->Offsets[p]);
    }
  }

  const std::vector<DifferentialPoint>& Points;
  const double Scale;
  const double MinimumCosine;
  const double Slope;
  std::vector<std::int64_t> Offsets;
  std::vector<std::int64_t> Covered;
};
}

#endif
