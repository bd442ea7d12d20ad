// SPDX-License-Identifier: BSD-3-Clause
// The greedy simplification of differential points of Kalaiah and Varshney 2003, section IV-C,
// for vtkDifferentialPointGenerator: a max-heap on the redundancy factor (eq. 6), the enclosure
// test on line segments of the point's rectangle against its neighbors' rectangles, and the
// neighborhood update of eq. 5 with the overlap test. Rectangles are scaled down by the margin
// in every test. Heap entries are not updated in place: a changed redundancy pushes a new entry
// and the stale ones are skipped when popped.
#ifndef SplatDifferentialPointSimplifier_h
#define SplatDifferentialPointSimplifier_h

#include "SplatDifferentialPointGeometry.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <queue>
#include <tuple>
#include <utility>
#include <vector>

namespace splat
{
class DifferentialPointSimplifier
{
public:
  // A neighbor can cover a point only when their normals are within 60 degrees: the projection
  // along the point's normal onto the neighbor's tangent plane degenerates beyond, and creases
  // keep their points on both sides.
  static constexpr double MinimumCoverCosine = 0.5;

  DifferentialPointSimplifier(const std::vector<DifferentialPoint>& points, double margin)
    : Points(points)
    , Scale(1.0 - margin)
  {
  }

  // Returns which points are kept. rings[p] are p's candidate neighbors (a mesh vertex's 1-ring,
  // a cloud point's nearest neighbors; symmetric); those that overlap p start as N(p).
  // progress(fraction) returns false to stop, keeping every point not yet pruned.
  std::vector<bool> Run(const std::vector<std::vector<std::int64_t>>& rings,
    const std::function<bool(double)>& progress)
  {
    const std::int64_t n = static_cast<std::int64_t>(this->Points.size());
    this->Neighbors.assign(n, {});
    for (std::int64_t p = 0; p < n; ++p)
    {
      for (std::int64_t q : rings[p])
      {
        if (q != p && Overlaps(this->Points[p], this->Points[q], this->Scale))
        {
          this->Neighbors[p].push_back(q);
        }
      }
    }
    enum State : char
    {
      Live,
      Kept,
      Pruned
    };
    std::vector<char> state(n, Live);
    std::vector<std::uint32_t> version(n, 0);
    using Entry = std::tuple<double, std::int64_t, std::uint32_t>;
    std::priority_queue<Entry> heap;
    // Eq. 6 as sums of the symmetric pair terms over N(p), updated as N(p) changes.
    std::vector<double> sums(n, 0.0);
    for (std::int64_t p = 0; p < n; ++p)
    {
      for (std::int64_t q : this->Neighbors[p])
      {
        sums[p] += this->Agreement(p, q);
      }
    }
    auto redundancy = [&](std::int64_t p)
    {
      const std::size_t count = this->Neighbors[p].size();
      return count > 0 ? sums[p] / count : 0.0;
    };
    for (std::int64_t p = 0; p < n; ++p)
    {
      heap.emplace(redundancy(p), p, 0);
    }
    std::vector<std::uint64_t> mark(n, 0);
    std::uint64_t stamp = 0;
    std::int64_t decided = 0;
    while (!heap.empty())
    {
      const auto [key, p, entryVersion] = heap.top();
      heap.pop();
      if (state[p] != Live || entryVersion != version[p])
      {
        continue;
      }
      if (++decided % 1024 == 0 && !progress(static_cast<double>(decided) / n))
      {
        break;
      }
      if (!this->Enclosed(p))
      {
        state[p] = Kept;
        continue;
      }
      state[p] = Pruned;
      const std::vector<std::int64_t> former = std::move(this->Neighbors[p]);
      this->Neighbors[p].clear();
      for (std::int64_t q : former)
      {
        auto& list = this->Neighbors[q];
        list.erase(std::remove(list.begin(), list.end(), p), list.end());
        sums[q] -= this->Agreement(p, q);
      }
      // Eq. 5: p's neighbors that overlap become each other's neighbors (q1's neighbors
      // marked with the stamp).
      for (std::size_t i = 0; i < former.size(); ++i)
      {
        const std::int64_t q1 = former[i];
        ++stamp;
        for (std::int64_t q : this->Neighbors[q1])
        {
          mark[q] = stamp;
        }
        for (std::size_t j = i + 1; j < former.size(); ++j)
        {
          const std::int64_t q2 = former[j];
          if (mark[q2] != stamp && Overlaps(this->Points[q1], this->Points[q2], this->Scale))
          {
            this->Neighbors[q1].push_back(q2);
            this->Neighbors[q2].push_back(q1);
            const double agreement = this->Agreement(q1, q2);
            sums[q1] += agreement;
            sums[q2] += agreement;
          }
        }
      }
      for (std::int64_t q : former)
      {
        if (state[q] == Live)
        {
          heap.emplace(redundancy(q), q, ++version[q]);
        }
      }
    }
    std::vector<bool> kept(n);
    for (std::int64_t p = 0; p < n; ++p)
    {
      kept[p] = state[p] != Pruned;
    }
    return kept;
  }

private:
  // Eq. 6's term for a pair: how well p predicts q's normal and q predicts p's, the same for
  // (q, p).
  double Agreement(std::int64_t p, std::int64_t q) const
  {
    const DifferentialPoint& dp = this->Points[p];
    const DifferentialPoint& dq = this->Points[q];
    return 0.5 *
      (std::abs(dq.Normal.dot(PredictedNormal(dp, dq.Position))) +
        std::abs(dp.Normal.dot(PredictedNormal(dq, dp.Position))));
  }

  // Enclosed(p): the segments of p's rectangle (its diagonals, midlines, the diamond through
  // the edge midpoints as in the paper's Fig. 5, and its border), projected along p's normal onto
  // each neighbor's tangent plane, nearest neighbor first, and clipped by its rectangle until
  // nothing is left.
  bool Enclosed(std::int64_t p) const
  {
    const DifferentialPoint& dp = this->Points[p];
    const double hu = this->Scale * dp.ExtentU, hv = this->Scale * dp.ExtentV;
    const Eigen::Vector2d a(-hu, hv), b(0, hv), c(hu, hv), d(hu, 0), e(hu, -hv), f(0, -hv),
      g(-hu, -hv), h(-hu, 0);
    using Segment = std::pair<Eigen::Vector2d, Eigen::Vector2d>;
    std::vector<Segment> segments = { { a, e }, { c, g }, { b, f }, { h, d }, { b, h }, { h, f },
      { f, d }, { d, b }, { a, c }, { c, e }, { e, g }, { g, a } };
    const double negligible = 1e-9 * std::max(hu, hv);

    std::vector<std::pair<double, std::int64_t>> order;
    for (std::int64_t q : this->Neighbors[p])
    {
      order.emplace_back((this->Points[q].Position - dp.Position).squaredNorm(), q);
    }
    std::sort(order.begin(), order.end());
    std::vector<Segment> left;
    for (const auto& entry : order)
    {
      const DifferentialPoint& dq = this->Points[entry.second];
      const double cosine = dp.Normal.dot(dq.Normal);
      if (cosine < MinimumCoverCosine)
      {
        continue;
      }
      const Eigen::Vector2d hq(this->Scale * dq.ExtentU, this->Scale * dq.ExtentV);
      // Along p's normal onto q's tangent plane, in q's (u, v) coordinates.
      auto project = [&](const Eigen::Vector2d& uv)
      {
        const Eigen::Vector3d x = dp.Global(uv);
        return dq.Local(x - ((x - dq.Position).dot(dq.Normal) / cosine) * dp.Normal);
      };
      left.clear();
      for (const Segment& segment : segments)
      {
        double t0, t1;
        if (!ClipSegment(project(segment.first), project(segment.second), hq, t0, t1))
        {
          left.push_back(segment);
          continue;
        }
        const Eigen::Vector2d delta = segment.second - segment.first;
        if (t0 * delta.norm() > negligible)
        {
          left.emplace_back(segment.first, segment.first + t0 * delta);
        }
        if ((1.0 - t1) * delta.norm() > negligible)
        {
          left.emplace_back(segment.first + t1 * delta, segment.second);
        }
      }
      segments.swap(left);
      if (segments.empty())
      {
        return true;
      }
    }
    return false;
  }

  const std::vector<DifferentialPoint>& Points;
  const double Scale;
  std::vector<std::vector<std::int64_t>> Neighbors;
};
}

#endif
